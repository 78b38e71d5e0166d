"""Where a door's queries run: the Prolog that answers ``protocol.Ask``.

Both doors ask json_query/2 (prolog/json_query.pl) for rosprolog_json's solutions, so the
read-only allow-list, the time limit and the stack limit are those of ``/api/prolog``; writes
run only where the user allowed them. The ``rosprolog`` command asks a bridge of its own, on the
one thread its Prolog engine lives on; the live service's rosbridge route asks exactly where
``/api/prolog`` asks (its query process, or its engine thread when it allows writes).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from oracle.errors import NeemOracleError
from oracle.rosprolog.protocol import Ask, Page, QueryFailed, page_of, request

if TYPE_CHECKING:
    from oracle.bridge import Bridge
    from oracle.service.app import Context
    from oracle.service.engine import EngineThread


class OwnBridge:
    """A bridge over ``--store``/``--neem`` (the store's only NEEM when none is named), opened
    read-only unless ``writes``, asked on its engine thread."""

    def __init__(self, args: argparse.Namespace, writes: bool, seconds: float) -> None:
        from oracle.commands.target import connect
        from oracle.service.engine import EngineThread

        self.writes = writes
        self.seconds = seconds
        self.thread: EngineThread = EngineThread()
        self.bridge: Bridge = self.thread.call(lambda: connect(args, write=writes)[0])

    @property
    def neem(self) -> str:
        return str(self.bridge.neem_id)

    def ask(self, text: str, offset: int, limit: int) -> Page:
        from oracle.service.queries import ask

        query, bindings = request(text, self.writes)
        try:
            reply = self.thread.call(ask, self.bridge, query, bindings, offset, limit, self.seconds, self.writes)
        except NeemOracleError as error:
            raise QueryFailed(str(error)) from None
        return page_of(reply)

    def close(self) -> None:
        self.thread.call(self.bridge.close)


def service_ask(ctx: Context, neem: str) -> Ask:
    """The live service's way to ask about ``neem``: its query process (read-only) or, with
    ``--allow-prolog-writes``, its engine thread, both within ``--query-seconds``."""
    seconds = ctx.limits.query_seconds

    def ask(text: str, offset: int, limit: int) -> Page:
        query, bindings = request(text, ctx.prolog_writes)
        try:
            reply: dict[str, Any]
            if ctx.query_process is None:
                reply = ctx.thread.call(ctx.engine.prolog, neem, query, bindings, offset, limit, seconds, ctx.prolog_writes)
            else:
                reply = ctx.query_process.ask(neem, query, bindings, offset, limit, seconds)
        except NeemOracleError as error:
            raise QueryFailed(str(error)) from None
        return page_of(reply)

    return ask


__all__ = ["OwnBridge", "service_ask"]
