"""Interchange: the mongodump layout, exact round trips, and dumps written by KnowRob."""

from __future__ import annotations

import datetime as dt
import json
import os
import stat

import pytest
from bson.decimal128 import Decimal128
from bson.int64 import Int64
from bson.objectid import ObjectId
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from oracle.errors import StoreError
from oracle.store import RDF_TYPE, SUBCLASS_OF, Triple
from oracle.store.dump import export_all, export_neem, iter_bson, load_dump, write_dump
from oracle.store.sqlite import SQLiteStore
from tests.store.conftest import make_store

X = "http://example.org/x#"
DUL = "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#"


def bson_files(root):
    """The collections of a dump; not the hub registry document (``meta/``), which names the
    NEEM it describes: two NEEMs with the same documents have two registry entries."""
    return {p.relative_to(root): p.read_bytes() for p in sorted(root.rglob("*.bson")) if p.relative_to(root).parts[0] != "meta"}


def small_neem(store, neem="n1"):
    store.create_neem(neem, user="alice")
    store.insert(neem, [Triple(X + "Cup", SUBCLASS_OF, X + "Item"), Triple(X + "c", RDF_TYPE, X + "Cup"),
                        Triple(X + "ti", X + "begin", 1700000000.25), Triple(X + "r", X + "n", 3),
                        Triple(X + "r", X + "big", 2**40), Triple(X + "r", X + "ok", True)])  # fmt: skip


def test_export_writes_knowrob_names_and_types(store, tmp_path):
    small_neem(store)
    export_neem(store, "n1", tmp_path / "out")
    for kind in ("triples", "annotations", "tf", "inferred"):
        assert (tmp_path / "out" / kind / "roslog" / f"{kind}.bson").is_file()
        meta = json.loads((tmp_path / "out" / kind / "roslog" / f"{kind}.metadata.json").read_text())
        assert meta["collectionName"] == kind
    meta = json.loads((tmp_path / "out" / "triples" / "roslog" / "triples.metadata.json").read_text())
    assert len(meta["indexes"]) == 16  # _id plus KnowRob's 15
    docs = list(iter_bson(tmp_path / "out" / "triples" / "roslog" / "triples.bson"))
    assert all(list(d) == ["_id", "s", "p", "o", "p*", "o*", "graph", "scope"] for d in docs)
    by_p = {d["p"]: d for d in docs}
    assert isinstance(by_p[X + "begin"]["o"], Decimal128)
    assert by_p[X + "begin"]["o"].to_decimal() == Decimal128("1700000000.25").to_decimal()
    assert type(by_p[X + "n"]["o"]) is int and isinstance(by_p[X + "big"]["o"], Int64)
    assert by_p[X + "ok"]["o"] is True
    assert isinstance(by_p[RDF_TYPE]["_id"], ObjectId)
    assert by_p[RDF_TYPE]["scope"]["time"]["until"] == Decimal128("Infinity")
    for path in (tmp_path / "out").rglob("*"):
        if path.is_file():
            assert stat.S_IMODE(os.stat(path).st_mode) == 0o600


def test_export_load_export_is_identical(store, tmp_path):
    small_neem(store)
    export_neem(store, "n1", tmp_path / "a")
    (copy,) = load_dump(store, tmp_path / "a", neem_id="copy")  # a new NEEM named copy
    assert copy != "n1" and store.neem(copy).meta["alias"] == "copy"
    export_neem(store, copy, tmp_path / "b")
    assert bson_files(tmp_path / "a") == bson_files(tmp_path / "b")
    assert store.neem(copy).user == "alice"


def test_load_into_the_other_backend_is_identical(tmp_path):
    sqlite = make_store("sqlite", tmp_path)
    mongo = make_store("mongomock", tmp_path)
    small_neem(sqlite)
    export_neem(sqlite, "n1", tmp_path / "a")
    assert load_dump(mongo, tmp_path / "a") == ["n1"]  # the id recorded in meta.json
    export_neem(mongo, "n1", tmp_path / "b")
    assert bson_files(tmp_path / "a") == bson_files(tmp_path / "b")


def knowrob_doc(s, p, o, ostar, pstar=None):
    """A document as KnowRob 2.x writes it (Decimal128 scope, o* closure)."""
    return {"_id": ObjectId(), "s": s, "p": p, "o": o, "p*": pstar or [p], "o*": ostar, "graph": "user",
            "scope": {"time": {"since": Decimal128("0"), "until": Decimal128("Infinity")}}}  # fmt: skip


def test_load_an_openease_style_hub_dump(tmp_path):
    """openEASE keeps NEEMs as <24-hex id>_triples etc.; values may be Decimal128 and Dates."""
    neem_id = "5fc8ff968f880006aa208e19"
    triples = [
        knowrob_doc(X + "act", RDF_TYPE, DUL + "Action", [DUL + "Action", DUL + "Event", DUL + "Entity"]),
        knowrob_doc(X + "ti", "http://www.ease-crc.org/ont/SOMA.owl#hasIntervalBegin",
                    Decimal128("1606991255.8176"), [Decimal128("1606991255.8176")]),  # fmt: skip
    ]
    tf = [{"_id": ObjectId(), "header": {"seq": 1, "stamp": dt.datetime(2020, 12, 3, 10, 27, 35, 817000),
           "frame_id": "map"}, "child_frame_id": "base_link",
           "transform": {"translation": {"x": 1.0, "y": 0.0, "z": 0.0}, "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}},
           "__recorded": dt.datetime(2020, 12, 3, 10, 27, 36), "__topic": "/tf"}]  # fmt: skip
    write_dump(tmp_path / "hub", {"triples": triples, "tf": tf}, prefix=neem_id, db_name="neems")
    store = SQLiteStore(tmp_path / "s.sqlite")
    assert load_dump(store, tmp_path / "hub") == [neem_id]
    assert [d["s"] for d in store.find(neem_id, p=RDF_TYPE, o=DUL + "Event")] == [X + "act"]
    assert [d["s"] for d in store.find(neem_id, o=1606991255.8176)] == [X + "ti"]
    export_neem(store, neem_id, tmp_path / "again", db_name="neems")
    assert list(iter_bson(tmp_path / "again" / "triples" / "neems" / "triples.bson")) == triples
    assert list(iter_bson(tmp_path / "again" / "tf" / "neems" / "tf.bson")) == tf


def test_export_all_and_load_a_folder_of_neems(store, tmp_path):
    small_neem(store, "n1")
    small_neem(store, "n2")
    export_all(store, tmp_path / "all")
    target = SQLiteStore(tmp_path / "t.sqlite")
    assert load_dump(target, tmp_path / "all") == ["n1", "n2"]
    with pytest.raises(StoreError, match="already exists"):
        load_dump(target, tmp_path / "all" / "n1")


def test_a_truncated_dump_is_an_error_and_leaves_nothing(tmp_path):
    store = SQLiteStore(tmp_path / "s.sqlite")
    small_neem(store)
    export_neem(store, "n1", tmp_path / "a")
    path = tmp_path / "a" / "triples" / "roslog" / "triples.bson"
    path.write_bytes(path.read_bytes()[:-7])
    with pytest.raises(StoreError, match="triples.bson: document 6 is truncated"):
        load_dump(store, tmp_path / "a", neem_id="broken")
    assert not store.has_neem("broken")


iris = st.from_regex(r"http://example\.org/[a-z]{1,8}#[A-Za-z_]{1,10}", fullmatch=True)
values = st.one_of(
    iris,
    st.text(max_size=20),
    st.integers(min_value=-(2**31), max_value=2**31 - 1),
    st.integers(min_value=2**31, max_value=2**62).map(Int64),
    st.floats(allow_nan=False),
    st.decimals(min_value=-10**12, max_value=10**12, allow_nan=False, allow_infinity=False, places=4).map(lambda d: Decimal128(str(d))),
    st.booleans(),
    st.datetimes(min_value=dt.datetime(1970, 1, 1), max_value=dt.datetime(2100, 1, 1)).map(
        lambda d: d.replace(microsecond=d.microsecond // 1000 * 1000)
    ),
)


@st.composite
def documents(draw):
    p = draw(st.one_of(st.just(RDF_TYPE), st.just(SUBCLASS_OF), iris))
    o = draw(values)
    doc = {"_id": ObjectId(), "s": draw(iris), "p": p, "o": o, "p*": draw(st.lists(iris, min_size=1, max_size=3)),
           "o*": draw(st.one_of(st.just([o]), st.lists(iris, min_size=1, max_size=4))),
           "graph": draw(st.sampled_from(["user", "SOMA"]))}  # fmt: skip
    if draw(st.booleans()):
        since = draw(st.one_of(st.just(Decimal128("0")), st.floats(0, 2e9)))
        doc["scope"] = {"time": {"since": since, "until": draw(st.sampled_from([Decimal128("Infinity"), float("inf"), 2e9]))}}
    return doc


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(documents(), max_size=12), st.lists(st.fixed_dictionaries({"s": iris, "p": iris, "v": st.text(max_size=10)}), max_size=3))
def test_dump_load_dump_is_the_identity(tmp_path_factory, triples, annotations):
    root = tmp_path_factory.mktemp("rt")
    annotations = [{"_id": ObjectId(), **a} for a in annotations]
    write_dump(root / "a", {"triples": triples, "annotations": annotations}, meta={"created_by": "x"})
    store = SQLiteStore(root / "s.sqlite")
    (neem_id,) = load_dump(store, root / "a", neem_id="n")
    export_neem(store, neem_id, root / "b")
    assert bson_files(root / "a") == bson_files(root / "b")
    store.close()
