import json
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.chains import read_chains
from oracle.evaluation.conditions import derive, write_conditions
from oracle.evaluation.replay import LEGACY, load_users, replay
from oracle.ontology import build_ontology

SCRIPT = Path(__file__).resolve().parents[2] / "experiments" / "dev-conditions.py"
ROWS = [
    {"user": "u", "time": "2026-03-02T08:00:00", "end": "2026-03-02T08:00:05", "action": "pick(red_mug)",
     "available": ["pick(red_mug)", "open(fridge)"]},
    {"user": "u", "time": "2026-03-02T09:00:00", "duration": 3, "action": "open(fridge)",
     "available": ["pick(red_mug)", "open(fridge)"], "activity": "breakfast"},
    {"user": "u", "time": "2026-03-02T09:00:10", "action": "pick(red_mug)", "available": ["pick(red_mug)"]},
]


class Seen:
    """Records what the replay shows a method: the time of day of each ranking and each observed step."""

    name = "seen"

    def __init__(self) -> None:
        self.ranked: list[tuple[int, str | None]] = []
        self.idle = 0

    def reset(self) -> None:
        pass

    def rank(self, candidates, time_of_day=None, at=None):
        self.ranked.append((len(candidates), time_of_day))
        return list(candidates)

    def observe(self, step) -> None:
        self.idle += step.idle


@pytest.fixture
def chains(tmp_path):
    path = tmp_path / "dev.jsonl"
    path.write_text("".join(json.dumps(row) + "\n" for row in ROWS))
    return path


def test_open_drops_only_the_available_sets(chains):
    rows = list(read_chains(chains))
    derived = list(derive(rows, "open"))
    assert [r.available for r in derived] == [None] * 3
    assert [(r.user, r.action, r.time, r.end, r.extra) for r in derived] == [
        (r.user, r.action, r.time, r.end, r.extra) for r in rows]


def test_clockless_drops_the_clock_too(chains):
    derived = list(derive(read_chains(chains), "clockless"))
    assert all(r.available is None and r.time is None and r.end is None for r in derived)
    assert derived[1].extra == {"activity": "breakfast"}


def test_unknown_condition_is_refused(chains):
    with pytest.raises(ValueError, match="unknown condition 'dark'"):
        list(derive(read_chains(chains), "dark"))


def test_replay_of_derived_sets_offers_all_actions_and_reads_no_clock(chains, tmp_path):
    written = write_conditions(chains, tmp_path / "out")
    kitchen = build_ontology()
    seen = {}
    for condition in ("open", "clockless"):
        method = seen[condition] = Seen()
        replay(kitchen, load_users(written[condition]), [method], protocol=LEGACY)  # the vocabulary rule
    # the source has an idle gap (08:00:05 -> 09:00) and parts of day; open keeps them
    assert seen["open"].idle == 1
    assert seen["open"].ranked == [(2, "Morning")] * 3
    # clockless: no part of day, no idle step
    assert seen["clockless"].idle == 0
    assert seen["clockless"].ranked == [(2, None)] * 3


def test_script_writes_both_conditions_and_refuses_a_bad_file(chains, tmp_path):
    out = tmp_path / "derived"
    done = subprocess.run([sys.executable, str(SCRIPT), str(chains), str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*.jsonl")) == [
        "clockless/dev.jsonl", "open/dev.jsonl"]
    assert all("available" not in json.loads(line) for line in (out / "open" / "dev.jsonl").read_text().splitlines())
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"user": "u", "action": "pick("}\n')
    refused = subprocess.run([sys.executable, str(SCRIPT), str(bad), str(tmp_path / "none")],
                             capture_output=True, text=True)
    assert refused.returncode == 1
    assert refused.stderr.count("\n") == 1 and "bad.jsonl:1" in refused.stderr
    assert not (tmp_path / "none").exists()
