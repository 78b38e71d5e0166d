"""The explorer's own reader: a thread with a read-only connection to the store, so the page's
first paint never queues on the engine thread.

The engine thread serves the robot's calls, the routines and every read through Prolog one at a
time; a page opened while another page's routines (0.7 s at 10,000 actions) or a NEEM's first read
(6-10 s) hold it waited for all of that before its timeline could be sent. What the first paint
needs is only the view the store keeps (oracle.historycache: kept beside the NEEM by ``import``
and by every read since): this reader sends it when it is at the store's mark now, and says
``None`` otherwise (nothing kept, kept behind the mark, a temporary NEEM, a store that cannot tell
such as MongoDB), and the caller then reads through the engine as before.

Only a SQLite store is opened here (read-only, at its first use): a second connection to a server
would only double the sessions for nothing, since a server's store keeps no view.
"""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from oracle.ontology import OdbOntology
    from oracle.store import Store


def _is_file_store(location: str) -> bool:
    return "://" not in location or location.startswith("sqlite://")


@dataclass
class ExploreReader:
    """One thread, one read-only store of ``location`` (opened on first use)."""

    location: str
    ontology: OdbOntology | None
    pool: ThreadPoolExecutor = field(default_factory=lambda: ThreadPoolExecutor(1, thread_name_prefix="explore-read"))
    _store: list[Store] = field(default_factory=list)
    _lock: threading.Lock = field(default_factory=threading.Lock)

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
        self.pool.shutdown(wait=False, cancel_futures=True)
        with self._lock:
            for store in self._store:
                store.close()
            self._store.clear()


def newest(store: Store) -> str | None:
    """The newest NEEM of the store (the engine's rule, engine.Engine.newest)."""
    infos = store.neems()
    return max(infos, key=lambda info: (info.created_at or "", info.id)).id if infos else None


def kept_timeline(store: Store, ontology: OdbOntology | None, neem: str) -> tuple[str, str, dict[str, Any]] | None:
    """The NEEM's id, user and its history in ``historycache.compact``'s shape, as the store
    keeps it at its mark now; None when it does not (the engine then reads it)."""
    from oracle.historycache import kept_history
    from oracle.store.ids import find_neem

    info = find_neem(store, neem)
    if info is None:
        return None
    history = kept_history(store, ontology, info.id)
    if history is None:
        return None
    return info.id, info.user or info.id, history


__all__ = ["ExploreReader", "kept_timeline", "newest"]
