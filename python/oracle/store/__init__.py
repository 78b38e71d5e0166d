"""NEEM store: KnowRob 2.x documents in an embedded SQLite file (default) or in MongoDB.

``open_store(spec)`` picks the backend from a command line's ``--store`` value; everything
else talks to the ``Store`` interface (docs/store.md).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any
from pathlib import Path

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, NeemInfo, Store, check_neem_id
from oracle.store.uri import PASSWORD_FILE_ENV, PasswordFileError, with_password_file
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
#: KnowRob 2.x's connection variables (``mng_client``): used when all four are set and
#: $NEEM_MONGO_URI is not, as KnowRob builds ``mongodb://USER:PASS@HOST:PORT`` from them.
KNOWROB_MONGO_ENV = ("KNOWROB_MONGO_HOST", "KNOWROB_MONGO_USER", "KNOWROB_MONGO_PASS", "KNOWROB_MONGO_PORT")


def mongo_uri_from_env(env: Mapping[str, str] | None = None) -> str | None:
    """The MongoDB URI the environment names: $NEEM_MONGO_URI (with the password read from
    $NEEM_MONGO_PASSWORD_FILE when that is set), else KnowRob's four variables."""
    env = os.environ if env is None else env
    uri = env.get(MONGO_ENV)
    if uri:
        password_file = env.get(PASSWORD_FILE_ENV)
        if not password_file:
            return uri
        try:
            return with_password_file(uri, password_file)
        except PasswordFileError as error:
            raise StoreError(str(error)) from None
    host, user, password, port = (env.get(name, "") for name in KNOWROB_MONGO_ENV)
    if not (host and user and password and port):
        return None
    from urllib.parse import quote

    return f"mongodb://{quote(user, safe='')}:{quote(password, safe='')}@{host}:{port}"


def default_store_path() -> Path:
    """Where the embedded store lives unless told otherwise: the user's data directory."""
    from platformdirs import user_data_dir

    return Path(user_data_dir("neem-oracle", appauthor=False)) / "default.sqlite"


def open_store(
    spec: str | os.PathLike[str] | None = None,
    *,
    number_format: NumberFormat = "decimal128",
    create: bool = True,
    read_only: bool = False,
    check_while_reading: bool = False,
) -> Store:
    """Open the store a ``--store`` value names.

    None: the server at $NEEM_MONGO_URI when it is set (or KnowRob's KNOWROB_MONGO_HOST, _USER,
    _PASS and _PORT, all four), else the default SQLite file;
    ``mongodb://...``: that server (database from the URI path, else ``roslog``); ``mongodb``:
    the server at $NEEM_MONGO_URI; ``sqlite:///PATH`` or a plain path: a SQLite file, created
    0600 if missing unless ``create`` is False (commands that only read pass False, so a typo'd
    path is an error instead of a new empty store). ``read_only`` (implies not ``create``)
    opens a SQLite file without writing anything, so a reader never waits for a writer.
    ``check_while_reading``: a writer's whole-file check of a SQLite file runs beside its reads,
    and its first write waits for it (for commands that read much and then write a little).
    """
    def sqlite_file(path: str | os.PathLike[str]) -> Store:
        from oracle.store.sqlite import SQLiteStore

        return SQLiteStore(path, number_format, create=create, read_only=read_only,
                           check_while_reading=check_while_reading)

    if spec is None:
        uri = mongo_uri_from_env()
        if uri:
            return open_mongo(uri, number_format=number_format)
        return sqlite_file(default_store_path())
    text = os.fspath(spec)
    if text in ("mongodb", "mongo"):
        uri = mongo_uri_from_env()
        if not uri:
            raise StoreError(
                f"--store {text}: set {MONGO_ENV} to the server's mongodb:// URI "
                f"(or KnowRob's {', '.join(KNOWROB_MONGO_ENV)})"
            )
        return open_mongo(uri, number_format=number_format)
    if text.startswith(("mongodb://", "mongodb+srv://")):
        return open_mongo(text, number_format=number_format)
    if text.startswith("sqlite://"):
        text = text[len("sqlite://") :]
        if not text:
            raise StoreError("sqlite:// needs a path, e.g. sqlite:///home/me/neems.sqlite")
    elif "://" in text:
        raise StoreError(f"unknown store {text!r}: expected a path, sqlite:///PATH or mongodb://HOST")
    return sqlite_file(text)


def open_mongo(uri: str, *, number_format: NumberFormat = "decimal128", timeout_ms: int = 3000) -> Store:
    """A MongoStore on a real server; the database is the URI's path or ``roslog``. Writes are
    acknowledged once a majority of the replica set has them in its journal, unless the URI sets
    ``w`` or ``journal``."""
    import pymongo
    from pymongo import uri_parser

    from oracle.store.mongo import DEFAULT_DB, MongoStore
    from oracle.store.uri import mask_uri, scrub

    try:
        parsed = uri_parser.parse_uri(uri)
        for name, _ in parsed["nodelist"]:
            # no resolver answers such a name: refused here, not after a lookup's timeout
            if not name or any(ch.isspace() or not ch.isprintable() for ch in name):
                raise ValueError(f"host {name!r} is not a host name")
        # An acknowledged write is on a majority of the replica set, in its journal (a standalone
        # server is its own majority), unless the URI says otherwise (w=, journal=): a failover
        # then loses nothing a robot was told is stored (docs/store.md, "Many robots on one hub").
        concern: dict[str, Any] = {} if {"w", "journal"} & set(parsed["options"]) else {"w": "majority", "journal": True}
        client: pymongo.MongoClient[dict[str, Any]] = pymongo.MongoClient(uri, serverSelectionTimeoutMS=timeout_ms,
                                                                          **concern)
    except Exception as error:
        # The URI may hold a password (from --store or $NEEM_MONGO_URI): never echo it.
        hint = "; percent-encode '@', '/' and ':' in a user name or password" if "@" in uri else ""
        raise StoreError(f"{mask_uri(uri)}: not a usable MongoDB URI ({scrub(str(error), uri)}){hint}") from None
    host = ",".join(f"{h}:{p}" for h, p in parsed["nodelist"])
    db_name = parsed.get("database") or DEFAULT_DB
    return MongoStore(client, db_name, number_format, location=f"mongodb://{host}/{db_name}")


__all__ = [
    "INFINITY", "COLLECTION_KINDS", "MONGO_ENV", "RDF_TYPE", "SUBCLASS_OF", "SUBPROPERTY_OF", "TAXONOMIC",
    "Annotation", "Cmp", "NeemInfo", "NumberFormat", "Scope", "Store", "Triple", "TriplePattern", "Var",
    "KNOWROB_MONGO_ENV", "check_neem_id", "default_store_path", "mongo_uri_from_env", "open_mongo", "open_store",
]  # fmt: skip
