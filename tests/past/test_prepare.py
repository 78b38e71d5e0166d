"""What to prepare: the moved objects of the routines of a coming part of the day, with reasons."""

from __future__ import annotations

import json
import subprocess
import sys

from oracle.past.prepare import most_used, next_part, to_prepare, used_in
from oracle.past.routines import mine_routines
from oracle.timeline import seconds_of
from tests.past.test_routines import day, week


def test_the_objects_of_the_coming_routines_that_the_user_moves():
    done = week()
    routines = mine_routines(done)
    morning = to_prepare(routines, done, "Morning")
    assert [(p.obj, p.weight, p.routines) for p in morning] == [
        ("cereal_bowl", 1.0, (("r1", "Milk in the cereal bowl"),)), ("milk_carton", 1.0, (("r1", "Milk in the cereal bowl"),))]
    assert morning[0].reason == "Milk in the cereal bowl is usual at 07:10 (5 of 5 days) and needs the cereal bowl"
    assert [p.obj for p in to_prepare(routines, done, "Midday")] == ["red_mug"]  # not the coffee machine
    assert to_prepare(routines, done, "Evening") == []


def test_baseline_and_what_was_used():
    done = week()
    assert most_used(done, 2) == ["red_mug", "cereal_bowl"]  # in 5 and 4 actions a day
    assert used_in(done + day(5, 7, ("pick(apple)",)), "2025-03-08", "Morning") == {"apple"}


def test_next_part_of_the_day():
    from datetime import datetime

    parts = [next_part(seconds_of(datetime(2025, 3, 3, h))) for h in (3, 8, 12, 18, 23)]
    assert parts == ["Morning", "Midday", "Evening", "Night", "Morning"]


def test_cli_prepare(routine_store):
    run = [sys.executable, "-m", "oracle", "prepare", "--store", str(routine_store), "--neem", "weekly"]
    reply = json.loads(subprocess.run([*run, "--for", "midday", "--json"], capture_output=True, text=True,
                                      check=True).stdout)
    assert reply["for"] == "Midday" and [p["object"] for p in reply["prepare"]] == ["red_mug"]
    assert reply["prepare"][0]["last_used"]["task"] == "place(red_mug, kitchen_table)"
    text = subprocess.run([*run, "--for", "evening"], capture_output=True, text=True, check=True).stdout
    assert text == "nothing to prepare for the evening: no routine of the user's begins then\n"
