"""``python -m oracle serve``: the live service for the robot framework and the tablet page."""

from __future__ import annotations

import argparse
import os
import stat
from collections.abc import Callable
from pathlib import Path
from typing import Any

from oracle.commands.common import METHOD, ONTOLOGY_OPTIONS, SETTINGS, STORE, add_options, ontology_from
from oracle.errors import NeemOracleError
from oracle.service.guard import Limits

#: A token shorter than this, or made of fewer different characters, is refused.
TOKEN_MIN_LENGTH = 12
TOKEN_MIN_DISTINCT = 6


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("serve", help="run the robot's live service and the tablet page (HTTP, loopback)")
    STORE.add(parser)
    parser.add_argument("--neem", metavar="ID", help="the page's NEEM and the default for /api/prolog (default: the newest)")
    parser.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1; any other needs a token)")
    parser.add_argument("--port", type=int, default=8765, help="TCP port (default 8765)")
    parser.add_argument("--token-file", type=Path,
                        help="read the token every request must present from this file (0600; needed beyond loopback)")
    parser.add_argument("--token", help="the token itself (visible to other local users in /proc: prefer --token-file)")
    parser.add_argument("--tokens", type=Path, metavar="FILE",
                        help="per-user and read-only tokens, one a line: 'TOKEN [user=ID] [read-only]' (0600; docs/security.md)")
    parser.add_argument("--allowed-host", action="append", default=[], metavar="NAME",
                        help="a Host name the service answers to besides its address and localhost (repeatable)")
    parser.add_argument("--allow-prolog-writes", action="store_true",
                        help="let /api/prolog run kb_project/kb_unproject (needs a token; default: read-only)")
    parser.add_argument("--query-seconds", type=float, default=Limits.query_seconds, metavar="S",
                        help=f"longest a /api/prolog query may run (default {Limits.query_seconds})")
    parser.add_argument("--max-body", type=int, default=Limits.body_bytes, metavar="BYTES",
                        help=f"largest request body (default {Limits.body_bytes})")
    add_options(parser, METHOD, SETTINGS)
    parser.add_argument("--prior", metavar="PRIOR.json",
                        help="rank with this shared prior ('prior build'; default: the store's own, STORE.prior.json "
                             "beside a SQLite store, if there is one; 'none': without)")
    writes = parser.add_mutually_exclusive_group()
    writes.add_argument("--write-behind", action="store_true",
                        help="answer a situation before its NEEM write is committed (faster; a kill can lose the"
                             " situation just answered)")
    writes.add_argument("--sync-writes", action="store_true",
                        help="answer a situation only after its NEEM write is committed (the default)")
    parser.add_argument("--tz", metavar="ZONE", help="the zone the page shows times in, e.g. Europe/Berlin (default: the machine's)")
    parser.add_argument("--confirm", choices=("tap", "dwell"), default="tap",
                        help="how the page confirms a choice: a second tap on Yes, or dwelling (default tap)")
    parser.add_argument("--dwell", type=float, default=3.0, metavar="S", help="seconds a dwell takes to confirm (default 3)")
    parser.add_argument("--undo", type=float, default=5.0, metavar="S",
                        help="seconds a confirmed choice can be undone before it reaches the robot (default 5)")
    parser.add_argument("--scan", choices=("off", "one", "two"), default="off",
                        help="the page's own switch scanning: one switch (it moves by itself, a press selects) or two"
                             " (Space moves, Enter selects) (default off)")
    parser.add_argument("--scan-speed", type=float, default=1.5, metavar="S",
                        help="with --scan one: seconds the highlight rests on each button (default 1.5)")
    parser.add_argument("--repeat-filter", type=float, default=0.5, metavar="S",
                        help="a second hit within S seconds of one that counted changes nothing (default 0.5; 0: off)")
    parser.add_argument("--gaze", type=float, default=0.0, metavar="S",
                        help="a pointer or eye gaze resting S seconds on a button selects it (default 0: off)")
    add_options(parser, *ONTOLOGY_OPTIONS)
    parser.set_defaults(handler=run)


def read_token(args: argparse.Namespace) -> str | None:
    if args.token is not None and args.token_file is not None:
        raise NeemOracleError("give --token or --token-file, not both")
    if args.token_file is not None:
        try:
            mode = args.token_file.stat().st_mode
            text = args.token_file.read_text(encoding="utf-8").strip()
        except OSError as error:
            raise NeemOracleError(f"--token-file {args.token_file}: cannot read ({error.strerror})") from None
        if mode & (stat.S_IRWXG | stat.S_IRWXO):
            raise NeemOracleError(f"--token-file {args.token_file}: others can read it; chmod 600 it first")
        if not text:
            raise NeemOracleError(f"--token-file {args.token_file}: the file is empty")
        return strong_token(text, f"--token-file {args.token_file}")
    return None if args.token is None else strong_token(args.token, "--token")


def strong_token(token: str, where: str) -> str:
    """The one rule for a token, however it is given: long enough and not a repeated pattern
    (``python -c 'import secrets; print(secrets.token_urlsafe(24))'`` makes a good one)."""
    if len(token) < TOKEN_MIN_LENGTH:
        raise NeemOracleError(f"{where}: the token has {len(token)} characters; use at least {TOKEN_MIN_LENGTH}")
    if len(set(token)) < TOKEN_MIN_DISTINCT:
        raise NeemOracleError(f"{where}: the token has only {len(set(token))} different characters; use a random one")
    if any(ch.isspace() for ch in token):
        raise NeemOracleError(f"{where}: the token holds white space")
    return token


def run(args: argparse.Namespace) -> int:
    import logging

    from oracle.commands.common import method_from, settings_from
    from oracle.service import boot, build_context, is_loopback
    from oracle.service.app import create_app
    from oracle.service.page import Manner
    from oracle.timeline import TimeValueError, display_zone

    token = read_token(args)
    access = None
    if args.tokens is not None:
        from oracle.service.access import read_tokens

        access = read_tokens(args.tokens, strong_token)
    if token is None and access is None and not is_loopback(args.host):
        raise NeemOracleError(f"--host {args.host}: binding beyond loopback needs --token or --token-file")
    if args.allow_prolog_writes and token is None:
        raise NeemOracleError("--allow-prolog-writes needs --token-file (a page could write the NEEM otherwise)")
    if not 0 < args.query_seconds <= 60:
        raise NeemOracleError(f"--query-seconds {args.query_seconds}: expected more than 0 and at most 60")
    if not 1024 <= args.max_body <= 64 << 20:
        raise NeemOracleError(f"--max-body {args.max_body}: expected 1024 to {64 << 20} bytes")
    if not 1 <= args.port <= 65535:
        raise NeemOracleError(f"--port {args.port}: expected 1-65535")
    if not (0 < args.dwell <= 60 and 0 <= args.undo <= 60):
        raise NeemOracleError("--dwell and --undo: expected seconds in (0, 60] and [0, 60]")
    if not (0.3 <= args.scan_speed <= 10 and 0 <= args.repeat_filter <= 5 and (args.gaze == 0 or 0.3 <= args.gaze <= 10)):
        raise NeemOracleError("--scan-speed and --gaze: expected 0.3 to 10 seconds (--gaze 0: off);"
                              " --repeat-filter: 0 to 5 seconds")
    try:
        zone = display_zone(args.tz)
    except TimeValueError as error:
        raise NeemOracleError(str(error)) from None
    listening = _listen(args.host, args.port)  # a busy port is one line, before anything is loaded
    settings = settings_from(args.settings)
    method_from(args)  # an unknown --method is refused before the store is opened
    ontology = ontology_from(args)
    limits = Limits(query_seconds=args.query_seconds, body_bytes=args.max_body)
    ctx = build_context(args.store, ontology, settings, args.neem, token, write_behind=args.write_behind,
                        method=method_from(args), host=args.host, extra_hosts=tuple(args.allowed_host),
                        limits=limits, prolog_writes=args.allow_prolog_writes, prior=args.prior)
    ctx.zone = zone
    ctx.access = access
    ctx.manner = Manner(confirm=args.confirm, dwell_s=args.dwell, undo_s=args.undo, scan=args.scan,
                        scan_s=args.scan_speed, filter_s=args.repeat_filter, gaze_s=args.gaze)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(message)s")
    location = ctx.thread.call(lambda: ctx.engine.store.location)
    app = create_app(ctx)
    boot(ctx, app)  # Prolog's modules, the words and the app's first request before the first question
    print(f"serving {location}; the page: {shown_link(args.host, args.port, token)} (API docs at /docs); Ctrl-C stops",
          flush=True)
    os.umask(0o077)  # anything the service writes (a new SQLite file's journal) stays private
    app.state.explore_replay = _explore_replay  # /explore's decisions; the product never imports the evaluation
    server = _server(app, ctx.hub.close, limits)
    try:
        server.run(sockets=[listening])
    except KeyboardInterrupt:  # uvicorn raises the Ctrl-C it held once it has stopped
        pass
    finally:
        ctx.thread.close()
    print("stopped", flush=True)
    return 0


def shown_link(host: str, port: int, token: str | None) -> str:
    """The page's address as ``serve`` prints it: the token only to a terminal (stdout is often a
    log, and logs are kept and shared); otherwise the address without it and the file (0600, in
    the user's private cache) that holds the whole link."""
    import sys

    from oracle.files import default_cache_dir, write_private_bytes

    if token is None or sys.stdout.isatty():
        return page_url(host, port, token)
    link = default_cache_dir() / f"serve-{port}.link"
    try:
        write_private_bytes(link, (page_url(host, port, token) + "\n").encode())
    except OSError:
        return f"{page_url(host, port, None)} (add ?token= with the service's token)"
    return f"{page_url(host, port, None)} (with its token: the link in {link}, 0600)"


def page_url(host: str, port: int, token: str | None) -> str:
    """The address to open on the tablet (with ``?token=`` when the service has one)."""
    from urllib.parse import quote

    if host in ("0.0.0.0", "::"):
        import socket

        host = socket.gethostname()
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}/" + (f"?token={quote(token, safe='')}" if token else "")


def _listen(host: str, port: int) -> Any:
    import socket

    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    # IPPROTO_TCP named: asyncio turns Nagle off (TCP_NODELAY) only on sockets that say so, and an
    # accepted socket inherits it; without it every answer waited ~40 ms for a delayed ACK
    sock = socket.socket(family, socket.SOCK_STREAM, socket.IPPROTO_TCP)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        sock.bind((host, port))
    except OSError as error:
        sock.close()
        raise NeemOracleError(f"--port {port}: cannot listen on {host}:{port} ({error.strerror or error}); "
                              "another service may be using it: pick another --port") from None
    sock.set_inheritable(True)
    return sock


def _explore_replay(*args: Any, **kwargs: Any) -> Any:
    """The replay /explore shows (oracle.evaluation.neem_replay), imported on its first use."""
    from oracle.evaluation.neem_replay import replay_neem

    return replay_neem(*args, **kwargs)


def _server(app: Any, on_stop: Callable[[], None], limits: Any) -> Any:
    """uvicorn's server, told to end the page's event streams as soon as it is asked to stop
    (an open stream would otherwise hold Ctrl-C for the graceful timeout). No limit_concurrency:
    it answered 503 to every request once that many sockets were open, idle or not; the http
    protocol limits connections per client and closes idle ones instead, and puts deadlines on
    headers (service.connections); timeout_keep_alive closes idle keep-alive connections."""
    import asyncio

    from oracle.service.connections import http_protocol

    import uvicorn

    class Server(uvicorn.Server):
        loop: asyncio.AbstractEventLoop | None = None

        async def serve(self, sockets: Any = None) -> None:
            self.loop = asyncio.get_running_loop()
            await super().serve(sockets)

        def handle_exit(self, sig: int, frame: Any) -> None:
            super().handle_exit(sig, frame)
            if self.loop is not None:
                self.loop.call_soon_threadsafe(on_stop)

    config = uvicorn.Config(app, access_log=False, log_level="warning", server_header=False, timeout_graceful_shutdown=1,
                            timeout_keep_alive=int(limits.keep_alive_seconds),
                            backlog=128, http=http_protocol(limits))
    return Server(config)
