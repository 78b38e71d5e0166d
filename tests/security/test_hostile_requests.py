"""Requests sent to stall the robot (issue 54): idle sockets, slow bodies, the worst 1 MiB bodies,
a client that sends its whole oversized body before reading. A real ``serve`` process for what
crosses sockets; the guard and the connection limits in-process for the rest. Timing figures are
``make bench`` (area flood); these tests assert the behaviour.
"""

from __future__ import annotations

import asyncio
import shutil
import socket
import time
from collections.abc import Iterator
from types import SimpleNamespace
from typing import Any

import pytest

from oracle.benchmarks.flood import worst_bodies
from oracle.benchmarks.security import Service, call, start, stop
from oracle.service.connections import Crowd
from oracle.service.guard import Guard, Limits, allowed_hosts
from tests.service.conftest import AVAILABLE, ROUTINE, at

needs_swipl = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


@pytest.fixture(scope="module")
def served(tmp_path_factory) -> Iterator[Service]:
    service = start(tmp_path_factory.mktemp("hostile") / "s.sqlite")
    try:
        assert call(service.url, "/api/neems", {"user": "ada", "neem": "ada"})[0] == 201
        for i, action in enumerate(ROUTINE):
            assert call(service.url, "/api/neems/ada/actions", {"call": action, "begin": at(0, 10 * i)})[0] == 200
        yield service
    finally:
        stop(service)


def situations(service: Service, n: int, first: int) -> list[int]:
    return [call(service.url, "/api/neems/ada/situation", {"available": AVAILABLE, "at": at(1, first + i)}, timeout=60)[0]
            for i in range(n)]


def _post_head(length: int | None, path: str = "/api/neems/ada/situation") -> bytes:
    framing = b"Transfer-Encoding: chunked" if length is None else b"Content-Length: %d" % length
    return b"POST " + path.encode() + b" HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n" + framing + b"\r\n\r\n"


@needs_swipl
def test_idle_sockets_beyond_every_limit_do_not_turn_the_robot_away(served):
    """300 sockets that send nothing (more than one client may hold): the robot's situations,
    each on a new connection, are all answered 200; idle sockets are closed to make room."""
    idle = [socket.create_connection(("127.0.0.1", served.port), timeout=10) for _ in range(300)]
    try:
        assert situations(served, 10, 0) == [200] * 10
        closed = 0
        for sock in idle:
            sock.setblocking(False)
            try:
                closed += sock.recv(1024) == b""
            except BlockingIOError:
                pass
            except OSError:
                closed += 1
        assert closed >= 300 - Limits.peer_connections
    finally:
        for sock in idle:
            sock.close()


@needs_swipl
def test_slow_bodies_do_not_turn_the_robot_away(served):
    """80 requests whose bodies come a byte at a time (more than the 64 that may run at once):
    they hold no request slot while their bodies stream in, and the robot is answered."""
    slow = []
    try:
        for _ in range(80):
            sock = socket.create_connection(("127.0.0.1", served.port), timeout=10)
            sock.sendall(_post_head(1000) + b"{")
            slow.append(sock)
        assert situations(served, 10, 100) == [200] * 10
        slow[0].settimeout(Limits.body_seconds + 10)
        assert slow[0].recv(1024).startswith(b"HTTP/1.1 408")  # dropped at the body deadline
    finally:
        for sock in slow:
            sock.close()


@needs_swipl
@pytest.mark.parametrize("chunked", [False, True])
def test_a_client_that_sends_its_whole_body_first_reads_the_413(served, chunked):
    """The whole of a 3 MiB body sent before anything is read (as most HTTP clients do): the
    rest of the body is drained after the answer, so the client reads the 413, not a reset."""
    body = b"[" + b"1," * (3 << 19) + b"1]"
    with socket.create_connection(("127.0.0.1", served.port), timeout=30) as sock:
        sock.sendall(_post_head(None if chunked else len(body)))
        if chunked:
            for i in range(0, len(body), 1 << 16):
                piece = body[i:i + (1 << 16)]
                sock.sendall(b"%x\r\n" % len(piece) + piece + b"\r\n")
            sock.sendall(b"0\r\n\r\n")
        else:
            sock.sendall(body)
        answer = b""
        while b"\r\n\r\n" not in answer:
            got = sock.recv(4096)
            if not got:
                break
            answer += got
    assert answer.startswith(b"HTTP/1.1 413"), answer[:200]


@needs_swipl
def test_the_worst_bodies_are_refused_and_the_service_answers_on(served):
    """Each worst-shaped 1 MiB body (flood.worst_bodies: escapes, brackets, values, keys, long
    numbers...) gets a 4xx, never a 5xx or a hang; the robot is answered after them."""
    import urllib.error
    import urllib.request

    statuses = {}
    for name, body in worst_bodies().items():
        request = urllib.request.Request(served.url + "/api/neems/ada/situation", data=body,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=60) as response:
                statuses[name] = response.status
        except urllib.error.HTTPError as error:
            statuses[name] = error.code
    assert all(status in (400, 413, 422) for status in statuses.values()), statuses
    assert statuses["escaped quotes"] == 422 and statuses["open brackets"] == 400  # parsed in linear time, then refused
    assert situations(served, 3, 200) == [200] * 3


class _Conn:
    def __init__(self, idle_since: float | None) -> None:
        self.idle_since = idle_since
        self.evicted = False

    def evict(self) -> None:
        self.evicted = True
        self.idle_since = None


def test_a_full_crowd_makes_room_by_closing_the_longest_idle_connection():
    crowd = Crowd(Limits(peer_connections=3, connections=5))
    busy, old, new = _Conn(None), _Conn(1.0), _Conn(2.0)
    for conn in (busy, old, new):
        assert crowd.join("10.0.0.1", conn)
    assert crowd.join("10.0.0.1", _Conn(None)) and old.evicted and not new.evicted and not busy.evicted
    crowd.leave("10.0.0.1", old)  # its close, as connection_lost reports it
    assert crowd.join("10.0.0.2", _Conn(None)) and crowd.join("10.0.0.2", _Conn(None))  # another client has its own room
    assert crowd.join("10.0.0.3", _Conn(None)) and new.evicted  # all 5 taken: the one idle connection made room
    crowd.leave("10.0.0.1", new)
    assert crowd.count == 5 and not crowd.join("10.0.0.4", _Conn(None))  # all busy: the newcomer is turned away


def test_the_robot_routes_keep_slots_no_other_request_may_take():
    """With 4 slots and 2 reserved, two slow /api/prolog requests fill what others may take: a
    third is refused 503, while the robot's situation and action posts still get through."""
    limits = Limits(in_flight=4, robot_reserve=2)
    ctx = SimpleNamespace(limits=limits, allowed_hosts=allowed_hosts("127.0.0.1"), token=None)
    release = asyncio.Event()

    async def app(scope: Any, receive: Any, send: Any) -> None:
        if scope["path"] == "/api/prolog":
            await release.wait()
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    guard = Guard(app, ctx)

    async def request(path: str) -> int:
        statuses: list[int] = []

        async def receive() -> dict[str, Any]:
            return {"type": "http.request", "body": b"{}", "more_body": False}

        async def send(message: dict[str, Any]) -> None:
            if message["type"] == "http.response.start":
                statuses.append(message["status"])

        scope = {"type": "http", "method": "POST", "path": path, "headers": [(b"host", b"127.0.0.1")], "query_string": b""}
        await guard(scope, receive, send)
        return statuses[0]

    async def scenario() -> list[int]:
        held = [asyncio.create_task(request("/api/prolog")) for _ in range(2)]
        await asyncio.sleep(0.01)
        got = [await request("/api/prolog"), await request("/api/neems/ada/situation"),
               await request("/api/neems/ada/actions")]
        release.set()
        got += await asyncio.gather(*held)
        return got

    assert asyncio.run(scenario()) == [503, 200, 200, 200, 200]


def test_bodies_streaming_in_share_a_byte_budget():
    """Bodies that have not come whole hold at most ``buffered_bytes`` together: one more is
    refused 503 (with Retry-After), and a small one (declared under ``small_body``) still passes."""
    limits = Limits(buffered_bytes=100, small_body=10, body_bytes=1000)
    ctx = SimpleNamespace(limits=limits, allowed_hosts=allowed_hosts("127.0.0.1"), token=None)

    async def app(scope: Any, receive: Any, send: Any) -> None:
        await receive()
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b""})

    guard = Guard(app, ctx)
    stalled = asyncio.Event()

    async def request(body: bytes, stall: bool) -> int:
        statuses: list[int] = []
        sent = [False]

        async def receive() -> dict[str, Any]:
            if not sent[0]:
                sent[0] = True
                return {"type": "http.request", "body": body, "more_body": stall}
            await stalled.wait()
            return {"type": "http.request", "body": b"", "more_body": False}

        async def send(message: dict[str, Any]) -> None:
            if message["type"] == "http.response.start":
                statuses.append(message["status"])

        headers = [(b"host", b"127.0.0.1"), (b"content-length", str(len(body) + (5 if stall else 0)).encode())]
        await guard({"type": "http", "method": "POST", "path": "/x", "headers": headers, "query_string": b""}, receive, send)
        return statuses[0]

    async def scenario() -> list[int]:
        first = asyncio.create_task(request(b"[" + b" " * 80, True))  # holds 81 bytes, waiting for the rest
        await asyncio.sleep(0.01)
        got = [await request(b"[" + b" " * 30, True), await request(b"[]", False)]
        stalled.set()
        got.append(await first)
        return got

    assert asyncio.run(scenario()) == [503, 200, 200]
    assert guard.budget.held == 0


def test_a_large_body_waits_while_the_robot_is_served():
    """While a robot's situation is being answered, a large body is held back (up to 50 ms a
    step): it reaches its handler after the robot's answer; the robot's own request waits for
    nobody."""
    from oracle.service.guard import OFF_LOOP_BYTES

    ctx = SimpleNamespace(limits=Limits(), allowed_hosts=allowed_hosts("127.0.0.1"), token=None)
    order: list[str] = []
    robot_may_finish = asyncio.Event()

    async def app(scope: Any, receive: Any, send: Any) -> None:
        order.append(scope["path"])
        if scope["path"].endswith("/situation"):
            await robot_may_finish.wait()
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b""})
        order.append("done " + scope["path"])

    guard = Guard(app, ctx)

    async def request(path: str, body: bytes) -> None:
        pieces = [body[i:i + (64 << 10)] for i in range(0, len(body), 64 << 10)]
        messages = [{"type": "http.request", "body": p, "more_body": k < len(pieces) - 1} for k, p in enumerate(pieces)]

        async def receive() -> dict[str, Any]:
            return messages.pop(0) if messages else {"type": "http.disconnect"}

        async def send(message: dict[str, Any]) -> None:
            pass

        headers = [(b"host", b"127.0.0.1"), (b"content-length", str(len(body)).encode())]
        await guard({"type": "http", "method": "POST", "path": path, "headers": headers, "query_string": b""}, receive, send)

    async def scenario() -> None:
        robot = asyncio.create_task(request("/api/neems/ada/situation", b'{"available": ["pick(red_mug)"]}'))
        await asyncio.sleep(0.01)
        strings = b",".join([b'"' + b"a" * 1000 + b'"'] * (OFF_LOOP_BYTES // 500))  # about twice OFF_LOOP_BYTES
        large = asyncio.create_task(request("/api/prolog", b'{"query": "X = 1", "bindings": {"X": [' + strings + b"]}}"))
        await asyncio.sleep(0.03)  # less than one step's wait (guard.ROBOT_FIRST_SECONDS)
        assert order == ["/api/neems/ada/situation"]  # the large body is held while the robot is served
        robot_may_finish.set()
        await asyncio.gather(robot, large)

    asyncio.run(scenario())
    assert order == ["/api/neems/ada/situation", "done /api/neems/ada/situation", "/api/prolog", "done /api/prolog"]
