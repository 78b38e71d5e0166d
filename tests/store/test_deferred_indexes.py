"""A bulk import leaves some of a new NEEM's indexes out while it writes (Store.defer_indexes)
and builds them when the user's rows end (Store.make_indexes): the NEEM ends with every index
a NEEM made at once has, and reads give the same answers with the indexes left out."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from oracle.neem.importing import import_chains
from oracle.store import RDF_TYPE, Triple, TriplePattern, Var, open_store
from oracle.store.sqlite import SQLiteStore
from oracle.store.sqlite.tables import DEFERRED

X = "http://example.org/x#"
SIDE = X + "plans"


def _targets(store: SQLiteStore, neem: str) -> list[str]:
    """The NEEM's indexes by what they index, its id left out of the text."""
    tables = [f"{neem}_{kind}" for kind in ("triples", "annotations", "tf", "inferred", "side")]
    rows = store._conn.execute(
        f"SELECT sql FROM sqlite_master WHERE type='index' AND sql IS NOT NULL AND tbl_name IN ({', '.join('?' * 5)})",
        tables).fetchall()
    return sorted(sql[sql.index(" ON "):].replace(f'"{neem}_', '"N_') for (sql,) in rows)


def test_defer_drops_only_the_deferred_kinds_and_make_builds_them_back(tmp_path):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1", side_property=SIDE)
    whole = _targets(store, "n1")
    assert len(whole) == 8
    store.defer_indexes("n1")
    left = _targets(store, "n1")
    assert len(left) == len(whole) - len(DEFERRED) and set(left) < set(whole)
    # every index of the triple tables (the import's logger reads none back meanwhile), not the others'
    assert not any(target.startswith(('ON "N_triples"', 'ON "N_side"')) for target in left) and left
    store.make_indexes("n1")
    assert _targets(store, "n1") == whole
    store.make_indexes("n1")  # nothing missing: nothing added
    assert _targets(store, "n1") == whole
    assert store._conn.execute("PRAGMA integrity_check").fetchone() == ("ok",)


def test_reads_answer_the_same_while_indexes_are_left_out(tmp_path):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1", side_property=SIDE)
    store.defer_indexes("n1")
    store.insert("n1", [Triple(X + f"a{i}", RDF_TYPE, X + ("Cup" if i % 2 else "Plate")) for i in range(50)]
                 + [Triple(X + "a1", SIDE, X + f"p{i}") for i in range(5)] + [Triple(X + "a1", X + "on", X + "a2")])
    pattern = [TriplePattern(Var("S"), RDF_TYPE, X + "Cup"), TriplePattern(Var("S"), X + "on", Var("O"))]

    def reads() -> tuple[object, ...]:
        return (list(store.match("n1", pattern)), sorted(d["o"] for d in store.find("n1", s=X + "a1", p=SIDE)),
                sorted(d["s"] for d in store.find("n1", p=RDF_TYPE, o=X + "Plate")))

    before = reads()
    store.make_indexes("n1")
    assert reads() == before and before[0] == [{"S": X + "a1", "O": X + "a2"}] and len(before[2]) == 25


def _chains(path: Path, users: dict[str, int]) -> Path:
    lines = [{"user": user, "time": f"2025-03-03T08:{i // 6:02d}:{i % 6 * 10:02d}",
              "action": "open(fridge)" if i % 2 == 0 else "close(fridge)", "available": ["open(fridge)", "close(fridge)"]}
             for user, n in users.items() for i in range(n)]  # fmt: skip
    path.write_text("".join(json.dumps(line) + "\n" for line in lines))
    return path


def test_an_imported_neem_has_every_index_a_neem_made_at_once_has(tmp_path):
    from oracle.ontology import build_ontology

    onto = build_ontology()
    with open_store(str(tmp_path / "s.sqlite")) as store:
        assert isinstance(store, SQLiteStore)
        report = import_chains(store, onto, _chains(tmp_path / "c.jsonl", {"ada": 7, "bob": 3}), commit_every=2)
        store.create_neem("fresh", side_property=onto.vocab.imagines_situation)
        expected = _targets(store, "fresh")
        assert len(report) == 2
        for neem in report:
            assert _targets(store, neem) == expected


def test_an_import_stopped_between_rows_leaves_its_cut_neem_indexed(tmp_path):
    from oracle.ontology import build_ontology

    onto = build_ontology()
    seen = [0]

    def stop() -> bool:
        seen[0] += 1
        return seen[0] > 4

    with open_store(str(tmp_path / "s.sqlite")) as store, pytest.raises(KeyboardInterrupt):
        import_chains(store, onto, _chains(tmp_path / "c.jsonl", {"ada": 8}), commit_every=2, stop=stop)
    with open_store(str(tmp_path / "s.sqlite")) as store:
        assert isinstance(store, SQLiteStore)
        (cut,) = store.neems()
        store.create_neem("fresh", side_property=onto.vocab.imagines_situation)
        assert _targets(store, cut.id) == _targets(store, "fresh")
