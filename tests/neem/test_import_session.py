"""Privacy (thesis 3.5): session imports are temporary until persisted, and the next session wipes them."""

import json

from oracle.cli import main
from oracle.store import open_store
from tests.store.conftest import backend, store  # noqa: F401 - the shared backend fixtures


def chains(tmp_path, user):
    path = tmp_path / f"{user}.jsonl"
    path.write_text(json.dumps({"user": user, "time": "2026-01-01T08:00:00", "action": "pick(apple)"}) + "\n")
    return path


def test_next_session_wipes_unpersisted_neems(tmp_path, capsys):
    store = tmp_path / "s.sqlite"
    assert main(["import", str(chains(tmp_path, "ada")), "--store", str(store), "--session"]) == 0
    first = capsys.readouterr().out.split("\t")[0]
    assert [(n.id, n.temporary) for n in open_store(store).neems()] == [(first, True)]
    assert main(["persist", "--neem", first, "--as", "kept", "--store", str(store)]) == 0
    assert main(["import", str(chains(tmp_path, "bo")), "--store", str(store), "--session"]) == 0
    second = capsys.readouterr().out.strip().splitlines()[-1].split("\t")[0]
    assert main(["import", str(chains(tmp_path, "cy")), "--store", str(store), "--session"]) == 0
    ids = {n.id: n.temporary for n in open_store(store).neems()}
    assert ids.get(first) is False and second not in ids  # kept survives, the unpersisted one is wiped
    assert open_store(store).neem(first).meta["alias"] == "kept"
    assert sum(ids.values()) == 1  # only the newest session remains temporary


def test_persist_then_import_under_the_old_id(store):
    """rename_neem must move everything named after the NEEM (SQLite: its indexes too), so a
    new NEEM may take the old id (store fixture: SQLite and mongomock-ng)."""
    from oracle.store import RDF_TYPE, Triple

    x = "http://example.org/x#"
    store.create_neem("alice", user="alice")
    store.insert("alice", [Triple(x + "a1", RDF_TYPE, x + "Action")])
    store.rename_neem("alice", "alice-monday")
    store.create_neem("alice", user="alice")
    store.insert("alice", [Triple(x + "a2", RDF_TYPE, x + "Action")])
    assert [d["s"] for d in store.find("alice-monday", p=RDF_TYPE)] == [x + "a1"]
    assert [d["s"] for d in store.find("alice", p=RDF_TYPE)] == [x + "a2"]
    store.drop_neem("alice-monday")
    store.create_neem("alice-monday")  # nothing of the dropped NEEM is left behind


def _session_workflow(spec: str, tmp_path, capsys) -> None:
    ada = chains(tmp_path, "ada")
    assert main(["import", str(ada), "--store", spec]) == 0
    assert main(["persist", "--neem", "ada", "--as", "ada-monday", "--store", spec]) == 0
    assert main(["import", str(ada), "--store", spec]) == 1  # ada has a NEEM: refused, one line
    assert "--as-new" in capsys.readouterr().err
    assert main(["import", str(ada), "--store", spec, "--as-new"]) == 0  # a new NEEM takes the old id
    assert main(["import", str(ada), "--store", spec, "--session"]) == 0
    session = capsys.readouterr().out.strip().splitlines()[-1].split("\t")[0]
    assert main(["persist", "--neem", session, "--as", "ada-tuesday", "--store", spec]) == 0
    assert main(["import", str(ada), "--store", spec, "--session"]) == 0
    latest = capsys.readouterr().out.strip().splitlines()[-1].split("\t")[0]
    assert main(["neems", "--store", spec, "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)
    rows = {row["name"]: row for row in listed}
    assert {"ada", "ada-monday", "ada-tuesday"} <= set(rows) and len(rows) == 4
    assert all(row["actions"] == 1 for row in rows.values())
    assert [row["id"] for row in listed if row["temporary"]] == [latest]
    assert rows["ada-tuesday"]["id"] == session  # persisting names a NEEM, its id stays


def test_session_workflow_on_sqlite(tmp_path, capsys):
    _session_workflow(str(tmp_path / "s.sqlite"), tmp_path, capsys)


def test_session_workflow_on_the_mongo_code_path(tmp_path, capsys, monkeypatch):
    mongomock_ng = __import__("pytest").importorskip("mongomock_ng")
    import oracle.store as store_module
    from oracle.store.mongo import MongoStore

    client = mongomock_ng.MongoClient()
    client.close = lambda: None  # every command closes its store; the double must keep its data
    monkeypatch.setattr(store_module, "open_mongo", lambda uri, **kw: MongoStore(client, "roslog", **kw))
    _session_workflow("mongodb://127.0.0.1:1/roslog", tmp_path, capsys)
