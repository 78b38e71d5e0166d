"""One time rule (docs/time.md): the machine's time zone never changes an answer about a NEEM."""

import json
import os
import shutil
import subprocess
import sys

import pytest

from oracle.cli import main

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")

#: A morning habit at 10:30 wall clock: Morning, but Midday if read as Berlin time shown in UTC+1.
MORNING = ["pick(red_mug)", "place(red_mug, counter_top)", "pick(thermos)", "pour(thermos, red_mug)"]
ZONES = ("UTC", "Europe/Berlin")


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("zones")
    available = sorted(set(MORNING + ["pick(banana)", "open(fridge)"]))
    rows = [{"user": "ada", "time": f"2026-03-0{2 + day}T10:30:{10 * i:02d}", "duration": 5, "action": action,
             "available": available} for day in range(3) for i, action in enumerate(MORNING)]
    chains = tmp / "c.jsonl"
    chains.write_text("".join(json.dumps(r) + "\n" for r in rows))
    path = tmp / "s.sqlite"
    assert main(["import", str(chains), "--store", str(path)]) == 0
    # One decision at 10:00 UTC on the next day (a time with its zone: the same instant anywhere).
    assert main(["rank", "--store", str(path), "--available", "pick(banana)", "pick(red_mug)",
                 "--at", "2026-03-05T10:00:00+00:00", "--json"]) == 0
    return path


def _run(zone: str, *args: str) -> dict:
    env = {**os.environ, "TZ": zone}
    done = subprocess.run([sys.executable, "-m", "oracle", *args], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def _each_zone(*args: str) -> list[dict]:
    answers = [_run(zone, *args) for zone in ZONES]
    for answer in answers:
        answer.pop("ms", None)  # the only field that may differ: how long ranking took
    return answers


def test_rank_reads_the_neem_the_same_in_every_zone(store):
    utc, berlin = _each_zone("rank", "--store", str(store), "--no-write", "--json")
    assert utc["time_of_day"] == "Morning"  # logged at 10:30 wall clock
    assert berlin == utc


def test_rank_at_a_time_without_zone_is_the_same_in_every_zone(store):
    utc, berlin = _each_zone("rank", "--store", str(store), "--available", "pick(banana)", "pick(red_mug)",
                             "--at", "2026-03-06T10:45", "--no-write", "--json")
    assert utc["time_of_day"] == "Morning" and utc["at"] == 1772793900.0
    assert berlin == utc


def test_why_not_at_a_time_without_zone_is_the_same_in_every_zone(store):
    # 10:30 without a zone is 10:30 UTC, after the 10:00 decision, wherever the machine is
    utc, berlin = _each_zone("why-not", "pick(banana)", "--at", "2026-03-05T10:30", "--store", str(store), "--json")
    assert utc["at"] == 1772706600.0 and utc["reasons"][0]["reason"] == "ranked_lower"
    assert berlin == utc
