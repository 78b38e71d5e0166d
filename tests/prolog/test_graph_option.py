"""kb_call/4 and kb_project/3 with KnowRob's graph(G) option through the bridge: a query reads
G and the graphs above it (``common``, the graphs G's ontology imports), ``user`` and ``'*'``
every graph, ``=(G)`` G alone, an unknown graph nothing. SQLite and the Mongo code path."""

from __future__ import annotations

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.store.sqlite import SQLiteStore
from tests.prolog.conftest import log_episode
from tests.store.conftest import make_store
from tests.store.test_owlfile import find_soma

SUB = "http://www.w3.org/2000/01/rdf-schema#subClassOf"


def subclass_pairs(bridge: Bridge, graph: str) -> set[tuple[str, str]]:
    rows = bridge.query(f"kb_call(triple(C, rdfs:subClassOf, D), dict{{}}, _, [graph({graph})]), atom(D)")
    return {(str(r["C"]), str(r["D"])) for r in rows}


def stored_pairs(store, neem: str, graphs: set[str]) -> set[tuple[str, str]]:
    return {(d["s"], d["o"]) for d in store.read_documents(neem, "triples")
            if d["p"] == SUB and d["graph"] in graphs and isinstance(d["o"], str)}  # fmt: skip


@pytest.fixture(params=["sqlite", "mongomock"])
def episode(request, tmp_path, onto):
    store = make_store(request.param, tmp_path)
    neem = log_episode(store, onto).neem_id
    bridge = Bridge(store, neem, onto)
    yield store, neem, bridge
    bridge.close()
    store.close()


def test_a_graph_reads_its_own_documents_and_common(episode):
    store, neem, bridge = episode
    mongomock = not isinstance(store, SQLiteStore)  # mongomock-ng's $lookup is slow: the small graphs
    for graph in ("DUL", "SOMA") if mongomock else ("odb", "DUL", "SOMA"):
        expected = stored_pairs(store, neem, {graph})
        assert expected and subclass_pairs(bridge, f"'{graph}'") == expected
        assert subclass_pairs(bridge, f"=('{graph}')") == expected
    if not mongomock:
        everything = stored_pairs(store, neem, {"odb", "DUL", "SOMA", "user"})
        assert subclass_pairs(bridge, "user") == subclass_pairs(bridge, "'*'") == everything


def test_the_narrative_is_in_user_only(episode):
    _, _, bridge = episode
    actions = "kb_call(is_action(A), dict{{}}, _, [graph({})])"
    every = bridge.query(actions.format("user"))
    assert every and every == bridge.query(actions.format("'*'"))
    assert bridge.query(actions.format("odb")) == []
    assert bridge.query(actions.format("nothing_here")) == []  # an unknown graph: no answer, no error


def test_kb_project_writes_into_the_graph_it_names(episode):
    store, neem, bridge = episode
    bridge.query("kb_project(triple('http://e.org/x', rdfs:subClassOf, 'http://e.org/y'), dict{}, [graph(mine)])")
    (doc,) = store.find(neem, "http://e.org/x", SUB, "http://e.org/y", exact=True)
    assert doc["graph"] == "mine"
    assert subclass_pairs(bridge, "mine") == {("http://e.org/x", "http://e.org/y")}
    assert ("http://e.org/x", "http://e.org/y") not in subclass_pairs(bridge, "odb")
    assert ("http://e.org/x", "http://e.org/y") in subclass_pairs(bridge, "user")


def test_the_fact_scope_of_a_graph_query_reads_that_graph(episode):
    store, neem, bridge = episode
    goal = "kb_call(triple('http://e.org/s', 'http://e.org/p', o), dict{{}}, F, [graph({})])"
    bridge.query("kb_project(triple('http://e.org/s', 'http://e.org/p', o), scope(10, 20), [graph(g1)])")
    bridge.query("kb_project(triple('http://e.org/s', 'http://e.org/p', o), scope(50, 60), [graph(g2)])")
    (first,) = bridge.query(goal.format("user"))  # a ground goal succeeds once (KnowRob)
    assert first["F"]["time"] == {"since": 10.0, "until": 20.0}
    (row,) = bridge.query(goal.format("g2"))  # only g2's document is read for the fact scope
    assert row["F"]["time"] == {"since": 50.0, "until": 60.0}


def test_a_soma_neem_graph_reads_the_graphs_its_ontology_imports(tmp_path):
    # SQLite only: on mongomock-ng the $lookup over a --soma NEEM's 16,000 documents takes
    # over ten minutes; the Mongo code path of the filter is the same $in as above
    from oracle.ontology import build_ontology

    soma_onto = build_ontology(None, None, find_soma())
    store = make_store("sqlite", tmp_path)
    logger = NeemLogger.create(store, soma_onto, user="ada")
    logger.close()
    neem = logger.neem_id
    bridge = Bridge(store, neem)
    try:
        dul, soma, home = (stored_pairs(store, neem, {g}) for g in ("DUL", "SOMA", "SOMA-HOME"))
        assert subclass_pairs(bridge, "'DUL'") == dul
        assert subclass_pairs(bridge, "'SOMA'") == soma | dul  # SOMA.owl imports DUL.owl
        assert subclass_pairs(bridge, "'SOMA-HOME'") == home | soma | dul
        assert subclass_pairs(bridge, "=('SOMA')") == soma
    finally:
        bridge.close()
        store.close()
