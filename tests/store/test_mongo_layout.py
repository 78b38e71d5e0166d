"""The Mongo code path writes KnowRob's layout and queries the way mongolog does."""

from __future__ import annotations

from bson.decimal128 import Decimal128
from bson.objectid import ObjectId

from oracle.store import RDF_TYPE, Triple, TriplePattern, Var
from oracle.store.mongo import _EXTENT, TRIPLE_INDEXES, compile_pipeline
from tests.store.conftest import make_store

X = "http://example.org/x#"


def test_collections_indexes_one_and_meta(tmp_path):
    store = make_store("mongomock", tmp_path)
    store.create_neem("5fc8ff968f880006aa208e19", user="alice")
    names = set(store.db.list_collection_names())
    assert {f"5fc8ff968f880006aa208e19_{k}" for k in ("triples", "annotations", "tf", "inferred")} <= names
    keys = {tuple(k for k, _ in spec["key"]) for spec in store.db["5fc8ff968f880006aa208e19_triples"].index_information().values()}
    assert len(TRIPLE_INDEXES) == 15 and set(TRIPLE_INDEXES) <= keys
    (one,) = store.db["one"].find({}, {"_id": 0})
    assert one == {"v_scope": {"time": {"since": Decimal128("0"), "until": Decimal128("Infinity")}}}
    # openEASE looks a NEEM up by find_one({"_id": ObjectId(id)})
    assert store.db["meta"].find_one({"_id": ObjectId("5fc8ff968f880006aa208e19")})["created_by"] == "alice"
    assert [info.id for info in store.neems()] == ["5fc8ff968f880006aa208e19"]
    store.update_meta("5fc8ff968f880006aa208e19", description="mornings")
    assert store.db["meta"].count_documents({}) == 1 and store.neem("5fc8ff968f880006aa208e19").meta["description"] == "mornings"
    store.create_neem("alice", user="alice")  # other ids stay strings
    assert store.db["meta"].find_one({"_id": "alice"})["created_by"] == "alice"


def test_restored_collections_without_meta_are_listed(tmp_path):
    store = make_store("mongomock", tmp_path)
    store.db["abc_triples"].insert_one({"s": X + "a", "p": RDF_TYPE, "o": X + "C", "p*": [RDF_TYPE], "o*": [X + "C"]})
    assert [info.id for info in store.neems()] == ["abc"]
    assert [d["s"] for d in store.find("abc", p=RDF_TYPE, o=X + "C")] == [X + "a"]


def test_a_conjunction_is_one_aggregation_on_one():
    pipeline = compile_pipeline(
        "n_triples",
        [TriplePattern(Var("A"), X + "hasParticipant", Var("O")), TriplePattern(Var("O"), RDF_TYPE, X + "Cup")],
        None,
        None,
    )
    lookups = [stage["$lookup"] for stage in pipeline if "$lookup" in stage]
    assert [lk["from"] for lk in lookups] == ["n_triples", "n_triples"]
    assert "let" not in lookups[0] and lookups[1]["let"] == {"v_O": "$v_O"}
    # every lookup also keeps only documents whose scope has an extent (KnowRob's since < until)
    assert lookups[0]["pipeline"][0]["$match"] == {"p*": X + "hasParticipant", "$expr": _EXTENT}
    second = lookups[1]["pipeline"][0]["$match"]
    assert second["p"] == RDF_TYPE and second["o*"] == X + "Cup"
    assert second["$expr"] == {"$and": [{"$eq": ["$s", "$$v_O"]}, _EXTENT]}
    # and the rows, where the joined documents' scopes share one (mongolog's v_scope)
    assert {"$match": {"$expr": {"$lt": ["$k_since", "$k_until"]}}} in pipeline


def test_numbers_written_as_decimal128_are_found_by_a_double(tmp_path):
    store = make_store("mongomock", tmp_path)
    store.create_neem("n")
    store.insert("n", [Triple(X + "i", X + "begin", 12.5)])
    (doc,) = store.db["n_triples"].find({})
    assert doc["o"] == Decimal128("12.5")
    assert list(store.match("n", [TriplePattern(Var("I"), X + "begin", 12.5)])) == [{"I": X + "i"}]


def test_meta_has_the_fields_openease_reads(tmp_path):
    from datetime import datetime

    from oracle.store.meta import OPENEASE_FIELDS

    store = make_store("mongomock", tmp_path)
    store.create_neem("5fc8ff968f880006aa208e19", user="alice", meta={"description": "kitchen mornings"})
    doc = store.db["meta"].find_one({"_id": ObjectId("5fc8ff968f880006aa208e19")})
    assert set(OPENEASE_FIELDS) <= set(doc)  # openEASE's NEEM list reads these without a default
    assert doc["name"] == "5fc8ff968f880006aa208e19" and doc["description"] == "kitchen mornings"
    assert datetime.fromisoformat(doc["created_at"]).tzinfo is not None and isinstance(doc["url"], str)
    assert doc["visibility"] is False and "image" not in doc  # an absent image shows openEASE's cover
