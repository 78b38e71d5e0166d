"""rosbridge v2 in the live service: roslibpy and roslibjs clients call rosprolog with no ROS.

A websocket at ``/rosbridge`` (and at ``/``, where roslibpy's ``Ros(host, port)`` connects)
takes rosbridge's JSON operations: ``call_service`` for ``/rosprolog/query``,
``/rosprolog/next_solution`` and ``/rosprolog/finish`` (and json_prolog's older names,
``/json_prolog/simple_query`` ...), answered with ``service_response``
(``values``, ``result``); ``advertise``, ``publish``, ``subscribe`` and the other topic
operations a client sends first are taken without an answer (no topic is served). The route
passes the service's own checks (guard.Guard: Host, Origin, token) before it accepts, and asks
Prolog where ``/api/prolog`` asks (backend.service_ask). ``?neem=ID`` picks the NEEM (one the store does not hold is refused before the
upgrade); else the
service's ``--neem``, else the store's only one (service.neem_choice: with several, the query
fails saying how to choose).
"""

from __future__ import annotations

import asyncio
import json
import logging
from typing import TYPE_CHECKING, Any

from fastapi import APIRouter, WebSocket, WebSocketDisconnect

from oracle.errors import NeemOracleError
from oracle.rosprolog.backend import service_ask
from oracle.rosprolog.protocol import SERVICES, DoorError, Page, Queries, QueryFailed

if TYPE_CHECKING:
    from oracle.service.app import Context

LOG = logging.getLogger("oracle.service")
router = APIRouter()
#: The namespaces of the services: rosprolog's, and json_prolog's of older clients.
NAMESPACES = ("rosprolog", "json_prolog")
#: Operations a client may send that need no answer here (topics, and the bridge's own settings).
QUIET_OPS = frozenset({"advertise", "unadvertise", "publish", "subscribe", "unsubscribe", "advertise_service",
                       "unadvertise_service", "set_level", "status", "auth"})
#: Service calls of one connection answered at once (its next frames wait unread meanwhile).
CALLS_PER_SOCKET = 16
#: The websocket close code for a refused connection (policy violation).
REFUSED = 1008


@router.websocket("/rosbridge")
async def rosbridge(websocket: WebSocket) -> None:
    await _serve(websocket)


@router.websocket("/")
async def rosbridge_root(websocket: WebSocket) -> None:
    await _serve(websocket)


async def _serve(websocket: WebSocket) -> None:
    from oracle.service.guard import Guard, Refusal

    ctx: Context = websocket.app.state.ctx
    headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in websocket.scope["headers"]}
    try:
        Guard(None, ctx)._check(dict(websocket.scope), headers)  # the same Host, Origin and token rules as HTTP
    except Refusal as refusal:
        LOG.info("websocket %s refused %d", websocket.scope["path"], refusal.status)
        await websocket.close(code=REFUSED, reason=str(refusal)[:120])
        return
    neem = websocket.query_params.get("neem")
    if neem is not None:  # a NEEM of the store, by id: the open-query tables stay one per NEEM
        try:
            neem = await ctx.thread.run(ctx.engine.resolve, neem)
        except NeemOracleError as error:
            await websocket.close(code=REFUSED, reason=str(error)[:120])
            return
    queries = _queries(websocket, ctx, neem)
    await websocket.accept()
    mine: set[str] = set()
    send_lock = asyncio.Lock()
    slots = asyncio.Semaphore(CALLS_PER_SOCKET)
    tasks: set[asyncio.Task[None]] = set()

    async def send(message: dict[str, Any]) -> None:
        async with send_lock:
            await websocket.send_text(json.dumps(message))

    async def call(message: dict[str, Any]) -> None:
        try:
            await send(await _call_service(queries, message, mine))
        finally:
            slots.release()

    try:
        while True:
            text = await websocket.receive_text()
            message = _message(text, ctx.limits.body_bytes)
            if isinstance(message, str):
                await send({"op": "status", "level": "error", "msg": message})
            elif message.get("op") == "call_service":
                await slots.acquire()  # no more frames are read while CALLS_PER_SOCKET are running
                task = asyncio.create_task(call(message))
                tasks.add(task)
                task.add_done_callback(tasks.discard)
            elif message.get("op") not in QUIET_OPS:
                await send({"op": "status", "level": "error", "id": message.get("id"),
                            "msg": f"op {message.get('op')!r} is not served here (call_service for /rosprolog/...)"})
    except (WebSocketDisconnect, RuntimeError):
        pass  # the client went away (RuntimeError: a send after the close)
    finally:
        for task in tasks:
            task.cancel()
        for id in mine:  # a client that left without finishing leaves nothing open
            queries.finish(id)


def _message(text: str, limit: int) -> dict[str, Any] | str:
    """The operation a frame holds, or why it is refused."""
    if len(text) > limit:
        return f"the message is larger than {limit} bytes"
    try:
        message = json.loads(text)
    except (ValueError, RecursionError):
        return "the message is not JSON"
    if not isinstance(message, dict) or not isinstance(message.get("op"), str):
        return "the message is not a rosbridge operation (a JSON object with an 'op')"
    return message


async def _call_service(queries: Queries, message: dict[str, Any], mine: set[str]) -> dict[str, Any]:
    name = str(message.get("service", ""))
    answer: dict[str, Any] = {"op": "service_response", "service": name}
    if "id" in message:
        answer["id"] = message["id"]
    namespace, _, service = name.strip("/").rpartition("/")
    args = message.get("args") or {}
    if namespace not in NAMESPACES or service not in SERVICES:
        return {**answer, "result": False, "values": f"Service {name} does not exist (this bridge serves /rosprolog/...)"}
    if isinstance(args, list):  # rosbridge also takes the request's fields in order
        fields = ("mode", "id", "query") if service in ("query", "simple_query") else ("id",)
        args = dict(zip(fields, args))
    if not isinstance(args, dict):
        return {**answer, "result": False, "values": "the call's 'args' must be an object"}
    try:
        values = await asyncio.get_running_loop().run_in_executor(None, queries.call, service, args)
    except DoorError as error:
        return {**answer, "result": False, "values": str(error)}
    if service == "query" and values.get("ok"):
        mine.add(str(args["id"]))
    elif service == "finish":
        mine.discard(str(args.get("id")))
    return {**answer, "result": True, "values": values}


def _queries(websocket: WebSocket, ctx: Context, neem: str | None) -> Queries:
    """The open queries about ``neem`` (the default NEEM's when None), shared by every
    connection of this service, as rosprolog's ids are."""
    state = websocket.app.state
    if not hasattr(state, "rosprolog_queries"):
        state.rosprolog_queries = {}
    table: dict[str | None, Queries] = state.rosprolog_queries
    if neem not in table:
        table[neem] = Queries(_ask(ctx, neem))
    return table[neem]


def _ask(ctx: Context, neem: str | None) -> Any:
    """Ask about ``neem``, or the service's default NEEM, found when a query runs (the store
    may get its first NEEM after the service started)."""

    def ask(text: str, offset: int, limit: int) -> Page:
        from oracle.service.neem_choice import store_neem

        try:
            chosen = neem or ctx.default_neem or ctx.thread.call(store_neem, ctx.engine.store, "?neem=ID on the address")
        except NeemOracleError as error:
            raise QueryFailed(str(error)) from None
        return service_ask(ctx, chosen)(text, offset, limit)

    return ask


__all__ = ["router"]
