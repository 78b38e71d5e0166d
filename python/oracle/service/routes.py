"""The HTTP API: robot calls, answers, Prolog queries, events and the page.

Handlers only move JSON: each hands one job to the engine thread and publishes what happened.

Why this module is large: it is the one router of the robot API (every route, its input model
and its typed answer side by side, as /openapi.json documents them); each handler is a few
lines that hand one job to the engine. The questions about the past have their own router
(past_routes.py).
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
import threading
import time
from typing import TYPE_CHECKING, Annotated, Any, Literal, cast

from fastapi import APIRouter, BackgroundTasks, Query, Request
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse, StreamingResponse
from pydantic import BaseModel, ConfigDict, Field

from oracle.errors import LoggingError
from oracle.service import schemas as S
from oracle.service.events import Event
from oracle.service.examples import example
from oracle.service.page import STATIC, render_page
from oracle.service.tablet import decision_of as _decision, record_choice, recorded_choice
from oracle.service.sliced_jobs import open_session

if TYPE_CHECKING:
    from oracle.service.app import Context
    from oracle.service.session import NeemSession

Time = float | str | None
#: Who performs an action (chains.MODES, held equal by a test: a Literal is what /openapi.json lists).
Mode = Literal["robot", "user", "together"]
router = APIRouter(responses=S.ERRORS)


class NewNeem(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("NewNeem"))
    user: str = Field(min_length=1, max_length=200, description="the user's name (kept in the NEEM, never logged)")
    neem: str | None = Field(None, description="NEEM id (default: made from the user's name)")


class Seen(BaseModel):
    name: str = Field(description="odb object name, e.g. red_mug")
    pose: list[Annotated[float, Field(allow_inf_nan=False)]] | None = Field(None, min_length=3, max_length=7,
                                     description="x, y, z [, qx, qy, qz, qw] in the robot's frame")


class Perception(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("Perception"))
    objects: list[Seen] = Field(min_length=1, max_length=1000)
    at: Time = Field(None, description="unix seconds or ISO-8601 (default: now)")


class SituationIn(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("SituationIn"))
    available: list[str] = Field(min_length=1, max_length=1000, description="calls in the chain syntax, e.g. pick(red_mug)")
    at: Time = Field(None, description="unix seconds or ISO-8601 (default: now)")


class ActionIn(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("ActionIn"))
    call: str | None = Field(None, description="the task call, e.g. pick(red_mug)")
    phase: Literal["done", "begin", "end"] = Field(
        "done", description="done: begin (and end) given at once; begin: opens it; end: closes the open action `id`")
    at: Time = Field(None, description="time of a begin or end phase (default: now)")
    begin: Time = Field(None, description="phase done: when it began (default: now)")
    end: Time = Field(None, description="phase done: when it ended (default: its begin)")
    id: str | None = Field(None, max_length=100, description="the action's key, to end it later")
    performed_by: Mode = Field("robot", description="who did it: the robot, the user by hand, or the two together")
    state: Literal["succeeded", "failed", "cancelled"] = Field(
        "succeeded", description="phase done or end: how it went, as the robot reports it (soma:hasExecutionState)")


class ChoiceIn(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("ChoiceIn"))
    task: str = Field(description="the task the user chose")
    workflow: list[str] | None = Field(None, description="the whole predicted chain, when chosen as one workflow")
    modes: list[Mode] | None = Field(None, max_length=1000, description=(
        "who does each step of the workflow (or the task: one), e.g. [\"user\", \"robot\"] for \"I bring the cup, "
        "you pour\" (default: who usually does each step, from the user's past; else the robot)"))
    at: Time = Field(None, description="when the user confirmed it (default: now)")


class PrologIn(BaseModel):
    model_config = ConfigDict(json_schema_extra=example("PrologIn"))
    query: str = Field(min_length=1, max_length=10_000, description="a Prolog goal, e.g. kb_call(executes_task(A, T))")
    bindings: dict[str, Any] = Field(default_factory=dict, max_length=100,
                                     description="values for named variables: strings are atoms")
    neem: str | None = Field(None, description="NEEM to query (default: the service's NEEM)")
    offset: int = Field(0, ge=0, le=1_000_000)
    limit: int = Field(100, ge=1, le=10_000)
    timeout: float = Field(1.0, gt=0, le=60, description="seconds (at most the service's limit: serve --query-seconds, 1 s by default)")


class DuplicateNeem(LoggingError):
    """A new NEEM named like one in the store (409)."""


def _ctx(request: Request) -> Context:
    ctx: Context = request.app.state.ctx
    return ctx


@router.get("/api/health", tags=["neems"], response_model=S.Health)
async def health(request: Request) -> dict[str, Any]:
    """A round trip through the engine thread doing nothing: the floor under every answer."""
    ctx = _ctx(request)
    sessions = await ctx.thread.run(lambda: len(ctx.engine.sessions))
    return {"ok": True, "sessions": sessions, "subscribers": ctx.hub.subscribers}


# -- NEEMs --------------------------------------------------------------------------------
@router.get("/api/neems", tags=["neems"], response_model=list[S.NeemListed])
async def list_neems(request: Request) -> list[dict[str, Any]]:
    ctx = _ctx(request)
    return await ctx.thread.run(ctx.engine.neems)


@router.post("/api/neems", status_code=201, tags=["neems"], response_model=S.NeemMade)
async def create_neem(body: NewNeem, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)

    def job() -> dict[str, Any]:
        from oracle.store.ids import find_neem

        if body.neem is not None and find_neem(ctx.engine.store, body.neem) is not None:
            raise DuplicateNeem(f"NEEM {body.neem!r} already exists: choose another name")
        return ctx.engine.create(body.user, body.neem)

    made = await ctx.thread.run(job)
    ctx.hub.publish(Event("neem", made["id"], {"id": made["id"]}))
    return made


# -- the robot ------------------------------------------------------------------------------
@router.post("/api/neems/{neem}/perception", tags=["robot"], response_model=S.PerceptionAnswer)
async def perception(neem: str, body: Perception, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    seen = [(o.name, o.pose) for o in body.objects]

    def job() -> tuple[str, list[str]]:
        _join(ctx)
        session = ctx.engine.session(neem)
        return session.neem, session.perceive(seen, body.at)

    neem, iris = await ctx.thread.run(job)  # events and answers name the NEEM by its id
    data = {"objects": [name for name, _ in seen], "logged": iris}
    ctx.hub.publish(Event("perception", neem, data))
    return {"neem": neem, **data}


@router.post("/api/neems/{neem}/situation", tags=["robot"], response_model=S.SituationAnswer)
async def situation(neem: str, body: SituationIn, request: Request, background: BackgroundTasks) -> JSONResponse:
    """Log the available tasks as the imagined situation, rank them, write the ranking back as
    the imagined preference. The answer is sent once the situation is committed; the ranking is
    written right after it (derived: nothing the robot waits for), as the next job on the engine
    thread, before any later request (with serve --write-behind the situation too). The Server-Timing header
    says how long the job waited for the engine thread and how long it ran (ms)."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    queued = time.perf_counter()

    def job() -> tuple[str, Any, Any, dict[str, Any], float, float]:
        started = time.perf_counter()
        session = ctx.engine.session(neem)
        if ctx.write_behind:
            found, ranking, ms = session.situation(body.available, body.at)
        else:  # committed in the same job: acknowledged means on disk
            alone = not ctx.thread.busy()  # no other request waits to share the group's commit
            _join(ctx)
            found = session.offer(body.available, body.at)
            # written, and committed when alone, before it is ranked: the disk flushes (on the
            # syncer's thread, oracle.service.groupcommit) while the engine ranks
            session.write_imagined(found)
            if alone and ctx.thread.group is not None:
                ctx.thread.group.commit()
            ranking, ms = session.rank(found)
        answer = cast(dict[str, Any], session.describe(found, ranking, ms))
        answer["routine"] = routine_now(ctx.engine, session, found.when.seconds)
        return session.neem, found, ranking, answer, started, time.perf_counter()

    neem, found, ranking, answer, started, done = await ctx.thread.run(job)
    timing = f"queue;dur={(started - queued) * 1000:.3f}, engine;dur={(done - started) * 1000:.3f}"
    if ctx.write_behind:  # before any later request: the robot's next action counts this offer
        _after_answer(ctx, background, lambda: ctx.engine.session(neem).write_situation(found, ranking))
    else:  # the ranking written back after the answer: derived, nothing the robot waits for
        _once_answered(ctx, background, lambda: _write_ranking(ctx, neem, found, ranking))
    ctx.hub.publish(Event("situation", neem, answer))
    # answered as JSON directly: FastAPI's jsonable_encoder walks every field of the ranking and
    # cost more than the ranking itself (0.6 ms against 0.8 ms for 15 tasks); the values are plain
    return JSONResponse(answer, headers={"Server-Timing": timing})


def _write_ranking(ctx: Any, neem: str, found: Any, ranking: Any) -> None:
    """The ranking written back in a group commit that lingers for the robot's next request
    (its own commit would cost an fsync per situation; nothing waits for it)."""
    if ctx.thread.group is not None:
        ctx.thread.group.join(linger=LINGER_S)
    ctx.engine.session(neem).write_ranking(found, ranking)


def routine_now(engine: Any, session: NeemSession, at: float) -> dict[str, Any] | None:
    """The routine the user is in at ``at`` (oracle.past.mine's recognition), from the steps
    the session's predictor already holds, with who usually does each step that remains: only
    the user's names are read from the NEEM (one Prolog query); None on a NEEM without a clock
    (its begins are positions, not times of day)."""
    ranker = session.ranker
    if not ranker.clocked:
        return None
    # as oracle.past.mine.neem_routines finds it, from what the session keeps per history
    _, current = session.warm.in_progress(ranker, at, session.warm.stored(stored_reader(engine, session)))
    if current is None:
        return None
    return {**current.to_json(), "steps_left": len(current.remaining),
            "remaining_modes": [session.usual_mode(call, at) for call in current.remaining]}


def stored_reader(engine: Any, session: NeemSession) -> Callable[[], list[dict[str, Any]]]:
    """The read of the workflows stored in the session's NEEM (one Prolog query), for ``Warm.stored``."""
    return lambda: cast(list[dict[str, Any]], engine.past.stored(engine.bridge(session.neem)))


def _join(ctx: Any) -> None:
    """This job's writes commit with those of every request already waiting (a group commit,
    oracle.service.groupcommit); the answer waits for that commit (EngineThread.run)."""
    if ctx.thread.group is not None:
        ctx.thread.group.join()


def _after_answer(ctx: Any, background: BackgroundTasks, work: Any) -> None:
    """``work`` queued on the engine thread now (so no later request overtakes it) but run once
    the answer is on the wire: run at once, it would hold the GIL while the event loop sends it."""
    sent = threading.Event()
    ctx.thread.submit(_after, sent, work)

    async def release() -> None:
        sent.set()

    background.add_task(release)


def _once_answered(ctx: Any, background: BackgroundTasks, work: Any, idle: bool = False) -> None:
    """``work`` queued on the engine thread once the answer is on the wire, behind whatever came
    meanwhile (a preference stamped with its decision's time may follow a later action: the
    history read skips it, oracle.historycache). Unlike ``_after_answer`` the engine thread never
    waits for the event loop, which with many robots kept it idle between answers. ``idle``: work
    that changes no answer (the warm-up after an action), run after the requests queued when its
    turn comes (``EngineThread.submit_idle``)."""

    async def queue() -> None:
        if idle:
            ctx.thread.submit_idle(work)
        else:
            ctx.thread.submit(work)

    background.add_task(queue)


def _after(sent: threading.Event, write: Any) -> None:
    sent.wait(RELEASE_S)
    write()


#: Longest the ranking written back waits, uncommitted, for a request to share its commit.
LINGER_S = 0.05
#: Longest a queued write waits for its answer to be sent (a client that vanished).
RELEASE_S = 1.0


@router.get("/api/neems/{neem}/situation", tags=["robot"], response_model=S.SituationAnswer)
async def latest_situation(neem: str, request: Request) -> dict[str, Any]:
    """The latest ranking this service answered for the NEEM (`ranking` empty before the first)."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    latest = await ctx.thread.run(lambda: ctx.engine.session(neem).latest)
    return cast(dict[str, Any], latest) if latest else {"neem": neem, "ranking": [], "chain": [], "chain_modes": []}


@router.post("/api/neems/{neem}/actions", tags=["robot"], response_model=S.ActionAnswer)
async def action(neem: str, body: ActionIn, request: Request, background: BackgroundTasks) -> dict[str, Any]:
    """An executed action. `done` logs it at once; `begin` keeps it open (in memory) until its
    `end`. A gap of the logger's idle threshold before it is logged as an idle action."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job

    def job() -> tuple[NeemSession, dict[str, Any]]:
        _join(ctx)
        session = ctx.engine.session(neem)
        return session, _logged_action(session, body)

    session, answer = await ctx.thread.run(job)
    neem = session.neem
    if not answer.get("open"):  # what the next situation derives from the history, fitted now
        _once_answered(ctx, background, lambda: session.warm.warm(session.ranker, session.ranker.last_end,
                                                                  stored_reader(ctx.engine, session)), idle=True)
    ctx.hub.publish(Event("action", neem, answer))
    return {"neem": neem, **answer}


def _logged_action(session: NeemSession, body: ActionIn) -> dict[str, Any]:
    """What ``POST .../actions`` logs, and its answer."""
    if body.phase == "begin":
        if body.call is None:
            raise _missing("call")
        opened = session.begin(body.call, body.at, body.performed_by, body.id)
        return {"id": opened.key, "call": str(opened.call), "open": True}
    if body.phase == "end":
        logged = session.end(body.id, body.call, body.at, body.state)
    else:
        if body.call is None:
            raise _missing("call")
        logged = session.log(body.call, body.begin, body.end, body.performed_by, body.state)
    return {"id": logged.iri, "call": str(logged.call), "begin": logged.begin, "end": logged.end,
            "time_of_day": logged.part_of_day, "idle": logged.idle, "open": False,
            "history": session.predictor.n_steps_}


def _missing(field: str) -> Exception:
    from oracle.errors import LoggingError

    return LoggingError(f"{field} is required for this phase")


@router.post("/api/neems/{neem}/choice", tags=["tablet"], response_model=S.ChoiceAnswer)
async def choice(neem: str, body: ChoiceIn, request: Request) -> dict[str, Any]:
    """The user's confirmed decision on the tablet: recorded in the NEEM as the user's own
    decision (oracle.neem.decisions), with who does each step (`modes`: a workflow in mixed
    mode, "I bring the cup, you pour"), and handed to the robot (event `choice`, and GET
    .../choice). What the robot then does is logged apart, as its action."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job

    def job() -> tuple[str, dict[str, Any]]:
        session = ctx.engine.session(neem)
        task = session.calls([body.task], "task")[0]
        workflow = session.calls(body.workflow, "workflow") if body.workflow else None
        if workflow is not None and str(workflow[0]) != str(task):
            raise _refused(f"workflow: its first step {workflow[0]} is not the task {task}")
        made = record_choice(session, list(workflow or [task]), body.at, None if body.modes is None else list(body.modes))
        session.choice = made
        return session.neem, made

    neem, made = await ctx.thread.run(job)
    ctx.hub.publish(Event("choice", neem, made))
    return {"neem": neem, **made}


@router.get("/api/neems/{neem}/choice", tags=["tablet"], response_model=S.ChoiceAnswer)
async def latest_choice(neem: str, request: Request) -> dict[str, Any]:
    """The user's latest decision: this service's, or after a restart the NEEM's."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job

    def job() -> tuple[str, dict[str, Any] | None]:
        session = ctx.engine.session(neem)
        return session.neem, recorded_choice(session)

    neem, made = await ctx.thread.run(job)
    return {"neem": neem, "task": None, "workflow": None, "modes": None, **(made or {})}


def _refused(message: str) -> Exception:
    from oracle.errors import LoggingError

    return LoggingError(message)


# -- answers ------------------------------------------------------------------------------
Lang = Query(None, description="the language of `said`: en or de (default: the browser's, else en)")


@router.get("/api/neems/{neem}/why-not", tags=["answers"], response_model=S.SpokenAnswer)
async def why_not(neem: str, request: Request, task: str = Query(description="a task call, e.g. pick(banana)"),
                  at: str | None = Query(None, description="time asked about (default: the latest decision)"),
                  lang: str | None = Lang) -> dict[str, Any]:
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    when: Time = float(at) if at is not None and _is_number(at) else at
    words = _words(request, lang)

    def job() -> dict[str, Any]:
        from oracle.service.tablet import why_not_said

        made = ctx.engine.why_not(neem, task, when)
        session = ctx.engine.session(neem)
        call = str(session.calls([task], "task")[0])
        return {**made, "said": why_not_said(call, session.latest, made["answer"], _decision(session), words)}

    return await ctx.thread.run(job)


@router.get("/api/neems/{neem}/what-next", tags=["answers"], response_model=S.SpokenAnswer)
async def what_next(neem: str, request: Request, lang: str | None = Lang) -> dict[str, Any]:
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    words = _words(request, lang)

    def job() -> dict[str, Any]:
        from oracle.service.tablet import what_next_said

        made = ctx.engine.what_next(neem)
        session = ctx.engine.session(neem)
        last = next(({"call": s.label, "begin": s.time} for s in reversed(session.ranker.steps) if not s.idle), None)
        return {**made, "said": what_next_said(made["answer"], _decision(session), last, words)}

    return await ctx.thread.run(job)


@router.get("/api/neems/{neem}/something-else", tags=["answers"], response_model=S.SpokenAnswer)
async def something_else(neem: str, request: Request,
                         task: str | None = Query(None, description="proposed task (default: the latest action's)"),
                         lang: str | None = Lang) -> dict[str, Any]:
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    words = _words(request, lang)

    def job() -> dict[str, Any]:
        from oracle.service.tablet import something_else_said

        made = ctx.engine.something_else(neem, task)
        return {**made, "said": something_else_said(made["answer"], words)}

    return await ctx.thread.run(job)


# -- the tablet's words -----------------------------------------------------------------------
def _words(request: Request, lang: str | None) -> Any:
    """The words for this request: ``lang``, else the browser's language; the service's zone."""
    from oracle.words import Words, load_lexicon, pick_lang

    ctx = _ctx(request)
    if ctx.lexicon is None:
        ctx.lexicon = load_lexicon(ontology=ctx.engine.ontology)
    return Words(ctx.lexicon, pick_lang(lang, request.headers.get("accept-language")), ctx.zone)


@router.get("/api/neems/{neem}/tablet", tags=["tablet"], response_model=S.TabletView)
async def tablet(neem: str, request: Request, lang: str | None = Lang) -> dict[str, Any]:
    """The latest ranking as the page shows it: plain words in the asked language, the time on
    the person's clock, the user's name (the robot's calls kept beside each)."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    words = _words(request, lang)
    return await ctx.thread.run(_view, ctx, neem, words)


def _view(ctx: Any, neem: str, words: Any) -> dict[str, Any]:
    from oracle.service.tablet import tablet_view

    session = ctx.engine.session(neem)
    return tablet_view(session.neem, session.logger.user, session.latest, words)


@router.get("/api/neems/{neem}/words", tags=["tablet"], response_model=S.Said)
async def said(neem: str, request: Request, call: str = Query(description="a task call, e.g. open(fridge)"),
               lang: str | None = Lang) -> dict[str, Any]:
    """A call as a person says it (what the page shows for the robot's latest action)."""
    ctx = _ctx(request)
    await open_session(ctx.thread, ctx.engine, neem)  # its history read a slice a job
    words = _words(request, lang)
    parsed = await ctx.thread.run(lambda: ctx.engine.session(neem).calls([call], "call")[0])
    return {"call": str(parsed), "said": words.said(parsed)}


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


# -- Prolog and events --------------------------------------------------------------------
@router.post("/api/prolog", tags=["prolog"], response_model=S.PrologAnswer)
async def prolog(body: PrologIn, request: Request) -> dict[str, Any]:
    """A read-only Prolog query over one NEEM, answered as a page of JSON solutions."""
    ctx = _ctx(request)
    neem = body.neem or ctx.default_neem
    if neem is None:  # KnowRob's clients name no NEEM: the store's only one
        from oracle.service.neem_choice import store_neem

        neem = await ctx.thread.run(store_neem, ctx.engine.store, "the request's \"neem\" or serve --neem NAME")
    if ctx.queries >= ctx.limits.queries:  # a queue of queries would hold the robot's calls
        from oracle.service.engine import Overloaded

        raise Overloaded(429, "another Prolog query is running; retry when it is done")
    ctx.queries += 1
    try:
        if ctx.query_process is None:
            return await ctx.thread.run(ctx.engine.prolog, neem, body.query, body.bindings, body.offset,
                                        body.limit, body.timeout, ctx.prolog_writes)
        # off the robot's path: not even the engine thread is asked (the NEEM is found there)
        seconds = min(body.timeout, ctx.limits.query_seconds)
        return await asyncio.get_running_loop().run_in_executor(
            None, ctx.query_process.ask, neem, body.query, body.bindings, body.offset, body.limit, seconds)
    finally:
        ctx.queries -= 1


@router.get("/api/events", tags=["events"], response_class=StreamingResponse,
            responses={200: {"content": {"text/event-stream": {"schema": {"type": "string"}}}}})
async def events(request: Request, neem: str | None = Query(None, description="only this NEEM's events")) -> StreamingResponse:
    """Server-Sent Events: `situation` (a new ranking), `action`, `perception`, `choice`, `neem`."""
    ctx = _ctx(request)
    if ctx.hub.subscribers >= ctx.limits.subscribers:
        from oracle.service.engine import Overloaded

        raise Overloaded(503, f"{ctx.hub.subscribers} event streams are open, this service's limit")
    if neem is not None:  # events name NEEMs by id
        neem = await ctx.thread.run(ctx.engine.resolve, neem)
    return StreamingResponse(_until_closed(request, ctx.hub.stream(neem, ctx.stopping)), media_type="text/event-stream",
                             headers={"Cache-Control": "no-store", "X-Accel-Buffering": "no"})


async def _until_closed(request: Request, stream: Any) -> Any:
    async for chunk in stream:
        if await request.is_disconnected():
            break
        yield chunk


# -- the page -----------------------------------------------------------------------------
@router.get("/", response_class=HTMLResponse, include_in_schema=False)
async def page(request: Request, neem: str | None = None, lang: str | None = None) -> HTMLResponse:
    ctx = _ctx(request)
    words = _words(request, lang)

    def job() -> dict[str, Any] | None:
        chosen = neem or ctx.default_neem or ctx.engine.newest()
        return None if chosen is None else _view(ctx, chosen, words)

    view = await ctx.thread.run(job)
    text = dict(words.text)
    return HTMLResponse(render_page(view, text, ctx.token, ctx.manner), headers=PAGE_HEADERS)


@router.get("/static/{name}", include_in_schema=False)
async def static(name: str) -> FileResponse:
    """The page's own style, script and icon (nothing else is served from the folder)."""
    if name not in STATIC_FILES:
        from starlette.exceptions import HTTPException

        raise HTTPException(404, "Not Found")
    return FileResponse(STATIC / name, media_type=STATIC_FILES[name], headers={"Cache-Control": "no-cache"})


@router.get("/favicon.ico", include_in_schema=False)
async def favicon() -> FileResponse:
    return FileResponse(STATIC / "favicon.svg", media_type="image/svg+xml")


STATIC_FILES = {"page.js": "text/javascript", "page.css": "text/css", "favicon.svg": "image/svg+xml"}

#: The page loads nothing from elsewhere; the policy makes that a promise the browser keeps.
PAGE_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'self'; style-src 'self'; "
                               "connect-src 'self'; img-src 'self'; base-uri 'none'; form-action 'self'",
    "Cache-Control": "no-store",
    "Referrer-Policy": "no-referrer",
}
