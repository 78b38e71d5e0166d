"""The engine thread's low-priority lane (EngineThread.submit_idle): work nobody waits for (the
warm-up after an action) yields to the requests queued when its turn comes, and still runs."""

from __future__ import annotations

import threading
import time

from oracle.service.engine import EngineThread


def _blocked(thread: EngineThread) -> threading.Event:
    """The engine thread held by a job until the event is set."""
    gate, running = threading.Event(), threading.Event()

    def hold() -> None:
        running.set()
        gate.wait(10)

    thread.submit(hold)
    assert running.wait(10)
    return gate


def test_idle_work_runs_after_a_request_queued_behind_it():
    thread, order = EngineThread(), []
    gate = _blocked(thread)
    thread.submit_idle(lambda: order.append("warm-up"))
    thread.submit(lambda: order.append("situation"))  # queued after the warm-up ...
    gate.set()
    thread.call(lambda: None)
    deadline = time.monotonic() + 10
    while len(order) < 2 and time.monotonic() < deadline:
        time.sleep(0.01)
    assert order == ["situation", "warm-up"]  # ... yet it ran first


def test_idle_work_runs_at_once_when_nothing_waits():
    thread, ran = EngineThread(), threading.Event()
    thread.submit_idle(ran.set)
    assert ran.wait(10)


def test_idle_work_yields_for_a_bounded_time_only():
    """Requests that keep coming delay the idle work by at most ``within`` seconds."""
    thread, ran, stop = EngineThread(), threading.Event(), threading.Event()

    def busy() -> None:  # one request always waiting behind the running one
        time.sleep(0.005)
        if not stop.is_set():
            thread.submit(busy)

    thread.submit(busy)
    thread.submit(busy)
    started = time.monotonic()
    thread.submit_idle(ran.set, within=0.2)
    try:
        assert ran.wait(10)
        assert time.monotonic() - started < 5
    finally:
        stop.set()
        thread.call(lambda: None)


def test_idle_work_does_not_yield_to_idle_work():
    """Two pieces of idle work queued with nothing else waiting both run at once (each yielding
    to the other would spin the thread until their deadline)."""
    thread, ran = EngineThread(), []
    gate = _blocked(thread)
    thread.submit_idle(lambda: ran.append(time.monotonic()), within=5.0)
    thread.submit_idle(lambda: ran.append(time.monotonic()), within=5.0)
    released = time.monotonic()
    gate.set()
    deadline = released + 10
    while len(ran) < 2 and time.monotonic() < deadline:
        time.sleep(0.01)
    assert len(ran) == 2 and max(ran) - released < 2.0
    assert not thread.busy()
