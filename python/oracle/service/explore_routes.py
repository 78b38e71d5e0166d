"""The researcher's NEEM explorer (``/explore``): one page, and one read-only data route per view.

- ``/explore/api/neems``: the store's NEEMs (user, span, action count, ontology, consent);
- ``/explore/api/neems/{neem}/timeline``: the history as the oracle reads it (actions, idle
  actions, the situation each was chosen in), compact;
- ``/explore/api/neems/{neem}/decisions``: each decision replayed as ``evaluate`` replays it (the
  predictor's order, what the user did, the truth's rank) and the rolling Top-1/3/5 curve.
The routines come from ``/api/neems/{neem}/routines`` and the console asks ``/api/prolog``: the
page uses those routes as they are, so its answers and refusals are theirs.

The product never imports the evaluation (tests/test_architecture.py): the replay is handed in
by whoever builds the app, as ``app.state.explore_replay`` (the ``serve`` command; tests). A
replay of a long NEEM takes tens of seconds (37 s at 10,000 actions), so it runs once per NEEM
state in a child process, niced more than the query process (oracle.service.queries): it shares
neither the engine thread nor the GIL with the robot's calls, and a service that stops ends it
(a daemon process), niced from its start (its imports and unpickling are a second of CPU). The
route answers 202 until it is done.

The page's first paint needs only the NEEM's timeline: the explorer's own reader
(oracle.service.explore_reader, a thread with a read-only connection) sends the view the store
keeps, so an open never queues behind the engine thread's work (another page's routines, a robot's
call, a NEEM's first read). Where nothing is kept, the engine reads the history through Prolog
once (6-10 s at 10,000 actions) while the route answers 202 with what it is reading, and the page
says so; the next open finds it kept.
"""

from __future__ import annotations

import asyncio
import json
import multiprocessing
import os
import threading
import time
from collections import OrderedDict
from collections.abc import Sequence
from concurrent.futures import Future
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

from fastapi import APIRouter, Query, Request
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse, Response

from oracle.service.explore_page import EXPLORE_FILES, EXPLORE_STATIC, render_explore
from oracle.service.explore_reader import ExploreReader, KeptTimeline, newest

if TYPE_CHECKING:
    from oracle.algorithm.params import Hyperparameters
    from oracle.algorithm.prior import Prior
    from oracle.bridge.records import HistoryRow
    from oracle.ontology import OdbOntology
    from oracle.service.app import Context

router = APIRouter(include_in_schema=False)  # the page's own data, shaped for it, not an API
#: Replays kept (one per NEEM state and predictor); each holds a few MB at 10,000 decisions.
KEPT_REPLAYS = 4
#: Calls of the predictor's order kept per decision (the page shows them).
SHOWN = 10
#: How much nicer than the service a replay runs: nicer than a Prolog query (5, which a person
#: waits on), since nobody waits on a replay's minute but a page opened meanwhile should not.
REPLAY_NICENESS = 10
#: How long a request waits for a NEEM's first read before it answers what is being read: a
#: small NEEM's read ends sooner, and its page then shows no passing status.
QUICK_READ_S = 0.3


class Replayed(Protocol):
    """What a replay hands back (oracle.evaluation.neem_replay.NeemReplay)."""

    @property
    def decisions(self) -> Sequence[Any]: ...
    @property
    def summary(self) -> dict[str, Any]: ...
    @property
    def method(self) -> str: ...
    @property
    def prior(self) -> bool: ...
    def rolling(self, window: int) -> dict[str, list[float]]: ...


class Replayer(Protocol):
    def __call__(self, ontology: OdbOntology, settings: Hyperparameters, method: str, rows: Sequence[HistoryRow],
                 user: str, keep: int = ..., prior: Prior | None = ...) -> Replayed: ...


@dataclass
class Reading:
    """A NEEM's history being read through Prolog, what it is (``said``) and since when."""

    task: asyncio.Future[tuple[str, str, list[HistoryRow]]]
    said: dict[str, Any]
    began: float = field(default_factory=time.monotonic)


@dataclass
class ExploreState:
    """Replays done or running, by (NEEM id, its history's length and last begin, predictor)."""

    replays: OrderedDict[tuple[Any, ...], Future[Replayed]] = field(default_factory=OrderedDict)
    lock: threading.Lock = field(default_factory=threading.Lock)
    # one replay at a time: two would only share the cores the robot's calls need
    turn: threading.Lock = field(default_factory=threading.Lock)
    #: the first reads of NEEMs nothing was kept for, on the engine thread, by the name asked
    reading: dict[str, Reading] = field(default_factory=dict)
    #: the latest read of each NEEM whose store keeps nothing (MongoDB), by the name asked: what
    #: its page shows, so the replay's polls do not read it all again each second
    unkept: OrderedDict[str, tuple[str, str, list[HistoryRow]]] = field(default_factory=OrderedDict)
    reader: ExploreReader | None = None

    def submit(self, replayer: Replayer, *args: Any) -> Future[Replayed]:
        """Run ``replayer(*args)`` in a child process after the replays asked before it."""
        future: Future[Replayed] = Future()

        def wait() -> None:
            with self.turn:
                context = multiprocessing.get_context("spawn")
                parent, child = context.Pipe(duplex=False)
                niceness = min(19, os.getpriority(os.PRIO_PROCESS, 0) + REPLAY_NICENESS)
                process = context.Process(target=_replay_child, args=(child, niceness, replayer, args), daemon=True,
                                          name="explore-replay")
                process.start()
                if process.pid is not None:  # at once: the child's start-up is CPU work too
                    _nice(process.pid, niceness)
                child.close()
                try:
                    ok, value = parent.recv()
                except (EOFError, OSError):
                    future.set_exception(RuntimeError("the replay process ended without an answer"))
                else:
                    if ok:
                        future.set_result(value)
                    else:
                        future.set_exception(RuntimeError(f"the replay failed: {value}"))
                finally:
                    parent.close()
                    process.join()

        threading.Thread(target=wait, name="explore-replay-wait", daemon=True).start()
        return future


def _nice(pid: int, niceness: int) -> None:
    try:
        os.setpriority(os.PRIO_PROCESS, pid, niceness)
    except OSError:
        pass  # the process ended already, or the system refuses: it runs as nice as its parent


def _replay_child(conn: Any, niceness: int, replayer: Replayer, args: tuple[Any, ...]) -> None:
    _nice(0, niceness)  # the parent set it as the child started; this covers a parent too slow for that
    try:
        conn.send((True, replayer(*args)))
    except Exception as error:  # the parent turns it into the route's error answer
        conn.send((False, f"{type(error).__name__}: {error}"))
    finally:
        conn.close()


def _state(request: Request) -> ExploreState:
    state = getattr(request.app.state, "explore", None)
    if state is None:
        ctx = _ctx(request)
        state = request.app.state.explore = ExploreState(reader=ExploreReader(ctx.engine.store.location, ctx.engine.ontology))
    assert isinstance(state, ExploreState)
    return state


async def _read(request: Request, job: Any, *args: Any) -> Any:
    """``job(store, *args)`` on the explorer's reader; None where it cannot answer (no file
    store, or the store refuses the name: the engine then answers, with its own error)."""
    from oracle.errors import NeemOracleError

    reader = _state(request).reader
    if reader is None:
        return None
    try:
        return await reader.run(job, *args)
    except NeemOracleError:
        return None


def close_explorer(app: Any) -> None:
    """End the explorer's reader (its thread and read-only connection) when the service stops."""
    state = getattr(app.state, "explore", None)
    if isinstance(state, ExploreState) and state.reader is not None:
        state.reader.close()


def _ctx(request: Request) -> Context:
    ctx: Context = request.app.state.ctx
    return ctx


@router.get("/explore", response_class=HTMLResponse)
async def explore_page(request: Request, neem: str | None = None) -> HTMLResponse:
    ctx = _ctx(request)
    # the NEEM shown first is named in the page, so it asks for the list and the timeline at once
    chosen = neem or ctx.default_neem or await _read(request, newest) or await ctx.thread.run(ctx.engine.newest)
    return HTMLResponse(render_explore(chosen, ctx.token), headers=PAGE_HEADERS)


@router.get(EXPLORE_STATIC + "{name}")
async def explore_static(name: str) -> FileResponse:
    """The explorer's script and style (nothing else is served from its folder)."""
    if name not in EXPLORE_FILES:
        from starlette.exceptions import HTTPException

        raise HTTPException(404, "Not Found")
    path, media = EXPLORE_FILES[name]
    return FileResponse(path, media_type=media, headers={"Cache-Control": "no-cache"})


def _neems(ctx: Context) -> list[dict[str, Any]]:
    from oracle.neem.query import summarize_neem
    from oracle.neem.sharing import is_shared
    from oracle.store.ids import alias_of

    out = []
    for info in ctx.engine.store.neems():
        summary = summarize_neem(ctx.engine.store, info.id, info)
        ontology = info.meta.get("ontology")
        out.append({"id": info.id, "name": alias_of(info), "user": info.user, "actions": summary.actions,
                    "begin": summary.begin, "end": summary.end, "temporary": info.temporary,
                    "ontology": _ontology_said(ontology, info.meta.get("model_version")),
                    "consent": "shared: its counts may enter a prior" if is_shared(info) else "not shared"})
    return out


def _ontology_said(ontology: Any, model: Any) -> str:
    """The NEEM's ontology in a few words: its files where it names them, else its fingerprint."""
    if isinstance(ontology, dict):
        files = [f"{k} {v}" for k, v in ontology.items() if k in ("odb", "mapping", "soma", "owl") and v]
        said = ", ".join(files) or "the sample kitchen"
        if ontology.get("fingerprint"):
            said += f" (fingerprint {ontology['fingerprint']})"
        return said
    return str(model or "not recorded")


@router.get("/explore/api/neems")
async def explore_neems(request: Request) -> list[dict[str, Any]]:
    ctx = _ctx(request)
    return await ctx.thread.run(_neems, ctx)


def _view(ctx: Context, neem: str) -> tuple[str, str, list[HistoryRow]]:
    from oracle.historycache import HistoryCache

    neem_id = ctx.engine.resolve(neem)
    info = ctx.engine.store.neem(neem_id)
    rows = HistoryCache.default().view(ctx.engine.bridge(neem_id)).rows
    return neem_id, info.user or neem_id, rows


async def _view_in_slices(ctx: Context, neem_id: str) -> tuple[str, str, list[HistoryRow]]:
    """``_view``, its whole read one slice per engine-thread job: a robot's situation waits one
    slice, not the read (oracle.service.sliced_jobs)."""
    from oracle.service.sliced_jobs import view_in_jobs

    view = await view_in_jobs(ctx.thread, ctx.engine, neem_id)
    info = await ctx.thread.run(ctx.engine.store.neem, neem_id)
    return neem_id, info.user or neem_id, view.rows


def _unread(ctx: Context, neem: str) -> dict[str, Any] | None:
    """What a NEEM's first read will read (its id, user and number of actions), or None when
    the history is kept: the engine then reads it at once."""
    from oracle.historycache import kept_history
    from oracle.neem.query import summarize_neem

    neem_id = ctx.engine.resolve(neem)
    info = ctx.engine.store.neem(neem_id)
    if info.temporary or kept_history(ctx.engine.store, ctx.engine.ontology, neem_id) is not None:
        return None
    return {"neem": neem_id, "user": info.user or neem_id, "actions": summarize_neem(ctx.engine.store, neem_id, info).actions,
            "kept_after": ctx.engine.store.append_mark(neem_id) is not None}


async def _kept(request: Request, neem: str) -> KeptTimeline | None:
    reader = _state(request).reader
    if reader is None:
        return None
    kept: KeptTimeline | None = await _read(request, reader.kept_timeline, neem)
    return kept


async def _rows(request: Request, neem: str, again: bool = True) -> tuple[str, str, list[HistoryRow]] | dict[str, Any]:
    """The NEEM's id, user and history: from the reader when the store keeps it, else read by
    the engine. A NEEM whose history nothing kept is read once in the background (6-10 s at
    10,000 actions): until then the answer is what is being read, as a dict. Where the store
    keeps nothing at all (MongoDB), ``again`` False takes the latest read (the replay's polls)."""
    ctx, state = _ctx(request), _state(request)
    kept = await _kept(request, neem)
    if kept is not None:
        return kept.neem, kept.user, kept.rows()
    if not again and neem in state.unkept:
        return state.unkept[neem]
    reading = state.reading.get(neem)
    if reading is None:
        unread = await ctx.thread.run(_unread, ctx, neem)
        if unread is None:  # kept after all (a temporary NEEM, or a store the reader cannot open)
            return await ctx.thread.run(_view, ctx, neem)
        reading = state.reading.get(neem)  # another request may have started it meanwhile
        if reading is None:
            reading = state.reading[neem] = Reading(asyncio.ensure_future(_view_in_slices(ctx, unread["neem"])), unread)
    if not reading.task.done():
        await asyncio.wait({reading.task}, timeout=QUICK_READ_S)
    if not reading.task.done():
        return {"reading": True, **reading.said, "seconds": round(time.monotonic() - reading.began, 1)}
    if state.reading.get(neem) is reading:
        del state.reading[neem]  # kept now: the next request finds it in the store
    read = reading.task.result()
    if not reading.said["kept_after"]:
        state.unkept[neem] = read
        while len(state.unkept) > KEPT_REPLAYS:
            state.unkept.popitem(last=False)
    return read


def _json(data: Any, status: int = 200) -> Response:
    """JSON written at once (the timeline is 60,000 numbers at 10,000 actions: FastAPI's encoder
    would walk each of them in Python first)."""
    return Response(json.dumps(data, separators=(",", ":")), status_code=status, media_type="application/json")


@router.get("/explore/api/neems/{neem}/timeline")
async def explore_timeline(neem: str, request: Request) -> Response:
    """The history compact (historycache.compact's shape): ``calls``, ``sets`` of available call
    indexes, and ``rows`` flat, six values each: begin, end, call, part of day, set (-1: none),
    mode. Idle actions are the call ``idle``. 202 with ``reading``, the NEEM's ``actions`` and
    ``seconds`` since the read began while a history nothing kept is read through Prolog."""
    from oracle.historycache import compact

    kept = await _kept(request, neem)
    if kept is not None:
        return Response(kept.body(), media_type="application/json")
    got = await _rows(request, neem)
    if isinstance(got, dict):
        return _json(got, 202)
    neem_id, user, rows = got
    return _json({"neem": neem_id, "user": user, **compact(rows)})


@router.get("/explore/api/neems/{neem}/decisions")
async def explore_decisions(neem: str, request: Request,
                            window: int = Query(100, ge=5, le=5000, description="decisions in the rolling window")) -> Any:
    """Every decision replayed: ``begin``, ``truth`` and ``ranked`` as call indexes, ``rank`` of the
    truth (0: not offered), ``candidates``; the rolling Top-k; ``summary``: evaluate's figures."""
    ctx = _ctx(request)
    replayer: Replayer | None = getattr(request.app.state, "explore_replay", None)
    if replayer is None:
        return JSONResponse({"error": "this service was built without the replay (python -m oracle serve hands it in)"},
                            status_code=501)
    got = await _rows(request, neem, again=False)
    if isinstance(got, dict):  # the history is still being read: the replay waits for it
        return JSONResponse({"pending": True, **got}, status_code=202)
    neem_id, user, rows = got
    if all(r["call"] == "idle" for r in rows):  # nothing was decided: nothing to replay
        return {"method": ctx.engine.method, "calls": [], "begin": [], "truth": [], "rank": [], "candidates": [],
                "ranked": [], "window": window, "rolling": {"top1": [], "top3": [], "top5": []},
                "summary": {"top1": 0.0, "top3": 0.0, "top5": 0.0}, "n_predictions": 0,
                "prior": _prior_json(ctx.engine.prior is not None, [])}
    state = _state(request)
    prior = ctx.engine.prior  # the one every session's predictor ranks with (serve --prior)
    key = (neem_id, len(rows), rows[-1]["begin"] if rows else None, ctx.engine.method, repr(ctx.engine.settings),
           prior.digest() if prior is not None else None)
    with state.lock:
        future = state.replays.get(key)
        if future is None:
            future = state.submit(replayer, ctx.engine.ontology, ctx.engine.settings, ctx.engine.method, rows, user, SHOWN,
                                  prior)
            state.replays[key] = future
            while len(state.replays) > KEPT_REPLAYS:
                state.replays.popitem(last=False)
    if not future.done():
        return JSONResponse({"pending": True, "decisions": sum(1 for r in rows if r["call"] != "idle")}, status_code=202)
    failed = future.exception()
    if failed is not None:
        with state.lock:
            state.replays.pop(key, None)  # the next request tries again
        return JSONResponse({"error": str(failed)}, status_code=500)
    replayed = await asyncio.wrap_future(future)
    return _decisions_json(replayed, window)


def _decisions_json(replayed: Replayed, window: int) -> dict[str, Any]:
    calls: dict[str, int] = {}
    begin, truth, rank, candidates, ranked, shares = [], [], [], [], [], []
    for d in replayed.decisions:
        shares.append(None if d.prior_share is None else round(d.prior_share, 4))
        begin.append(d.begin)
        truth.append(calls.setdefault(d.truth, len(calls)))
        rank.append(d.rank or 0)
        candidates.append(d.candidates)
        ranked.append([calls.setdefault(c, len(calls)) for c in d.ranked])
    figures = replayed.summary["methods"][replayed.method]
    return {"method": replayed.method, "calls": list(calls), "begin": begin, "truth": truth, "rank": rank,
            "candidates": candidates, "ranked": ranked, "window": window, "rolling": replayed.rolling(window),
            "summary": {k: figures[k] for k in ("top1", "top3", "top5")},
            "n_predictions": replayed.summary["n_predictions"], "prior": _prior_json(replayed.prior, shares)}


def _prior_json(given: bool, shares: list[float | None]) -> dict[str, Any]:
    """Where the shared prior took part: each decision's share (None: it took no part), how many
    decisions it took part in, and its mean share over them."""
    used = [s for s in shares if s is not None]
    return {"given": given, "shares": shares, "decisions": len(used),
            "mean": round(sum(used) / len(used), 4) if used else None}


#: As the tablet page's: nothing from elsewhere; images are drawn here (blob: for the exports).
PAGE_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; "
                               "img-src 'self' blob: data:; base-uri 'none'; form-action 'self'",
    "Cache-Control": "no-store",
    "Referrer-Policy": "no-referrer",
}
