"""Ontology (TBox) triples into a NEEM, as KnowRob's ``load_owl`` puts them there.

A NEEM carries the SOMA/DUL/odb axioms it was recorded with, so closures and type queries work
on the NEEM alone. Literals are typed as load_owl types them (knowrob-2x-facts §4) and
annotation values go to the ``annotations`` collection, English or untagged only. Which TBox a
NEEM logged with an ontology stores, and its cache, is ``store.ontology_tbox``.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from typing import TYPE_CHECKING

from oracle.namespaces import DUL_IRI, OWL_IRI, RDFS_IRI, SOMA_IRI, XSD_IRI
from oracle.store.base import Store
from oracle.store.model import HIERARCHY, VERSION_PREDICATE, Annotation, Triple, Value, version_document

if TYPE_CHECKING:
    from rdflib import Graph, Literal

# rdflib is imported where a graph is converted: an import or a session whose ontology's TBox is
# in the cache (``store.ontology_tbox.tbox_for``) never loads it (~45 ms of every such call).
_ANNOTATION_PROPERTIES = frozenset((RDFS_IRI + "comment", RDFS_IRI + "label", RDFS_IRI + "seeAlso", OWL_IRI + "versionInfo"))
_INTEGER_TYPES = frozenset(
    XSD_IRI + name
    for name in (
        "integer", "int", "long", "short", "byte", "nonNegativeInteger", "positiveInteger",
        "nonPositiveInteger", "negativeInteger", "unsignedInt", "unsignedLong", "unsignedShort", "unsignedByte",
    )
)  # fmt: skip
_FLOAT_TYPES = frozenset(XSD_IRI + name for name in ("decimal", "double", "float"))
#: Graph names KnowRob gives the upper ontologies (the base name of their OWL files).
_KNOWN_GRAPHS = ((SOMA_IRI, "SOMA"), (DUL_IRI, "DUL"))


@dataclass(frozen=True)
class TBox:
    """An ontology converted once into what each NEEM stores."""

    triples: tuple[Triple, ...]
    annotations: tuple[Annotation, ...]
    #: (ontology IRI, graph name, version): KnowRob's ``tripledbVersionString`` marker per graph.
    markers: tuple[tuple[str, str, str], ...]

    @staticmethod
    def combined(parts: list[TBox]) -> TBox:
        """Several ontologies as one load (parents first across all of them, see _hierarchy_first)."""
        triples = [t for part in parts for t in part.triples]
        return TBox(tuple(_hierarchy_first(triples)), tuple(a for part in parts for a in part.annotations),
                    tuple(m for part in parts for m in part.markers))  # fmt: skip


def graph_name(iri: str, default: str) -> str:
    for namespace, name in _KNOWN_GRAPHS:
        if iri.startswith(namespace):
            return name
    return default


def _literal_value(literal: Literal) -> Value:
    datatype = str(literal.datatype) if literal.datatype is not None else None
    if datatype in _INTEGER_TYPES:
        try:
            return int(literal)
        except ValueError:
            return str(literal)
    if datatype in _FLOAT_TYPES:
        try:
            return float(literal)
        except ValueError:
            return str(literal)
    if datatype == XSD_IRI + "boolean":
        return str(literal).strip().lower() in ("true", "1")
    return str(literal)


def _hierarchy_first(triples: list[Triple]) -> list[Triple]:
    """Edges of superclasses before edges of their subclasses, then everything else.

    With this order no edge ever has to rewrite closures already stored (KnowRob loads files
    triple by triple for the same reason), which keeps loading linear.
    """
    edges = [t for t in triples if t.p in HIERARCHY and isinstance(t.o, str)]
    parents: dict[str, list[str]] = {}
    for t in edges:
        parents.setdefault(t.s, []).append(t.o)  # type: ignore[arg-type]
    depth: dict[str, int] = {}

    def depth_of(term: str, visiting: frozenset[str] = frozenset()) -> int:
        if term in depth:
            return depth[term]
        if term in visiting:
            return 0
        result = 1 + max((depth_of(p, visiting | {term}) for p in parents.get(term, ())), default=-1)
        depth[term] = result
        return result

    for term in parents:
        depth_of(term)
    edges.sort(key=lambda t: (depth[t.s], t.s, t.p, str(t.o)))
    rest = [t for t in triples if not (t.p in HIERARCHY and isinstance(t.o, str))]
    return edges + rest


def tbox_from_graph(graph: Graph, default_graph: str | None = None, *, one_graph: bool = False,
                    version: str | None = None) -> TBox:
    """Convert an rdflib graph; subjects in SOMA/DUL go to graphs ``SOMA``/``DUL`` (all to
    ``default_graph`` with ``one_graph``, as KnowRob loads one file), the rest to the ontology's
    own name (the last path segment of its owl:Ontology IRI). Each graph gets a version marker:
    ``version``, else a digest of the triples."""
    from rdflib import BNode, Literal, URIRef
    from rdflib.namespace import OWL, RDF

    ontologies = sorted(str(s) for s in graph.subjects(RDF.type, OWL.Ontology) if isinstance(s, URIRef))
    if default_graph is None:
        default_graph = ontologies[0].rstrip("/#").rsplit("/", 1)[-1] if ontologies else "ontology"
    base = ontologies[0] if ontologies else "urn:neem-oracle:tbox"
    annotation_props = set(_ANNOTATION_PROPERTIES)
    annotation_props.update(str(s) for s in graph.subjects(RDF.type, OWL.AnnotationProperty))
    blank: dict[object, str] = {}

    def node(term: object) -> str:
        if isinstance(term, BNode):
            if term not in blank:
                blank[term] = f"{base}#_:b{len(blank)}"
            return blank[term]
        return str(term)

    rows = sorted(graph, key=lambda t: (isinstance(t[0], BNode), str(t[0]), str(t[1]), str(t[2])))
    triples: list[Triple] = []
    annotations: list[Annotation] = []
    for s, p, o in rows:
        subject, prop = node(s), str(p)
        if prop in annotation_props:
            if isinstance(o, Literal):
                if o.language not in (None, "en"):
                    continue
                annotations.append(Annotation(subject, prop, str(o)))
            else:
                annotations.append(Annotation(subject, prop, node(o)))
            continue
        value: Value = _literal_value(o) if isinstance(o, Literal) else node(o)
        name = default_graph if one_graph else graph_name(subject, default_graph)
        triples.append(Triple(subject, prop, value, graph=name))
    if version is None:
        digest = hashlib.sha1()
        for t in triples:
            digest.update(f"{t.s}\x1f{t.p}\x1f{t.o!r}\n".encode())
        version = digest.hexdigest()
    graphs = sorted({t.graph for t in triples})
    markers = tuple((base if g == default_graph else next(ns for ns, n in _KNOWN_GRAPHS if n == g).rstrip("#"), g, version)
                    for g in graphs)  # fmt: skip
    return TBox(tuple(_hierarchy_first(triples)), tuple(annotations), markers)


def load_tbox(store: Store, neem_id: str, tbox: TBox) -> int:
    """Store the TBox in a NEEM unless its version markers say it is already there."""
    present = {(doc.get("graph"), doc.get("o")) for doc in store.find(neem_id, p=VERSION_PREDICATE, exact=True)}
    if all((graph, version) in present for _, graph, version in tbox.markers):
        return 0
    with store.transaction():
        count = store.insert(neem_id, tbox.triples)
        store.insert_annotations(neem_id, tbox.annotations)
        store.write_documents(
            neem_id, "triples", [version_document(iri, version, graph) for iri, graph, version in tbox.markers]
        )
    return count
