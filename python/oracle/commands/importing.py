"""``import``: log action chains (JSONL) into a store, one NEEM per user."""

from __future__ import annotations

import argparse
from pathlib import Path

from oracle.commands.common import NUMBERS, ONTOLOGY_OPTIONS, STORE, add_options, ontology_from
from oracle.errors import NeemOracleError


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("import", help="log action chains (JSONL) as one NEEM per user")
    parser.add_argument("chains", type=Path, metavar="CHAINS.jsonl")
    add_options(parser, STORE, NUMBERS, *ONTOLOGY_OPTIONS)
    parser.add_argument("--replace", action="store_true", help="replace a user's NEEM instead of adding a new one")
    parser.add_argument("--session", action="store_true",
                        help="log into temporary NEEMs, wiping earlier temporary ones (keep them with 'persist')")
    parser.add_argument("--commit-every", type=int, default=100, metavar="N",
                        help="actions per transaction (1 = each action durable before the next; default 100)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.neem.importing import import_chains
    from oracle.store import open_store

    onto = ontology_from(args)
    with open_store(args.store, number_format=args.numbers) as store:
        report: dict[str, int] = {}
        try:
            import_chains(store, onto, args.chains, replace=args.replace, report=report, commit_every=args.commit_every,
                          session=args.session)
        except NeemOracleError:
            _print(report)
            raise
        _print(report)
    return 0


def _print(report: dict[str, int]) -> None:
    for neem_id, count in report.items():
        print(f"{neem_id}\t{count} actions")
