"""Backends the shared suite runs on: SQLite always, mongomock-ng as a double for the Mongo code
path, and a real MongoDB only when NEEM_MONGO_URI names one."""

from __future__ import annotations

import os
import uuid

import pytest

from oracle.store.mongo import MongoStore
from oracle.store.sqlite import SQLiteStore

NO_SERVER = "no MongoDB server at NEEM_MONGO_URI"


def make_store(kind: str, tmp_path, number_format: str = "decimal128"):
    if kind == "sqlite":
        return SQLiteStore(tmp_path / "store.sqlite", number_format)
    if kind == "mongomock":
        mongomock_ng = pytest.importorskip("mongomock_ng")
        return MongoStore(mongomock_ng.MongoClient(), "roslog", number_format)
    uri = os.environ.get("NEEM_MONGO_URI")
    if not uri:
        pytest.skip(NO_SERVER)
    import pymongo

    client = pymongo.MongoClient(uri, serverSelectionTimeoutMS=3000)
    db_name = f"neem_oracle_test_{uuid.uuid4().hex[:8]}"
    store = MongoStore(client, db_name, number_format)
    store._test_cleanup = lambda: client.drop_database(db_name)  # type: ignore[attr-defined]
    return store


@pytest.fixture(params=["sqlite", "mongomock", "mongodb"])
def backend(request):
    return request.param


@pytest.fixture
def store(backend, tmp_path):
    store = make_store(backend, tmp_path)
    yield store
    cleanup = getattr(store, "_test_cleanup", None)
    if cleanup is not None:
        cleanup()
    store.close()
