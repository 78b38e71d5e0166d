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
from typing import NoReturn

from oracle import __version__
from oracle.errors import NeemOracleError
from oracle.store.uri import mask_credentials

#: Command modules in the order their sub-commands appear in ``--help``.
COMMAND_MODULES = (
    "ontology",
    "store",
    "logging",
    "prolog",
    "rank",
    "evaluation",
    "evaluate",
    "demo",
    "bench",
)


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line on stderr (exit 2), like every other error of the tool."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"error: {self.prog}: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
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
        print(f"error: {parser.prog}: give a command (see {parser.prog} --help)", file=sys.stderr)
        return 2
    try:
        return int(handler(args) or 0)
    except NeemOracleError as error:
        # One line, and never a password (a message may quote a --store URI).
        text = " ".join(str(error).split()) or type(error).__name__
        print(f"error: {mask_credentials(text)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
