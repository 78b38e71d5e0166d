"""SQLite's append marks (Store.append_mark / appended): every update and deletion of a NEEM's
triples is counted, its tables keep their token through a rename and lose it when dropped, and
``fresh`` says whether the triples added since a mark are about new individuals only."""

from __future__ import annotations

from oracle.store import Triple
from oracle.store.model import RDF_TYPE
from oracle.store.sqlite import SQLiteStore

EX = "http://example.org/x#"
IMAG = EX + "imagines"


def _store(tmp_path) -> SQLiteStore:
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n", side_property=IMAG)
    store.insert("n", [Triple(EX + "M1", RDF_TYPE, EX + "Event"), Triple(EX + "M1", IMAG, EX + "P1"),
                       Triple(EX + "A1", EX + "uses", EX + "O1")])
    return store


def test_additions_move_last_and_changes_count_the_rest(tmp_path):
    store = _store(tmp_path)
    first = store.append_mark("n")
    store.insert("n", [Triple(EX + "M2", RDF_TYPE, EX + "Event")])
    grown = store.append_mark("n")
    assert (grown.token, grown.changes) == (first.token, first.changes) and grown.last == first.last + 1
    store._rescope("n", grown.last, 0.0, 5.0)
    store._delete_triples("n", [grown.last])
    after = store.append_mark("n")
    assert after.token == first.token and after.changes == first.changes + 2


def test_a_renamed_neem_keeps_its_token_a_dropped_one_loses_it(tmp_path):
    store = _store(tmp_path)
    token = store.append_mark("n").token
    store.rename_neem("n", "m")
    assert store.append_mark("m").token == token
    store.drop_neem("m")
    store.create_neem("m")
    assert store.append_mark("m").token != token


def test_fresh_only_when_every_added_subject_is_new(tmp_path):
    store = _store(tmp_path)
    last = store.append_mark("n").last
    store.insert("n", [Triple(EX + "M2", IMAG, EX + "P1"), Triple(EX + "M2", RDF_TYPE, EX + "Event")])
    added = store.appended("n", last)
    assert added.fresh and [doc["s"] for doc in added.docs] == [EX + "M2", EX + "M2"]
    for subject in (EX + "M1", EX + "O1", EX + "P1"):  # a subject, an object, a side table's object
        mark = store.append_mark("n").last
        store.insert("n", [Triple(subject, EX + "note", "x")])
        assert not store.appended("n", mark).fresh, subject


def test_a_neem_from_before_is_counted_from_its_first_write(tmp_path):
    store = _store(tmp_path)
    store._conn.execute("DELETE FROM revisions")  # as a store made before the revisions table
    store._registry.tracked.clear()
    read_only = SQLiteStore(tmp_path / "s.sqlite", read_only=True)
    assert read_only.append_mark("n") is None
    store.insert("n", [Triple(EX + "M3", RDF_TYPE, EX + "Event")])
    assert read_only.append_mark("n") is not None
