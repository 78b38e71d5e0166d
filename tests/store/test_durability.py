"""The durability promises: atomic replacement, readers that never wait, nothing leaked."""

from __future__ import annotations

import json
import os
import sqlite3
import stat
from pathlib import Path

import mongomock_ng as mongomock
import pytest

from oracle.cli import main
from oracle.errors import LoggingError, StoreError
from oracle.neem.importing import import_chains
from oracle.neem.lifecycle import wipe_temporary_neems
from oracle.neem.writer import NeemLogger
from oracle.store import COLLECTION_KINDS, open_store
from oracle.store.dump import export_all, export_neem, load_dump
from oracle.store.ids import alias_of, resolve_neem
from oracle.store.mongo import MongoStore
from oracle.store.sqlite import SQLiteStore
from oracle.store.staging import drop_abandoned

ROOT = Path(__file__).resolve().parents[2]


def rows(user: str, n: int, start_minute: int = 0, **extra: object) -> list[dict]:
    return [{"user": user, "time": f"2025-03-03T{8 + (start_minute + i) // 60:02d}:{(start_minute + i) % 60:02d}:00",
             "action": "open(fridge)" if i % 2 == 0 else "close(fridge)", **extra} for i in range(n)]  # fmt: skip


def write(path: Path, lines: list[dict]) -> Path:
    path.write_text("".join(json.dumps(line) + "\n" for line in lines))
    return path


@pytest.fixture(params=["sqlite", "mongomock"])
def store(request, tmp_path):
    if request.param == "sqlite":
        s = SQLiteStore(tmp_path / "s.sqlite")
    else:
        s = MongoStore(mongomock.MongoClient(), "roslog")
    yield s
    s.close()


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


def neem_of(store, name: str) -> str:
    """The id of the NEEM called ``name`` (ids are ObjectIds, the user's name is the alias)."""
    return resolve_neem(store, name)


def content(store, neem_id: str) -> dict[str, int]:
    return {kind: store.count(neem_id, kind) for kind in COLLECTION_KINDS}


def test_the_durability_promise_is_stated():
    text = " ".join((ROOT / "docs" / "store.md").read_text().split())
    for claim in (
        "A NEEM becomes visible (in `neems`, to readers) only together with its TBox",
        "until then, and after any error or kill, the old NEEM is untouched",
        "a killed import loses at most the rows since the last commit of the user in flight",
        "Bad input is refused before anything is written, and a store never holds a row that a reader cannot read",
    ):
        assert claim in text


def test_import_replace_keeps_the_old_neem_until_the_new_one_is_complete(store, onto, tmp_path, monkeypatch):
    import_chains(store, onto, write(tmp_path / "a.jsonl", rows("alice", 6)), commit_every=2)
    alice = neem_of(store, "alice")
    before = content(store, alice)
    calls = {"n": 0}
    original = NeemLogger.action

    def failing(self, *args, **kwargs):  # noqa: ANN001, ANN202 - a disk that fills up mid-import
        calls["n"] += 1
        if calls["n"] == 4:
            raise LoggingError("disk full")
        return original(self, *args, **kwargs)

    monkeypatch.setattr(NeemLogger, "action", failing)
    with pytest.raises(LoggingError, match="disk full"):
        import_chains(store, onto, write(tmp_path / "b.jsonl", rows("alice", 9)), replace=True, commit_every=2)
    assert [info.id for info in store.neems()] == [alice]
    assert content(store, alice) == before
    monkeypatch.setattr(NeemLogger, "action", original)
    import_chains(store, onto, write(tmp_path / "b.jsonl", rows("alice", 9)), replace=True, commit_every=2)
    assert [(info.id, alias_of(info)) for info in store.neems()] == [(alice, "alice")]  # the replacement keeps id and name
    assert content(store, alice)["triples"] > before["triples"]


def _inside_a_document(data: bytes, near: int) -> int:
    """A cut point at or after ``near`` that falls inside a BSON document (never on a boundary
    between two: the ids in a dump are random, so a half cut could land on one)."""
    at = 0
    while at < len(data):
        end = at + int.from_bytes(data[at:at + 4], "little")
        if end > near:  # the document [at, end) holds the cut point; a BSON document has 5 bytes or more
            return near if near > at else at + 1
        at = end
    raise AssertionError("no document ends after the cut point")


def test_load_replace_with_a_cut_dump_keeps_the_old_neem(store, onto, tmp_path):
    import_chains(store, onto, write(tmp_path / "a.jsonl", rows("alice", 6)))
    alice = neem_of(store, "alice")
    export_neem(store, alice, tmp_path / "dump")
    before = content(store, alice)
    bson_file = tmp_path / "dump" / "triples" / "roslog" / "triples.bson"
    data = bson_file.read_bytes()
    bson_file.write_bytes(data[: _inside_a_document(data, len(data) // 2)])
    with pytest.raises(StoreError, match="truncated or corrupt"):
        load_dump(store, tmp_path / "dump", replace=True)
    assert content(store, alice) == before
    # Cut exactly at a document boundary: only meta.json's count tells.
    first = int.from_bytes(data[:4], "little")
    bson_file.write_bytes(data[:first])
    with pytest.raises(StoreError, match="counts"):
        load_dump(store, tmp_path / "dump", replace=True)
    assert content(store, alice) == before
    assert [info.id for info in store.neems()] == [alice]


def test_duplicate_ids_are_refused_whatever_the_commit_interval(store, onto):
    logger = NeemLogger.create(store, onto, user="alice", commit_every=100)
    logger.action("open(fridge)", 1_740_988_800, action_id="x1")
    with pytest.raises(LoggingError, match="duplicate action id 'x1'"):
        logger.action("close(fridge)", 1_740_988_860, action_id="x1")


def test_a_user_named_robot_is_not_the_robot(store, onto):
    logger = NeemLogger.create(store, onto, user="robot")
    done = logger.action("open(fridge)", 1_740_988_800, performed_by="user")
    logger.close()
    performers = {doc["o"] for doc in store.find(logger.neem_id, s=done.iri, exact=True) if doc["p"].endswith("isPerformedBy")}
    assert performers and not any(iri.endswith("#Agent_robot") for iri in performers)


def test_a_session_import_in_progress_is_not_wiped_by_another_session(store, onto):
    logger = NeemLogger.create(store, onto, user="alice", temporary=True, hidden=True)
    logger.action("open(fridge)", 1_740_988_800)
    assert wipe_temporary_neems(store) == []  # the other session's start
    logger.close()
    assert [(info.id, alias_of(info)) for info in store.neems()] == [(logger.neem_id, "alice")]


def test_mongo_filter_values_are_literals(onto):
    store = MongoStore(mongomock.MongoClient(), "roslog")
    logger = NeemLogger.create(store, onto, user="alice")
    logger.action("open(fridge)", 1_740_988_800)
    logger.close()
    for bad in ({"$gt": ""}, {"$ne": None}, ["a", "b"]):
        with pytest.raises(StoreError, match="query constant"):
            list(store.find(logger.neem_id, s=bad))


def test_readers_do_not_wait_for_a_writer(tmp_path, onto, capsys):
    path = tmp_path / "s.sqlite"
    with SQLiteStore(path) as s:
        import_chains(s, onto, write(tmp_path / "a.jsonl", rows("alice", 3)))
    writer = sqlite3.connect(path, isolation_level=None)
    writer.execute("BEGIN IMMEDIATE")  # a long load holds the write lock
    writer.execute("INSERT INTO store_info VALUES ('busy', 'yes')")
    try:
        assert main(["neems", "--store", str(path), "--json"]) == 0
        assert [n["name"] for n in json.loads(capsys.readouterr().out)] == ["alice"]
    finally:
        writer.execute("ROLLBACK")
        writer.close()


def test_a_store_readable_by_others_is_made_private_when_opened_for_writing(tmp_path, onto):
    path = tmp_path / "s.sqlite"
    SQLiteStore(path).close()
    os.chmod(path, 0o644)
    with open_store(path, read_only=True):
        pass
    assert stat.S_IMODE(path.stat().st_mode) == 0o644  # reading changes nothing
    SQLiteStore(path).close()
    assert stat.S_IMODE(path.stat().st_mode) == 0o600


def test_export_is_private_and_never_follows_a_symlink(tmp_path, onto):
    store = SQLiteStore(tmp_path / "s.sqlite")
    import_chains(store, onto, write(tmp_path / "a.jsonl", rows("alice", 2)))
    alice = neem_of(store, "alice")
    out = tmp_path / "out"
    (out / "triples" / "roslog").mkdir(parents=True)
    old = out / "triples" / "roslog" / "triples.metadata.json"
    old.write_text("{}")
    os.chmod(old, 0o644)
    victim = tmp_path / "victim"
    victim.write_text("keep")
    os.symlink(victim, out / "triples" / "roslog" / "triples.bson")
    with pytest.raises(StoreError, match="symbolic link"):
        export_neem(store, alice, out)
    assert victim.read_text() == "keep"
    os.remove(out / "triples" / "roslog" / "triples.bson")
    previous = os.umask(0)
    try:
        export_neem(store, alice, out / "deeper" / "dump")
        export_neem(store, alice, out)
    finally:
        os.umask(previous)
    for path in [out, *out.rglob("*")]:
        assert stat.S_IMODE(path.stat().st_mode) == (0o700 if path.is_dir() else 0o600), path


@pytest.mark.parametrize("uri", ["mongodb://alice:s3cret@localhost:99999/db", "mongodb://alice:p@ss@localhost/db",
                                 "mongodb://alice:pa/ss@localhost/db", "mongodb://alice:s3cret@ho st/db"])
def test_no_message_shows_a_password(uri, capsys, monkeypatch):
    assert main(["neems", "--store", uri]) == 1
    assert main(["import", str(ROOT / "ontology" / "sample-chains.jsonl"), "--store", uri]) == 1
    monkeypatch.setenv("NEEM_MONGO_URI", uri)
    assert main(["neems", "--store", "mongodb"]) == 1
    err = capsys.readouterr().err
    password = uri.split("://", 1)[1].rsplit("@", 1)[0].split(":", 1)[1]
    assert password not in err, err


def _two_neem_dump(store, onto, tmp_path: Path) -> tuple[Path, str, str]:
    import_chains(store, onto, write(tmp_path / "ab.jsonl", rows("alice", 4) + rows("bob", 4, start_minute=30)))
    alice, bob = neem_of(store, "alice"), neem_of(store, "bob")
    export_neem(store, alice, tmp_path / "two" / "alice")
    export_neem(store, bob, tmp_path / "two" / "bob")
    store.drop_neem(alice)
    store.drop_neem(bob)
    return tmp_path / "two", alice, bob


def test_a_dump_of_two_neems_loads_both_or_neither(store, onto, tmp_path):
    dump, alice, bob = _two_neem_dump(store, onto, tmp_path)
    bson_file = dump / "bob" / "triples" / "roslog" / "triples.bson"
    whole = bson_file.read_bytes()
    bson_file.write_bytes(whole[: len(whole) - 7])  # alice's folder sorts first and is fine
    with pytest.raises(StoreError, match="truncated or corrupt"):
        load_dump(store, dump)
    assert store.neems() == [] and store.staging_neems() == []
    bson_file.write_bytes(whole)
    assert load_dump(store, dump) == [alice, bob]  # each keeps its id
    assert [(info.id, alias_of(info)) for info in store.neems()] == [(alice, "alice"), (bob, "bob")]


def test_two_folders_holding_one_neem_id_are_refused(store, onto, tmp_path):
    dump, alice, _ = _two_neem_dump(store, onto, tmp_path)
    meta = json.loads((dump / "bob" / "meta.json").read_text())
    (dump / "bob" / "meta.json").write_text(json.dumps({**meta, "id": alice}))
    with pytest.raises(StoreError, match=f"both hold NEEM '{alice}'"):
        load_dump(store, dump, replace=True)
    assert store.neems() == [] and store.staging_neems() == []


def _dead_pid() -> int:
    import subprocess
    import sys

    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_hidden_neems_of_dead_builders_are_dropped_by_the_next_writer(store, onto):
    from oracle.store.staging import STAGED_BY

    dead = store.create_staging("alice", user="alice")
    store.update_meta(dead, **{STAGED_BY: {**store.neem(dead).meta[STAGED_BY], "pid": _dead_pid()}})
    elsewhere = store.create_staging("bob", user="bob")
    store.update_meta(elsewhere, **{STAGED_BY: {"host": "another-host", "pid": 1}})
    old = store.create_staging("carol", user="carol")
    store.update_meta(old, **{STAGED_BY: {"host": "another-host", "pid": 1}, "created_at": "2020-01-01T00:00:00+00:00"})
    alive = store.create_staging("dave", user="dave")  # this very process: still building it
    assert {info.id for info in store.staging_neems()} == {elsewhere, alive}
    assert store.neems() == []
    # A session start wipes temporary NEEMs and, with them, what killed processes left.
    store.update_meta(alive, **{STAGED_BY: {"host": store.neem(alive).meta[STAGED_BY]["host"], "pid": _dead_pid()}})
    wipe_temporary_neems(store)
    assert [info.id for info in store.staging_neems()] == [elsewhere]


def test_a_loaded_neem_takes_the_space_an_imported_one_does_and_dumps_back_byte_for_byte(onto, tmp_path):
    imported = tmp_path / "imported.sqlite"
    with SQLiteStore(imported) as s:
        import_chains(s, onto, ROOT / "ontology" / "sample-chains.jsonl")
        export_all(s, tmp_path / "dump")
    loaded = tmp_path / "loaded.sqlite"
    with SQLiteStore(loaded) as s:
        load_dump(s, tmp_path / "dump")
        export_all(s, tmp_path / "again")
    for store in (imported, loaded):  # fold the write-ahead log in, so file sizes compare
        with sqlite3.connect(store) as raw:
            raw.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    assert loaded.stat().st_size <= 1.1 * imported.stat().st_size, (loaded.stat().st_size, imported.stat().st_size)
    first = {p.relative_to(tmp_path / "dump"): p.read_bytes() for p in (tmp_path / "dump").rglob("*") if p.is_file()}
    second = {p.relative_to(tmp_path / "again"): p.read_bytes() for p in (tmp_path / "again").rglob("*") if p.is_file()}
    assert first == second


def test_a_chains_file_is_private_complete_and_never_written_through_a_link(tmp_path):
    from oracle.chains import read_chains, write_chains

    rows = list(read_chains(ROOT / "ontology" / "sample-chains.jsonl"))
    out = tmp_path / "new" / "deeper" / "chains.jsonl"
    previous = os.umask(0)
    try:
        assert write_chains(rows, out) == len(rows)
    finally:
        os.umask(previous)
    assert stat.S_IMODE(out.stat().st_mode) == 0o600
    assert all(stat.S_IMODE(p.stat().st_mode) == 0o700 for p in (tmp_path / "new", tmp_path / "new" / "deeper"))
    victim = tmp_path / "victim"
    victim.write_text("keep")
    os.symlink(victim, tmp_path / "link.jsonl")
    with pytest.raises(OSError, match="symbolic link"):
        write_chains(rows, tmp_path / "link.jsonl")
    assert victim.read_text() == "keep"

    def failing():  # noqa: ANN202 - a source that breaks mid-way (as a full disk would)
        yield from rows[:5]
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError, match="No space"):
        write_chains(failing(), out)
    assert len(list(read_chains(out))) == len(rows)  # the earlier file, whole
    assert sorted(p.name for p in out.parent.iterdir()) == ["chains.jsonl"]


def test_a_builder_killed_inside_the_swap_leaves_the_old_neem_or_the_new_one(store, onto, tmp_path):
    # MongoDB has no transaction: swap_in drops the old NEEM, then renames the new one. Both
    # moments a kill can fall between are set up by hand; the next writer must repair either.
    from oracle.store.staging import READY, STAGED_BY

    import_chains(store, onto, write(tmp_path / "a.jsonl", rows("alice", 4)))
    alice = neem_of(store, "alice")
    old = content(store, alice)
    dead = {"host": __import__("socket").gethostname(), "pid": _dead_pid()}
    before_drop = store.create_staging(alice, user="alice")
    store.update_meta(before_drop, **{STAGED_BY: dead, READY: True})
    drop_abandoned(store)  # the old NEEM is still there: the half-done replacement goes
    assert content(store, alice) == old and store.staging_neems() == []

    logger = NeemLogger.create(store, onto, user="alice", replace=True)
    for i in range(7):
        logger.action("open(fridge)", 1_740_988_800 + 60 * i)
    logger.flush()
    store.update_meta(logger.writes_to, **{STAGED_BY: dead, READY: True})
    new = content(store, logger.writes_to)
    store.drop_neem(alice)  # killed right after dropping the old NEEM
    drop_abandoned(store)
    assert [info.id for info in store.neems()] == [alice] and content(store, alice) == new
    assert store.staging_neems() == [] and READY not in {k for k, v in store.neem(alice).meta.items() if v}


def test_a_builder_killed_between_two_collection_renames_loses_nothing(tmp_path, onto):
    # On MongoDB a NEEM's four collections are renamed one by one. A kill after some of them
    # leaves the new NEEM split across the two names; the next writer must finish the rename
    # rather than drop the staging half (which would lose the rest of the new NEEM).
    from oracle.store.staging import READY, STAGED_BY

    store = MongoStore(mongomock.MongoClient(), "split")
    import_chains(store, onto, write(tmp_path / "a.jsonl", rows("alice", 4)))
    alice = neem_of(store, "alice")
    logger = NeemLogger.create(store, onto, user="alice", replace=True)
    for i in range(7):
        logger.action("open(fridge)", 1_740_988_800 + 60 * i)
    logger.flush()
    staging = logger.writes_to
    new = content(store, staging)
    dead = {"host": __import__("socket").gethostname(), "pid": _dead_pid()}
    store.update_meta(staging, **{STAGED_BY: dead, READY: True})
    store.drop_neem(alice)
    for kind in COLLECTION_KINDS[:2]:  # killed after two of the renames
        store.db[f"{staging}_{kind}"].rename(f"{alice}_{kind}")
    fresh = MongoStore(store.client, "split")  # the next process
    drop_abandoned(fresh)
    assert [info.id for info in fresh.neems()] == [alice] and content(fresh, alice) == new
    assert resolve_neem(fresh, "alice") == alice and fresh.neem(alice).user == "alice"  # its registry entry too
    assert fresh.staging_neems() == [] and not {k for k, v in fresh.neem(alice).meta.items() if v} & {READY, STAGED_BY}
    assert not [name for name in fresh.db.list_collection_names() if name.startswith(staging)]
