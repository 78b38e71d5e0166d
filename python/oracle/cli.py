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
from typing import Any, NoReturn

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
    "rosprolog",
    "simulate",
    "ask",
    "routines",
    "prepare",
    "prior",
)


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line on stderr (exit 2), like every other error of the tool, with the
    nearest command or option when a word was misspelt (oracle.commands.manners)."""

    def error(self, message: str) -> NoReturn:
        from oracle.commands.manners import reworded

        self.exit(2, f"error: {self.prog}: {reworded(self, message)} (see {self.prog} --help)\n")


class _Unused:
    """Stands in for the parser of a command that is not run: its options are never built.

    Building every command's options costs more than the interpreter's own start, and a call
    runs one command (or prints the list of commands, which needs only names and help lines)."""

    def __getattr__(self, name: str) -> Any:
        return lambda *args, **kwargs: self


class _Subcommands:
    """The sub-parsers action as command modules see it: full parsers only for ``wanted``."""

    def __init__(self, action: argparse._SubParsersAction[Any], wanted: str | None) -> None:
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
    parser = _Parser(
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
    from oracle.commands.manners import mind_repeats

    for sub in action.choices.values():
        mind_repeats(sub)  # a repeated option adds up or is refused, never silently the last
    return parser


def _command(argv: Sequence[str]) -> str | None:
    """The command named on a command line: the first word that is not an option (the top
    level's own options, --help and --version, take no value)."""
    return next((word for word in argv if not word.startswith("-")), None)


def main(argv: Sequence[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(_command(words), complete=False)
    from oracle.commands.manners import drop_notes

    args = drop_notes(parser.parse_args(words))
    handler = getattr(args, "handler", None)
    if handler is None:
        print(f"error: {parser.prog}: give a command (see {parser.prog} --help)", file=sys.stderr)
        return 2
    try:
        return int(handler(args) or 0)
    except NeemOracleError as error:
        from oracle.store.uri import mask_credentials  # here: importing oracle.store costs --help 40 ms

        # One line, and never a password (a message may quote a --store URI).
        text = " ".join(str(error).split()) or type(error).__name__
        print(f"error: {mask_credentials(text)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except OSError as error:
        # The machine's fault, not a bug: a full disk, a read-only or vanished folder. Commands
        # that write a person's data turn these into their own errors; this catches the rest
        # (a report, a settings file) in one line too.
        from oracle.store.uri import mask_credentials

        where = f"{error.filename}: " if error.filename else ""
        print(f"error: {mask_credentials(where + (error.strerror or str(error)))}", file=sys.stderr)
        return 1
