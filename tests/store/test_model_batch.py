"""Closures computed once per batch (store.base) equal closures computed triple by triple."""

from __future__ import annotations

import pickle

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from oracle.store import RDF_TYPE, SUBCLASS_OF, SUBPROPERTY_OF, Triple
from oracle.store.model import DocumentBuilder, Hierarchy
from tests.store.conftest import make_store

X = "http://example.org/x#"
classes = st.sampled_from([X + c for c in ("A", "B", "C", "D")])
props = st.sampled_from([X + p for p in ("p", "q", "r")])
things = st.sampled_from([X + i for i in ("i1", "i2")])
triples = st.one_of(
    st.builds(Triple, classes, st.just(SUBCLASS_OF), classes),
    st.builds(Triple, props, st.just(SUBPROPERTY_OF), props),
    st.builds(Triple, things, st.just(RDF_TYPE), classes),
    st.builds(Triple, things, props, st.one_of(things, st.sampled_from([1, 2.5, "lit"]))),
)


def without_ids(docs):
    return [{k: v for k, v in d.items() if k != "_id"} for d in docs]


def two_stores(kind, root):
    (root / "a").mkdir()
    (root / "b").mkdir()
    return make_store(kind, root / "a"), make_store(kind, root / "b")


@pytest.mark.parametrize("kind", ["sqlite", "mongomock"])
def test_one_batch_stores_what_one_insert_per_triple_stores(tmp_path_factory, kind):
    """Hierarchy edges arriving mid-batch invalidate the per-batch closure cache."""

    @settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(st.lists(triples, max_size=30))
    def check(batch):
        whole, single = two_stores(kind, tmp_path_factory.mktemp("batch"))
        for store in (whole, single):
            store.create_neem("n")
        whole.insert("n", batch)
        for triple in batch:
            single.insert("n", [triple])
        assert without_ids(whole.read_documents("n", "triples")) == without_ids(single.read_documents("n", "triples"))
        whole.close()
        single.close()

    check()


def test_batch_closures_are_the_document_builders(tmp_path):
    edges = [Triple(X + "B", SUBCLASS_OF, X + "A"), Triple(X + "q", SUBPROPERTY_OF, X + "p")]
    rows = [Triple(X + "i1", RDF_TYPE, X + "B"), Triple(X + "i1", X + "q", X + "i2")]
    store = make_store("sqlite", tmp_path)
    store.create_neem("n")
    store.insert("n", edges + rows)
    hierarchy = Hierarchy()
    for edge in edges:
        hierarchy.add_edge(edge.s, edge.o)
    builder = DocumentBuilder(hierarchy)
    stored = {(d["s"], d["p"], d["o"]): (d["p*"], d["o*"]) for d in store.read_documents("n", "triples")}
    for triple in edges + rows:
        pstar, ostar = builder.closures(triple)
        assert stored[(triple.s, triple.p, triple.o)] == (list(pstar), list(ostar))
    assert stored[(X + "i1", RDF_TYPE, X + "B")][1] == [X + "B", X + "A"]
    assert stored[(X + "i1", X + "q", X + "i2")][0] == [X + "q", X + "p"]
    store.close()


def test_a_scope_ending_before_it_starts_is_refused(tmp_path):
    store = make_store("sqlite", tmp_path)
    store.create_neem("n")
    with pytest.raises(ValueError, match="ends before it starts"):
        store.insert("n", [Triple(X + "a", X + "p", X + "b", since=2.0, until=1.0)])
    assert store.count("n") == 0
    store.close()


def test_triples_are_immutable_values():
    t = Triple(X + "a", X + "p", 1.5, since=2.0)
    assert (t.s, t.p, t.o, t.graph, t.since, t.until) == (X + "a", X + "p", 1.5, "user", 2.0, float("inf"))
    assert pickle.loads(pickle.dumps(t)) == t and hash(t) == hash(Triple(X + "a", X + "p", 1.5, "user", 2.0))
    with pytest.raises(AttributeError):
        t.s = X + "b"  # type: ignore[misc]
