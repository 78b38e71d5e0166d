"""The one-pass history read (odb_history:situation_history/1) returns exactly the rows of the
first implementation (prolog/fixtures/history_reference.pl) on a NEEM logged by the real logger."""

from __future__ import annotations

import os
import random
from datetime import datetime, timedelta

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.paths import prolog_dir
from oracle.store import MONGO_ENV, open_store

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]


def log_random_neem(store, onto, n_actions: int, seed: int) -> None:
    rng = random.Random(seed)
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    t = datetime(2024, 1, 1, 5)
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, t)
    for _ in range(n_actions):
        t += timedelta(seconds=rng.choice([1, 5, 30, 3600]))  # some gaps change the part of day
        for _ in range(rng.choice([0, 1, 1, 2])):  # no, one or two imaginings before an action
            log.available(rng.sample(CALLS, rng.randint(1, len(CALLS))), t)
            t += timedelta(seconds=rng.choice([0, 1]))
        end = t + timedelta(seconds=rng.choice([0, 2, 25]))
        log.action(rng.choice(CALLS), t, end)
        t = end
    log.flush()


def _sqlite(tmp_path):
    return open_store(tmp_path / "h.sqlite")


def _real_mongo(_):
    # Not mongomock-ng: it runs the history's joined pipeline in pure Python, about a minute for
    # three actions; the compiled pipeline itself is pinned on mongomock-ng by
    # test_compiled_vs_stepwise.
    uri = os.environ.get(MONGO_ENV)
    if not uri:
        pytest.skip("no MongoDB server at NEEM_MONGO_URI")
    store = open_store(uri)
    if store.has_neem("r"):
        store.drop_neem("r")
    return store


@pytest.mark.parametrize("make_store, actions", [(_sqlite, 300), (_real_mongo, 300)], ids=["sqlite", "mongodb"])
def test_one_pass_history_equals_reference(tmp_path, onto, make_store, actions):
    store = make_store(tmp_path)
    log_random_neem(store, onto, actions, seed=7)
    bridge = Bridge(store, "r", onto)
    try:
        fixture = prolog_dir() / "fixtures" / "history_reference.pl"
        rows = bridge.query(
            f"use_module('{fixture}'), odb_history:situation_history(New),"
            " history_reference:situation_history_reference(Old), length(New, N),"
            " aggregate_all(count, member(situation(_, _, _, _, none), New), Nones),"
            " ( New == Old -> Same = true ; Same = false )"
        )
        assert rows[0]["Same"] == "true"
        assert rows[0]["N"] >= actions
        assert 0 < rows[0]["Nones"] < rows[0]["N"]  # both branches of the availability rule ran
    finally:
        bridge.close()
        store.close()
