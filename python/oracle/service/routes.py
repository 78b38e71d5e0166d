"""The HTTP API: robot calls, answers, Prolog queries, events and the page.

Handlers only move JSON: each hands one job to the engine thread and publishes what happened.
"""

from __future__ import annotations

import threading
import time
from typing import TYPE_CHECKING, Annotated, Any, Literal

from fastapi import APIRouter, BackgroundTasks, Query, Request
from fastapi.responses import HTMLResponse, JSONResponse, StreamingResponse
from pydantic import BaseModel, Field

from oracle.service.events import Event
from oracle.service.page import render_page

if TYPE_CHECKING:
    from oracle.service.session import NeemSession

Time = float | str | None
router = APIRouter()


class NewNeem(BaseModel):
    user: str = Field(min_length=1, max_length=200, description="the user's name (kept in the NEEM, never logged)")
    neem: str | None = Field(None, description="NEEM id (default: made from the user's name)")


class Seen(BaseModel):
    name: str = Field(description="odb object name, e.g. red_mug")
    pose: list[Annotated[float, Field(allow_inf_nan=False)]] | None = Field(None, min_length=3, max_length=7,
                                     description="x, y, z [, qx, qy, qz, qw] in the robot's frame")


class Perception(BaseModel):
    objects: list[Seen] = Field(min_length=1, max_length=1000)
    at: Time = Field(None, description="unix seconds or ISO-8601 (default: now)")


class SituationIn(BaseModel):
    available: list[str] = Field(min_length=1, max_length=1000, description="calls in the chain syntax, e.g. pick(red_mug)")
    at: Time = Field(None, description="unix seconds or ISO-8601 (default: now)")


class ActionIn(BaseModel):
    call: str | None = Field(None, description="the task call, e.g. pick(red_mug)")
    phase: Literal["done", "begin", "end"] = Field(
        "done", description="done: begin (and end) given at once; begin: opens it; end: closes the open action `id`")
    at: Time = Field(None, description="time of a begin or end phase (default: now)")
    begin: Time = Field(None, description="phase done: when it began (default: now)")
    end: Time = Field(None, description="phase done: when it ended (default: its begin)")
    id: str | None = Field(None, max_length=100, description="the action's key, to end it later")
    performed_by: Literal["robot", "user"] = "robot"
    state: Literal["succeeded", "failed", "cancelled"] | None = Field(
        None, description="phase done: how it went, as the robot reports it (soma:hasExecutionState)")


class ChoiceIn(BaseModel):
    task: str = Field(description="the task the user chose")
    workflow: list[str] | None = Field(None, description="the whole predicted chain, when chosen as one workflow")


class PrologIn(BaseModel):
    query: str = Field(min_length=1, max_length=10_000, description="a Prolog goal, e.g. kb_call(executes_task(A, T))")
    bindings: dict[str, Any] = Field(default_factory=dict, description="values for named variables: strings are atoms")
    neem: str | None = Field(None, description="NEEM to query (default: the service's NEEM)")
    offset: int = Field(0, ge=0, le=1_000_000)
    limit: int = Field(100, ge=1, le=10_000)
    timeout: float = Field(5.0, gt=0, le=60, description="seconds")


def _ctx(request: Request) -> Any:
    return request.app.state.ctx


@router.get("/api/health", tags=["neems"])
async def health(request: Request) -> dict[str, Any]:
    """A round trip through the engine thread doing nothing: the floor under every answer."""
    ctx = _ctx(request)
    sessions = await ctx.thread.run(lambda: len(ctx.engine.sessions))
    return {"ok": True, "sessions": sessions, "subscribers": ctx.hub.subscribers}


# -- NEEMs --------------------------------------------------------------------------------
@router.get("/api/neems", tags=["neems"])
async def list_neems(request: Request) -> list[dict[str, Any]]:
    ctx = _ctx(request)
    return await ctx.thread.run(ctx.engine.neems)


@router.post("/api/neems", status_code=201, tags=["neems"])
async def create_neem(body: NewNeem, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)
    made = await ctx.thread.run(ctx.engine.create, body.user, body.neem)
    ctx.hub.publish(Event("neem", made["id"], {"id": made["id"]}))
    return made


# -- the robot ------------------------------------------------------------------------------
@router.post("/api/neems/{neem}/perception", tags=["robot"])
async def perception(neem: str, body: Perception, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)
    seen = [(o.name, o.pose) for o in body.objects]

    def job() -> tuple[str, list[str]]:
        session = ctx.engine.session(neem)
        return session.neem, session.perceive(seen, body.at)

    neem, iris = await ctx.thread.run(job)  # events and answers name the NEEM by its id
    data = {"objects": [name for name, _ in seen], "logged": iris}
    ctx.hub.publish(Event("perception", neem, data))
    return {"neem": neem, **data}


@router.post("/api/neems/{neem}/situation", tags=["robot"])
async def situation(neem: str, body: SituationIn, request: Request, background: BackgroundTasks) -> JSONResponse:
    """Log the available tasks as the imagined situation, rank them, write the ranking back as
    the imagined preference. The answer is sent as soon as the ranking is known; the NEEM write
    is the next job on the engine thread, before any later request. The Server-Timing header
    says how long the job waited for the engine thread and how long it ran (ms)."""
    ctx = _ctx(request)
    queued = time.perf_counter()

    def job() -> tuple[str, Any, Any, dict[str, Any], float, float]:
        started = time.perf_counter()
        session = ctx.engine.session(neem)
        found, ranking, ms = session.situation(body.available, body.at)
        return session.neem, found, ranking, session.describe(found, ranking, ms), started, time.perf_counter()

    neem, found, ranking, answer, started, done = await ctx.thread.run(job)
    timing = f"queue;dur={(started - queued) * 1000:.3f}, engine;dur={(done - started) * 1000:.3f}"
    write = lambda: ctx.engine.session(neem).write_situation(found, ranking)  # noqa: E731
    if ctx.write_behind:
        # The write is queued now (so no later request overtakes it) but waits until the answer
        # is on the wire: run at once, it holds the GIL while the event loop sends the answer.
        sent = threading.Event()
        ctx.thread.submit(_after, sent, write)

        async def release() -> None:
            sent.set()

        background.add_task(release)
    else:
        await ctx.thread.run(write)
    ctx.hub.publish(Event("situation", neem, answer))
    # answered as JSON directly: FastAPI's jsonable_encoder walks every field of the ranking and
    # cost more than the ranking itself (0.6 ms against 0.8 ms for 15 tasks); the values are plain
    return JSONResponse(answer, headers={"Server-Timing": timing})


def _after(sent: threading.Event, write: Any) -> None:
    sent.wait(RELEASE_S)
    write()


#: Longest a queued write waits for its answer to be sent (a client that vanished).
RELEASE_S = 1.0


@router.get("/api/neems/{neem}/situation", tags=["robot"])
async def latest_situation(neem: str, request: Request) -> dict[str, Any]:
    """The latest ranking this service answered for the NEEM (`ranking` empty before the first)."""
    ctx = _ctx(request)
    latest = await ctx.thread.run(lambda: ctx.engine.session(neem).latest)
    return latest or {"neem": neem, "ranking": [], "chain": []}


@router.post("/api/neems/{neem}/actions", tags=["robot"])
async def action(neem: str, body: ActionIn, request: Request) -> dict[str, Any]:
    """An executed action. `done` logs it at once; `begin` keeps it open (in memory) until its
    `end`. A gap of the logger's idle threshold before it is logged as an idle action."""
    ctx = _ctx(request)

    def job() -> tuple[str, dict[str, Any]]:
        session = ctx.engine.session(neem)
        return session.neem, _logged_action(session, body)

    neem, answer = await ctx.thread.run(job)
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
        logged = session.end(body.id, body.call, body.at)
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


@router.post("/api/neems/{neem}/choice", tags=["tablet"])
async def choice(neem: str, body: ChoiceIn, request: Request) -> dict[str, Any]:
    """The user's decision on the tablet, handed to the robot (event `choice`, and GET
    .../choice). The NEEM records it when the robot executes it, as the next action."""
    ctx = _ctx(request)

    def job() -> tuple[str, dict[str, Any]]:
        session = ctx.engine.session(neem)
        task = str(session.calls([body.task], "task")[0])
        workflow = [str(c) for c in session.calls(body.workflow, "workflow")] if body.workflow else None
        session.choice = {"task": task, "workflow": workflow}
        return session.neem, session.choice

    neem, made = await ctx.thread.run(job)
    ctx.hub.publish(Event("choice", neem, made))
    return {"neem": neem, **made}


@router.get("/api/neems/{neem}/choice", tags=["tablet"])
async def latest_choice(neem: str, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)
    made = await ctx.thread.run(lambda: ctx.engine.session(neem).choice)
    return {"neem": neem, "task": None, "workflow": None, **(made or {})}


# -- answers ------------------------------------------------------------------------------
@router.get("/api/neems/{neem}/why-not", tags=["answers"])
async def why_not(neem: str, request: Request, task: str = Query(description="a task call, e.g. pick(banana)"),
                  at: str | None = Query(None, description="time asked about (default: the latest decision)")) -> dict[str, Any]:
    ctx = _ctx(request)
    when: Time = float(at) if at is not None and _is_number(at) else at
    return await ctx.thread.run(ctx.engine.why_not, neem, task, when)


@router.get("/api/neems/{neem}/what-next", tags=["answers"])
async def what_next(neem: str, request: Request) -> dict[str, Any]:
    ctx = _ctx(request)
    return await ctx.thread.run(ctx.engine.what_next, neem)


@router.get("/api/neems/{neem}/something-else", tags=["answers"])
async def something_else(neem: str, request: Request,
                         task: str | None = Query(None, description="proposed task (default: the latest action's)")) -> dict[str, Any]:
    ctx = _ctx(request)
    return await ctx.thread.run(ctx.engine.something_else, neem, task)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


# -- Prolog and events --------------------------------------------------------------------
@router.post("/api/prolog", tags=["prolog"])
async def prolog(body: PrologIn, request: Request) -> dict[str, Any]:
    """A read-only Prolog query over one NEEM, answered as a page of JSON solutions."""
    ctx = _ctx(request)
    neem = body.neem or ctx.default_neem
    if neem is None:
        from oracle.errors import StoreError

        raise StoreError("name the NEEM to query: the store holds none yet")
    return await ctx.thread.run(ctx.engine.prolog, neem, body.query, body.bindings, body.offset,
                                body.limit, body.timeout)


@router.get("/api/events", tags=["events"])
async def events(request: Request, neem: str | None = Query(None, description="only this NEEM's events")) -> StreamingResponse:
    """Server-Sent Events: `situation` (a new ranking), `action`, `perception`, `choice`, `neem`."""
    ctx = _ctx(request)
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
async def page(request: Request, neem: str | None = None) -> HTMLResponse:
    ctx = _ctx(request)

    def job() -> tuple[str | None, dict[str, Any] | None]:
        chosen = neem or ctx.default_neem or ctx.engine.newest()
        if chosen is None:
            return None, None
        session = ctx.engine.session(chosen)
        return session.neem, session.latest

    chosen, state = await ctx.thread.run(job)
    html = render_page(chosen, state, ctx.token)
    return HTMLResponse(html, headers=PAGE_HEADERS)


#: The page loads nothing from elsewhere; the policy makes that a promise the browser keeps.
PAGE_HEADERS = {
    "Content-Security-Policy": "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                               "connect-src 'self'; img-src 'self' data:; base-uri 'none'; form-action 'none'",
    "Cache-Control": "no-store",
    "Referrer-Policy": "no-referrer",
}
