"""Options several commands share, each declared once with one help text, and what they resolve to.

A command lists the options it takes (``add_options(parser, STORE, NEEM, JSON)``) and turns the
parsed values into objects with the helpers below (``ontology_from``, ``connect``,
``settings_from``, ``moment_from``), so no command imports another command's helpers.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

from oracle.errors import NeemOracleError, SettingsError

if TYPE_CHECKING:  # imported lazily at run time, so that --help stays fast
    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import OdbOntology
    from oracle.timeline import Instant


class Option(NamedTuple):
    """One command-line option: its flags and the keyword arguments of ``add_argument``
    (a named tuple, not a dataclass: ``dataclasses`` costs every call ~10 ms of imports)."""

    flags: tuple[str, ...]
    settings: dict[str, Any]

    def add(self, parser: argparse.ArgumentParser) -> None:
        parser.add_argument(*self.flags, **self.settings)


STORE = Option(("--store",), {
    "metavar": "S",
    "help": "PATH or sqlite:///PATH (embedded, the default lives in the user data dir), "
            "mongodb://HOST[:PORT][/DB], or 'mongodb' for $NEEM_MONGO_URI",
})
NUMBERS = Option(("--numbers",), {
    "choices": ("decimal128", "double"), "default": "decimal128",
    "help": "how new numbers are written: Decimal128 (KnowRob 2.x, default) or double (KnowRob 3)",
})
NEEM = Option(("--neem",), {"metavar": "ID", "help": "NEEM id or name (needed when the store holds several)"})
JSON = Option(("--json",), {"action": "store_true", "help": "print the result as JSON"})
AT = Option(("--at",), {
    "help": "time of the decision: unix seconds or ISO-8601, a time without zone read as UTC "
            "(default: the latest decision; for rank --available: now)",
})
SETTINGS = Option(("--settings",), {
    "default": "recommended",
    "help": "settings YAML, 'recommended', or a thesis Fig. 5.5 letter A-N (default: recommended)",
})
ODB = Option(("--odb",), {"type": Path, "help": "odb folder (default: the sample kitchen shipped in ontology/)"})
MAPPING = Option(("--mapping",), {"type": Path, "help": "mapping YAML (default: the sample kitchen's, shipped in ontology/)"})
SOMA = Option(("--soma",), {"type": Path, "help": "folder with the official SOMA.owl/SOMA-HOME.owl/DUL.owl (default: the core TBox)"})
ONTOLOGY = Option(("--ontology",), {"type": Path, "help": "OWL file written by 'ontology build' (instead of --odb/--mapping)"})
METHOD = Option(("--method",), {
    "metavar": "NAME",
    "help": "predictor (oracle.algorithm.predictors): personal (the default: a per-user online logit over "
            "routine's evidence and, given one, the shared prior's), pooled (routine and a per-user logit over its "
            "evidence, pooled log-linearly where that leads), routine (exact contexts backed off to ontology "
            "similarity, self-tuned), routine-fixed, routine-mixture, stacked (routine re-weighed by a per-user logit "
            "where that leads), online (routine re-weighed by a per-user logit learnt after every decision, where "
            "that leads), thesis (the thesis "
            "oracle with --settings) or thesis-normalized (its distances divided by "
            "their mean, thesis 6.4)",
})
#: The options naming the ontology a command works with (see ``ontology_from``).
ONTOLOGY_OPTIONS = (ODB, MAPPING, SOMA, ONTOLOGY)


def add_options(parser: argparse.ArgumentParser, *options: Option) -> None:
    for option in options:
        option.add(parser)


def ontology_from(args: argparse.Namespace) -> OdbOntology:
    from oracle.ontology import build_ontology, load_ontology

    if getattr(args, "ontology", None) is not None:
        if args.odb is not None or args.mapping is not None:
            raise NeemOracleError("give either --ontology or --odb/--mapping, not both")
        return load_ontology(args.ontology)
    return build_ontology(getattr(args, "odb", None), getattr(args, "mapping", None), getattr(args, "soma", None))


def settings_from(text: str) -> Hyperparameters:
    """A settings YAML path, a preset name, or a Fig. 5.5 letter."""
    from oracle.algorithm.params import load_settings, preset

    path = Path(text)
    if path.suffix in (".yaml", ".yml") or path.exists():
        return load_settings(path)
    try:
        return preset(text)
    except SettingsError:
        raise SettingsError(f"--settings {text!r}: not a YAML file, 'recommended' or a letter A-N") from None


def moment_from(text: str | None) -> Instant | None:
    """``--at`` as an Instant (oracle.timeline's rule for times without a zone), or None."""
    from oracle.timeline import TimeValueError, parse_instant

    if text is None:
        return None
    try:
        return parse_instant(text)
    except TimeValueError as error:
        raise NeemOracleError(f"--at {error}") from None


def method_from(args: argparse.Namespace) -> str:
    """The predictor name of ``--method`` (default: the registry's); one-line error when unknown."""
    from oracle.algorithm.predictors import DEFAULT, predictor_spec

    return predictor_spec(getattr(args, "method", None) or DEFAULT).name


def bounded_int(low: int, high: int) -> Callable[[str], int]:
    """An argparse ``type`` for a whole number in [low, high]: a value outside would make a
    command run without bound (``demo --days 100000000``) or do nothing useful."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected a whole number from {low} to {high}, got {text}")
        return value

    return parse
