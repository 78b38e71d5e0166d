"""``import``: log action chains (JSONL) into a store, one NEEM per user."""

from __future__ import annotations

import argparse
from pathlib import Path

from oracle.commands.store import add_store_argument
from oracle.errors import NeemOracleError
from oracle.store import open_store


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("import", help="log action chains (JSONL) as one NEEM per user")
    parser.add_argument("chains", type=Path, metavar="CHAINS.jsonl")
    add_store_argument(parser)
    parser.add_argument("--ontology", type=Path, metavar="OWL", help="odb ontology file (default: build the shipped one)")
    parser.add_argument("--replace", action="store_true", help="replace a user's NEEM instead of adding a new one")
    parser.add_argument("--commit-every", type=int, default=100, metavar="N",
                        help="actions per transaction (1 = each action durable before the next; default 100)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from oracle.logger import import_chains
    from oracle.ontology import build_ontology, load_ontology

    onto = load_ontology(args.ontology) if args.ontology else build_ontology()
    with open_store(args.store, number_format=args.numbers) as store:
        report: dict[str, int] = {}
        try:
            import_chains(store, onto, args.chains, replace=args.replace, report=report, commit_every=args.commit_every)
        except NeemOracleError:
            _print(report)
            raise
        _print(report)
    return 0


def _print(report: dict[str, int]) -> None:
    for neem_id, count in report.items():
        print(f"{neem_id}\t{count} actions")
