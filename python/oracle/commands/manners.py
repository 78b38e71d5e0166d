"""What the command line does with a misspelt word or a repeated option.

A misspelt command or option gets the nearest names ("Did you mean 'rank'?", oracle.suggest). An
option given twice either adds up (a list option: ``--available A --available B`` ranks both)
or is refused in one line (``--neem a --neem b``): argparse alone keeps the last silently.
"""

from __future__ import annotations

import argparse
import re
from collections.abc import Sequence
from typing import Any

from oracle.suggest import did_you_mean

_CHOICE = re.compile(r"invalid choice: '([^']*)'")
_UNKNOWN = re.compile(r"unrecognized arguments: (.*)")
#: Where argparse notes the options a parse has met (a namespace attribute no command reads).
_GIVEN = "_options_given"


def reworded(parser: argparse.ArgumentParser, message: str) -> str:
    """A usage error's message with the did-you-mean at its end: a misspelt command is named as
    such (not argparse's list of every choice), an unknown option gets the nearest ones."""
    found = _CHOICE.search(message)
    if found is not None and message.startswith(("argument COMMAND", "argument SUBCOMMAND")):
        return f"no such command {found.group(1)!r}.{did_you_mean(found.group(1), _choices(parser))}"
    if found is not None:
        hint = did_you_mean(found.group(1), _choices(parser))
        return message + ("." + hint if hint else "")
    found = _UNKNOWN.search(message)
    if found is not None:
        options = _option_strings(parser)
        for word in found.group(1).split():
            if word.startswith("-"):
                hint = did_you_mean(word.split("=", 1)[0], options)
                if hint:
                    return message + "." + hint
    return message


def _choices(parser: argparse.ArgumentParser) -> list[str]:
    return [str(c) for action in parser._actions for c in (action.choices or ()) if isinstance(c, str)]


def _option_strings(parser: argparse.ArgumentParser) -> list[str]:
    """The parser's options and those of its sub-commands (only the command run has its own)."""
    found: list[str] = []
    for action in parser._actions:
        found.extend(action.option_strings)
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                found.extend(_option_strings(sub))
    return found


class _ExtendList(argparse._ExtendAction):
    """A list option (``nargs='+'``) given twice: the values add up."""


class _Once(argparse._StoreAction):
    """A one-value option given twice with different values is refused in one line."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: Any,
                 option_string: str | None = None) -> None:
        given: dict[str, Any] = namespace.__dict__.setdefault(_GIVEN, {})
        if self.dest in given and given[self.dest] != values:
            parser.error(f"{option_string or self.dest} given twice ({str(given[self.dest])!r} and {str(values)!r}): "
                         "give it once")
        given[self.dest] = values
        super().__call__(parser, namespace, values, option_string)


def mind_repeats(parser: argparse.ArgumentParser) -> None:
    """Make ``parser``'s list options add up and its one-value options refuse a second value."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):  # ontology build, ontology distance, ...
            for sub in action.choices.values():
                mind_repeats(sub)
        if not action.option_strings or type(action) is not argparse._StoreAction:
            continue
        if action.nargs in ("+", "*"):
            action.__class__ = _ExtendList  # type: ignore[assignment]  # the same fields, another __call__
        elif action.nargs in (None, "?"):
            action.__class__ = _Once


def drop_notes(namespace: argparse.Namespace) -> argparse.Namespace:
    """The namespace without the parse's own notes."""
    namespace.__dict__.pop(_GIVEN, None)
    return namespace


__all__: Sequence[str] = ("drop_notes", "mind_repeats", "reworded")
