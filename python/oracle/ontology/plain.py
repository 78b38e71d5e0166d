"""A built ontology and its report as plain JSON data, both ways (the user's cache entry).

What the cache keeps (oracle.ontology.cache) is read back through ``json`` and these functions
alone: strings, numbers, lists and dicts, each checked as it is turned back into the odb's classes,
the taxonomy and the graph's terms. Nothing in an entry names code. The graph is kept as its
triples, each term a string (an IRI), ``["b", id]`` (a blank node) or ``["l", text, datatype,
language]`` (a literal), and made into an rdflib graph only when something reads it
(``OdbOntology.graph``): the names, classes, taxonomy, prefixes and labels most commands need load
without rdflib.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from oracle.ontology.inputs import BuildReport
from oracle.ontology.model import ObjectClass, OdbOntology, TaskClass
from oracle.ontology.provenance import OntologySource
from oracle.ontology.plaingraph import PlainEntryError, checked_graph, graph_to_plain, maybe_text, rows, text, texts
from oracle.ontology.taxonomy import Taxonomy

def to_plain(built: tuple[OdbOntology, BuildReport]) -> dict[str, Any]:
    """The ontology and its report as JSON-ready data."""
    onto, report = built
    source = onto.source
    return {
        "namespace": onto.namespace,
        "objects": [[c.name, c.iri, list(c.parents), list(c.tasks), c.abstract] for c in onto.objects.values()],
        "tasks": [[t.name, t.iri, t.soma_task, t.target_role, t.ref_role, t.disposition, t.parent] for t in onto.tasks.values()],
        "cache_dir": None if onto.cache_dir is None else str(onto.cache_dir),
        "source": None if source is None else [source.odb, source.mapping, source.soma, source.owl],
        "cache_key": onto.cache_key,
        "taxonomy": {child: list(parents) for child, parents in onto.taxonomy.parent_table().items()},
        "prefixes": [list(pair) for pair in onto.prefixes],
        "labels": onto.labels,
        "graph": graph_to_plain(onto.graph),
        "report": [report.n_objects, report.n_abstract, report.n_tasks, list(report.unmapped), list(report.mapped_absent),
                   list(report.default_tasks), report.n_triples],
    }


def from_plain(data: Any) -> tuple[OdbOntology, BuildReport]:
    """What ``to_plain`` made, checked part by part; PlainEntryError (or another ValueError,
    TypeError, KeyError) for anything else."""
    if not isinstance(data, dict):
        raise PlainEntryError("not an entry")
    objects = {}
    for name, iri, parents, tasks, abstract in rows(data["objects"], 5):
        if not isinstance(abstract, bool):
            raise PlainEntryError("an object's 'abstract' is not a boolean")
        objects[text(name)] = ObjectClass(text(name), text(iri), texts(parents), texts(tasks), abstract)
    task_classes = {}
    for name, iri, soma_task, target, ref, disposition, parent in rows(data["tasks"], 7):
        task_classes[text(name)] = TaskClass(text(name), text(iri), text(soma_task), maybe_text(target), maybe_text(ref),
                                              maybe_text(disposition), maybe_text(parent))
    source = data["source"]
    labels = data["labels"]
    if not isinstance(labels, dict) or not all(isinstance(forms, dict) for forms in labels.values()):
        raise PlainEntryError("labels are not a mapping of mappings")
    taxonomy = data["taxonomy"]
    if not isinstance(taxonomy, dict):
        raise PlainEntryError("the taxonomy is not a mapping")
    cache_dir = maybe_text(data["cache_dir"])
    onto = OdbOntology(
        namespace=text(data["namespace"]), graph=None,  # type: ignore[arg-type]  # read on first use, below
        objects=objects, tasks=task_classes, cache_dir=None if cache_dir is None else Path(cache_dir),
        source=None if source is None else OntologySource(*(maybe_text(part) for part in rows([source], 4)[0])),
        cache_key=maybe_text(data["cache_key"]))
    del onto.__dict__["graph"]
    onto.__dict__["_graph_plain"] = checked_graph(data["graph"])
    onto.__dict__["taxonomy"] = Taxonomy({text(c): texts(ps) for c, ps in taxonomy.items()})
    onto.__dict__["prefixes"] = tuple((text(p), text(ns)) for p, ns in rows(data["prefixes"], 2))
    onto.__dict__["_labels_plain"] = {text(iri): {text(lang): text(text) for lang, text in forms.items()}
                               for iri, forms in labels.items()}
    n_objects, n_abstract, n_tasks, unmapped, absent, defaults, n_triples = rows([data["report"]], 7)[0]
    if not all(isinstance(n, int) and not isinstance(n, bool) for n in (n_objects, n_abstract, n_tasks, n_triples)):
        raise PlainEntryError("the report's counts are not whole numbers")
    report = BuildReport(n_objects, n_abstract, n_tasks, texts(unmapped), texts(absent), texts(defaults), n_triples)
    return onto, report
