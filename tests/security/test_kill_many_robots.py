"""SIGKILL in the middle of twenty robots' traffic (issue 57's "during a 20-robot run").

Twenty robots, each with a NEEM of its own, post a situation and then an action as fast as they
are answered, all at once, against a real ``serve`` process; the process is killed while they
post. After each kill the store file must pass SQLite's check, and once the service is up again
every action any robot was answered 200 for must be in its NEEM: an answer means durable, whoever
shared the commit's fsync. Several rounds, each killing at another moment.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import sqlite3
import threading
import time
from pathlib import Path

import pytest

from oracle.benchmarks.security import Service, call, start, stop
from oracle.store.integrity import problems_of
from tests.service.conftest import AVAILABLE, ROUTINE, at

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")]
ROBOTS = 20
ROUNDS = 3


def robot(url: str, neem: str, first: int, acknowledged: list[str], stop_flag: threading.Event) -> None:
    """Post situation, action, situation, ... until the service is gone; keep each action's id
    the service answered 200 for."""
    step = first
    while not stop_flag.is_set():
        try:
            status, _, _ = call(url, f"/api/neems/{neem}/situation", {"available": AVAILABLE, "at": at(0, step)}, timeout=30)
            if status != 200:
                return
            status, answer, _ = call(url, f"/api/neems/{neem}/actions",
                                     {"call": ROUTINE[step % len(ROUTINE)], "begin": at(0, step)}, timeout=30)
        except OSError:  # the process is gone: whatever was not answered is not acknowledged
            return
        if status != 200:
            return
        acknowledged.append(str(answer["id"]))
        step += 1


def stored_actions(url: str, neem: str) -> set[str]:
    status, answer, _ = call(url, "/api/prolog", {"query": "findall(A, kb_call(is_action(A)), As)", "neem": neem})
    assert status == 200, answer
    return {str(a) for a in answer["solutions"][0]["As"]}


def test_no_acknowledged_action_is_lost_when_twenty_robots_are_killed(tmp_path: Path) -> None:
    store = tmp_path / "s.sqlite"
    neems = [f"robot{i}" for i in range(ROBOTS)]
    acknowledged: dict[str, list[str]] = {neem: [] for neem in neems}
    chance = random.Random(57)
    service: Service = start(store)
    for neem in neems:
        assert call(service.url, "/api/neems", {"user": neem, "neem": neem})[0] == 201
    for round_ in range(ROUNDS):
        stop_flag = threading.Event()
        threads = [threading.Thread(target=robot, args=(service.url, neem, 10_000 * round_ + 1, acknowledged[neem], stop_flag))
                   for neem in neems]
        before = sum(len(ids) for ids in acknowledged.values())
        for thread in threads:
            thread.start()
        deadline = time.monotonic() + 60  # on a busy machine the first answers come late
        while sum(len(ids) for ids in acknowledged.values()) < before + 2 * ROBOTS and time.monotonic() < deadline:
            time.sleep(0.05)
        time.sleep(chance.uniform(0.0, 1.5))  # kill at another moment each round, robots mid-request
        os.kill(service.process.pid, signal.SIGKILL)
        service.process.wait()
        stop_flag.set()
        for thread in threads:
            thread.join(timeout=60)
        assert sum(len(ids) for ids in acknowledged.values()) > before, "no robot was answered before the kill"
        with sqlite3.connect(store) as conn:
            assert problems_of(conn) == []
        service = start(store)
    try:
        lost = {neem: sorted(set(ids) - stored_actions(service.url, neem)) for neem, ids in acknowledged.items()}
        assert {neem: ids for neem, ids in lost.items() if ids} == {}
        for neem in neems:  # every NEEM still takes the next situation
            assert call(service.url, f"/api/neems/{neem}/situation", {"available": AVAILABLE, "at": at(1, 0)})[0] == 200
    finally:
        stop(service)
