"""A NEEM's whole history read on the engine thread one slice per job (oracle.slicedread), so that
the jobs queued meanwhile (a robot's situation) run between two slices instead of behind the whole
read: /explore's first read of a NEEM nothing kept (oracle.service.explore_routes), and the read
that opens a NEEM's session (``open_session``, before the request's own job).

The slices are read at the store's append mark of the first job; when the NEEM grows before the
last (a robot logging into it), the read starts again, and after ``ATTEMPTS`` it is done in one
job as ``HistoryCache.view`` does it. A store that keeps no mark (MongoDB) cannot say that it
grew: the slices then see the actions logged between them, and an action logged with a begin
before a slice already read (a robot logs at its now, after every slice) would be missed until
the next read."""

from __future__ import annotations

from typing import TYPE_CHECKING

from oracle.bridge.records import HistoryView
from oracle.historycache import HistoryCache
from oracle.slicedread import SLICE_ACTIONS, SlicedRead
from oracle.store.ids import find_neem

if TYPE_CHECKING:
    from oracle.service.engine import Engine, EngineThread

#: Reads begun again because the NEEM grew meanwhile, before one read in a single job.
ATTEMPTS = 3


async def view_in_jobs(thread: EngineThread, engine: Engine, neem: str, size: int = SLICE_ACTIONS) -> HistoryView:
    """``HistoryCache.default().view`` of NEEM ``neem`` (its id), its whole read (when one is
    needed) done one slice per engine-thread job."""
    view, _ = await _read_in_jobs(thread, engine, neem, size)
    return view


async def _read_in_jobs(thread: EngineThread, engine: Engine, neem: str, size: int) -> tuple[HistoryView, object]:
    """``view_in_jobs`` and the store's append mark it was read at."""
    cache = HistoryCache.default()
    for _ in range(ATTEMPTS):
        read = SlicedRead(size)

        def start(read: SlicedRead = read) -> object:
            read.start(engine.bridge(neem))
            return engine.store.append_mark(neem)

        mark = await thread.run(start)
        while read.slices_left > 0:
            await thread.run(lambda read=read: read.step(engine.bridge(neem)))

        def finish(read: SlicedRead = read, mark: object = mark) -> HistoryView | None:
            if engine.store.append_mark(neem) != mark:
                return None  # grown meanwhile: the slices may not be of one state
            return cache.view(engine.bridge(neem), whole=read.finish)

        view = await thread.run(finish)
        if view is not None:
            return view, mark
    return await thread.run(lambda: (cache.view(engine.bridge(neem)), engine.store.append_mark(neem)))


async def open_session(thread: EngineThread, engine: Engine, name: str, size: int = SLICE_ACTIONS) -> None:
    """Open the session of NEEM ``name`` (its id or alias) as ``Engine.session`` would on first
    use, its history read one slice per job when nothing is kept: a robot's job queued meanwhile
    (another NEEM's situation) waits one slice, not the whole read. Nothing happens when the
    session is open, the NEEM unknown or no session may open: ``Engine.session`` in the request's
    own job then answers as it does (NotFound, Overloaded)."""

    def which() -> str | None:
        if name in engine.sessions or len(engine.sessions) >= engine.limits.sessions:
            return None
        found = find_neem(engine.store, name)
        return None if found is None or found.id in engine.sessions else found.id

    if name in engine.sessions:
        return  # open: no job (a dict look-up, safe beside the engine thread's writes)
    neem = await thread.run(which)
    if neem is None:
        return
    view, mark = await _read_in_jobs(thread, engine, neem, size)

    def opened() -> None:
        # Nothing but its own session logs into a NEEM here; another process might: then the
        # view is no longer the NEEM's, and the session reads what the cache extends it by.
        fresh = engine.store.append_mark(neem) == mark
        engine.session(neem, view if fresh else None)

    await thread.run(opened)
