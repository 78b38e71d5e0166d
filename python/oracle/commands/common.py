"""Options several commands share: which ontology to use."""

from __future__ import annotations

import argparse
from pathlib import Path

from oracle.errors import NeemOracleError


def add_ontology_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--odb", type=Path, help="odb folder (default: the sample kitchen)")
    parser.add_argument("--mapping", type=Path, help="mapping YAML (default: the sample kitchen's)")
    parser.add_argument("--soma", type=Path, help="official SOMA/DUL folder (default: core TBox)")
    parser.add_argument("--ontology", type=Path, help="OWL file written by 'ontology build' (instead of --odb/--mapping)")


def ontology_from(args: argparse.Namespace):  # noqa: ANN201 - OdbOntology, imported lazily for a fast --help
    from oracle.ontology import build_ontology, load_ontology

    if getattr(args, "ontology", None) is not None:
        if args.odb is not None or args.mapping is not None:
            raise NeemOracleError("give either --ontology or --odb/--mapping, not both")
        return load_ontology(args.ontology)
    return build_ontology(getattr(args, "odb", None), getattr(args, "mapping", None), getattr(args, "soma", None))


def bounded_int(low: int, high: int):  # noqa: ANN201 - an argparse type
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
