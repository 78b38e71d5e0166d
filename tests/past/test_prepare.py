"""What to prepare: the moved objects of the routines of a coming part of the day, with reasons."""

from __future__ import annotations

import json
import subprocess
import sys

from oracle.past.prepare import IN_WASHER, UNKNOWN, USED, WASHED, most_used, next_part, object_state, to_prepare, used_in
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


def test_the_state_of_an_object_follows_its_use_and_the_dishwasher():
    cup = day(0, 8, ("pick(red_mug)", "pour(thermos, red_mug)", "drink_from(red_mug)", "place(red_mug, dish_washer)",
                     "turn_on(dish_washer)", "pick(red_mug)", "stir(spoon, red_mug)"))
    states = [object_state("red_mug", cup[:n]) for n in range(len(cup) + 1)]
    assert [s.state for s in states] == [UNKNOWN, UNKNOWN, USED, USED, IN_WASHER, WASHED, WASHED, USED]
    assert (states[3].since, states[3].call) == (cup[2].begin, "drink_from(red_mug)")
    assert states[5].call == "turn_on(dish_washer)"
    assert object_state("spoon", cup).state == USED and object_state("thermos", cup).state == UNKNOWN
    # taken out before the dishwasher ran: as used as before
    unwashed = cup[:4] + day(0, 9, ("pick(red_mug)",))
    assert object_state("red_mug", unwashed) == states[3]
    # the dishwasher run without the mug inside washes nothing
    assert object_state("red_mug", cup[:3] + day(0, 9, ("turn_on(dish_washer)",))).state == USED


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
    assert reply["prepare"][0]["state"]["state"] == "used"  # drunk from, never in the dishwasher
    assert reply["prepare"][0]["state"]["action"] == "drink_from(red_mug)"
    line = subprocess.run([*run, "--for", "midday"], capture_output=True, text=True, check=True).stdout
    assert "; used in drink_from(red_mug) on " in line and "not washed since: worth washing now" in line
    text = subprocess.run([*run, "--for", "evening"], capture_output=True, text=True, check=True).stdout
    assert text == "nothing to prepare for the evening: no routine of the user's begins then\n"
