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


def test_the_password_comes_from_neem_mongo_password_file(tmp_path):
    from oracle.store import mongo_uri_from_env

    secret = tmp_path / "pw"
    secret.write_text("p@ss/w:rd%\n")
    env = {"NEEM_MONGO_URI": "mongodb://neem@mongo:27017/roslog?authSource=admin", "NEEM_MONGO_PASSWORD_FILE": str(secret)}
    assert mongo_uri_from_env(env) == "mongodb://neem:p%40ss%2Fw%3Ard%25@mongo:27017/roslog?authSource=admin"
    assert mongo_uri_from_env({**env, "NEEM_MONGO_URI": "mongodb://neem@h1:1,h2:2"}) == "mongodb://neem:p%40ss%2Fw%3Ard%25@h1:1,h2:2"


@pytest.mark.parametrize(
    ("uri", "content", "message"),
    [
        ("mongodb://mongo:27017/roslog", "pw\n", "names no user"),
        ("mongodb://neem:inline-pw@mongo/roslog", "pw\n", "already holds a password"),
        ("mongodb://neem@mongo/roslog", None, "cannot read it"),
        ("mongodb://neem@mongo/roslog", "", "one password on one line"),
        ("mongodb://neem@mongo/roslog", "two\nlines\n", "one password on one line"),
        ("mongodb://neem@mongo/roslog", b"\xff\xfe-secret", "not UTF-8"),
        ("mongodb://neem@mongo/roslog", "s" * 5000, "longer than 4096"),
    ],
)
def test_a_bad_password_file_is_one_line_that_never_shows_a_password(tmp_path, uri, content, message):
    from oracle.store import mongo_uri_from_env

    secret = tmp_path / "pw"
    if isinstance(content, bytes):
        secret.write_bytes(content)
    elif content is not None:
        secret.write_text(content)
    with pytest.raises(StoreError, match=message) as caught:
        mongo_uri_from_env({"NEEM_MONGO_URI": uri, "NEEM_MONGO_PASSWORD_FILE": str(secret)})
    text = str(caught.value)
    assert "\n" not in text and "inline-pw" not in text and "secret" not in text and "sss" not in text


def test_a_command_with_a_bad_password_file_exits_with_one_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("NEEM_MONGO_URI", "mongodb://neem@127.0.0.1:1/roslog")
    monkeypatch.setenv("NEEM_MONGO_PASSWORD_FILE", str(tmp_path / "missing"))
    assert main(["neems"]) != 0
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "NEEM_MONGO_PASSWORD_FILE" in err and "cannot read it" in err


def test_a_host_name_no_resolver_answers_is_refused_before_any_lookup():
    # a lookup of "ho st" would wait for the resolver's timeout (9 s for three commands)
    from oracle.errors import StoreError
    from oracle.store import open_store

    with pytest.raises(StoreError, match=r"host 'ho st' is not a host name") as refused:
        open_store("mongodb://alice:s3cret@ho st/db")
    assert "s3cret" not in str(refused.value)


def test_acknowledged_writes_wait_for_a_majority_in_its_journal_unless_the_uri_says_otherwise(monkeypatch):
    """The client is asked for acknowledgement once a majority of the replica set has a write in
    its journal (docs/store.md, "Many robots on one hub"); a URI that sets w or journal keeps its
    own. mongomock-ng stands in for the server; the options are pymongo's own."""
    import pymongo

    mongomock_ng = pytest.importorskip("mongomock_ng")
    asked: list[dict[str, object]] = []
    pymongo_client = pymongo.MongoClient

    def client(uri, **options):
        real = pymongo_client(uri, connect=False, **options)  # pymongo's reading of the options
        asked.append(real.write_concern.document)
        real.close()
        return mongomock_ng.MongoClient()

    monkeypatch.setattr("pymongo.MongoClient", client)
    from oracle.store import open_mongo

    with open_mongo("mongodb://127.0.0.1:27999/labdb"):
        assert asked[-1] == {"w": "majority", "j": True}
    with open_mongo("mongodb://127.0.0.1:27999/labdb?w=1"):
        assert asked[-1] == {"w": 1}
