"""The shared behavioural suite: every backend must give these answers."""

from __future__ import annotations

import math

import pytest
from bson.decimal128 import Decimal128

from oracle.errors import StoreError
from oracle.store import RDF_TYPE, SUBCLASS_OF, SUBPROPERTY_OF, Annotation, Cmp, Scope, Triple, TriplePattern, Var
from tests.store.conftest import make_store

X = "http://example.org/x#"


def world(store, neem="n1"):
    """A 6-class taxonomy, two properties and a few individuals."""
    store.create_neem(neem, user="alice")
    store.insert(
        neem,
        [
            Triple(X + "Cup", SUBCLASS_OF, X + "Crockery"),
            Triple(X + "Crockery", SUBCLASS_OF, X + "Item"),
            Triple(X + "Thermos", SUBCLASS_OF, X + "Item"),
            Triple(X + "hasParticipant", SUBPROPERTY_OF, X + "associatedWith"),
            Triple(X + "isPerformedBy", SUBPROPERTY_OF, X + "hasParticipant"),
            Triple(X + "cup1", RDF_TYPE, X + "Cup"),
            Triple(X + "thermos1", RDF_TYPE, X + "Thermos"),
            Triple(X + "a1", X + "hasParticipant", X + "cup1"),
            Triple(X + "a1", X + "isPerformedBy", X + "robot"),
            Triple(X + "a2", X + "hasParticipant", X + "thermos1"),
            Triple(X + "a1", X + "begin", 10.5),
            Triple(X + "a2", X + "begin", 20.0),
        ],
    )
    return neem


def subjects(docs):
    return sorted(doc["s"] for doc in docs)


def test_type_query_uses_o_star(store):
    world(store)
    assert subjects(store.find("n1", p=RDF_TYPE, o=X + "Item")) == [X + "cup1", X + "thermos1"]
    assert subjects(store.find("n1", p=RDF_TYPE, o=X + "Crockery")) == [X + "cup1"]


def test_documents_carry_knowrob_closures(store):
    world(store)
    (doc,) = store.find("n1", s=X + "cup1", p=RDF_TYPE)
    assert doc["p*"] == [RDF_TYPE]
    assert doc["o*"] == [X + "Cup", X + "Crockery", X + "Item"]
    (doc,) = store.find("n1", s=X + "a1", p=X + "isPerformedBy")
    assert doc["p*"] == [X + "isPerformedBy", X + "hasParticipant", X + "associatedWith"]
    assert doc["o*"] == [X + "robot"]
    assert doc["scope"]["time"]["until"] == Decimal128("Infinity")


def test_property_query_uses_p_star(store):
    world(store)
    found = {(d["s"], d["o"]) for d in store.find("n1", p=X + "hasParticipant")}
    assert found == {(X + "a1", X + "cup1"), (X + "a1", X + "robot"), (X + "a2", X + "thermos1")}
    assert subjects(store.find("n1", p=X + "isPerformedBy")) == [X + "a1"]


def test_exact_find_ignores_closures(store):
    world(store)
    assert subjects(store.find("n1", p=X + "hasParticipant", exact=True)) == [X + "a1", X + "a2"]
    assert subjects(store.find("n1", p=RDF_TYPE, o=X + "Item", exact=True)) == []


def test_new_superclass_propagates_to_stored_documents(store):
    world(store)
    store.insert("n1", [Triple(X + "Item", SUBCLASS_OF, X + "Entity")])
    assert subjects(store.find("n1", p=RDF_TYPE, o=X + "Entity")) == [X + "cup1", X + "thermos1"]
    store.insert("n1", [Triple(X + "associatedWith", SUBPROPERTY_OF, X + "relatedTo")])
    assert subjects(store.find("n1", p=X + "relatedTo")) == [X + "a1", X + "a1", X + "a2"]


def test_numbers_match_whatever_their_stored_type(store):
    world(store)
    assert subjects(store.find("n1", o=10.5)) == [X + "a1"]
    assert subjects(store.find("n1", o=20)) == [X + "a2"]
    assert subjects(store.find("n1", o="20")) == []


def test_match_joins_patterns_in_one_query(store):
    world(store)
    rows = list(
        store.match(
            "n1",
            [
                TriplePattern(Var("A"), X + "hasParticipant", Var("O")),
                TriplePattern(Var("O"), RDF_TYPE, X + "Crockery"),
                TriplePattern(Var("A"), X + "begin", Var("T")),
            ],
        )
    )
    assert rows == [{"A": X + "a1", "O": X + "cup1", "T": 10.5}]


def test_match_select_keeps_the_rows_and_only_the_named_variables(store):
    world(store)
    patterns = [TriplePattern(Var("A"), X + "hasParticipant", Var("O")), TriplePattern(Var("A"), X + "begin", Var("T"))]
    every = list(store.match("n1", patterns))
    kept = list(store.match("n1", patterns, select=["T"]))
    assert kept == [{"T": row["T"]} for row in every] and len(kept) >= 2
    with pytest.raises(StoreError, match="'Z', which no pattern binds"):
        store.match("n1", patterns, select=["Z"])


def test_match_group_collects_one_variable_per_combination_of_the_others(store):
    world(store)
    store.insert("n1", [Triple(X + "a1", X + "hasParticipant", X + "cup2"), Triple(X + "a2", X + "begin", 20.25)])
    patterns = [TriplePattern(Var("A"), X + "hasParticipant", Var("O")), TriplePattern(Var("A"), X + "begin", Var("T"))]
    every = list(store.match("n1", patterns))
    expected: dict = {}
    for row in every:
        expected.setdefault((row["A"], row["T"]), []).append(row["O"])
    grouped = list(store.match("n1", patterns, select=["A", "T", "O"], group="O"))
    assert len(grouped) == len(expected) >= 3 and any(len(values) > 1 for values in expected.values())
    assert {(row["A"], row["T"]): sorted(row["O"]) for row in grouped} == {k: sorted(v) for k, v in expected.items()}
    alone = list(store.match("n1", patterns, select=["O"], group="O"))
    assert len(alone) == 1 and sorted(alone[0]["O"]) == sorted(row["O"] for row in every)
    with pytest.raises(StoreError, match="'O', which select drops"):
        store.match("n1", patterns, select=["A"], group="O")
    with pytest.raises(StoreError, match="no limit or order"):
        store.match("n1", patterns, group="O", limit=1)


def test_match_free_object_binds_asserted_type_and_bound_object_uses_closure(store):
    world(store)
    rows = list(store.match("n1", [TriplePattern(X + "cup1", RDF_TYPE, Var("C"))]))
    assert rows == [{"C": X + "Cup"}]
    rows = list(
        store.match(
            "n1",
            [TriplePattern(X + "Crockery", SUBCLASS_OF, Var("C")), TriplePattern(Var("I"), RDF_TYPE, Var("C"))],
        )
    )
    assert sorted(r["I"] for r in rows) == [X + "cup1", X + "thermos1"]


def test_match_repeated_variable_and_limit(store):
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "a", X + "knows", X + "a"), Triple(X + "a", X + "knows", X + "b")])
    assert list(store.match("n1", [TriplePattern(Var("S"), X + "knows", Var("S"))])) == [{"S": X + "a"}]
    assert len(list(store.match("n1", [TriplePattern(Var("S"), X + "knows", Var("O"))], limit=1))) == 1


@pytest.mark.parametrize("number_format", ["decimal128", "double"])
def test_comparisons_are_evaluated_by_the_database(backend, tmp_path, number_format):
    store = make_store(backend, tmp_path, number_format)
    try:
        world(store)
        store.insert("n1", [Triple(X + "a3", X + "begin", 30), Triple(X + "a4", X + "begin", "15"),
                            Triple(X + "a5", X + "begin", True)])  # fmt: skip
        begin = lambda op, v: sorted(  # noqa: E731
            (r["A"], r["T"]) for r in store.match("n1", [TriplePattern(Var("A"), X + "begin", Cmp(op, v, Var("T")))])
        )
        assert begin(">=", 20) == [(X + "a2", 20.0), (X + "a3", 30)]
        assert begin(">", 20.0) == [(X + "a3", 30)]
        assert begin("<", 20) == [(X + "a1", 10.5)]
        assert begin("=<", 20) == [(X + "a1", 10.5), (X + "a2", 20.0)]
        # a comparison without a variable, joined with other patterns
        rows = store.match("n1", [TriplePattern(Var("A"), X + "hasParticipant", Var("O")),
                                  TriplePattern(Var("A"), X + "begin", Cmp(">", 15))])  # fmt: skip
        assert [r["O"] for r in rows] == [X + "thermos1"]
        with pytest.raises(StoreError):
            list(store.find("n1", o=Cmp(">", 1)))
    finally:
        getattr(store, "_test_cleanup", lambda: None)()
        store.close()


def test_order_and_limit_give_the_latest_before_a_time(store):
    world(store)
    # (floats only: the mongomock-ng double cannot sort Decimal128 among ints; MongoDB can)
    store.insert("n1", [Triple(X + "a3", X + "begin", 30.0), Triple(X + "a4", X + "begin", 25.0)])
    latest = lambda *extra, limit=1, desc=True: list(  # noqa: E731
        store.match("n1", [TriplePattern(Var("A"), X + "begin", Cmp(*extra, Var("T")) if extra else Var("T"))],
                    order=[("T", desc)], limit=limit)  # fmt: skip
    )
    assert latest() == [{"A": X + "a3", "T": 30.0}]
    assert latest("=<", 26) == [{"A": X + "a4", "T": 25}]
    assert latest("<", 25, limit=None) == [{"A": X + "a2", "T": 20.0}, {"A": X + "a1", "T": 10.5}]
    assert [r["T"] for r in latest(limit=None, desc=False)] == [10.5, 20.0, 25, 30.0]
    with pytest.raises(StoreError):
        list(store.match("n1", [TriplePattern(Var("A"), X + "begin", Var("T"))], order=[("B", True)]))


def test_scope_hides_facts_outside_the_window(store):
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "r", X + "classifies", X + "cup1", since=100.0, until=200.0),
                        Triple(X + "r", X + "classifies", X + "cup2")])  # fmt: skip
    assert {d["o"] for d in store.find("n1", p=X + "classifies", scope=Scope(150, 150))} == {X + "cup1", X + "cup2"}
    assert {d["o"] for d in store.find("n1", p=X + "classifies", scope=Scope(300, 300))} == {X + "cup2"}
    rows = store.match("n1", [TriplePattern(Var("R"), X + "classifies", Var("O"))], scope=Scope(0, 50))
    assert [r["O"] for r in rows] == [X + "cup2"]


def test_registry_create_rename_drop(store):
    world(store)
    with pytest.raises(StoreError, match="already exists"):
        store.create_neem("n1")
    with pytest.raises(StoreError, match="invalid NEEM id"):
        store.create_neem("bad_id")
    store.rename_neem("n1", "kept")
    assert [info.id for info in store.neems()] == ["kept"]
    assert subjects(store.find("kept", p=RDF_TYPE, o=X + "Item")) == [X + "cup1", X + "thermos1"]
    assert store.neem("kept").user == "alice"
    store.drop_neem("kept")
    assert store.neems() == []
    with pytest.raises(StoreError, match="no NEEM"):
        list(store.find("kept"))


def test_neems_are_isolated(store):
    world(store, "n1")
    store.create_neem("n2")
    store.insert("n2", [Triple(X + "other", RDF_TYPE, X + "Cup")])
    assert subjects(store.find("n2", p=RDF_TYPE, o=X + "Crockery")) == []  # n2 has no taxonomy
    assert store.count("n1") == 12 and store.count("n2") == 1


def test_annotations_are_kept_apart(store):
    store.create_neem("n1")
    store.insert_annotations("n1", [Annotation(X + "Cup", "http://www.w3.org/2000/01/rdf-schema#label", "cup")])
    assert store.count("n1", "triples") == 0
    assert list(store.annotations("n1", s=X + "Cup")) == [
        Annotation(X + "Cup", "http://www.w3.org/2000/01/rdf-schema#label", "cup")
    ]
    (doc,) = store.read_documents("n1", "annotations")
    assert set(doc) == {"_id", "s", "p", "v"}


def test_double_number_format_writes_doubles(backend, tmp_path):
    store = make_store(backend, tmp_path, "double")
    try:
        store.create_neem("n1")
        store.insert("n1", [Triple(X + "t", X + "begin", 1.25)])
        (doc,) = store.read_documents("n1", "triples")
        assert type(doc["o"]) is float and doc["o*"] == [1.25]
        assert doc["scope"]["time"]["until"] == math.inf
        assert subjects(store.find("n1", o=1.25)) == [X + "t"]
    finally:
        getattr(store, "_test_cleanup", lambda: None)()
        store.close()


def test_failed_insert_writes_nothing(store):
    store.create_neem("n1")
    with pytest.raises((StoreError, TypeError)):
        store.insert("n1", [Triple(X + "a", X + "p", X + "b"), Triple(X + "a", X + "p", object())])  # type: ignore[arg-type]
    if store.__class__.__name__ == "SQLiteStore":
        assert store.count("n1") == 0
