"""openEASE-ready exports: the registry as the NEEM hub's ``meta`` collection (restorable as
mongorestore restores it, listed by ``find({visibility: true})`` and found by ``$text``), the
hub's ``<id>_`` collections, whole SOMA/DUL graphs with ``--soma``, incomplete dumps refused,
and honest provenance of NEEMs someone else recorded."""

from __future__ import annotations

import json
import os
import re
import shutil
from datetime import datetime
from pathlib import Path

import bson
import pytest
from bson import json_util
from bson.objectid import ObjectId

from oracle.cli import main
from oracle.errors import StoreError
from oracle.neem.writer import NeemLogger
from oracle.store import open_store
from oracle.store.dump import export_neem, iter_bson, load_dump
from oracle.store.meta import OPENEASE_FIELDS

mongomock_ng = pytest.importorskip("mongomock_ng")
#: The official SOMA, DUL and SOMA-HOME files (the test that needs them skips without them).
SOMA_DIR = Path(os.environ.get("NEEM_SOMA_DIR", "/work/shared/soma"))


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


def logged(tmp_path: Path, onto) -> tuple[object, str]:
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="ada", neem_id="breakfast")
    log.action("pick(apple)", datetime(2024, 5, 1, 8, 0), datetime(2024, 5, 1, 8, 1), state="succeeded")
    log.close()
    return store, log.neem_id


def mongorestore(dump: Path, db) -> None:
    """What mongorestore does with a dump folder: each ``<name>.bson`` into collection ``name``
    of the database named by its folder, then the indexes its ``.metadata.json`` lists."""
    for path in sorted(dump.rglob("*.bson")):
        name = path.name[: -len(".bson")]
        docs = list(iter_bson(path))
        if docs:
            db[name].insert_many(docs)
        meta = json_util.loads((path.parent / f"{name}.metadata.json").read_text())
        for index in meta["indexes"]:
            if index["name"] == "_id_":
                continue
            if index["key"].get("_fts") == "text":
                db[name].create_index([(f, "text") for f in index["weights"]], name=index["name"], weights=index["weights"])
            else:
                db[name].create_index(list(index["key"].items()), name=index["name"])


def text_search(coll, words: str, query: dict) -> list[dict]:
    """``find({...query, $text: {$search: words}})`` as MongoDB answers it (any word, case
    folded, over the fields the text index weighs). mongomock-ng does not implement ``$text``;
    the index it holds names the fields."""
    (index,) = [i for i in coll.index_information().values() if any(v == "text" for _, v in i["key"])]
    fields = [f for f, _ in index["key"]]
    wanted = set(words.lower().split())

    def text(doc: dict, field: str) -> str:
        value: object = doc
        for part in field.split("."):
            value = value.get(part) if isinstance(value, dict) else None
        return " ".join(value) if isinstance(value, list) else str(value or "")

    return [d for d in coll.find(query) if wanted & set(re.findall(r"\w+", " ".join(text(d, f) for f in fields).lower()))]


def test_registry_restores_is_listed_and_found_by_text(tmp_path, onto) -> None:
    store, neem_id = logged(tmp_path, onto)
    export_neem(store, neem_id, tmp_path / "dump", db_name="neems", hub_prefix=True, visibility=True)
    (entry,) = iter_bson(tmp_path / "dump" / "meta" / "neems" / "meta.bson")
    assert isinstance(entry["_id"], ObjectId) and str(entry["_id"]) == neem_id
    assert all(field in entry for field in OPENEASE_FIELDS) and entry["visibility"] is True
    db = mongomock_ng.MongoClient()["neems"]
    mongorestore(tmp_path / "dump", db)
    assert f"{neem_id}_triples" in db.list_collection_names() and f"{neem_id}_tf" in db.list_collection_names()
    assert [str(d["_id"]) for d in db.meta.find({"visibility": True})] == [neem_id]
    assert [d["name"] for d in text_search(db.meta, "Breakfast", {"visibility": True})] == ["breakfast"]
    assert text_search(db.meta, "lunch", {"visibility": True}) == []
    store.close()


def test_private_by_default_and_said_so(tmp_path, onto, capsys) -> None:
    store, neem_id = logged(tmp_path, onto)
    store.close()
    assert main(["export", "--store", str(tmp_path / "s.sqlite"), "--neem", neem_id, "--out", str(tmp_path / "d")]) == 0
    err = capsys.readouterr().err
    assert "visibility: false" in err and "--soma" in err
    (entry,) = iter_bson(tmp_path / "d" / "meta" / "roslog" / "meta.bson")
    assert entry["visibility"] is False


def test_a_dump_without_its_triples_is_refused_in_one_line(tmp_path, onto) -> None:
    store, neem_id = logged(tmp_path, onto)
    export_neem(store, neem_id, tmp_path / "d")
    (tmp_path / "d" / "triples" / "roslog" / "triples.bson").unlink()
    other = open_store(tmp_path / "o.sqlite")
    with pytest.raises(StoreError, match=r"no triples\.bson beside .*incomplete") as caught:
        load_dump(other, tmp_path / "d")
    assert "\n" not in str(caught.value) and other.neems() == []
    store.close()
    other.close()


def test_someone_elses_neem_is_not_claimed(tmp_path, onto) -> None:
    store, neem_id = logged(tmp_path, onto)
    export_neem(store, neem_id, tmp_path / "d")
    (tmp_path / "d" / "meta.json").unlink()  # a KnowRob memorize dump has no registry entry
    shutil.rmtree(tmp_path / "d" / "meta")
    other = open_store(tmp_path / "o.sqlite")
    (loaded,) = load_dump(other, tmp_path / "d")
    meta = other.neem(loaded).meta
    assert "neem-oracle" not in json.dumps(meta, default=str)
    assert not str(meta["name"]).startswith("staging-") and meta["created_by"] is None
    store.close()
    other.close()


@pytest.mark.skipif(not (SOMA_DIR / "SOMA.owl").is_file(), reason=f"no official SOMA files in {SOMA_DIR}")
def test_soma_puts_the_whole_graphs_in_the_neem(tmp_path, onto) -> None:
    store, neem_id = logged(tmp_path, onto)
    small = export_neem(store, neem_id, tmp_path / "a")
    files = [SOMA_DIR / n for n in ("SOMA.owl", "DUL.owl", "SOMA-HOME.owl")]
    full = export_neem(store, neem_id, tmp_path / "b", ontology_files=files)
    graphs = {d.get("graph") for d in iter_bson(tmp_path / "b" / "triples" / "roslog" / "triples.bson")}
    assert {"SOMA", "DUL", "SOMA-HOME", "user"} <= graphs
    assert full["triples"] > small["triples"] + 5000
    other = open_store(tmp_path / "o.sqlite")
    (loaded,) = load_dump(other, tmp_path / "b")  # the counts meta.json states match what was written
    assert other.count(loaded) == full["triples"]
    store.close()
    other.close()


def test_the_mongo_backend_indexes_its_registry_for_text_search(tmp_path) -> None:
    from oracle.store.meta import HUB_TEXT_FIELDS, HUB_TEXT_INDEX
    from tests.store.conftest import make_store

    store = make_store("mongomock", tmp_path)
    store.create_neem("n")
    index = store.db["meta"].index_information()[HUB_TEXT_INDEX]
    assert [field for field, _ in index["key"]] == list(HUB_TEXT_FIELDS)
    store.close()
