"""A NEEM logged by the real logger, and bridges over SQLite and mongomock-ng."""

from __future__ import annotations

from datetime import datetime

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.ontology import build_ontology
from oracle.store import open_store


@pytest.fixture(scope="session")
def onto():
    return build_ontology()


def log_episode(store, onto, neem_id: str = "alice") -> NeemLogger:
    """Two decisions: at 08:00 pour is preferred over pick(apple) and chosen; at 12:00 only
    pick(apple) is available and done. A banana is perceived only at 13:00."""
    log = NeemLogger.create(store, onto, user="alice", neem_id=neem_id)
    t = lambda h, m=0: datetime(2024, 5, 1, h, m)  # noqa: E731
    for obj in ("apple", "thermos", "green_mug"):
        log.perceive(obj, t(7, 59))
    log.available(["pick(apple)", "pour(thermos, green_mug)"], t(8))
    log.preference([("pour(thermos, green_mug)", 0.2), ("pick(apple)", 0.7)], t(8))
    log.action("pour(thermos, green_mug)", t(8, 1), t(8, 3))
    log.available(["pick(apple)"], t(12))
    log.preference([("pick(apple)", 0.1), ("pour(thermos, green_mug)", 0.9)], t(12))
    log.action("pick(apple)", t(12, 1), t(12, 2))
    log.perceive("banana", t(13))
    log.flush()
    return log


@pytest.fixture()
def sqlite_bridge(tmp_path, onto):
    store = open_store(tmp_path / "neems.sqlite")
    log_episode(store, onto)
    bridge = Bridge(store, "alice", onto)
    yield bridge
    bridge.close()
    store.close()
