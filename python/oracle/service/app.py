"""The ASGI application: configuration, the token check, error answers and offline docs.

Privacy (thesis 3.5): the service binds to loopback unless it has a token; with a token every
API call, the event stream and the page must present it (``Authorization: Bearer T``, or
``?token=T`` where a browser cannot set headers). There is no CORS: a page from elsewhere
cannot read the answers. Host names, origins, the token and the limits are checked by
guard.Guard before any handler runs (docs/security.md).
"""

from __future__ import annotations

import asyncio
import logging
from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from datetime import tzinfo
from typing import Any
from urllib.parse import parse_qs

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException

from oracle.errors import NeemOracleError
from oracle.service.explore_routes import close_explorer
from oracle.service.explore_routes import router as explore_router
from oracle.service.engine import Engine, EngineThread, NotFound, Overloaded, PrologRefused
from oracle.service.events import EventHub
from oracle.service.guard import STATIC_DOCS, Guard, Limits, allowed_hosts
from oracle.service.access import Access, AccessCheck
from oracle.service.queries import NoSuchNeem, QueryProcess
from oracle.service.page import Manner, render_token_page
from oracle.rosprolog.rosbridge import router as rosbridge_router
from oracle.service.past_routes import router as past_router
from oracle.service.routes import DuplicateNeem, router
from oracle.service.session import OutOfOrder
from oracle.words import TEXT, Lexicon, pick_lang
from oracle.timeline import display_zone

LOG = logging.getLogger("oracle.service")


@dataclass
class Context:
    """What every handler reaches through ``request.app.state.ctx``."""

    engine: Engine
    thread: EngineThread
    default_neem: str | None = None
    token: str | None = None
    write_behind: bool = False
    #: Host names the service answers to (guard.allowed_hosts of the bound address).
    allowed_hosts: frozenset[str] = field(default_factory=lambda: allowed_hosts("127.0.0.1"))
    limits: Limits = field(default_factory=Limits)
    #: /api/prolog may run `write` predicates (serve --allow-prolog-writes, which needs a token).
    prolog_writes: bool = False
    #: Prolog queries running now (at most limits.queries).
    queries: int = 0
    #: The process read-only queries run in (None: on the engine thread).
    query_process: QueryProcess | None = None
    hub: EventHub = field(default_factory=EventHub)
    stopping: asyncio.Event = field(default_factory=asyncio.Event)
    #: The zone the page shows times in (``serve --tz``; None: the machine's).
    zone: tzinfo = field(default_factory=lambda: display_zone(None))
    #: How the page confirms and undoes a choice (``serve --confirm``, ``--undo``).
    manner: Manner = field(default_factory=Manner)
    #: The page's words (oracle.words), read on first use.
    lexicon: Lexicon | None = None
    #: Per-user and read-only tokens (``serve --tokens``, oracle.service.access); None: only ``token``.
    access: Access | None = None


def create_app(ctx: Context) -> FastAPI:
    @asynccontextmanager
    async def lifespan(app: FastAPI) -> Any:
        yield
        ctx.stopping.set()  # ends the event streams so the server can stop
        close_explorer(app)  # its reader's thread and read-only connection
        # each NEEM's recording session ends as KnowRob's mem_episode_stop ends one
        await ctx.thread.run(ctx.engine.close)
        if ctx.query_process is not None:
            ctx.query_process.close()

    app = FastAPI(title="neem-oracle service", version="1", docs_url=None, redoc_url=None, lifespan=lifespan,
                  description="The robot's live NEEM logger and PreferenceOracle (docs/service.md).")
    app.state.ctx = ctx
    app.include_router(router)
    app.include_router(past_router)
    app.include_router(explore_router)
    app.include_router(rosbridge_router)  # KnowRob's roslibpy/roslibjs clients (docs/knowrob.md)
    _offline_docs(app)
    app.add_middleware(AccessCheck, ctx=ctx)  # inside the guard: a token's grant, once admitted
    app.add_middleware(Guard, ctx=ctx, token_page=_token_page)

    @app.exception_handler(NeemOracleError)
    async def domain_error(request: Request, error: NeemOracleError) -> JSONResponse:
        status = (404 if isinstance(error, (NotFound, NoSuchNeem)) else 409 if isinstance(error, (OutOfOrder, DuplicateNeem))
                  else 403 if isinstance(error, PrologRefused) else error.status if isinstance(error, Overloaded) else 400)
        return _error(status, str(error))

    @app.exception_handler(RequestValidationError)
    async def bad_request(request: Request, error: RequestValidationError) -> JSONResponse:
        first = error.errors()[0] if error.errors() else {}
        where = ".".join(str(p) for p in first.get("loc", ()) if p != "body") or "request"
        return _error(422, f"{where}: {first.get('msg', 'invalid')}")

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, error: StarletteHTTPException) -> JSONResponse:
        # unknown paths and methods answer in the same one-line form as every other refusal
        answer = _error(error.status_code, f"{request.method} {request.url.path}: {error.detail}")
        for name, value in (error.headers or {}).items():
            answer.headers[name] = value
        if error.status_code == 405:  # every method of every route on the path, not the first route's
            answer.headers["Allow"] = ", ".join(_methods(request.app, request.url.path))
        return answer

    @app.exception_handler(Exception)
    async def bug(request: Request, error: Exception) -> JSONResponse:
        LOG.error("internal error on %s: %s", _route(request), type(error).__name__)
        return _error(500, f"internal error ({type(error).__name__}); the service keeps running")

    return app


def _error(status: int, message: str) -> JSONResponse:
    line = message.strip().splitlines()[0] if message.strip() else "error"
    return JSONResponse({"error": line}, status_code=status)


def _methods(app: FastAPI, path: str) -> list[str]:
    from starlette.routing import Route

    found: set[str] = set()
    for route in [*app.routes, *router.routes]:  # the API's routes sit in an included router
        if isinstance(route, Route) and route.methods and route.path_regex.match(path):
            found.update(route.methods)
    return sorted(found)


def _route(request: Request) -> str:
    return getattr(request.scope.get("route"), "path", None) or "(no route)"


def _token_page(headers: dict[str, str], query: bytes) -> Response:
    from fastapi.responses import HTMLResponse

    asked = parse_qs(query.decode("latin-1"))
    lang = pick_lang(next(iter(asked.get("lang", [])), None), headers.get("accept-language"))
    html = render_token_page(lang, TEXT[lang], next(iter(asked.get("neem", [])), None))
    return HTMLResponse(html, status_code=401, headers={
        "Content-Security-Policy": "default-src 'none'; style-src 'self'; img-src 'self'; form-action 'self'; base-uri 'none'",
        "Cache-Control": "no-store"})


def _offline_docs(app: FastAPI) -> None:
    """Swagger UI 5 (it reads OpenAPI 3.1) from the fastapi-offline package's files: /docs
    works without a network."""
    from pathlib import Path

    from fastapi.openapi.docs import get_swagger_ui_html
    from fastapi.staticfiles import StaticFiles

    try:
        import fastapi_offline
    except ImportError:  # the schema stays at /openapi.json
        return
    app.mount(STATIC_DOCS, StaticFiles(directory=Path(fastapi_offline.__file__).parent / "static"), name="docs-static")

    @app.get("/docs", include_in_schema=False)
    async def docs() -> Response:
        return get_swagger_ui_html(openapi_url="/openapi.json", title="neem-oracle service",
                                   swagger_js_url=f"{STATIC_DOCS}/swagger-ui-bundle.js",
                                   swagger_css_url=f"{STATIC_DOCS}/swagger-ui.css",
                                   swagger_favicon_url=f"{STATIC_DOCS}/favicon.png")


__all__ = ["Context", "create_app"]
