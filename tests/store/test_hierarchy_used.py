"""A NEEM's taxonomy reads the terms its stored closures use (a scan of every row) only when a
new subClassOf/subPropertyOf edge asks for them: a write that adds no edge (a ranking written
back) does not pay for it, and an edge added later still reaches the stored documents."""

from __future__ import annotations

from oracle.store import RDF_TYPE, SUBCLASS_OF, Triple, TriplePattern, Var
from oracle.store.model import Hierarchy
from oracle.store.sqlite import SQLiteStore

X = "http://example.org/x#"


def test_used_given_as_a_function_is_read_once_when_asked():
    calls: list[int] = []

    def read() -> set[str]:
        calls.append(1)
        return {X + "Old"}

    hierarchy = Hierarchy([(X + "Cup", (X + "Item",))], read)
    assert hierarchy.closure(X + "Cup") == (X + "Cup", X + "Item")
    assert calls == []  # closures are computed without it
    assert hierarchy.used == {X + "Old", X + "Cup", X + "Item"}  # read, with the terms marked meanwhile
    assert hierarchy.used == {X + "Old", X + "Cup", X + "Item"} and calls == [1]


def test_an_edge_added_after_other_writes_still_extends_the_stored_closures(tmp_path):
    store = SQLiteStore(tmp_path / "s.sqlite")
    store.create_neem("n1")
    store.insert("n1", [Triple(X + "Cup", SUBCLASS_OF, X + "Item"), Triple(X + "c", RDF_TYPE, X + "Cup")])
    store.close()
    store = SQLiteStore(tmp_path / "s.sqlite")  # a new process: the taxonomy read from the file
    store.insert("n1", [Triple(X + "e", RDF_TYPE, X + "Other")])  # no edge: nothing asks for used
    assert store._hierarchies["n1"]._read_used is not None
    store.insert("n1", [Triple(X + "Item", SUBCLASS_OF, X + "Thing")])  # an edge: used read, closures extended
    found = {row["S"] for row in store.match("n1", [TriplePattern(Var("S"), RDF_TYPE, X + "Thing")])}
    assert found == {X + "c"}  # Item was in a stored closure only: known from the read
