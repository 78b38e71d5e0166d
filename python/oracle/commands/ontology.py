"""``python -m oracle ontology build|distance|info``."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TYPE_CHECKING

from oracle.errors import OntologyError
from oracle.commands.common import JSON, MAPPING, ODB, ONTOLOGY, SOMA, add_options

if TYPE_CHECKING:  # the ontology package (rdflib, numpy) is imported where a command runs
    from oracle.ontology import OdbOntology


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("ontology", help="build the odb ontology and query its distances")
    sub = parser.add_subparsers(dest="ontology_command", metavar="SUBCOMMAND", required=True)

    build = sub.add_parser("build", help="odb folder + mapping YAML -> OWL ontology under SOMA/DUL")
    add_options(build, ODB, MAPPING, SOMA)
    build.add_argument("--out", type=Path, default=Path("odb.owl"),
                       help="output file; .ttl writes Turtle, anything else RDF/XML (default: odb.owl)")
    JSON.add(build)
    build.set_defaults(handler=run_build)

    distance = sub.add_parser("distance", help="distance between two classes (thesis Algorithm 1)")
    distance.add_argument("a", help="odb name (thermos, pick) or full class IRI")
    distance.add_argument("b", help="odb name or full class IRI")
    add_options(distance, ONTOLOGY, ODB, MAPPING, SOMA, JSON)
    distance.set_defaults(handler=run_distance)


def run_build(args: argparse.Namespace) -> int:
    from oracle.ontology import build_with_report, write_ontology

    ontology, report = build_with_report(args.odb, args.mapping, args.soma)
    out = write_ontology(ontology, args.out)
    summary = {
        "out": str(out),
        "namespace": ontology.namespace,
        "objects": report.n_objects,
        "abstract_objects": report.n_abstract,
        "tasks": report.n_tasks,
        "classes": len(ontology.taxonomy.classes),
        "triples": report.n_triples,
        "unmapped_objects": list(report.unmapped),
        "mapped_but_absent": list(report.mapped_absent),
        "tasks_with_default_mapping": list(report.default_tasks),
        "upper": "official SOMA/DUL from " + str(args.soma) if args.soma else "core TBox",
    }
    if args.json:
        print(json.dumps(summary, indent=2))
        return 0
    print(f"wrote {out} ({report.n_triples} triples, upper ontology: {summary['upper']})")
    print(f"  namespace        {ontology.namespace}")
    print(f"  objects          {report.n_objects} ({report.n_abstract} abstract)")
    print(f"  tasks            {report.n_tasks}")
    print(f"  classes in total {summary['classes']}")
    print(f"  unmapped objects {', '.join(report.unmapped) or '-'} (placed under the mapping's root_object)")
    if report.mapped_absent:
        print(f"  note: mapped but not in the odb: {', '.join(report.mapped_absent)}")
    if report.default_tasks:
        print(f"  note: tasks without mapping (action_defaults used): {', '.join(report.default_tasks)}")
    return 0


def _resolve(ontology: OdbOntology, name: str) -> str:
    if name.startswith(("http://", "https://", "urn:")):
        if name not in ontology.taxonomy:
            raise OntologyError(f"unknown class {name}")
        return name
    if ":" in name:
        prefix, local = name.split(":", 1)
        namespaces = {p: str(n) for p, n in ontology.graph.namespaces()}
        if prefix in namespaces and namespaces[prefix] + local in ontology.taxonomy:
            return namespaces[prefix] + local
        raise OntologyError(f"unknown class {name}")
    if name in ontology.objects or name in ontology.tasks or ontology.iri(name) in ontology.taxonomy:
        return ontology.iri(name)
    raise OntologyError(f"unknown class {name!r}: not an odb object or task (try a full IRI or soma:Name)")


def run_distance(args: argparse.Namespace) -> int:
    from oracle.ontology import build_with_report, load_ontology, owl_distance

    if args.ontology is not None:
        ontology = load_ontology(args.ontology)
    else:
        ontology = build_with_report(args.odb, args.mapping, args.soma)[0]
    a, b = _resolve(ontology, args.a), _resolve(ontology, args.b)
    result = owl_distance(ontology.taxonomy, a, b)
    matrix_value = ontology.distances().distance(a, b)
    if abs(matrix_value - result.value) > 1e-12:  # the cached matrix must agree with Algorithm 1
        raise AssertionError(f"distance matrix disagrees with Algorithm 1 for {a}, {b}")
    if args.json:
        print(json.dumps({"a": a, "b": b, "distance": result.value, "lcs": result.lcs, "path": result.path,
                          "cspec": result.cspec, "depth_ontology": ontology.taxonomy.max_depth}))
        return 0
    print(f"dist({ontology.name(a)}, {ontology.name(b)}) = {result.value:.4f}")
    print(f"  lcs {ontology.name(result.lcs)}, path {result.path}, CSpec {result.cspec:.4f}, "
          f"depth(lcs) {ontology.taxonomy.depth(result.lcs)} of {ontology.taxonomy.max_depth}")
    return 0
