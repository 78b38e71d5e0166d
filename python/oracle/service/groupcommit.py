"""Group commit: the writes of every request that reaches the engine thread while a commit is
pending share that commit, and so one fsync. Each request is still acknowledged only
once its writes are committed.

A request's job ``join``s the open group first: the first to join opens the store's transaction
and queues the commit behind the jobs already waiting on the engine thread (the executor runs jobs
in order), so every request that arrived meanwhile joins it and none waits for a later one. A
job's own writes are a savepoint inside it (oracle.store.sqlite.connection): a request that fails
undoes its writes alone, and the others commit. The route awaits the group's future before it
answers. When the commit itself fails, every request of the group gets the error (none is
acknowledged) and the engine's sessions are dropped, to be read again from the store, since they
hold what was never committed.

A write nobody waits for (the ranking a situation writes back after its answer) joins with a
``linger``: when it opens the group, the commit is queued only after that many seconds, or as soon
as a request joins (the robot's next action, typically), so the two share one fsync instead of
paying one each.

The flush is off the engine thread: a group's transaction runs with synchronous=NORMAL
(``Store.unsynced``), so its COMMIT writes the WAL without waiting for the disk, and a thread of
its own (``Syncer``) then fsyncs the WAL (``Store.sync``) and only then resolves the group's
future; meanwhile the engine thread ranks the next request. One flush serves every group
committed while the previous flush ran. A job that ran while no group was open still answers only
after the flush in progress (``pending``): no answer shows a write that is not on disk yet.
Writes outside a group (no group open) commit with synchronous=FULL, flushed on the engine thread
as before.

On MongoDB a transaction groups nothing (each write is acknowledged as it is made, with the
write concern of the connection): a group there is only a pass through the engine thread.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from concurrent.futures import Future
from contextlib import AbstractContextManager
from typing import Any

from oracle.errors import StoreError
from oracle.store import Store

LOG = logging.getLogger("oracle.service")


class GroupCommit:
    """The open group of one engine thread. ``join`` and the commit run on that thread only."""

    def __init__(self, store: Store, submit: Callable[..., Any], dropped: Callable[[], None]) -> None:
        """``submit`` queues a job on the engine thread; ``dropped`` forgets the live sessions
        (after a failed commit)."""
        self.store = store
        self._submit = submit
        self._dropped = dropped
        self._transaction: AbstractContextManager[None] | None = None
        self._unsynced: AbstractContextManager[None] | None = None
        self._syncer = Syncer(store.sync)
        self._done: Future[None] | None = None
        self._queued = False  # whether the open group's commit is queued on the engine thread
        self._timer: threading.Timer | None = None  # a lingering group's
        #: How many commits and how many requests they carried (the bench prints them).
        self.commits = 0
        self.joined = 0

    def join(self, linger: float | None = None) -> Future[None]:
        """The group this job's writes commit with (opened, and its commit queued, if none is
        open). ``linger``: nobody waits for these writes; a group they open commits after that
        many seconds, or with the next request that joins it, whichever comes first."""
        if self._done is None:
            unsynced = self.store.unsynced()
            unsynced.__enter__()
            transaction = self.store.transaction()
            try:
                transaction.__enter__()
            except BaseException:
                unsynced.__exit__(None, None, None)
                raise
            self._unsynced, self._transaction, self._done, self._queued = unsynced, transaction, Future(), False
            if linger is not None:
                self._timer = threading.Timer(linger, self._lingered, (self._done,))
                self._timer.daemon = True
                self._timer.start()
        if linger is None and not self._queued:
            self._queued = True
            self._submit(self._commit, self._done)
        self.joined += 1
        return self._done

    def pending(self) -> Future[None] | None:
        """The open group's future, else the flush in progress (None when neither): the job that
        asks answers only once it is committed and on disk, so a lingering group's commit is
        queued now."""
        if self._done is not None and not self._queued:
            self._queued = True
            self._submit(self._commit, self._done)
        return self._done if self._done is not None else self._syncer.latest()

    def _lingered(self, group: Future[None]) -> None:
        """The linger passed (on the timer's thread): queue the commit of ``group`` if still open."""
        try:
            self._submit(self._commit, group)
        except RuntimeError:
            pass  # the engine thread has shut down, and committed as it closed (EngineThread.close)

    def commit(self) -> None:
        """Commit the open group now (nothing when none is open)."""
        self._commit()

    def _commit(self, group: Future[None] | None = None) -> None:
        """Commit the open group (``group``: only if it is still the one open; a job may have
        committed it early, ``commit``, and a later one opened since must keep its own turn)."""
        if group is not None and group is not self._done:
            return
        transaction, done, unsynced = self._transaction, self._done, self._unsynced
        self._transaction = self._done = self._unsynced = None
        self._queued = False
        if self._timer is not None:
            self._timer.cancel()  # committed now: nothing left to linger for
            self._timer = None
        if transaction is None or done is None:
            return
        try:
            try:
                transaction.__exit__(None, None, None)
            finally:
                if unsynced is not None:
                    unsynced.__exit__(None, None, None)
        except BaseException as error:  # nothing of the group is on disk: none of it acknowledged
            LOG.error("group commit failed: %s", type(error).__name__)
            self._dropped()
            done.set_exception(error)
            return
        self.commits += 1
        self._syncer.after(done)  # answered once the flush is done, on the syncer's thread

    def close(self) -> None:
        """Stop the flushing thread once the flushes asked for are done (the engine thread's
        ``close``)."""
        self._syncer.close()


class Syncer:
    """The thread that flushes committed groups to disk: ``after(done)`` resolves ``done`` once a
    ``sync`` begun after the call returned; every future queued while a flush runs shares the
    next one."""

    def __init__(self, sync: Callable[[], None]) -> None:
        self._sync = sync
        self._ready = threading.Condition()
        self._waiting: list[Future[None]] = []
        self._latest: Future[None] | None = None
        self._closed = False
        self._thread: threading.Thread | None = None
        #: How many flushes ran (the bench and the tests read it).
        self.flushes = 0

    def after(self, done: Future[None]) -> None:
        with self._ready:
            if self._thread is None:  # started on first use: a store nobody writes needs none
                self._thread = threading.Thread(target=self._run, name="oracle-sync", daemon=True)
                self._thread.start()
            self._waiting.append(done)
            self._latest = done
            self._ready.notify()

    def latest(self) -> Future[None] | None:
        """The future of the last group handed over, while its flush is not done."""
        latest = self._latest
        return None if latest is None or latest.done() else latest

    def close(self) -> None:
        """Wait for the flushes asked for and end the thread (the next ``after`` starts another)."""
        with self._ready:
            self._closed = True
            self._ready.notify()
            thread = self._thread
        if thread is not None:
            thread.join()
        with self._ready:
            self._closed = False

    def _run(self) -> None:
        while True:
            with self._ready:
                while not self._waiting and not self._closed:
                    self._ready.wait()
                if not self._waiting:  # closed, and nothing left to flush
                    self._thread = None
                    return
                batch, self._waiting = self._waiting, []
            try:
                self._sync()
            except BaseException as error:  # committed but maybe not on disk: none acknowledged
                LOG.error("flushing the group commit failed: %s", type(error).__name__)
                failed = StoreError(f"the store's commit was not flushed to disk: {type(error).__name__}: {error}")
                for done in batch:
                    done.set_exception(failed)
                continue
            self.flushes += 1
            for done in batch:
                done.set_result(None)
