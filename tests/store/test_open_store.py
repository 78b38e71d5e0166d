"""Which store a command opens: only writers create one, and NEEM_MONGO_URI is the default server."""

from __future__ import annotations

import pytest

from oracle.cli import main
from oracle.errors import StoreError
from oracle.store import open_store
from oracle.store.mongo import MongoStore
from oracle.store.sqlite import SQLiteStore


def test_reading_a_missing_store_is_an_error_naming_it(tmp_path):
    missing = tmp_path / "typo" / "x.sqlite"
    with pytest.raises(StoreError, match=str(missing)):
        open_store(missing, create=False)
    assert not missing.parent.exists()


@pytest.mark.parametrize("command", [["neems"], ["export", "--out", "OUT"], ["what-next"], ["rank"],
                                     ["persist", "--neem", "a", "--as", "b"], ["prolog"]])
def test_read_commands_never_create_a_store(tmp_path, capsys, command):
    missing = tmp_path / "nonexistent" / "dir" / "x.sqlite"
    argv = [str(tmp_path / "out") if a == "OUT" else a for a in command]
    assert main(argv + ["--store", str(missing)]) == 1
    err = capsys.readouterr().err
    assert str(missing) in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "nonexistent").exists()


def test_writing_commands_create_the_store(tmp_path, capsys):
    chains = tmp_path / "c.jsonl"
    chains.write_text('{"user": "ada", "time": "2026-01-01T08:00:00", "action": "pick(apple)"}\n')
    target = tmp_path / "new" / "x.sqlite"
    assert main(["import", str(chains), "--store", str(target)]) == 0
    assert target.exists()


def test_the_default_store_is_the_server_at_neem_mongo_uri(monkeypatch):
    mongomock_ng = pytest.importorskip("mongomock_ng")
    monkeypatch.setenv("NEEM_MONGO_URI", "mongodb://127.0.0.1:27999/labdb")
    monkeypatch.setattr("pymongo.MongoClient", mongomock_ng.MongoClient)
    with open_store(None) as store:
        assert isinstance(store, MongoStore)
        assert store.location == "mongodb://127.0.0.1:27999/labdb"


def test_without_neem_mongo_uri_the_default_store_is_sqlite(monkeypatch, tmp_path):
    from oracle.store import KNOWROB_MONGO_ENV

    for name in ("NEEM_MONGO_URI", *KNOWROB_MONGO_ENV):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    monkeypatch.setenv("HOME", str(tmp_path))
    with open_store(None) as store:
        assert isinstance(store, SQLiteStore)


def test_knowrobs_connection_variables_name_the_server(monkeypatch):
    from oracle.store import KNOWROB_MONGO_ENV, mongo_uri_from_env

    env = dict(zip(KNOWROB_MONGO_ENV, ["db.lab", "ro@bot", "p:w/d", "27018"]))
    assert mongo_uri_from_env(env) == "mongodb://ro%40bot:p%3Aw%2Fd@db.lab:27018"
    assert mongo_uri_from_env({**env, "NEEM_MONGO_URI": "mongodb://h:1"}) == "mongodb://h:1"  # ours first
    assert mongo_uri_from_env({k: v for k, v in env.items() if k != "KNOWROB_MONGO_PASS"}) is None  # all four
    mongomock_ng = pytest.importorskip("mongomock_ng")
    monkeypatch.delenv("NEEM_MONGO_URI", raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    monkeypatch.setattr("pymongo.MongoClient", mongomock_ng.MongoClient)
    with open_store("mongodb") as store:
        assert isinstance(store, MongoStore)
        assert "p:w/d" not in store.location  # the password is masked
