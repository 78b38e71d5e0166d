"""The service's front door: what a request must be before any handler sees it.

One pure ASGI middleware (cheaper than Starlette's BaseHTTPMiddleware on every request), in
this order: the Host must be one this service answers to (DNS rebinding: a page of another
site that resolves its name to 127.0.0.1 sends its own name as Host) -> 421; an Origin of
another site -> 403; the token when there is one -> 401; a body over the limit -> 413 (from
Content-Length, or while it streams in; never echoed), one that comes too slowly -> 408, more
body bytes buffered at once than the process allows -> 503; JSON too deep, with too many values,
too long a number or string, or not UTF-8 -> 400 (oracle.service.bodyshape, linear, in a
worker thread for a big body); then too many requests at once -> 503, with a reserve of slots
only the robot's routes may take. While a robot request is served, large bodies wait
(RobotFirst). Every answer carries the headers that keep the page out of frames and stop content
sniffing. Connections themselves (per-client limits, the header deadline, draining a refused
body) are oracle.service.connections' job. The request log holds the method, the route
template, the NEEM id, the status and the time; never a task, an object, a query or a token.
"""

from __future__ import annotations

import asyncio
import ipaddress
import json
import logging
import re
import time
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

from oracle.service.access import admits, presented

LOG = logging.getLogger("oracle.service")
#: Paths that show no user data: the schema, its viewer, the page's style, script and icon need no token.
OPEN_PATHS = ("/openapi.json", "/docs", "/docs/", "/favicon.ico")
STATIC_DOCS = "/docs/static"
STATIC_PAGE = "/static/"
#: Host names every service answers to (plus its bound address and ``--allowed-host`` names).
LOOPBACK_HOSTS = frozenset({"localhost", "127.0.0.1", "::1"})
#: Sent with every answer: no site may frame the page (clickjacking), no type sniffing.
FRAME_POLICY = "frame-ancestors 'none'"
SAFE_HEADERS = ((b"x-frame-options", b"DENY"), (b"x-content-type-options", b"nosniff"))
#: The robot's routes (situation, action, perception posts and the situation read): they may
#: take the in-flight slots other requests may not, so a crowd elsewhere cannot starve them.
ROBOT_ROUTE = re.compile(r"/api/neems/[^/]+/(situation|actions|perception)")
#: A body at least this large is measured in a worker thread (about 1 ms of scanning).
OFF_LOOP_BYTES = 64 << 10
#: Longest a large body yields to the robot's requests at each step (each piece read, the
#: measure, the parse): the robot goes first, a large body still moves on (about 18 steps a MiB).
ROBOT_FIRST_SECONDS = 0.05


@dataclass(frozen=True)
class Limits:
    """What one request and one process may take (docs/security.md lists them with why)."""

    #: Largest request body, bytes (413 above it).
    body_bytes: int = 1 << 20
    #: Deepest JSON nesting of a body (400 deeper).
    json_depth: int = 32
    #: Values, keys and containers in one body (400 more): what json.loads and pydantic then
    #: cost on the event loop stays a few milliseconds.
    json_values: int = 50_000
    #: Longest number literal in a body, characters (400 longer).
    number_chars: int = 100
    #: Longest string in a body, bytes as sent (400 longer; a Prolog query, the longest text
    #: the API takes, is at most 10,000 characters).
    string_bytes: int = 64 << 10
    #: Seconds a client may take to send its body once its headers are in (408 after).
    body_seconds: float = 5.0
    #: Body bytes all requests together may hold while their bodies stream in (503 beyond);
    #: a body declared at most ``small_body`` bytes long is not counted (connections bound those).
    buffered_bytes: int = 64 << 20
    small_body: int = 64 << 10
    #: Requests handled at once (their bodies read); more get 503. Event streams hold one each
    #: (at most ``subscribers``): with all 32 open, other requests keep 64 - 16 reserved - 32.
    in_flight: int = 64
    #: Of ``in_flight``, the slots only the robot's routes (ROBOT_ROUTE) may take.
    robot_reserve: int = 16
    #: Prolog queries running or queued at once; more get 429.
    queries: int = 1
    #: Longest a Prolog query may run, seconds (a client asking more gets this).
    query_seconds: float = 1.0
    #: Live NEEM sessions a process keeps; opening more gets 503.
    sessions: int = 64
    #: NEEMs one process may create; more get 429 (the store is the person's, not a dump).
    new_neems: int = 256
    #: Event stream subscribers at once; more get 503.
    subscribers: int = 32
    #: Seconds an idle keep-alive connection stays open (uvicorn's timeout_keep_alive).
    keep_alive_seconds: float = 5.0
    #: Seconds a client may take to send a request's headers (a slow trickle is closed).
    header_seconds: float = 5.0
    #: Open connections from one client address, and from all: beyond, the oldest idle one
    #: (no request in progress) is closed to make room, else the new one gets 503.
    peer_connections: int = 256
    connections: int = 512
    #: After an early answer (413, 408), what of the rest of the body is read and dropped so
    #: the client reads the answer rather than a reset: bytes and seconds.
    drain_bytes: int = 16 << 20
    drain_seconds: float = 2.0


def allowed_hosts(bound: str, extra: tuple[str, ...] = ()) -> frozenset[str]:
    """The Host names a service bound to ``bound`` answers to (lower case, no port)."""
    return frozenset({*LOOPBACK_HOSTS, _host_name(bound), *(_host_name(name) for name in extra)})


def _host_name(host: str) -> str:
    """``Example.org:8765`` -> ``example.org``; ``[::1]:8765`` -> ``::1``."""
    host = host.strip().lower()
    if host.startswith("["):
        return host[1:host.find("]")] if "]" in host else host
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def _wildcard(hosts: frozenset[str]) -> bool:
    return "0.0.0.0" in hosts or "::" in hosts


def _is_address(name: str) -> bool:
    try:
        ipaddress.ip_address(name)
    except ValueError:
        return False
    return True


class Refusal(Exception):
    """A request the guard answers itself: its status and one line."""

    def __init__(self, status: int, message: str, headers: tuple[tuple[bytes, bytes], ...] = ()) -> None:
        super().__init__(message)
        self.status = status
        self.headers = headers


class Guard:
    """The middleware (see the module docstring). ``ctx`` is the app's Context: its token, its
    allowed hosts and its limits."""

    def __init__(self, app: Any, ctx: Any, token_page: Any = None) -> None:
        self.app = app
        self.ctx = ctx
        #: ``token_page(headers, query) -> Response``: what a person opening ``/`` without the
        #: token sees (a page asking for it) instead of a JSON refusal.
        self.token_page = token_page
        self.in_flight = 0
        self.budget = BodyBudget(ctx.limits.buffered_bytes)
        self.robots = RobotFirst()

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = [0]

        async def framed(message: dict[str, Any]) -> None:
            if message["type"] == "http.response.start":
                status[0] = message["status"]
                message = {**message, "headers": _with_safe_headers(message.get("headers", []))}
            await send(message)

        limits: Limits = self.ctx.limits
        robot = False
        try:
            headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
            self._check(scope, headers)
            robot = ROBOT_ROUTE.fullmatch(scope["path"]) is not None and _small(headers, limits)
            if robot:
                self.robots.enter()
            body = await self._body(receive, headers, limits, robot)
            reserve = min(limits.robot_reserve, limits.in_flight // 2)
            allowed = limits.in_flight if ROBOT_ROUTE.fullmatch(scope["path"]) else limits.in_flight - reserve
            if self.in_flight >= allowed:
                raise Refusal(503, "the service is busy: too many requests at once; retry shortly",
                              ((b"retry-after", b"1"),))
            self.in_flight += 1
            try:
                await self.app(scope, _replay(body, receive), framed)
            finally:
                self.in_flight -= 1
        except Refusal as refusal:
            if status[0] == 0 and refusal.status == 401 and scope["path"] == "/" and self.token_page is not None:
                page = self.token_page(headers, scope.get("query_string", b""))
                await page(scope, receive, framed)
            elif status[0] == 0:
                await _answer(framed, refusal)
        finally:
            if robot:
                self.robots.leave()
            route = getattr(scope.get("route"), "path", None) or "(no route)"
            neem = scope.get("path_params", {}).get("neem")
            LOG.info("%s %s%s %d %.1f ms", scope["method"], route, f" neem={neem}" if neem else "", status[0],
                     (time.perf_counter() - started) * 1000)

    async def _body(self, receive: Any, headers: dict[str, str], limits: Limits, robot: bool) -> bytes:
        """The request's body, read within the limits and checked (bodyshape); a large one is
        read, measured and handed on only while no robot request is being served (a robot's own
        request waits for no other)."""
        robots = RobotFirst() if robot else self.robots
        body = await _read_body(receive, headers, limits, self.budget, robots)
        if len(body) >= OFF_LOOP_BYTES:
            await robots.wait(ROBOT_FIRST_SECONDS)
            await check_body(body, limits)
            await robots.wait(ROBOT_FIRST_SECONDS)  # json.loads and pydantic read it on the loop next
        else:
            await check_body(body, limits)
        return body

    def _check(self, scope: dict[str, Any], headers: dict[str, str]) -> None:
        host = headers.get("host")
        if host is None:
            raise Refusal(400, "the request has no Host header")
        hosts: frozenset[str] = self.ctx.allowed_hosts
        name = _host_name(host)
        if name not in hosts and not (_wildcard(hosts) and _is_address(name)):
            raise Refusal(421, "this service does not answer to that Host name (serve --allowed-host NAME adds one)")
        origin = headers.get("origin")
        if origin is not None and urlsplit(origin).netloc.lower() != host.lower():
            raise Refusal(403, "cross-origin requests are refused")
        path = scope["path"]
        if (self.ctx.token is None and getattr(self.ctx, "access", None) is None) or path in OPEN_PATHS \
                or path.startswith((STATIC_DOCS, STATIC_PAGE)):
            return
        # the service's token or one of serve --tokens' (oracle.service.access holds it to its grant)
        if not admits(self.ctx, presented(headers, scope.get("query_string", b""))):
            raise Refusal(401, "this service needs its token: Authorization: Bearer <token>")


def _small(headers: dict[str, str], limits: Limits) -> bool:
    """The request declares a body of at most ``limits.small_body`` bytes (or none)."""
    declared = headers.get("content-length", "0").strip()
    return declared.isdigit() and int(declared) <= limits.small_body and "transfer-encoding" not in headers


async def _read_body(receive: Any, headers: dict[str, str], limits: Limits, budget: BodyBudget, robots: RobotFirst) -> bytes:
    """The whole body, at most ``limits.body_bytes`` of it: decided from Content-Length before
    anything is read, and again while it streams in (a chunked body has no length); the bytes
    held count against ``budget`` until the body is whole. A large body is read only while no
    robot request is being served (``robots``); the time it waits is not counted against it."""
    too_big = Refusal(413, f"the request body is larger than {limits.body_bytes} bytes",
                      ((b"connection", b"close"),))
    declared = headers.get("content-length")
    if declared is not None:
        if not declared.strip().isdigit():
            raise Refusal(400, "Content-Length is not a number")
        if int(declared) > limits.body_bytes:
            raise too_big
    counted = declared is None or int(declared) > limits.small_body
    chunks: list[bytes] = []
    size = 0
    more = True
    deadline = time.monotonic() + limits.body_seconds
    try:
        while more:
            if counted:
                deadline += await robots.wait(ROBOT_FIRST_SECONDS)
            try:
                message = await asyncio.wait_for(receive(), max(0.0, deadline - time.monotonic()))
            except TimeoutError:
                raise Refusal(408, "the request body came too slowly", ((b"connection", b"close"),)) from None
            if message["type"] != "http.request":
                break  # the client went away; the handler sees an empty body and its disconnect
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > limits.body_bytes:
                raise too_big
            if counted:
                budget.take(len(chunk))
            chunks.append(chunk)
            more = message.get("more_body", False)
    finally:
        if counted:
            budget.give(size)
    return b"".join(chunks)


class RobotFirst:
    """The robot's requests in progress (small ones to ROBOT_ROUTE): while any is, large bodies
    wait before each piece is read, before they are measured and before they are parsed, so
    their CPU (and the GIL) goes to the robot first. Each wait is bounded (ROBOT_FIRST_SECONDS):
    a robot that never pauses slows a large body down, it does not starve it."""

    def __init__(self) -> None:
        self.running = 0
        self.idle = asyncio.Event()
        self.idle.set()

    def enter(self) -> None:
        self.running += 1
        self.idle.clear()

    def leave(self) -> None:
        self.running -= 1
        if self.running <= 0:
            self.running = 0
            self.idle.set()

    async def wait(self, most: float) -> float:
        """Until no robot request is in progress, at most ``most`` seconds; the seconds waited."""
        if not self.running:
            return 0.0
        started = time.monotonic()
        try:
            await asyncio.wait_for(self.idle.wait(), most)
        except TimeoutError:
            pass
        return time.monotonic() - started


@dataclass
class BodyBudget:
    """Body bytes held by requests whose bodies are still streaming in, against a cap."""

    cap: int
    held: int = 0

    def take(self, size: int) -> None:
        if self.held + size > self.cap:
            raise Refusal(503, "the service is busy reading other bodies; retry shortly",
                          ((b"retry-after", b"1"), (b"connection", b"close")))
        self.held += size

    def give(self, size: int) -> None:
        self.held = max(0, self.held - size)


async def check_body(body: bytes, limits: Limits) -> None:
    """Refuse (400) a body too deep, with too many values or too long a number: measured on the
    loop when small, in a worker thread when it would take more than about a millisecond."""
    if not body:
        return
    from oracle.service import bodyshape  # numpy: not on the command line's `--help` path (serve's Limits)

    shape = bodyshape.measure(body) if len(body) < OFF_LOOP_BYTES else await asyncio.to_thread(bodyshape.measure, body)
    reason = bodyshape.refusal(shape, limits.json_depth, limits.json_values, limits.number_chars, limits.string_bytes)
    if reason is not None:
        raise Refusal(400, reason)


def _replay(body: bytes, receive: Any) -> Any:
    """A receive that hands the app the body already read, then the client's later messages
    (its disconnect)."""
    sent = [False]

    async def replay() -> dict[str, Any]:
        if not sent[0]:
            sent[0] = True
            return {"type": "http.request", "body": body, "more_body": False}
        return dict(await receive())

    return replay


async def _answer(send: Any, refusal: Refusal) -> None:
    body = json.dumps({"error": str(refusal)}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()), *refusal.headers]
    await send({"type": "http.response.start", "status": refusal.status, "headers": headers})
    await send({"type": "http.response.body", "body": body})


def _with_safe_headers(headers: Any) -> list[tuple[bytes, bytes]]:
    out = [(bytes(k), bytes(v)) for k, v in headers]
    names = {k.lower() for k, _ in out}
    out.extend(pair for pair in SAFE_HEADERS if pair[0] not in names)
    for i, (key, value) in enumerate(out):
        if key.lower() == b"content-security-policy":
            if b"frame-ancestors" not in value:
                out[i] = (key, value + b"; " + FRAME_POLICY.encode())
            break
    else:
        out.append((b"content-security-policy", FRAME_POLICY.encode()))
    return out


__all__ = ["Guard", "LOOPBACK_HOSTS", "Limits", "OPEN_PATHS", "Refusal", "allowed_hosts", "check_body"]
