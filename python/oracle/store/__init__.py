"""NEEM store: KnowRob 2.x documents in an embedded SQLite file (default) or in MongoDB.

``open_store(spec)`` picks the backend from a command line's ``--store`` value; everything
else talks to the ``Store`` interface (docs/store.md).
"""

from __future__ import annotations

import os
from typing import Any
from pathlib import Path

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, NeemInfo, Store, check_neem_id
from oracle.store.model import (
    INFINITY,
    RDF_TYPE,
    SUBCLASS_OF,
    SUBPROPERTY_OF,
    TAXONOMIC,
    Annotation,
    Cmp,
    NumberFormat,
    Scope,
    Triple,
    TriplePattern,
    Var,
)

#: Environment variable naming the MongoDB server used by ``--store mongodb`` and the tests.
MONGO_ENV = "NEEM_MONGO_URI"


def default_store_path() -> Path:
    """Where the embedded store lives unless told otherwise: the user's data directory."""
    from platformdirs import user_data_dir

    return Path(user_data_dir("neem-oracle", appauthor=False)) / "default.sqlite"


def open_store(
    spec: str | os.PathLike[str] | None = None, *, number_format: NumberFormat = "decimal128", create: bool = True
) -> Store:
    """Open the store a ``--store`` value names.

    None: the server at $NEEM_MONGO_URI when it is set, else the default SQLite file;
    ``mongodb://...``: that server (database from the URI path, else ``roslog``); ``mongodb``:
    the server at $NEEM_MONGO_URI; ``sqlite:///PATH`` or a plain path: a SQLite file, created
    0600 if missing unless ``create`` is False (commands that only read pass False, so a typo'd
    path is an error instead of a new empty store).
    """
    if spec is None:
        uri = os.environ.get(MONGO_ENV)
        if uri:
            return open_mongo(uri, number_format=number_format)
        from oracle.store.sqlite import SQLiteStore

        return SQLiteStore(default_store_path(), number_format, create=create)
    text = os.fspath(spec)
    if text in ("mongodb", "mongo"):
        uri = os.environ.get(MONGO_ENV)
        if not uri:
            raise StoreError(f"--store {text}: set {MONGO_ENV} to the server's mongodb:// URI")
        return open_mongo(uri, number_format=number_format)
    if text.startswith(("mongodb://", "mongodb+srv://")):
        return open_mongo(text, number_format=number_format)
    if text.startswith("sqlite://"):
        text = text[len("sqlite://") :]
        if not text:
            raise StoreError("sqlite:// needs a path, e.g. sqlite:///home/me/neems.sqlite")
    elif "://" in text:
        raise StoreError(f"unknown store {text!r}: expected a path, sqlite:///PATH or mongodb://HOST")
    from oracle.store.sqlite import SQLiteStore

    return SQLiteStore(text, number_format, create=create)


def open_mongo(uri: str, *, number_format: NumberFormat = "decimal128", timeout_ms: int = 3000) -> Store:
    """A MongoStore on a real server; the database is the URI's path or ``roslog``."""
    import pymongo
    from pymongo import uri_parser

    from oracle.store.mongo import DEFAULT_DB, MongoStore

    try:
        parsed = uri_parser.parse_uri(uri)
        client: pymongo.MongoClient[dict[str, Any]] = pymongo.MongoClient(uri, serverSelectionTimeoutMS=timeout_ms)
    except Exception as error:
        raise StoreError(f"{uri}: not a usable MongoDB URI ({error})") from None
    host = ",".join(f"{h}:{p}" for h, p in parsed["nodelist"])
    db_name = parsed.get("database") or DEFAULT_DB
    return MongoStore(client, db_name, number_format, location=f"mongodb://{host}/{db_name}")


__all__ = [
    "INFINITY", "COLLECTION_KINDS", "MONGO_ENV", "RDF_TYPE", "SUBCLASS_OF", "SUBPROPERTY_OF", "TAXONOMIC",
    "Annotation", "Cmp", "NeemInfo", "NumberFormat", "Scope", "Store", "Triple", "TriplePattern", "Var",
    "check_neem_id", "default_store_path", "open_mongo", "open_store",
]  # fmt: skip
