"""Compatibility with the official SOMA/DUL files (skipped where they are absent)."""

import rdflib
from rdflib.namespace import OWL, RDF, RDFS

from oracle.ontology import build_with_report
from oracle.ontology.upper import CORE_TBOX, OFFICIAL_FILES, declared_entities


def official_graph(soma_dir):
    g = rdflib.Graph()
    for name in OFFICIAL_FILES:
        g.parse(soma_dir / name, format="xml")
    return g


def test_every_core_tbox_edge_is_in_the_official_files(soma_dir):
    official = official_graph(soma_dir)
    core = rdflib.Graph().parse(CORE_TBOX, format="turtle")
    edges = list(core.triples((None, RDFS.subClassOf, None))) + list(core.triples((None, RDFS.subPropertyOf, None)))
    assert len(edges) > 100
    missing = [e for e in edges if e not in official]
    assert missing == []
    kinds = [t for t in core.triples((None, RDF.type, None))]
    assert [t for t in kinds if t not in official] == []


def test_core_tbox_keeps_every_asserted_parent(soma_dir):
    official = official_graph(soma_dir)
    core = rdflib.Graph().parse(CORE_TBOX, format="turtle")
    for cls in core.subjects(RDF.type, OWL.Class):
        named = {p for p in official.objects(cls, RDFS.subClassOf) if isinstance(p, rdflib.URIRef)}
        assert named == set(core.objects(cls, RDFS.subClassOf)), cls


def test_build_with_official_files(soma_dir):
    onto, report = build_with_report(soma_dir=soma_dir)
    official = declared_entities(official_graph(soma_dir))
    referenced = {str(o) for s, p, o in onto.graph.triples((None, RDFS.subClassOf, None))
                  if str(s).startswith(onto.namespace) and isinstance(o, rdflib.URIRef)
                  and not str(o).startswith(onto.namespace)}
    assert referenced and referenced <= official
    core_onto, _ = build_with_report()
    # Same odb, same chains: every odb class has the same ancestors with either upper ontology.
    for name in ("red_mug", "pour", "open_fridge", "banana"):
        iri = onto.iri(name)
        assert set(core_onto.taxonomy.ancestors(iri)) <= set(onto.taxonomy.ancestors(iri))
