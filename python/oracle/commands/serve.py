"""``python -m oracle serve``: the live service for the robot framework and the tablet page."""

from __future__ import annotations

import argparse
import os
import stat
from pathlib import Path

from oracle.commands.common import METHOD, ONTOLOGY_OPTIONS, SETTINGS, STORE, add_options, ontology_from
from oracle.errors import NeemOracleError
from oracle.service.guard import Limits

#: A token shorter than this, or made of fewer different characters, is refused.
TOKEN_MIN_LENGTH = 12
TOKEN_MIN_DISTINCT = 6


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("serve", help="run the robot's live service and the tablet page (HTTP, loopback)")
    STORE.add(parser)
    parser.add_argument("--neem", metavar="ID", help="the page's NEEM and the default for /api/prolog (default: the newest)")
    parser.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1; any other needs a token)")
    parser.add_argument("--port", type=int, default=8765, help="TCP port (default 8765)")
    parser.add_argument("--token-file", type=Path,
                        help="read the token every request must present from this file (0600; needed beyond loopback)")
    parser.add_argument("--token", help="the token itself (visible to other local users in /proc: prefer --token-file)")
    parser.add_argument("--allowed-host", action="append", default=[], metavar="NAME",
                        help="a Host name the service answers to besides its address and localhost (repeatable)")
    parser.add_argument("--allow-prolog-writes", action="store_true",
                        help="let /api/prolog run kb_project/kb_unproject (needs a token; default: read-only)")
    parser.add_argument("--query-seconds", type=float, default=Limits.query_seconds, metavar="S",
                        help=f"longest a /api/prolog query may run (default {Limits.query_seconds})")
    parser.add_argument("--max-body", type=int, default=Limits.body_bytes, metavar="BYTES",
                        help=f"largest request body (default {Limits.body_bytes})")
    add_options(parser, METHOD, SETTINGS)
    writes = parser.add_mutually_exclusive_group()
    writes.add_argument("--write-behind", action="store_true",
                        help="answer a situation before its NEEM write is committed (faster; a kill can lose the"
                             " situation just answered)")
    writes.add_argument("--sync-writes", action="store_true",
                        help="answer a situation only after its NEEM write is committed (the default)")
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

    import uvicorn

    from oracle.commands.common import method_from, settings_from
    from oracle.service import build_context, is_loopback
    from oracle.service.app import create_app

    token = read_token(args)
    if token is None and not is_loopback(args.host):
        raise NeemOracleError(f"--host {args.host}: binding beyond loopback needs --token or --token-file")
    if args.allow_prolog_writes and token is None:
        raise NeemOracleError("--allow-prolog-writes needs --token-file (a page could write the NEEM otherwise)")
    if not 0 < args.query_seconds <= 60:
        raise NeemOracleError(f"--query-seconds {args.query_seconds}: expected more than 0 and at most 60")
    if not 1024 <= args.max_body <= 64 << 20:
        raise NeemOracleError(f"--max-body {args.max_body}: expected 1024 to {64 << 20} bytes")
    if not 1 <= args.port <= 65535:
        raise NeemOracleError(f"--port {args.port}: expected 1-65535")
    settings = settings_from(args.settings)
    method_from(args)  # an unknown --method is refused before the store is opened
    ontology = ontology_from(args)
    limits = Limits(query_seconds=args.query_seconds, body_bytes=args.max_body)
    ctx = build_context(args.store, ontology, settings, args.neem, token, write_behind=args.write_behind,
                        method=method_from(args), host=args.host, extra_hosts=tuple(args.allowed_host),
                        limits=limits, prolog_writes=args.allow_prolog_writes)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(message)s")
    location = ctx.thread.call(lambda: ctx.engine.store.location)
    print(f"serving {location} on http://{args.host}:{args.port}/ (API docs at /docs); Ctrl-C stops", flush=True)
    os.umask(0o077)  # anything the service writes (a new SQLite file's journal) stays private
    try:
        # an open event stream must not hold a stop (Ctrl-C, SIGTERM) for ever
        # limit_concurrency: connections beyond it get 503 at once (the guard's in-flight limit is
        # below it); timeout_keep_alive closes idle connections, so a slow crowd cannot hold sockets
        uvicorn.run(create_app(ctx), host=args.host, port=args.port, access_log=False, log_level="warning",
                    server_header=False, timeout_graceful_shutdown=5, limit_concurrency=limits.in_flight + 16,
                    timeout_keep_alive=int(limits.keep_alive_seconds), backlog=128)
    finally:
        ctx.thread.close()
    return 0
