"""Both backends hold the same documents and give the same answers, whatever is inserted."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from oracle.store import RDF_TYPE, SUBCLASS_OF, SUBPROPERTY_OF, Triple, TriplePattern, Var
from tests.store.conftest import make_store

X = "http://example.org/x#"
classes = st.sampled_from([X + c for c in ("A", "B", "C", "D", "E")])
props = st.sampled_from([X + p for p in ("p", "q", "r")])
things = st.sampled_from([X + i for i in ("i1", "i2", "i3")])
literals = st.one_of(st.integers(-5, 5), st.sampled_from([0.5, 1.5, 1e9]), st.sampled_from(["a", "b"]))

triples = st.one_of(
    st.builds(Triple, classes, st.just(SUBCLASS_OF), classes),
    st.builds(Triple, props, st.just(SUBPROPERTY_OF), props),
    st.builds(Triple, things, st.just(RDF_TYPE), classes),
    st.builds(Triple, things, props, st.one_of(things, literals)),
)
terms = st.one_of(st.builds(Var, st.sampled_from(["S", "O", "Z"])), st.none())
patterns = st.one_of(
    st.builds(TriplePattern, st.one_of(terms, things), st.just(RDF_TYPE), st.one_of(terms, classes)),
    st.builds(TriplePattern, st.one_of(terms, things), st.one_of(props, st.builds(Var, st.just("P"))), st.one_of(terms, things, literals)),
    st.builds(TriplePattern, st.one_of(terms, classes), st.just(SUBCLASS_OF), st.one_of(terms, classes)),
)


def without_ids(docs):
    return [{k: v for k, v in d.items() if k != "_id"} for d in docs]


def canonical(rows):
    return sorted(sorted((k, repr(v)) for k, v in row.items()) for row in rows)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(triples, max_size=25), st.lists(st.lists(patterns, min_size=1, max_size=3), max_size=4))
def test_sqlite_and_mongo_agree(tmp_path_factory, batch, queries):
    root = tmp_path_factory.mktemp("eq")
    stores = [make_store("sqlite", root), make_store("mongomock", root)]
    for store in stores:
        store.create_neem("n")
        store.insert("n", batch)
    sqlite, mongo = stores
    assert without_ids(sqlite.read_documents("n", "triples")) == without_ids(mongo.read_documents("n", "triples"))
    for query in queries:
        assert canonical(sqlite.match("n", query)) == canonical(mongo.match("n", query)), query
    for store in stores:
        store.close()
