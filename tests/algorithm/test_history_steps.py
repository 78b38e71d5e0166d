"""The steps of a history and what the user did in them, made in one pass (calls.history_steps,
what NeemRanker starts from): the same steps as ``steps_from_history`` and the same DoneBefore as
adding each step's option in order, as the ranker did before."""

from __future__ import annotations

import random

import pytest

from oracle.algorithm.records import Option
from oracle.calls import DoneBefore, history_steps, steps_from_history

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)", "close(fridge)"]


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


def _rows(seed: int, n: int) -> list[dict[str, object]]:
    rng = random.Random(seed)
    sets = [CALLS[:2], CALLS[1:4], CALLS]
    rows: list[dict[str, object]] = []
    t = 1_700_000_000.0
    for _ in range(n):
        t += rng.choice([1, 30, 4000])
        call = "idle" if rng.random() < 0.1 else rng.choice(CALLS)
        available = None if call == "idle" or rng.random() < 0.3 else rng.choice(sets)
        rows.append({"begin": t, "end": t + 1, "call": call, "part": rng.choice(["Morning", "none", None]),
                     "available": available, "mode": "user"})
    return rows


def test_one_pass_gives_the_steps_and_what_was_done_first_done_first(onto):
    for seed in range(4):
        rows = _rows(seed, 300)
        for clocked in (True, False):
            steps, done = history_steps(onto, rows, clocked)
            assert steps == steps_from_history(onto, rows, clocked)
            walked = DoneBefore()
            for step in steps:
                if not step.idle:
                    walked.add(Option(step.task, step.target, step.reference))
            assert list(done.done) == list(walked.done) and done.offer() == walked.offer()
            assert len(done.done) == len({r["call"] for r in rows if r["call"] != "idle"})
