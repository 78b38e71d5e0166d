"""A comparison with two bounds in one pattern (``Cmp(op, value, var, op2, value2)``): the same
solutions as the two comparisons in two patterns, on every backend, and on SQLite one range of
the (pstar, o) index (a slice of a NEEM's begins costs its own rows, not a scan from one bound
to the end)."""

from __future__ import annotations

import itertools

import pytest

from oracle.store import Cmp, Triple, TriplePattern, Var
from oracle.store.model import CMP_OPS
from tests.store.conftest import make_store

X = "http://example.org/x#"
#: Begins of every numeric type the store keeps (and a string and a boolean, which never compare).
VALUES = [5, 10, 10.0, 12.5, 15, 20.0, 25, 30.5, -3, "15", True]


def _begins(store):
    store.create_neem("n1")
    store.insert("n1", [Triple(X + f"i{k}", X + "begin", v) for k, v in enumerate(VALUES)])
    store.insert("n1", [Triple(X + f"i{k}", X + "end", k) for k in range(len(VALUES))])


def _match(store, *cmp):
    rows = store.match("n1", [TriplePattern(Var("I"), X + "begin", Cmp(*cmp))])
    return sorted((r["I"], float(r["B"])) for r in rows)


@pytest.mark.parametrize("number_format", ["decimal128", "double"])
def test_two_bounds_are_both_comparisons(backend, tmp_path, number_format):
    store = make_store(backend, tmp_path, number_format)
    try:
        _begins(store)
        for op, op2 in itertools.product(CMP_OPS, repeat=2):
            for low, high in [(10, 20), (10.0, 25), (-5, 12.5), (20, 10), (15, 15)]:
                both = _match(store, op, low, Var("B"), op2, high)
                first = set(_match(store, op, low, Var("B")))
                second = set(_match(store, op2, high, Var("B")))
                assert both == sorted(first & second), (op, low, op2, high)
        assert [i for i, _ in _match(store, ">", 10, Var("B"), "=<", 20)] == [X + "i3", X + "i4", X + "i5"]
        # joined with another pattern, the range first or second
        rows = store.match("n1", [TriplePattern(Var("I"), X + "begin", Cmp(">=", 10, None, "<", 15)),
                                  TriplePattern(Var("I"), X + "end", Var("E"))])  # fmt: skip
        assert sorted(r["E"] for r in rows) == [1, 2, 3]
        rows = store.match("n1", [TriplePattern(Var("I"), X + "end", Var("E")),
                                  TriplePattern(Var("I"), X + "begin", Cmp(">=", 10, Var("B"), "<", 15))])  # fmt: skip
        assert sorted(r["E"] for r in rows) == [1, 2, 3]
    finally:
        getattr(store, "_test_cleanup", lambda: None)()
        store.close()


def test_a_second_comparison_needs_its_operator_and_number():
    with pytest.raises(ValueError):
        Cmp(">", 1, Var("B"), "<")
    with pytest.raises(ValueError):
        Cmp(">", 1, Var("B"), None, 2)
    with pytest.raises(ValueError):
        Cmp(">", 1, Var("B"), "!=", 2)
    with pytest.raises(ValueError):
        Cmp(">", 1, Var("B"), "<", "2")  # type: ignore[arg-type]
    assert Cmp(">", 1, None, "=<", 2).holds(2) and not Cmp(">", 1, None, "=<", 2).holds(1)


def test_sqlite_reads_two_bounds_as_one_index_range(tmp_path):
    store = make_store("sqlite", tmp_path)
    try:
        _begins(store)
        matches = store._matches  # the SQL of one match, to ask SQLite for its plan
        names, columns, rest, params = matches._sql(
            "n1", [TriplePattern(Var("I"), X + "begin", Cmp(">", 10, Var("B"), "=<", 20)),
                   TriplePattern(Var("I"), X + "end", Var("E"))], None, None, [], None, None, False)  # fmt: skip
        plan = [row[3] for row in store._conn.execute(f"EXPLAIN QUERY PLAN SELECT {', '.join(columns)} {rest}", params)]
        assert any("pstaro" in step and "o>? AND o<?" in step for step in plan), plan
    finally:
        store.close()
