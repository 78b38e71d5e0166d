"""A writer's whole-file check (oracle.store.integrity): run before the first write, at open or
beside the writer's reads; a damaged file is refused in one line and left byte for byte as it was."""

from __future__ import annotations

import hashlib
import shutil
from pathlib import Path

import pytest

from oracle.cli import main
from oracle.errors import StoreError
from oracle.paths import project_home
from oracle.store.sqlite import SQLiteStore
from tests.corpus.built import corrupt

SAMPLE = project_home() / "ontology" / "sample-chains.jsonl"


def _digest(path: Path) -> str:
    """The store's content: the file and its write-ahead log (the -shm index is SQLite's scratch)."""
    wal = path.with_name(path.name + "-wal")
    return hashlib.sha256(path.read_bytes() + (wal.read_bytes() if wal.exists() else b"")).hexdigest()


@pytest.fixture(scope="module")
def imported(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("integrity") / "store.sqlite"
    assert main(["import", str(SAMPLE), "--store", str(path)]) == 0
    return path


@pytest.fixture
def store_file(imported, tmp_path) -> Path:
    path = tmp_path / "store.sqlite"
    shutil.copy(imported, path)
    return path


def _neem(path: Path) -> str:
    with SQLiteStore(path, read_only=True) as reader:
        return reader.neems()[0].id


def test_a_sound_store_is_written_after_the_check_beside_reads(store_file):
    neem = _neem(store_file)
    store = SQLiteStore(store_file, create=False, check_while_reading=True)
    try:
        assert [info.id for info in store.neems()][0] == neem     # reads while the check runs
        store.update_meta(neem, note="checked")
    finally:
        store.close()
    with SQLiteStore(store_file, read_only=True) as reader:
        assert reader.neem(neem).meta["note"] == "checked"


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("beside", [False, True])
def test_a_damaged_store_refuses_the_first_write_and_stays_as_it_was(store_file, seed, beside):
    neem = _neem(store_file)
    corrupt(store_file, seed)
    before = _digest(store_file)
    try:
        store = SQLiteStore(store_file, create=False, check_while_reading=beside)
    except StoreError as error:
        assert "corrupt" in str(error) and "nothing was written" in str(error)
    else:
        try:
            with pytest.raises(StoreError, match="corrupt.*nothing was written"):
                store.update_meta(neem, note="must not land")
            with pytest.raises(StoreError, match="corrupt"):       # and every later write too
                store.update_meta(neem, note="must not land")
        finally:
            store.close()
    assert _digest(store_file) == before


def test_rank_on_a_damaged_store_says_so_in_one_line_and_writes_nothing(store_file, capsys):
    neem = _neem(store_file)
    corrupt(store_file, 1)
    before = _digest(store_file)
    assert main(["rank", "--store", str(store_file), "--neem", neem]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "corrupt" in err[0]
    assert _digest(store_file) == before


def test_closing_without_a_write_cancels_the_check_and_writes_nothing(store_file):
    before = _digest(store_file)
    store = SQLiteStore(store_file, create=False, check_while_reading=True)
    assert store.neems()
    check = store._conn.check
    assert check is not None
    store.close()   # cancels the check: nothing to report, nothing written
    assert not check._thread.is_alive()
    assert _digest(store_file) == before


def test_what_counts_as_a_write():
    from oracle.store.sqlite.connection import may_write

    for sql in ("SELECT 1", "  select s FROM t", "BEGIN", "COMMIT", "ROLLBACK", "PRAGMA automatic_index = OFF",
                "EXPLAIN QUERY PLAN SELECT 1", "BEGIN DEFERRED"):
        assert not may_write(sql), sql
    for sql in ("BEGIN IMMEDIATE", "INSERT INTO t VALUES (1)", "UPDATE t SET a=1", "DELETE FROM t",
                "CREATE TABLE x(a)", "DROP TABLE x", "ALTER TABLE x RENAME TO y", "PRAGMA journal_mode=WAL",
                "CREATE TRIGGER x AFTER UPDATE ON t BEGIN SELECT 1; END"):
        assert may_write(sql), sql


def test_a_check_that_cannot_run_refuses_the_writes(store_file, monkeypatch):
    import oracle.store.integrity as integrity

    def broken(conn):
        raise OSError("no pages for you")

    monkeypatch.setattr(integrity, "problems_of", broken)
    store = SQLiteStore(store_file, create=False, check_while_reading=True)
    try:
        with pytest.raises(StoreError, match="corrupt .no pages for you"):
            store.update_meta(_neem(store_file), note="must not land")
    finally:
        store.close()


@pytest.mark.parametrize("damage", [False, True])
def test_a_store_that_opening_would_change_is_checked_first(store_file, damage):
    import sqlite3

    conn = sqlite3.connect(store_file)
    conn.execute("DROP TABLE revisions")   # the next writer makes it again: opening writes
    conn.commit()
    conn.close()
    if damage:
        corrupt(store_file, 2)
        before = _digest(store_file)
        with pytest.raises(StoreError, match="corrupt.*nothing was written"):
            SQLiteStore(store_file, create=False, check_while_reading=True)
        assert _digest(store_file) == before
    else:
        store = SQLiteStore(store_file, create=False, check_while_reading=True)
        try:
            assert store._conn.check is None   # checked at open, before the table was made
        finally:
            store.close()
