"""Live events for the page and the robot framework: Server-Sent Events from an in-process hub.

The hub lives on the event loop (publish and subscribe are called there); each subscriber
gets a bounded queue, and a subscriber too slow to keep up loses its oldest events rather
than holding memory for ever. Events carry the same JSON the API answered.
"""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from typing import Any

#: Events a subscriber may lag behind before the oldest are dropped.
QUEUE_SIZE = 256
#: A comment line this often keeps proxies and the browser from closing an idle stream.
KEEPALIVE_S = 15.0
#: How soon a browser reconnects a dropped stream (the page then fetches the latest ranking).
RETRY_MS = 2000


#: What ``close`` puts in a subscriber's queue: the stream ends.
_END = None


@dataclass(frozen=True)
class Event:
    kind: str  # situation | action | perception | choice | neem
    neem: str
    data: dict[str, Any] = field(default_factory=dict)

    def sse(self, number: int) -> str:
        body = json.dumps({"neem": self.neem, **self.data}, separators=(",", ":"))
        return f"id: {number}\nevent: {self.kind}\ndata: {body}\n\n"


class EventHub:
    def __init__(self) -> None:
        self._subscribers: set[tuple[asyncio.Queue[tuple[int, Event] | None], str | None]] = set()
        self._number = 0

    @property
    def subscribers(self) -> int:
        return len(self._subscribers)

    def close(self) -> None:
        """End every stream now (the service is stopping): each subscriber gets the end mark."""
        for queue, _ in list(self._subscribers):
            if queue.full():
                queue.get_nowait()
            queue.put_nowait(_END)

    def publish(self, event: Event) -> None:
        self._number += 1
        for queue, neem in list(self._subscribers):
            if neem is not None and neem != event.neem:
                continue
            if queue.full():
                queue.get_nowait()
            queue.put_nowait((self._number, event))

    async def stream(self, neem: str | None, until: asyncio.Event | None = None) -> AsyncIterator[str]:
        """SSE text for one subscriber, filtered to ``neem`` (None: every NEEM)."""
        queue: asyncio.Queue[tuple[int, Event] | None] = asyncio.Queue(QUEUE_SIZE)
        entry = (queue, neem)
        self._subscribers.add(entry)
        try:
            yield f"retry: {RETRY_MS}\n: connected\n\n"
            while until is None or not until.is_set():
                try:
                    item = await asyncio.wait_for(queue.get(), KEEPALIVE_S)
                except TimeoutError:
                    yield ": keep-alive\n\n"
                    continue
                if item is None:
                    return
                number, event = item
                yield event.sse(number)
        finally:
            self._subscribers.discard(entry)
