"""The service's connections: who may hold a socket, for how long, and how a refused body ends.

uvicorn's httptools protocol with three additions (serve runs uvicorn with ``http=`` this):

- a deadline on request headers: a connection that has not sent a request's headers
  ``limits.header_seconds`` after it opened (or after its last answer) is closed, so clients that
  send nothing or a byte at a time cannot hold sockets (uvicorn times out idle keep-alive
  connections only);
- connection limits, per client address and in all: a new connection beyond either closes the
  oldest idle one (no request in progress) of that address (or of any), so idle sockets cannot
  crowd out a robot that connects afresh; with none idle the newcomer is answered 503 and closed.
  uvicorn's own ``limit_concurrency`` answered every request 503 once 64 sockets were open,
  idle or not, which is how 70 idle sockets starved the robot;
- draining: when the guard answers before the body is in (413, 408) and closes, the rest of the
  body is read and dropped (at most ``limits.drain_bytes``, ``limits.drain_seconds``) after the
  answer and a half close, so a client that sends its whole body first reads the answer rather
  than a connection reset.

Slow bodies are the guard's (its body deadline); this module only sees sockets and bytes.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from oracle.service.guard import Limits

#: What a client over the connection limits reads before the socket closes.
_BUSY_BODY = b'{"error": "too many connections from this address; retry shortly"}'
BUSY = (b"HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/json\r\nretry-after: 1\r\n"
        b"connection: close\r\ncontent-length: %d\r\n\r\n%s" % (len(_BUSY_BODY), _BUSY_BODY))


@dataclass
class Crowd:
    """The open connections of one server, by client address (one per ``http_protocol`` call:
    no state outside the server it serves)."""

    limits: Limits
    by_peer: dict[str, set[Any]] = field(default_factory=dict)
    count: int = 0

    def join(self, peer: str, conn: Any) -> bool:
        """Admit ``conn`` from ``peer``, closing an idle connection to make room when a limit is
        reached; False when there is no room."""
        mine = self.by_peer.setdefault(peer, set())
        if len(mine) >= self.limits.peer_connections and not self._evict(mine):
            return False
        if self.count >= self.limits.connections and not self._evict(c for group in self.by_peer.values() for c in group):
            return False
        mine.add(conn)
        self.count += 1
        return True

    def leave(self, peer: str, conn: Any) -> None:
        mine = self.by_peer.get(peer)
        if mine is not None and conn in mine:
            mine.discard(conn)
            self.count -= 1
            if not mine:
                del self.by_peer[peer]

    def _evict(self, conns: Iterator[Any] | set[Any]) -> bool:
        """Close the connection idle the longest among ``conns``; False when none is idle."""
        idle = [c for c in conns if c.idle_since is not None]
        if not idle:
            return False
        oldest = min(idle, key=lambda c: c.idle_since)
        oldest.evict()
        return True


class _Transport:
    """The transport a request's cycle writes to: closing it after an early answer starts the
    drain instead (``Protocol.close_after_answer``); anything else goes to the real one."""

    def __init__(self, real: Any, on_close: Any) -> None:
        self._real = real
        self._on_close = on_close

    def close(self) -> None:
        self._on_close()

    def __getattr__(self, name: str) -> Any:
        return getattr(self._real, name)


def http_protocol(limits: Limits) -> Any:
    """The protocol class uvicorn runs each connection with (see the module docstring);
    ``"auto"`` without httptools (then none of the above holds)."""
    try:
        from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol
    except ImportError:
        return "auto"
    crowd = Crowd(limits)

    class Protocol(HttpToolsProtocol):
        _deadline: Any = None
        _peer = ""
        _admitted = False
        _drained: int | None = None  # bytes dropped so far while draining; None: not draining
        #: monotonic time since when no request is in progress (None: one is)
        idle_since: float | None = None

        def connection_made(self, transport: Any) -> None:
            super().connection_made(transport)
            self._peer = self.client[0] if self.client else ""
            if not crowd.join(self._peer, self):
                transport.write(BUSY)
                transport.close()
                return
            self._admitted = True
            self._arm(limits.header_seconds)

        def on_headers_complete(self) -> None:
            if self._drained is not None:
                return  # a request pipelined behind a refused body is not served
            self._disarm()
            self.idle_since = None
            super().on_headers_complete()
            if self.cycle is not None:
                setattr(self.cycle, "transport", _Transport(self.transport, self.close_after_answer))  # noqa: B010

        def on_response_complete(self) -> None:
            if self._drained is not None:
                return
            super().on_response_complete()
            if not self.pipeline and not self.transport.is_closing():
                self._arm(limits.header_seconds)

        def data_received(self, data: bytes) -> None:
            if self._drained is None:
                super().data_received(data)
                return
            self._drained += len(data)
            if self._drained > limits.drain_bytes:
                self.transport.close()

        def eof_received(self) -> None:
            if self._drained is not None:
                self.transport.close()  # the client has sent all it will: it can read the answer

        def connection_lost(self, exc: Exception | None) -> None:
            self._disarm()
            if self._admitted:
                crowd.leave(self._peer, self)
            super().connection_lost(exc)

        def close_after_answer(self) -> None:
            """The cycle closes the connection after its answer: drop the rest of a body the
            answer came before (bounded), after a half close that delivers the answer."""
            cycle = self.cycle
            if self.transport.is_closing() or cycle is None or not cycle.more_body or cycle.disconnected:
                self.transport.close()
                return
            self._drained = 0
            self.idle_since = time.monotonic()  # nothing left to serve: the first to make room
            self.flow.resume_reading()
            try:
                self.transport.write_eof()
            except (OSError, RuntimeError):
                self.transport.close()
                return
            self._arm(limits.drain_seconds)

        def evict(self) -> None:
            self._disarm()
            self.idle_since = None
            if not self.transport.is_closing():
                self.transport.close()

        def _arm(self, seconds: float) -> None:
            self._disarm()
            if self.idle_since is None and self._drained is None:
                self.idle_since = time.monotonic()
            self._deadline = self.loop.call_later(seconds, self._too_slow)

        def _disarm(self) -> None:
            if self._deadline is not None:
                self._deadline.cancel()
                self._deadline = None

        def _too_slow(self) -> None:
            self._deadline = None
            if not self.transport.is_closing():
                self.transport.close()

    return Protocol


__all__ = ["BUSY", "Crowd", "http_protocol"]
