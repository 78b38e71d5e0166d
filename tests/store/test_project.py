"""KnowRob's scope semantics on the stores: kb_project merges an overlapping scope (union),
until/since narrow it (intersection), kb_unproject deletes; SQLite, mongomock-ng and a real
MongoDB when NEEM_MONGO_URI names one (the shared ``store`` fixture)."""

from __future__ import annotations

import math

import pytest
from bson.decimal128 import Decimal128
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from oracle.errors import StoreError
from oracle.store import RDF_TYPE, Triple
from oracle.store.base import SUMMARY_KEY
from oracle.store.dump import export_neem, load_dump
from oracle.store.project import project, retract

X = "http://example.org/x#"
FACT = (X + "lea", X + "hasNumber", "+4934")


def scopes(store, neem="n", s=FACT[0], p=FACT[1], o=FACT[2]):
    found = []
    for doc in store.find(neem, s, p, o, exact=True):
        time = doc["scope"]["time"]
        found.append(tuple(float(v.to_decimal()) if isinstance(v, Decimal128) else float(v)
                           for v in (time["since"], time["until"])))  # fmt: skip
    return sorted(found)


def fact(since, until, o=FACT[2]):
    return Triple(FACT[0], FACT[1], o, since=since, until=until)


@pytest.fixture
def neem(store):
    store.create_neem("n")
    return store


def test_an_overlapping_projection_extends_the_stored_scope(neem):
    assert project(neem, "n", [fact(10, 20)]) == 1
    assert project(neem, "n", [fact(15, 30)]) == 0  # no new document: the stored one grows
    assert scopes(neem) == [(10.0, 30.0)]
    assert project(neem, "n", [fact(40, 50)]) == 1  # apart: a second document
    assert scopes(neem) == [(10.0, 30.0), (40.0, 50.0)]
    neem.update_meta("n", **{SUMMARY_KEY: {"actions": 0, "mark": neem.write_mark("n")}})
    assert project(neem, "n", [fact(25, 45)]) == 0  # bridges both: one document is left
    assert scopes(neem) == [(10.0, 50.0)]
    assert neem.count("n") == 1
    assert neem.neem("n").meta.get(SUMMARY_KEY) is None  # a delete drops the kept summary


def test_a_projection_of_another_value_is_another_fact(neem):
    project(neem, "n", [fact(10, 20), fact(15, 30, o="+49")])
    assert scopes(neem) == [(10.0, 20.0)] and scopes(neem, o="+49") == [(15.0, 30.0)]


def test_until_and_since_narrow_the_stored_scope(neem):
    project(neem, "n", [fact(0, math.inf)])
    assert project(neem, "n", [fact(0, 34)], merge="intersect") == 0
    assert scopes(neem) == [(0.0, 34.0)]
    project(neem, "n", [fact(10, math.inf)], merge="intersect")
    assert scopes(neem) == [(10.0, 34.0)]
    assert project(neem, "n", [fact(50, 60)], merge="intersect") == 1  # nothing to narrow: stored as new
    assert scopes(neem) == [(10.0, 34.0), (50.0, 60.0)]


def test_a_batch_merges_with_itself(neem):
    assert project(neem, "n", [fact(10, 20), fact(15, 30), fact(50, 60)]) == 2
    assert scopes(neem) == [(10.0, 30.0), (50.0, 60.0)]


def test_merged_documents_keep_their_closures(neem):
    project(neem, "n", [Triple(X + "Man", "http://www.w3.org/2000/01/rdf-schema#subClassOf", X + "Person"),
                        Triple(X + "lea", RDF_TYPE, X + "Man", since=1, until=5)])  # fmt: skip
    project(neem, "n", [Triple(X + "lea", RDF_TYPE, X + "Man", since=3, until=9)])
    (doc,) = neem.find("n", X + "lea", RDF_TYPE, X + "Person")
    assert doc["o*"][:2] == [X + "Man", X + "Person"] and doc["o"] == X + "Man"
    assert scopes(neem, s=X + "lea", p=RDF_TYPE, o=X + "Man") == [(1.0, 9.0)]


def test_retract_deletes_the_matching_documents_and_the_kept_summary(neem):
    project(neem, "n", [fact(0, 10), fact(0, 10, o="+49"), Triple(X + "bob", FACT[1], "+1")])
    neem.update_meta("n", **{SUMMARY_KEY: {"actions": 0, "mark": neem.write_mark("n")}})
    assert retract(neem, "n", FACT[0], FACT[1]) == 2
    assert scopes(neem) == [] and neem.count("n") == 1
    assert neem.neem("n").meta.get(SUMMARY_KEY) is None  # the next listing counts again
    assert retract(neem, "n", X + "nobody") == 0


def test_bad_arguments_change_nothing(neem):
    project(neem, "n", [fact(10, 20)])
    with pytest.raises(StoreError, match="merge must be"):
        project(neem, "n", [fact(15, 30)], merge="both")  # type: ignore[arg-type]
    with pytest.raises(StoreError, match="ends before it starts"):
        project(neem, "n", [fact(15, 30), fact(9, 5)])
    with pytest.raises(StoreError, match="query constant"):
        retract(neem, "n", {"$gt": ""})
    assert scopes(neem) == [(10.0, 20.0)]


def test_a_loaded_document_is_rescoped_in_its_own_bytes(neem, tmp_path):
    project(neem, "n", [fact(10, 20)])
    export_neem(neem, "n", tmp_path / "d")
    (loaded,) = load_dump(neem, tmp_path / "d", neem_id="copy")
    project(neem, loaded, [fact(15, 30)])
    assert scopes(neem, loaded) == [(10.0, 30.0)]
    (doc,) = neem.read_documents(loaded, "triples")
    assert doc["scope"]["time"] == {"since": Decimal128("10.0"), "until": Decimal128("30.0")}  # the dump's number type


def test_a_failed_batch_leaves_sqlite_as_it_was(tmp_path):
    from oracle.store.sqlite import SQLiteStore

    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n")
    project(store, "n", [fact(10, 20), fact(40, 50)])
    with pytest.raises(StoreError):
        project(store, "n", [fact(15, 45), Triple(FACT[0], FACT[1], object())])  # type: ignore[arg-type]
    assert scopes(store) == [(10.0, 20.0), (40.0, 50.0)]


intervals = st.tuples(st.integers(0, 30), st.integers(0, 30)).map(lambda t: (min(t), max(t)))


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(intervals, min_size=1, max_size=6))
def test_union_projections_hold_exactly_the_union_of_the_scopes(tmp_path_factory, spans):
    """Property: after any sequence of projections the stored scopes are disjoint and cover
    exactly the instants some projection covered (checked at every half second)."""
    from oracle.store.sqlite import SQLiteStore

    store = SQLiteStore(tmp_path_factory.mktemp("p") / "s.sqlite")
    store.create_neem("n")
    for since, until in spans:
        project(store, "n", [fact(since, until)])
    stored = scopes(store)
    assert all(a[1] < b[0] for a, b in zip(stored, stored[1:]))
    for tick in range(0, 62):
        t = tick / 2
        assert any(s <= t <= u for s, u in stored) == any(s <= t <= u for s, u in spans), (t, stored, spans)
    store.close()


def test_facts_of_a_side_table_property_merge_and_retract_like_any(store):
    """On SQLite a NEEM may keep one property's triples in a side table; a projection still
    finds and widens the stored copy there, and a retraction deletes it there."""
    store.create_neem("s", side_property=FACT[1])
    assert project(store, "s", [fact(10, 20)]) == 1
    assert project(store, "s", [fact(15, 30)]) == 0
    assert scopes(store, "s") == [(10.0, 30.0)]
    assert store.count("s") == 1
    retract(store, "s", FACT[0], FACT[1], FACT[2])
    assert scopes(store, "s") == [] and store.count("s") == 0
