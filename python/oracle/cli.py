"""Command-line interface: argument parsing only.

Each area of the package contributes its sub-commands from a module in ``oracle.commands``
exposing ``register(subparsers)``; every command calls one function of the package.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import sys
from collections.abc import Sequence

from oracle import __version__
from oracle.errors import NeemOracleError

#: Command modules in the order their sub-commands appear in ``--help``.
COMMAND_MODULES = (
    "ontology",
    "store",
    "importing",
    "prolog",
    "rank",
    "datasets",
    "evaluate",
    "demo",
    "bench",
    "serve",
    "simulate",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m oracle",
        description="KnowRob-compatible NEEM store, Prolog bridge and PreferenceOracle.",
    )
    parser.add_argument("--version", action="version", version=f"neem-oracle {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        module_name = f"oracle.commands.{name}"
        if importlib.util.find_spec(module_name) is None:
            continue
        importlib.import_module(module_name).register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help(sys.stderr)
        return 2
    try:
        return int(handler(args) or 0)
    except NeemOracleError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
