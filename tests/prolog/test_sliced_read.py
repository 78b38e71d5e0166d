"""A whole history read in slices (oracle.slicedread) equals the one-call read
(``Bridge.history_view()``) row for row, whatever the slice size: on a NEEM with idle gaps,
instant actions (an idle action then begins with the action before it: equal begins), several
imaginings before an action, imaginings no action followed, and actions of user and robot."""

from __future__ import annotations

import random
from datetime import datetime, timedelta

import pytest

from oracle.bridge import Bridge
from oracle.errors import PrologError
from oracle.neem.writer import NeemLogger
from oracle.slicedread import SlicedRead, sliced_view
from oracle.store import open_store

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]


@pytest.fixture(scope="module")
def neem(tmp_path_factory, onto):
    store = open_store(tmp_path_factory.mktemp("sliced") / "h.sqlite")
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    rng = random.Random(11)
    t = datetime(2024, 1, 1, 5)
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, t)
    for i in range(150):
        t += timedelta(seconds=rng.choice([0, 1, 5, 30, 3600]))  # idle gaps, parts of day
        for _ in range(rng.choice([0, 1, 1, 2, 3])):  # no, one or several imaginings
            log.available(rng.sample(CALLS, rng.randint(1, len(CALLS))), t)
            t += timedelta(seconds=rng.choice([0, 1]))
        end = t + timedelta(seconds=rng.choice([0, 0, 2, 25]))  # instant actions
        log.action(rng.choice(CALLS), t, end, performed_by=rng.choice(["robot", "user"]))
        t = end
        if i % 40 == 39:  # a situation no action followed, then a gap
            log.available(CALLS[:2], t + timedelta(seconds=1))
            t += timedelta(seconds=60)
    log.available(CALLS[1:], t + timedelta(seconds=2))  # the latest situation, after the last action
    log.flush()
    bridge = Bridge(store, "r", onto)
    yield bridge
    bridge.close()
    store.close()


def test_the_neem_has_what_slices_could_split(neem):
    rows = neem.history()
    begins = [r["begin"] for r in rows]
    assert len(rows) > 150 and any(r["call"] == "idle" for r in rows)
    assert len(set(begins)) < len(begins)  # equal begins
    assert any(r["begin"] == r["end"] for r in rows)  # instant actions
    assert {r["mode"] for r in rows} >= {"robot", "user"}
    assert any(r["available"] is None for r in rows if r["call"] != "idle")


@pytest.mark.parametrize("size", [1, 2, 3, 17, 64, 2000])
def test_slices_joined_equal_the_one_call_read(neem, size):
    whole = neem.history_view()
    sliced = sliced_view(neem, size)
    assert sliced.rows == whole.rows
    assert sliced.latest == whole.latest and whole.latest is not None


def test_bounds_end_slices_of_about_size_actions_at_distinct_begins(neem):
    rows = neem.history()
    bounds = neem.history_bounds(20)
    distinct = len({r["begin"] for r in rows})  # equal begins count once
    assert bounds == sorted(set(bounds)) and distinct // 20 - 1 <= len(bounds) <= distinct // 20
    assert bounds[-1] < rows[-1]["begin"]  # the last slice reads to the end
    begins = [r["begin"] for r in rows]
    assert all(b in begins for b in bounds)


def test_step_by_step_reads_one_slice_a_step(neem):
    read = SlicedRead(25)
    read.start(neem)
    steps = read.slices_left
    assert steps >= 5
    read.step(neem)
    assert read.slices_left == steps - 1 and 25 <= len(read.rows) <= 40
    assert read.finish(neem).rows == neem.history()


def test_a_slice_needs_numbers(neem):
    with pytest.raises(PrologError):
        neem.history_slice(None, float("nan"))
    with pytest.raises(PrologError):
        neem.history_bounds(0)


def test_a_slice_is_the_rows_between_its_bounds(neem):
    bounds = neem.history_bounds(30)
    after, until = bounds[1], bounds[3]
    rows = neem.history_slice(after, until)
    assert rows and [r for r in neem.history() if after < r["begin"] <= until] == rows
