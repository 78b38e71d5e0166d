"""A small NEEM whose answers were checked by hand (tests/past/test_ask.py names them)."""

from __future__ import annotations

import shutil
from datetime import datetime

import pytest

from oracle.neem.tf import Pose
from oracle.neem.writer import NeemLogger
from oracle.ontology import build_ontology
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

BREAKFAST = ["open(fridge)", "pick(milk_carton)", "pour(milk_carton, cereal_bowl)"]


def t(day: int, hour: int, minute: int = 0, second: int = 0) -> datetime:
    """Monday 2025-03-03 is day 0 (times without a zone: UTC)."""
    return datetime(2025, 3, 3 + day, hour, minute, second)


def log_small_neem(store, onto, neem_id: str = "small") -> None:
    """Monday: breakfast at 07:00 (three steps, 15 s apart), an apple at 12:00. Tuesday:
    breakfast at 07:05; the green mug perceived at 08:00 at (0.4, 1.2, 0.9); at 08:01 the
    robot offers pick(green_mug) first and open(fridge) second; the user picks the mug at
    08:01:10 and places it on the kitchen table at 08:01:30 (the NEEM's latest event)."""
    log = NeemLogger.create(store, onto, user="sam", neem_id=neem_id)
    for day, minute in ((0, 0), (1, 5)):
        for index, call in enumerate(BREAKFAST):
            log.action(call, t(day, 7, minute, 15 * index), t(day, 7, minute, 15 * index + 10))
        if day == 0:
            log.action("open(fridge)", t(0, 12, 0, 0), t(0, 12, 0, 10))
            log.action("pick(apple)", t(0, 12, 0, 15), t(0, 12, 0, 25))
            log.action("eat(apple)", t(0, 12, 0, 30), t(0, 12, 0, 40))
    log.perceive("green_mug", t(1, 8), Pose((0.4, 1.2, 0.9)))
    log.available(["pick(green_mug)", "open(fridge)"], t(1, 8, 1))
    log.preference([("pick(green_mug)", 0.1), ("open(fridge)", 0.5)], t(1, 8, 1))
    log.action("pick(green_mug)", t(1, 8, 1, 10), t(1, 8, 1, 20))
    log.action("place(green_mug, kitchen_table)", t(1, 8, 1, 30), t(1, 8, 1, 40))
    log.close()


@pytest.fixture(scope="session")
def onto():
    return build_ontology()


@pytest.fixture(scope="session")
def small_store(tmp_path_factory, onto):
    path = tmp_path_factory.mktemp("past") / "small.sqlite"
    store = open_store(path)
    log_small_neem(store, onto)
    store.close()
    return path


@pytest.fixture()
def bridge(small_store, onto):
    from oracle.bridge import Bridge

    store = open_store(small_store, create=False)
    bridge = Bridge(store, "small", onto)
    yield bridge
    bridge.close()
    store.close()
