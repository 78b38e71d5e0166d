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

from oracle.store import Store

LOG = logging.getLogger("oracle.service")


class GroupCommit:
    """The open group of one engine thread. ``join`` and the commit run on that thread only."""

    def __init__(self, store: Store, submit: Callable[[Callable[[], None]], Any], dropped: Callable[[], None]) -> None:
        """``submit`` queues a job on the engine thread; ``dropped`` forgets the live sessions
        (after a failed commit)."""
        self.store = store
        self._submit = submit
        self._dropped = dropped
        self._transaction: AbstractContextManager[None] | None = None
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
            transaction = self.store.transaction()
            transaction.__enter__()
            self._transaction, self._done, self._queued = transaction, Future(), False
            if linger is not None:
                self._timer = threading.Timer(linger, self._lingered)
                self._timer.daemon = True
                self._timer.start()
        if linger is None and not self._queued:
            self._queued = True
            self._submit(self._commit)
        self.joined += 1
        return self._done

    def pending(self) -> Future[None] | None:
        """The open group's future (None when no group is open); the job that asks answers only
        once it is committed, so a lingering group's commit is queued now."""
        if self._done is not None and not self._queued:
            self._queued = True
            self._submit(self._commit)
        return self._done

    def _lingered(self) -> None:
        """The linger passed (on the timer's thread): queue the commit of whatever group is open."""
        try:
            self._submit(self._commit)
        except RuntimeError:
            pass  # the engine thread has shut down, and committed as it closed (EngineThread.close)

    def commit(self) -> None:
        """Commit the open group now (nothing when none is open)."""
        self._commit()

    def _commit(self) -> None:
        transaction, done = self._transaction, self._done
        self._transaction = self._done = None
        self._queued = False
        if self._timer is not None:
            self._timer.cancel()  # committed now: nothing left to linger for
            self._timer = None
        if transaction is None or done is None:
            return
        try:
            transaction.__exit__(None, None, None)
        except BaseException as error:  # nothing of the group is on disk: none of it acknowledged
            LOG.error("group commit failed: %s", type(error).__name__)
            self._dropped()
            done.set_exception(error)
            return
        self.commits += 1
        done.set_result(None)
