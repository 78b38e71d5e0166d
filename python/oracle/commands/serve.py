"""``python -m oracle serve``: the live service for the robot framework and the tablet page."""

from __future__ import annotations

import argparse
import os
import stat
from pathlib import Path

from oracle.commands.common import ONTOLOGY_OPTIONS, SETTINGS, STORE, add_options, ontology_from
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("serve", help="run the robot's live service and the tablet page (HTTP, loopback)")
    STORE.add(parser)
    parser.add_argument("--neem", metavar="ID", help="the page's NEEM and the default for /api/prolog (default: the newest)")
    parser.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1; any other needs a token)")
    parser.add_argument("--port", type=int, default=8765, help="TCP port (default 8765)")
    parser.add_argument("--token", help="token every request must present (needed to bind beyond loopback)")
    parser.add_argument("--token-file", type=Path, help="read the token from this file (must be private, 0600)")
    add_options(parser, SETTINGS)
    parser.add_argument("--sync-writes", action="store_true",
                        help="answer a situation only after its NEEM write (default: answer first, write next)")
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
        return text
    if args.token is not None and len(args.token) < 12:
        raise NeemOracleError("--token: use at least 12 characters")
    return args.token


def run(args: argparse.Namespace) -> int:
    import logging

    import uvicorn

    from oracle.commands.common import settings_from
    from oracle.service import build_context, is_loopback
    from oracle.service.app import create_app

    token = read_token(args)
    if token is None and not is_loopback(args.host):
        raise NeemOracleError(f"--host {args.host}: binding beyond loopback needs --token or --token-file")
    if not 1 <= args.port <= 65535:
        raise NeemOracleError(f"--port {args.port}: expected 1-65535")
    settings = settings_from(args.settings)
    ontology = ontology_from(args)
    ctx = build_context(args.store, ontology, settings, args.neem, token, write_behind=not args.sync_writes)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(message)s")
    location = ctx.thread.call(lambda: ctx.engine.store.location)
    print(f"serving {location} on http://{args.host}:{args.port}/ (API docs at /docs); Ctrl-C stops", flush=True)
    os.umask(0o077)  # anything the service writes (a new SQLite file's journal) stays private
    try:
        # an open event stream must not hold a stop (Ctrl-C, SIGTERM) for ever
        uvicorn.run(create_app(ctx), host=args.host, port=args.port, access_log=False, log_level="warning",
                    server_header=False, timeout_graceful_shutdown=5)
    finally:
        ctx.thread.close()
    return 0
