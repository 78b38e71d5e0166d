"""What only the embedded backend promises: a private file that survives reopening."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from oracle.errors import StoreError
from oracle.store import RDF_TYPE, SUBCLASS_OF, Triple, TriplePattern, Var, open_store
from oracle.store.sqlite.compiler import SqlCompiler
from oracle.store.sqlite import SQLiteStore

X = "http://example.org/x#"


def test_store_files_are_private_and_survive_reopening(tmp_path):
    path = tmp_path / "sub" / "neems.sqlite"
    with open_store(f"sqlite://{path}") as store:
        store.create_neem("n1")
        store.insert("n1", [Triple(X + "Cup", SUBCLASS_OF, X + "Item"), Triple(X + "c", RDF_TYPE, X + "Cup")])
    for file in path.parent.iterdir():
        assert stat.S_IMODE(os.stat(file).st_mode) == 0o600, file
    with open_store(str(path)) as store:
        store.insert("n1", [Triple(X + "d", RDF_TYPE, X + "Cup")])  # taxonomy read back from the file
        assert sorted(d["s"] for d in store.find("n1", p=RDF_TYPE, o=X + "Item")) == [X + "c", X + "d"]


@pytest.mark.parametrize(
    "pattern",
    [
        TriplePattern(None, RDF_TYPE, X + "Item"),  # o* lookup
        TriplePattern(None, X + "hasPart", X + "c"),  # p* with o
        TriplePattern(X + "c", None, None),  # subject
    ],
)
def test_pattern_queries_use_an_index(tmp_path, pattern):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "Cup", SUBCLASS_OF, X + "Item"), Triple(X + "c", RDF_TYPE, X + "Cup"),
                        Triple(X + "a", X + "hasPart", X + "c")])  # fmt: skip
    query = SqlCompiler(store, '"n1_triples"', None)
    query.add(pattern)
    plan = store._conn.execute(
        f"EXPLAIN QUERY PLAN SELECT t0.id FROM {query.from_clause()} WHERE {query.where()}", query.params
    ).fetchall()
    outer = [row[-1] for row in plan if "t0" in row[-1]]
    assert outer and all("USING" in detail for detail in outer), plan



@pytest.mark.parametrize("cls", ["Cup", "Item"])  # one closure id, several
def test_an_inlined_class_test_seeks_by_its_closure_ids_not_every_type_triple(tmp_path, cls):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "Cup", SUBCLASS_OF, X + "Item"), Triple(X + "Plate", SUBCLASS_OF, X + "Item"),
                        Triple(X + "c", RDF_TYPE, X + "Cup"), Triple(X + "p", RDF_TYPE, X + "Plate"),
                        Triple(X + "o", RDF_TYPE, X + "Other")])  # fmt: skip
    query = SqlCompiler(store, '"n1_triples"', None)
    query.inline_closures = True
    query.add(TriplePattern(Var("S"), RDF_TYPE, X + cls))
    sql = f"SELECT t0.s FROM {query.from_clause()} WHERE {query.where()} ORDER BY t0.id"
    plan = " ".join(row[-1] for row in store._conn.execute("EXPLAIN QUERY PLAN " + sql, query.params))
    assert "ostar>? AND ostar<?" in plan, plan  # a bounded seek, not the whole "ostar > 0" range
    expected = {"Cup": [X + "c"], "Item": [X + "c", X + "p"]}[cls]
    assert [store._terms.value(s) for (s,) in store._conn.execute(sql, query.params)] == expected

def _index_columns(store, table):
    rows = store._conn.execute("SELECT sql FROM sqlite_master WHERE type='index' AND tbl_name=? AND sql IS NOT NULL",
                               (table,)).fetchall()
    return sorted(sql[sql.index(" ON "):].replace(f'"{table}"', "T") for (sql,) in rows)


def test_a_renamed_neem_keeps_its_indexes_and_its_old_id_can_be_taken_again(tmp_path):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "c", RDF_TYPE, X + "Cup")])
    made = _index_columns(store, "n1_triples")
    assert len(made) == 4
    store.rename_neem("n1", "n2")
    assert _index_columns(store, "n2_triples") == made
    store.create_neem("n1")  # its index names were taken by n2's: it gets others
    assert _index_columns(store, "n1_triples") == made
    store.rename_neem("n1", "n3")
    store.create_neem("n1")
    assert _index_columns(store, "n1_triples") == _index_columns(store, "n3_triples") == made
    assert list(store.match("n2", [TriplePattern(X + "c", RDF_TYPE, Var("C"))])) == [{"C": X + "Cup"}]
    assert store._conn.execute("PRAGMA integrity_check").fetchone() == ("ok",)


def test_unknown_store_specs_are_errors(monkeypatch):
    with pytest.raises(StoreError, match="unknown store"):
        open_store("ftp://host/x")
    monkeypatch.delenv("NEEM_MONGO_URI", raising=False)
    with pytest.raises(StoreError, match="NEEM_MONGO_URI"):
        open_store("mongodb")


def test_default_store_lives_in_the_user_data_dir(monkeypatch, tmp_path):
    monkeypatch.delenv("NEEM_MONGO_URI", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path))
    monkeypatch.setenv("HOME", str(tmp_path))
    with open_store(None) as store:
        assert str(store.location).startswith(str(tmp_path))
        assert store.location.endswith("default.sqlite")


def test_a_neem_dropped_by_another_process_is_a_store_error(tmp_path):
    first = SQLiteStore(tmp_path / "s.sqlite")
    first.create_neem("n1")
    first.insert("n1", [Triple(X + "c", RDF_TYPE, X + "Cup")])
    second = SQLiteStore(tmp_path / "s.sqlite")
    second.drop_neem("n1")
    with pytest.raises(StoreError, match="no such table"):
        first.insert("n1", [Triple(X + "d", RDF_TYPE, X + "Cup")])
    assert not second.has_neem("n1")


def test_the_store_schema_is_made_whole_or_not_at_all(tmp_path, monkeypatch):
    # Each schema statement used to commit on its own: a process killed in between left tables
    # without the schema row, which every reader then refused as "store schema None".
    import sqlite3

    import oracle.store.sqlite.opening as module

    path = tmp_path / "s.sqlite"
    broken = (*module.SCHEMA_STATEMENTS[:3], "SELECT no_such_function()", *module.SCHEMA_STATEMENTS[3:])
    monkeypatch.setattr(module, "SCHEMA_STATEMENTS", broken)
    with pytest.raises(StoreError, match="cannot open the NEEM store"):
        SQLiteStore(path)
    with sqlite3.connect(path) as raw:
        assert raw.execute("SELECT count(*) FROM sqlite_master").fetchone()[0] == 0  # nothing half-made
    monkeypatch.undo()
    # A file an older version left half-made: readers say so in one line, a writer completes it.
    with sqlite3.connect(path) as raw:
        raw.execute("CREATE TABLE store_info(key TEXT PRIMARY KEY, value TEXT)")
        raw.execute("CREATE TABLE neems(id TEXT PRIMARY KEY, meta BLOB NOT NULL)")
    with pytest.raises(StoreError, match="never completed.*import completes it"):
        SQLiteStore(path, read_only=True)
    SQLiteStore(path).close()
    with SQLiteStore(path, read_only=True) as store:
        assert store.neems() == []


def _open_at_once(path: str, barrier, results) -> None:  # noqa: ANN001 - multiprocessing objects
    barrier.wait()
    try:
        SQLiteStore(Path(path)).close()
        results.put("ok")
    except StoreError as error:
        results.put(str(error))


def test_processes_making_one_new_store_at_once_all_open_it(tmp_path):
    # SQLite refuses the switch to WAL at once ("database is locked", no busy wait) while another
    # process switches the same new file: two imports into one new store used to fail now and then.
    import multiprocessing

    context = multiprocessing.get_context("fork")
    for trial in range(20):
        path = str(tmp_path / f"s{trial}.sqlite")
        barrier, results = context.Barrier(3), context.Queue()
        processes = [context.Process(target=_open_at_once, args=(path, barrier, results)) for _ in range(3)]
        for process in processes:
            process.start()
        for process in processes:
            process.join(timeout=60)
        assert [results.get(timeout=5) for _ in processes] == ["ok"] * 3
