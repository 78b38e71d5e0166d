"""The explorer's own reader: a thread with a read-only connection to the store, so the page's
first paint never queues on the engine thread.

The engine thread serves the robot's calls, the routines and every read through Prolog one at a
time; a page opened while another page's routines (0.7 s at 10,000 actions) or a NEEM's first read
(6-10 s) hold it waited for all of that before its timeline could be sent. What the first paint
needs is only the view the store keeps (oracle.historycache: kept beside the NEEM by ``import``
and by every read since): this reader sends it when it is at the store's mark now, and says
``None`` otherwise (nothing kept, kept behind the mark, a temporary NEEM, a store that cannot tell
such as MongoDB), and the caller then reads through the engine as before.

What it read is kept in memory by NEEM and the store's mark (``KeptTimeline``: the parsed history,
the answer's bytes, the rows the replay takes): an open of a NEEM unchanged since, and each poll a
page makes while the replay runs, costs a mark and a name looked up, not 10,000 rows parsed again.

Only a SQLite store is opened here (read-only, at its first use): a second connection to a server
would only double the sessions for nothing, since a server's store keeps no view.
"""

from __future__ import annotations

import json
import threading
from collections import OrderedDict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from oracle.bridge.records import HistoryRow, history_rows

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store


def _is_file_store(location: str) -> bool:
    return "://" not in location or location.startswith("sqlite://")


@dataclass
class KeptTimeline:
    """A NEEM's kept history as read at ``mark``: the timeline route's answer and the replay's rows."""

    mark: Any
    neem: str
    user: str
    history: dict[str, Any]
    _body: list[bytes] = field(default_factory=list)
    _rows: list[list[HistoryRow]] = field(default_factory=list)

    def body(self) -> bytes:
        """The timeline route's answer (written once)."""
        if not self._body:
            self._body.append(json.dumps({"neem": self.neem, "user": self.user, **self.history}, separators=(",", ":")).encode())
        return self._body[0]

    def rows(self) -> list[HistoryRow]:
        """The history as rows (made once; the replay and its key read them)."""
        if not self._rows:
            self._rows.append(history_rows(self.history))
        return self._rows[0]


#: NEEMs whose timeline is kept in memory at once (each a few MB at 10,000 actions)
KEPT_TIMELINES = 4


@dataclass
class ExploreReader:
    """One thread, one read-only store of ``location`` (opened on first use)."""

    location: str
    ontology: OdbOntology | None
    pool: ThreadPoolExecutor = field(default_factory=lambda: ThreadPoolExecutor(1, thread_name_prefix="explore-read"))
    _store: list[Store] = field(default_factory=list)
    _lock: threading.Lock = field(default_factory=threading.Lock)
    #: by NEEM id, the latest read last (used on the reader's thread only)
    timelines: OrderedDict[str, KeptTimeline] = field(default_factory=OrderedDict)

    async def run(self, job: Any, *args: Any) -> Any:
        """``job(store, *args)`` on the reader's thread; None when there is no store to read."""
        import asyncio

        if not _is_file_store(self.location):
            return None
        return await asyncio.wrap_future(self.pool.submit(self._call, job, *args))

    def _call(self, job: Any, *args: Any) -> Any:
        store = self._opened()
        return None if store is None else job(store, *args)

    def _opened(self) -> Store | None:
        with self._lock:
            if not self._store:
                from oracle.errors import NeemOracleError
                from oracle.store import open_store

                try:
                    self._store.append(open_store(self.location, create=False, read_only=True))
                except NeemOracleError:
                    return None  # no file yet, or one this reader cannot open: the engine reads
            return self._store[0]

    def close(self) -> None:
        self.pool.shutdown(wait=True, cancel_futures=True)  # a read under way ends before its connection closes
        with self._lock:
            for store in self._store:
                store.close()
            self._store.clear()

    def kept_timeline(self, store: Store, neem: str) -> KeptTimeline | None:
        """The NEEM's history as the store keeps it at its mark now, from memory when it was read
        at that mark; None when the store keeps none at its mark (the engine then reads it)."""
        from oracle.historycache import kept_history
        from oracle.store.ids import find_neem

        info = find_neem(store, neem)
        if info is None or info.temporary:
            return None
        mark = store.append_mark(info.id)
        known = self.timelines.get(info.id)
        if mark is not None and known is not None and known.mark == mark:
            self.timelines.move_to_end(info.id)
            return known
        history = kept_history(store, self.ontology, info.id)
        if history is None or mark is None:
            return None
        # kept_history checked the entry against the mark it read; marks only grow, so an entry
        # newer than ``mark`` is only ever found again under a newer mark and read once more
        kept = self.timelines[info.id] = KeptTimeline(mark, info.id, info.user or info.id, history)
        while len(self.timelines) > KEPT_TIMELINES:
            self.timelines.popitem(last=False)
        return kept


def newest(store: Store) -> str | None:
    """The newest NEEM of the store (the engine's rule, engine.Engine.newest)."""
    infos = store.neems()
    return max(infos, key=lambda info: (info.created_at or "", info.id)).id if infos else None


__all__ = ["ExploreReader", "KeptTimeline", "newest"]
