"""SQLite's side table: a NEEM created with a side property keeps that property's triples apart
(fewer indexes), yet every query, count, write mark and dump sees exactly the documents a NEEM
without one holds."""

from __future__ import annotations

import itertools
import sqlite3

import pytest

from oracle.store import Triple, TriplePattern, Var
from oracle.store.dump import export_neem, load_dump
from oracle.store.model import RDF_TYPE, SUBPROPERTY_OF
from oracle.store.sqlite import SQLiteStore

EX = "http://example.org/x#"
IMAG, SUPER, OTHER, PLAN, EVENT = EX + "imagines", EX + "envisions", EX + "hasPart", EX + "Plan", EX + "Event"


def _triples() -> list[Triple]:
    out = [Triple(IMAG, SUBPROPERTY_OF, SUPER), Triple(PLAN, RDF_TYPE, EX + "Description")]
    for m in range(6):
        action = f"{EX}M{m}"
        out.append(Triple(action, RDF_TYPE, EVENT))
        out += [Triple(action, IMAG, f"{EX}P{(m + k) % 5}") for k in range(3)]
        out.append(Triple(action, OTHER, f"{EX}P{m % 5}"))
        out.append(Triple(f"{EX}P{m % 5}", RDF_TYPE, PLAN, since=m, until=m + 1))
    return out


def _stores(tmp_path):
    plain, sided = SQLiteStore(tmp_path / "plain.sqlite"), SQLiteStore(tmp_path / "sided.sqlite")
    plain.create_neem("n")
    sided.create_neem("n", side_property=IMAG)
    for store in (plain, sided):
        store.insert("n", _triples()[:10])
        store.insert("n", _triples()[10:])
    return plain, sided


def _docs(docs):
    return [{k: v for k, v in doc.items() if k != "_id"} for doc in docs]


def test_the_side_rows_are_in_the_side_table(tmp_path):
    plain, sided = _stores(tmp_path)
    conn = sqlite3.connect(tmp_path / "sided.sqlite")
    imag = conn.execute("SELECT id FROM terms WHERE value=?", (IMAG,)).fetchone()[0]
    assert conn.execute('SELECT count(*), min(p), max(p) FROM "n_side"').fetchone() == (18, imag, imag)
    assert conn.execute('SELECT count(*) FROM "n_triples" WHERE p=?', (imag,)).fetchone() == (0,)
    assert plain.count("n") == sided.count("n") == len(_triples())
    assert sided.write_mark("n") == len(_triples())  # ids run across both tables


def test_every_pattern_finds_the_same_documents_with_or_without_a_side_table(tmp_path):
    plain, sided = _stores(tmp_path)
    assert _docs(plain.read_documents("n", "triples")) == _docs(sided.read_documents("n", "triples"))
    subjects = (None, f"{EX}M1", IMAG)
    properties = (None, IMAG, SUPER, OTHER, RDF_TYPE, SUBPROPERTY_OF)
    objects = (None, f"{EX}P2", PLAN, SUPER)
    for s, p, o, exact in itertools.product(subjects, properties, objects, (False, True)):
        found = _docs(sided.find("n", s, p, o, exact=exact))
        assert found == _docs(plain.find("n", s, p, o, exact=exact)), (s, p, o, exact)


@pytest.mark.parametrize(
    "patterns",
    [
        [TriplePattern(Var("M"), IMAG, Var("P")), TriplePattern(Var("M"), RDF_TYPE, EVENT)],
        [TriplePattern(Var("M"), SUPER, Var("P")), TriplePattern(Var("P"), RDF_TYPE, PLAN)],
        [TriplePattern(Var("M"), Var("Q"), Var("P")), TriplePattern(Var("P"), RDF_TYPE, PLAN)],
        [TriplePattern(Var("M"), OTHER, Var("P")), TriplePattern(Var("M"), IMAG, Var("P"))],
        [TriplePattern(f"{EX}M2", IMAG, Var("P"))],
        [TriplePattern(Var("M"), IMAG, f"{EX}P3"), TriplePattern(Var("M"), OTHER, Var("O"))],
    ],
)
def test_every_conjunction_has_the_same_solutions_with_or_without_a_side_table(tmp_path, patterns):
    plain, sided = _stores(tmp_path)
    expected = list(plain.match("n", patterns))
    assert expected
    assert list(sided.match("n", patterns)) == expected


@pytest.mark.parametrize("reopened", [False, True])
@pytest.mark.parametrize("below", [SUPER, IMAG])  # IMAG: only side rows' closures hold it
def test_a_super_property_stated_later_reaches_the_side_rows(tmp_path, reopened, below):
    plain, sided = _stores(tmp_path)
    if reopened:  # the taxonomy is then read back from the file, the side table's closures too
        sided.close()
        sided = SQLiteStore(tmp_path / "sided.sqlite")
    later = EX + "thinksOf"
    for store in (plain, sided):
        store.insert("n", [Triple(below, SUBPROPERTY_OF, later)])
    found = _docs(sided.find("n", p=later))
    assert len(found) == 18
    assert found == _docs(plain.find("n", p=later))
    assert list(sided.match("n", [TriplePattern(Var("M"), later, Var("P"))])) == list(
        plain.match("n", [TriplePattern(Var("M"), later, Var("P"))])
    )


def test_a_dump_of_a_side_table_neem_is_the_same_documents_in_the_same_order(tmp_path):
    plain, sided = _stores(tmp_path)
    export_neem(sided, "n", tmp_path / "d1")
    export_neem(plain, "n", tmp_path / "p1")
    loaded = SQLiteStore(tmp_path / "loaded.sqlite")
    (loaded_id,) = load_dump(loaded, tmp_path / "d1", neem_id="n")  # a fresh id, alias "n"
    assert list(loaded.read_documents(loaded_id, "triples")) == list(sided.read_documents("n", "triples"))
    export_neem(loaded, loaded_id, tmp_path / "d2")
    first, again = (path / "triples" / "roslog" / "triples.bson" for path in (tmp_path / "d1", tmp_path / "d2"))
    assert first.read_bytes() == again.read_bytes()
    assert _docs(sided.read_documents("n", "triples")) == _docs(plain.read_documents("n", "triples"))


def test_a_renamed_or_dropped_neem_takes_its_side_table_along(tmp_path):
    _, sided = _stores(tmp_path)
    sided.rename_neem("n", "m")
    assert len(list(sided.find("m", p=IMAG))) == 18
    sided.create_neem("n")  # the old id is free again, without a side table
    assert list(sided.find("n", p=IMAG)) == []
    sided.drop_neem("m")
    conn = sqlite3.connect(tmp_path / "sided.sqlite")
    tables = {name for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    assert "m_side" not in tables
    assert conn.execute("SELECT count(*) FROM side_tables").fetchone() == (0,)


def test_a_schema_3_store_is_read_and_upgraded_when_written(tmp_path):
    path = tmp_path / "old.sqlite"
    store = SQLiteStore(path)
    store.create_neem("n")
    store.insert("n", _triples())
    store.close()
    conn = sqlite3.connect(path)
    conn.execute("UPDATE store_info SET value='3' WHERE key='schema'")
    conn.execute("DROP TABLE side_tables")
    conn.commit()
    conn.close()
    reader = SQLiteStore(path, read_only=True)
    assert len(list(reader.find("n", p=IMAG))) == 18
    reader.close()
    writer = SQLiteStore(path)
    assert len(list(writer.find("n", p=IMAG))) == 18
    writer.close()
    conn = sqlite3.connect(path)
    assert conn.execute("SELECT value FROM store_info WHERE key='schema'").fetchone() == ("4",)
