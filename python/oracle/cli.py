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
from typing import Any

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


class _Unused:
    """Stands in for the parser of a command that is not run: its options are never built.

    Building every command's options costs more than the interpreter's own start, and a call
    runs one command (or prints the list of commands, which needs only names and help lines)."""

    def __getattr__(self, name: str) -> Any:
        return lambda *args, **kwargs: self


class _Subcommands:
    """The sub-parsers action as command modules see it: full parsers only for ``wanted``."""

    def __init__(self, action: argparse._SubParsersAction, wanted: str | None) -> None:
        self.action = action
        self.wanted = wanted

    def add_parser(self, name: str, **kwargs: Any) -> Any:
        parser = self.action.add_parser(name, **kwargs)
        if self.wanted is None or name == self.wanted or name in kwargs.get("aliases", ()):
            return parser
        return _Unused()


def build_parser(command: str | None = None, *, complete: bool = True) -> argparse.ArgumentParser:
    """The parser; with ``complete=False`` only ``command`` gets its options (every command is
    still listed, so ``--help`` and a misspelt command read the same)."""
    parser = argparse.ArgumentParser(
        prog="python -m oracle",
        description="KnowRob-compatible NEEM store, Prolog bridge and PreferenceOracle.",
    )
    parser.add_argument("--version", action="version", version=f"neem-oracle {__version__}")
    action = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers: Any = action if complete else _Subcommands(action, command)
    for name in COMMAND_MODULES:
        module_name = f"oracle.commands.{name}"
        if importlib.util.find_spec(module_name) is None:
            continue
        importlib.import_module(module_name).register(subparsers)
    return parser


def _command(argv: Sequence[str]) -> str | None:
    """The command named on a command line: the first word that is not an option (the top
    level's own options, --help and --version, take no value)."""
    return next((word for word in argv if not word.startswith("-")), None)


def main(argv: Sequence[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(_command(words), complete=False)
    args = parser.parse_args(words)
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
