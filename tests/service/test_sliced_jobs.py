"""/explore's first read of a NEEM nothing kept, one slice per engine-thread job
(oracle.service.sliced_jobs): each slice is its own job, so a job queued meanwhile runs between
two slices; the view equals the one-call read, and a NEEM that grows between slices is read again."""

from __future__ import annotations

import asyncio
import random
from collections.abc import Callable
from datetime import datetime, timedelta
from types import SimpleNamespace
from typing import Any

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.service.sliced_jobs import view_in_jobs
from oracle.store import open_store
from tests.prolog.test_historycache import _log_some

CALLS = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]


class Thread:
    """The engine thread's ``run`` in order, each job counted; ``between`` runs after the
    ``at``-th job (another request's job queued meanwhile)."""

    def __init__(self, at: int = -1, between: Callable[[], None] | None = None) -> None:
        self.jobs = 0
        self.at, self.between = at, between

    async def run(self, fn: Callable[..., Any], *args: Any) -> Any:
        result = fn(*args)
        self.jobs += 1
        if self.jobs == self.at and self.between is not None:
            self.between()
        return result


def _log(log: NeemLogger, rng: random.Random, t: datetime, n: int) -> datetime:
    """Equal begins (a gap of 0) and instant actions among the rest."""
    return _log_some(log, rng, t, n, durations=(0, 2, 25), gaps=(0, 1, 30, 3600))


@pytest.fixture()
def neem(tmp_path, onto):
    store = open_store(tmp_path / "h.sqlite")
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, datetime(2024, 1, 1, 5))
    rng = random.Random(5)
    t = _log(log, rng, datetime(2024, 1, 1, 5), 90)
    bridge = Bridge(store, "r", onto)
    yield SimpleNamespace(store=store, bridge=lambda neem: bridge, id=bridge.neem_id), log, rng, t
    bridge.close()
    store.close()


def test_each_slice_is_its_own_job_and_the_view_is_the_whole_read(neem):
    engine, _, _, _ = neem
    bridge = engine.bridge("r")
    thread = Thread()
    view = asyncio.run(view_in_jobs(thread, engine, engine.id, size=10))  # type: ignore[arg-type]
    whole = bridge.history_view()
    assert view.rows == whole.rows and view.latest == whole.latest
    slices = len(bridge.history_bounds(10))
    assert slices >= 8 and thread.jobs == slices + 2  # the bounds, each slice, the last one with the cache


def test_a_neem_grown_between_slices_is_read_again(neem):
    engine, log, rng, t = neem
    thread = Thread(at=3, between=lambda: _log(log, rng, t, 2))  # a robot logs between two slices
    view = asyncio.run(view_in_jobs(thread, engine, engine.id, size=10))  # type: ignore[arg-type]
    whole = engine.bridge("r").history_view()
    assert view.rows == whole.rows and view.latest == whole.latest
    assert thread.jobs > 2 * (len(engine.bridge("r").history_bounds(10)) + 1)  # begun again



def test_a_session_opens_with_its_history_read_a_slice_a_job(tmp_path, onto):
    from oracle.algorithm.params import Hyperparameters
    from oracle.service.engine import Engine
    from oracle.service.sliced_jobs import open_session

    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="r", neem_id="r")
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, datetime(2024, 1, 1, 5))
    _log(log, random.Random(7), datetime(2024, 1, 1, 5), 60)
    log.flush()
    engine = Engine(store, onto, Hyperparameters())
    given: list[Any] = []
    opened = engine.session
    engine.session = lambda name, view=None: given.append(view) or opened(name, view)  # type: ignore[method-assign]
    try:
        whole = engine.bridge("r").history_view()
        ran: list[str] = []
        thread = Thread(at=2, between=lambda: ran.append("robot"))  # another robot's job between two slices
        asyncio.run(open_session(thread, engine, "r", size=10))  # type: ignore[arg-type]
        slices = len(engine.bridge("r").history_bounds(10))
        assert slices >= 5 and ran == ["robot"]
        assert thread.jobs == slices + 4  # which NEEM, the bounds, each slice, the last one, the open
        assert log.neem_id in engine.sessions and given[0].rows == whole.rows and given[0].latest == whole.latest
        asyncio.run(open_session(thread, engine, log.neem_id, size=10))  # type: ignore[arg-type]
        assert thread.jobs == slices + 4 and len(given) == 1  # open: no job
        asyncio.run(open_session(thread, engine, "r", size=10))  # type: ignore[arg-type]
        assert thread.jobs == slices + 5 and len(given) == 1  # open under its name: one job to say so
        asyncio.run(open_session(thread, engine, "no such NEEM", size=10))  # type: ignore[arg-type]
        assert thread.jobs == slices + 6 and len(given) == 1  # the request's own job answers 404
    finally:
        engine.close()
        store.close()
