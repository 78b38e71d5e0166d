"""OWL files in a NEEM as KnowRob's load_owl loads them: one graph per file, the version marker
KnowRob compares (so it neither drops nor reloads the graph), and load_owl finding a file that
a NEEM logged with --soma carries already loaded. SQLite and the Mongo code path."""

from __future__ import annotations

import os
import shutil
import subprocess
from collections import Counter
from pathlib import Path

import pytest
from rdflib import Graph
from rdflib.namespace import OWL, RDF

from oracle.errors import StoreError
from oracle.store.model import VERSION_PREDICATE
from oracle.store.owlfile import file_version, graph_of_file, tbox_from_file
from tests.store.conftest import make_store

NEEDS_SWIPL = pytest.mark.skipif(shutil.which("swipl") is None, reason="needs swipl (KnowRob's file_version/2)")
SMALL = """@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
<http://example.org/tiny> a owl:Ontology .
<http://example.org/tiny#A> a owl:Class ; rdfs:label "a"@en ; rdfs:subClassOf <http://example.org/tiny#B> .
<http://example.org/tiny#B> a owl:Class .
"""


def find_soma() -> Path:
    """The official SOMA/DUL folder: $NEEM_ORACLE_SOMA, else a ``shared/soma`` above this checkout."""
    given = os.environ.get("NEEM_ORACLE_SOMA")
    candidates = [Path(given)] if given else [p / "shared" / "soma" for p in Path(__file__).resolve().parents]
    for folder in candidates:
        if (folder / "SOMA.owl").is_file():
            return folder
    pytest.skip("the official SOMA/DUL files are not visible (set NEEM_ORACLE_SOMA to their folder)")


def knowrob_keeps(path: Path, version: str) -> bool:
    """KnowRob's test before it drops a graph: the recorded version, read as a number, is the
    file's modification time (lang/db.pl load_owl0 -> file_version/2)."""
    goal = f"set_time_file('{path}', [modified(T)], []), atom_number('{version}', T)"
    return subprocess.run(["swipl", "-q", "-g", goal, "-t", "halt"], capture_output=True, timeout=60).returncode == 0


@pytest.fixture
def tiny(tmp_path) -> Path:
    path = tmp_path / "tiny-onto.ttl"
    path.write_text(SMALL)
    os.utime(path, ns=(1_700_000_000_750_000_000, 1_700_000_000_750_000_000))
    return path


def test_a_file_is_one_graph_with_its_marker(tiny):
    tbox = tbox_from_file(tiny)
    assert graph_of_file(tiny) == "tiny-onto" and {t.graph for t in tbox.triples} == {"tiny-onto"}
    assert tbox.markers == (("http://example.org/tiny", "tiny-onto", "1700000000.0"),)
    assert [a.v for a in tbox.annotations] == ["a"]  # labels go to the annotations


@NEEDS_SWIPL
def test_the_marker_is_what_knowrob_compares(tiny):
    assert knowrob_keeps(tiny, file_version(tiny))
    os.utime(tiny, (1_700_000_100, 1_700_000_100))
    assert not knowrob_keeps(tiny, "1700000000.0")  # a changed file: KnowRob would reload it


def test_a_file_without_an_ontology_is_refused(tmp_path):
    bad = tmp_path / "bad.ttl"
    bad.write_text(SMALL.replace("<http://example.org/tiny> a owl:Ontology .", ""))
    with pytest.raises(StoreError, match=r"bad\.ttl: declares no owl:Ontology"):
        tbox_from_file(bad)


@pytest.fixture(scope="module")
def soma_onto():
    from oracle.ontology import build_ontology

    return build_ontology(None, None, find_soma())  # positional: the corpus suite wraps build_ontology


@pytest.mark.parametrize("backend", ["sqlite", "mongomock"])
def test_a_soma_neem_carries_each_file_as_knowrob_loads_it(soma_onto, backend, tmp_path):
    from oracle.neem.writer import NeemLogger

    soma = find_soma()
    store = make_store(backend, tmp_path)
    logger = NeemLogger.create(store, soma_onto, user="ada")
    logger.close()
    neem = logger.neem_id
    docs = list(store.read_documents(neem, "triples"))
    per_graph = Counter(d["graph"] for d in docs if d["p"] != VERSION_PREDICATE)
    markers = {d["graph"]: (d["s"], d["o"]) for d in docs if d["p"] == VERSION_PREDICATE}
    for name in ("DUL", "SOMA", "SOMA-HOME"):
        path = soma / f"{name}.owl"
        graph = Graph().parse(path, format="xml")
        ontology = str(next(graph.subjects(RDF.type, OWL.Ontology)))
        assert markers[name] == (ontology, file_version(path))
        tbox = tbox_from_file(path)
        assert per_graph[name] == len(tbox.triples) > 1000  # every axiom of the file, in its graph
    assert set(markers) == {"DUL", "SOMA", "SOMA-HOME", "odb"}
    assert store.count(neem, "annotations") >= sum(len(tbox_from_file(soma / f"{n}.owl").annotations)
                                                   for n in ("DUL", "SOMA", "SOMA-HOME"))  # fmt: skip
    if shutil.which("swipl"):
        assert all(knowrob_keeps(soma / f"{name}.owl", markers[name][1]) for name in ("DUL", "SOMA", "SOMA-HOME"))


@NEEDS_SWIPL
def test_load_owl_finds_the_files_of_a_soma_neem_loaded(soma_onto, tmp_path):
    from oracle.bridge import Bridge
    from oracle.neem.writer import NeemLogger

    soma = find_soma()
    store = make_store("sqlite", tmp_path)
    logger = NeemLogger.create(store, soma_onto, user="ada")
    logger.close()
    before = store.count(logger.neem_id)
    bridge = Bridge(store, logger.neem_id)
    try:
        for name in ("DUL", "SOMA", "SOMA-HOME"):
            bridge.query(f"load_owl('{soma / (name + '.owl')}')")
        assert store.count(logger.neem_id) == before  # each file found loaded: nothing dropped, nothing added
    finally:
        bridge.close()


@NEEDS_SWIPL
@pytest.mark.parametrize("backend", ["sqlite", "mongomock"])
def test_load_owl_skips_an_unchanged_file_and_replaces_the_graph_of_a_changed_one(backend, tiny, tmp_path):
    from oracle.bridge import Bridge

    store = make_store(backend, tmp_path)
    store.create_neem("k")
    bridge = Bridge(store, "k")
    sub = ("http://example.org/tiny#A", "http://www.w3.org/2000/01/rdf-schema#subClassOf")
    try:
        bridge.query(f"load_owl('{tiny}')")
        loaded = store.count("k")
        bridge.query(f"load_owl('{tiny}')")
        assert store.count("k") == loaded  # unchanged: not loaded twice
        tiny.write_text(SMALL.replace(" ; rdfs:subClassOf <http://example.org/tiny#B>", ""))
        os.utime(tiny, (1_700_000_200, 1_700_000_200))
        bridge.query(f"load_owl('{tiny}')")
        assert list(store.find("k", *sub, exact=True)) == []  # the old graph was dropped
        (marker,) = store.find("k", p=VERSION_PREDICATE, exact=True)
        assert (marker["graph"], marker["o"]) == ("tiny-onto", "1700000200.0")
        assert {d["graph"] for d in store.read_documents("k", "triples")} == {"tiny-onto"}
    finally:
        bridge.close()
