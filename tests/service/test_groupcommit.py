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

    @contextmanager
    def unsynced(self):
        yield

    def sync(self):
        raise AssertionError("a failed commit is not flushed")


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


def _gated_group(tmp_path, onto, engine_thread, fail: bool = False):
    """A group commit over a real store whose flush (``Store.sync``) waits for ``gate``; the
    names of the threads that flushed are in ``flushed``."""
    import threading

    path = tmp_path / "s.sqlite"
    store = engine_thread.submit(open_store, path).result()
    logger = engine_thread.submit(lambda: NeemLogger.create(store, onto, user="ann", commit_every=10**9)).result()
    gate, flushed, real = threading.Event(), [], store.sync

    def sync():
        gate.wait(10)
        flushed.append(threading.current_thread().name)
        if fail:
            raise OSError("I/O error")
        real()

    store.sync = sync
    group = GroupCommit(store, engine_thread.submit, lambda: None)

    def write(minute: int):
        done = group.join()
        logger.action("pick(apple)", datetime(2024, 5, 1, 8, minute))
        logger.flush()
        return done

    return path, store, logger, group, gate, flushed, write


def _synchronous(engine_thread, store) -> int:
    return engine_thread.submit(lambda: store._conn.execute("PRAGMA synchronous").fetchone()[0]).result()


def test_a_group_is_flushed_off_the_engine_thread_and_answered_after(tmp_path, onto, engine_thread):
    """The group's COMMIT does not wait for the disk (synchronous=NORMAL inside the group only):
    the engine thread runs the next job while another thread fsyncs, and the group's future (what
    its answers wait for) resolves only after that flush; a job that runs meanwhile waits for it too."""
    path, store, logger, group, gate, flushed, write = _gated_group(tmp_path, onto, engine_thread)
    assert _synchronous(engine_thread, store) == 2  # FULL outside a group
    before = _count(path, logger.writes_to)
    done = engine_thread.submit(write, 1).result()
    assert engine_thread.submit(lambda: "next job").result(timeout=10) == "next job"  # the commit ran, then this
    assert _count(path, logger.writes_to) > before  # committed (another connection sees it) ...
    assert not done.done() and flushed == []  # ... but not acknowledged: the flush waits
    assert engine_thread.submit(group.pending).result() is done  # a job run now answers after it too
    assert _synchronous(engine_thread, store) == 2  # FULL again once the group committed
    gate.set()
    done.result(timeout=10)
    assert flushed == ["oracle-sync"] and group.commits == 1
    assert engine_thread.submit(group.pending).result() is None
    group.close()
    engine_thread.submit(store.close).result()


def test_groups_committed_during_a_flush_share_the_next(tmp_path, onto, engine_thread):
    _, store, _, group, gate, flushed, write = _gated_group(tmp_path, onto, engine_thread)
    futures = []
    for minute in (1, 2, 3):  # three groups, one after the other (each committed before the next)
        futures.append(engine_thread.submit(write, minute).result())
        engine_thread.submit(lambda: None).result()
    assert group.commits == 3 and not any(f.done() for f in futures)
    gate.set()
    for done in futures:
        done.result(timeout=10)
    assert len(flushed) == 2  # the first group's flush, then one for the two committed meanwhile
    group.close()
    engine_thread.submit(store.close).result()


def test_a_failed_flush_acknowledges_none_of_its_groups(tmp_path, onto, engine_thread):
    from oracle.errors import StoreError

    _, store, _, group, gate, _, write = _gated_group(tmp_path, onto, engine_thread, fail=True)
    done = engine_thread.submit(write, 1).result()
    gate.set()
    with pytest.raises(StoreError, match="not flushed"):
        done.result(timeout=10)
    group.close()
    engine_thread.submit(store.close).result()


def test_a_situation_alone_is_committed_before_it_is_ranked(client, ctx):
    """With no other request waiting, a situation's imagining is committed before the ranking
    starts, so the disk flushes while the engine ranks; the answer still comes after the flush."""
    from tests.service.conftest import AVAILABLE, at

    neem = client.post("/api/neems", json={"user": "ann"}).json()["id"]
    session = ctx.thread.call(ctx.engine.session, neem)
    group, seen = ctx.thread.group, []
    rank = session.rank

    def ranked(found):
        seen.append(group.commits)
        return rank(found)

    session.rank = ranked
    before = group.commits
    answer = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(0, 0)})
    assert answer.status_code == 200 and answer.json()["ranking"]
    assert seen == [before + 1]  # committed when the ranking began
