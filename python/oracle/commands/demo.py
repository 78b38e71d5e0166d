"""``python -m oracle demo``: the main job on the embedded default store."""

from __future__ import annotations

import argparse

from oracle.ontology import build_with_report


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("demo", help="build the sample kitchen and show what the oracle does")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    ontology, report = build_with_report()
    print(f"sample kitchen ontology: {report.n_objects} objects, {report.n_tasks} tasks, "
          f"{len(ontology.taxonomy.classes)} classes under SOMA/DUL")
    matrix = ontology.distances()
    for a, b in (("red_mug", "green_mug"), ("red_mug", "banana"), ("pick", "place"), ("open", "eat")):
        print(f"  dist({a}, {b}) = {matrix.distance(ontology.iri(a), ontology.iri(b)):.3f}")
    return 0
