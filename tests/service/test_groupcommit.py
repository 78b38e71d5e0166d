"""Group commit (oracle.service.groupcommit): the requests that reach the engine thread while a
commit is pending share it; a request that fails undoes only its own writes; a commit that fails
acknowledges none of its group and drops the live sessions; through the HTTP API an action is
answered only once it is committed."""

from __future__ import annotations

import sqlite3
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from datetime import datetime

import pytest

from oracle.neem.writer import NeemLogger
from oracle.service.groupcommit import GroupCommit
from oracle.store import open_store


def _count(path, neem: str) -> int:
    """Committed actions of a NEEM, as another connection sees them."""
    conn = sqlite3.connect(path)
    try:
        tables = [name for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")
                  if name.startswith(neem) and name.endswith("_triples")]
        return sum(conn.execute(f'SELECT count(*) FROM "{name}"').fetchone()[0] for name in tables)
    finally:
        conn.close()


@pytest.fixture()
def engine_thread():
    pool = ThreadPoolExecutor(max_workers=1)
    yield pool
    pool.shutdown()


def test_requests_waiting_share_one_commit(tmp_path, onto, engine_thread):
    path = tmp_path / "s.sqlite"
    store = engine_thread.submit(open_store, path).result()
    logger = engine_thread.submit(lambda: NeemLogger.create(store, onto, user="ann", commit_every=10**9)).result()
    before = _count(path, logger.writes_to)
    group = GroupCommit(store, engine_thread.submit, lambda: None)
    gate = engine_thread.submit(lambda: None)

    def request(minute: int):
        done = group.join()
        logger.action("pick(apple)", datetime(2024, 5, 1, 8, minute))
        logger.flush()
        return done

    # three requests queued at once: the first opens the group and queues its commit behind
    # the other two, which join it
    gate.result()
    futures = [engine_thread.submit(request, m) for m in (1, 2, 3)]
    groups = [f.result() for f in futures]
    for done in groups:
        done.result(timeout=10)
    assert group.commits == 1 and group.joined == 3 and len({id(g) for g in groups}) == 1
    assert _count(path, logger.writes_to) > before
    engine_thread.submit(store.close).result()


def test_a_failing_request_undoes_its_own_writes_only(tmp_path, onto, engine_thread):
    path = tmp_path / "s.sqlite"
    store = engine_thread.submit(open_store, path).result()
    good = engine_thread.submit(lambda: NeemLogger.create(store, onto, user="ann", commit_every=10**9)).result()
    group = GroupCommit(store, engine_thread.submit, lambda: None)

    def both():
        done = group.join()
        good.action("pick(apple)", datetime(2024, 5, 1, 8, 1))
        good.flush()
        with pytest.raises(RuntimeError):
            with store.transaction():  # a request's writes, then its failure
                good.store.insert(good.writes_to, [(f"{onto.namespace}Stray", f"{onto.namespace}p", "x", "user", 0.0,
                                                    float("inf"))])
                raise RuntimeError("refused mid-way")
        return done

    engine_thread.submit(both).result().result(timeout=10)
    found = engine_thread.submit(lambda: list(store.find(good.writes_to, s=f"{onto.namespace}Stray"))).result()
    assert found == []  # the failed request's triple is gone
    assert engine_thread.submit(lambda: good.store.neem(good.writes_to)).result() is not None
    assert _count(path, good.writes_to) > 0  # the other request's action is committed
    engine_thread.submit(store.close).result()


class _FailingCommit:
    """A store whose commit fails (a full disk)."""

    @contextmanager
    def transaction(self):
        yield
        raise OSError("disk full")


def test_a_failed_commit_acknowledges_none_and_drops_the_sessions(engine_thread):
    dropped = []
    group = GroupCommit(_FailingCommit(), engine_thread.submit, lambda: dropped.append(True))  # type: ignore[arg-type]
    first, second = engine_thread.submit(lambda: (group.join(), group.join())).result()  # two requests, one turn
    with pytest.raises(OSError):
        first.result(timeout=10)
    assert first is second and dropped == [True] and group.commits == 0
    assert group.pending() is None  # the next request opens a new group


def test_the_ranking_written_back_commits_with_a_group_not_alone(client, ctx):
    """The ranking a situation writes back after its answer joins the open group commit: a
    step of the robot (situation, then action) commits at most twice, and every preference is
    in the store once the service is idle."""
    from tests.service.conftest import AVAILABLE, ROUTINE, at

    neem = client.post("/api/neems", json={"user": "ann"}).json()["id"]
    group = ctx.thread.group
    before = group.commits
    for i, call in enumerate(ROUTINE):
        assert client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(0, 10 * i)}).status_code == 200
        assert client.post(f"/api/neems/{neem}/actions", json={"call": call, "begin": at(0, 10 * i),
                                                                "end": at(0, 10 * i + 5)}).status_code == 200
    ctx.thread.close()  # the queued write-backs done, and their group committed
    assert group.pending() is None
    steps = len(ROUTINE)
    # without the write-back in a group: 3 commits a step (situation, its ranking, action)
    assert group.commits - before <= 2 * steps
    preferences = ctx.thread.call(lambda: ctx.engine.store.neem(neem))
    assert preferences is not None


def test_a_lingering_group_commits_by_itself_or_with_the_next_request(tmp_path, onto, engine_thread):
    """A write nobody waits for (``join(linger=...)``) opens a group whose commit waits for the
    next request (one commit for both) or, when none comes, for the linger to pass."""
    import time

    path = tmp_path / "s.sqlite"
    store = engine_thread.submit(open_store, path).result()
    logger = engine_thread.submit(lambda: NeemLogger.create(store, onto, user="ann", commit_every=10**9)).result()
    group = GroupCommit(store, engine_thread.submit, lambda: None)

    def write(minute: int, linger: float | None):
        done = group.join(linger)
        logger.action("pick(apple)", datetime(2024, 5, 1, 8, minute))
        logger.flush()
        return done

    alone = engine_thread.submit(write, 1, 0.05).result()
    assert not alone.done()  # lingering: not committed yet
    alone.result(timeout=10)  # ... until the linger passed
    assert group.commits == 1
    lingering = engine_thread.submit(write, 2, 30.0).result()
    shared = engine_thread.submit(write, 3, None).result()  # the next request: one commit for both
    assert shared is lingering
    shared.result(timeout=10)
    assert group.commits == 2
    before = _count(path, logger.writes_to)
    engine_thread.submit(write, 4, 30.0).result()
    assert engine_thread.submit(group.pending).result() is not None  # a job that asks: commit queued
    time.sleep(0.2)
    assert group.commits == 3 and _count(path, logger.writes_to) > before
    engine_thread.submit(store.close).result()
