"""``import``: log action chains (JSONL) into a store, one NEEM per user."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from oracle.commands.common import add_ontology_options, ontology_from
from oracle.commands.store import add_store_argument
from oracle.errors import NeemOracleError
from oracle.store import open_store


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("import", help="log action chains (JSONL) as one NEEM per user")
    parser.add_argument("chains", type=Path, metavar="CHAINS.jsonl")
    add_store_argument(parser)
    add_ontology_options(parser)
    parser.add_argument("--replace", action="store_true", help="replace a user's NEEM instead of adding a new one")
    parser.add_argument("--session", action="store_true",
                        help="log into temporary NEEMs, wiping earlier temporary ones (keep them with 'persist')")
    parser.add_argument("--commit-every", type=_positive, default=100, metavar="N",
                        help="actions per transaction (1 = each action durable before the next; default 100)")
    parser.set_defaults(handler=run)


def _positive(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {text!r}") from None
    if not 1 <= value <= 1_000_000:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 1000000, got {text}")
    return value


def run(args: argparse.Namespace) -> int:
    from oracle.neem.importing import check_chains, import_chains

    onto = ontology_from(args)
    plans = check_chains(onto, args.chains)  # before the store is opened: a bad file creates nothing
    with open_store(args.store, number_format=args.numbers) as store:
        report: dict[str, int] = {}
        try:
            import_chains(store, onto, args.chains, replace=args.replace, report=report, commit_every=args.commit_every,
                          session=args.session, plans=plans)
        except NeemOracleError:
            _print(report)
            raise
        except KeyboardInterrupt:
            _print(report)
            print(f"interrupted: {sum(report.values())} actions committed", file=sys.stderr)
            return 130
        _print(report)
    return 0


def _print(report: dict[str, int]) -> None:
    for neem_id, count in report.items():
        print(f"{neem_id}\t{count} actions")
