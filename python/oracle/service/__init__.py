"""The robot's live service (``python -m oracle serve``): one process holding the store, the
Prolog engine and a fitted predictor per NEEM, answering the robot framework over JSON/HTTP
and the user on the tablet page. See docs/service.md."""

from __future__ import annotations

import ipaddress
import socket
from typing import TYPE_CHECKING, Any

from oracle.errors import NeemOracleError

if TYPE_CHECKING:  # the package is imported by every command's --help: keep it light
    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import OdbOntology
    from oracle.service.app import Context
    from oracle.service.guard import Limits


def is_loopback(host: str) -> bool:
    """True for 127.0.0.0/8, ::1 and names that resolve only to them (localhost)."""
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        pass
    try:
        addresses = {str(info[4][0]) for info in socket.getaddrinfo(host, None)}
    except OSError:
        return False
    return bool(addresses) and all(ipaddress.ip_address(a.split("%")[0]).is_loopback for a in addresses)


def build_context(store_spec: str | None, ontology: OdbOntology, settings: Hyperparameters, neem: str | None = None,
                  token: str | None = None, write_behind: bool = False, method: str | None = None,
                  host: str = "127.0.0.1", extra_hosts: tuple[str, ...] = (), limits: Limits | None = None,
                  prolog_writes: bool = False, prior: str | None = None) -> Context:
    """Open the store on the engine thread (its connection belongs there) and check ``neem``;
    sessions fit the predictor ``method`` (default: the one ``rank`` uses). ``host`` is the bound
    address: with ``extra_hosts`` it makes the Host names the service answers to. ``prior``: the
    shared prior's file the sessions rank with (None: the store's own if it has one; 'none': none)."""
    from oracle.algorithm.predictors import DEFAULT
    from oracle.service.app import Context
    from oracle.service.engine import Engine, EngineThread
    from oracle.service.guard import Limits, allowed_hosts
    from oracle.service.queries import QueryProcess
    from oracle.store import open_store

    limits = limits or Limits()

    thread = EngineThread()

    def start() -> Engine:
        from oracle.algorithm.prior import find_prior

        store = open_store(store_spec)
        try:
            shared = find_prior(prior, store.location, ontology)
        except NeemOracleError:
            store.close()
            raise
        engine = Engine(store, ontology, settings, method or DEFAULT, limits, shared)
        if neem is not None:
            engine.session(neem)  # NotFound now rather than on the first request
        return engine

    try:
        engine = thread.call(start)
    except NeemOracleError:
        thread.close()
        raise
    from oracle.service.groupcommit import GroupCommit

    thread.group = GroupCommit(engine.store, thread.submit, engine.sessions.clear)
    queries = None if prolog_writes else QueryProcess(store_spec, ontology)
    return Context(engine=engine, thread=thread, default_neem=neem, token=token, write_behind=write_behind,
                   allowed_hosts=allowed_hosts(host, extra_hosts), limits=limits, prolog_writes=prolog_writes,
                   query_process=queries)


__all__ = ["build_context", "is_loopback"]


def boot(ctx: Context, app: Any = None) -> None:
    """What ``serve`` does once before it listens, so that the first answers pay only for their
    NEEM: the engine's warm-up (``Engine.warm_up``: Prolog's modules, the words, the question
    forms), one request through ``app`` in process (``GET /api/health``: Starlette builds its
    middleware stack on its first call, ~30 ms), then one full collection and every object alive
    frozen out of the collector's view (``gc.freeze``): the boot's many long-lived objects would
    otherwise be scanned by the first full collection, which falls in one of the first requests."""
    import gc

    ctx.thread.call(ctx.engine.warm_up)
    if app is not None:
        _first_request(app)
    gc.collect()
    gc.freeze()


def _first_request(app: Any) -> int:
    """``GET /api/health`` through the ASGI ``app`` on a loop of its own; its status."""
    import asyncio

    sent: list[dict[str, Any]] = []
    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "GET", "scheme": "http",
             "path": "/api/health", "raw_path": b"/api/health", "query_string": b"", "root_path": "",
             "headers": [(b"host", b"127.0.0.1")], "client": ("127.0.0.1", 0), "server": ("127.0.0.1", 0)}

    async def receive() -> dict[str, Any]:
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message: dict[str, Any]) -> None:
        sent.append(message)

    asyncio.run(app(scope, receive, send))
    return int(sent[0].get("status", 0)) if sent else 0
