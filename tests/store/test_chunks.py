"""``Store.match_chunks`` gives ``match``'s solutions, each distinct value once per chunk: on
every backend, in chunks of any size, grouped or not, and with values Python finds equal but
Prolog does not (1, 1.0 and True; 0.0 and -0.0)."""

from __future__ import annotations

import math

import pytest

from oracle.store import Triple, TriplePattern, Var
from oracle.store.chunks import MatchChunk
from tests.store.test_backends import X, world

VALUES = [0.0, -0.0, 1, 1.0, True, False, 0, 2.5, -7, "1", "", "o'k", 1e300, float("inf")]


def decoded(chunks: list[MatchChunk], names: list[str], grouped: bool) -> list[dict]:
    rows = []
    for chunk in chunks:
        assert len(chunk.values) == len({(type(v), repr(v)) for v in chunk.values}) or _has_float_kinds(chunk)
        for row in chunk.rows:
            solution = {n: chunk.values[p] for n, p in zip(names[:-1] if grouped else names, row)}
            if grouped:
                solution[names[-1]] = [chunk.values[p] for p in row[-1]]
            rows.append(solution)
    return rows


def _has_float_kinds(chunk: MatchChunk) -> bool:
    # SQLite keeps a double and a Decimal128 of one value apart (two kinds): both read as floats.
    return any(type(v) is float for v in chunk.values)


def typed(value):
    """A value with its type, so that 1 == 1.0 == True and 0.0 == -0.0 compare apart."""
    if isinstance(value, list):
        return [typed(v) for v in value]
    if isinstance(value, float) and value == 0.0:
        return (float, math.copysign(1.0, value))
    return (type(value), value)


def facts(store):
    world(store)
    store.insert("n1", [Triple(X + f"e{i}", X + "value", v) for i, v in enumerate(VALUES)]
                 + [Triple(X + f"e{i}", X + "tag", X + ("odd" if i % 2 else "even")) for i in range(len(VALUES))])


@pytest.mark.parametrize("size", [1, 3, 5000])
def test_chunks_decode_to_the_solutions_of_match_in_their_order(store, size):
    facts(store)
    patterns = [TriplePattern(Var("E"), X + "value", Var("V")), TriplePattern(Var("E"), X + "tag", Var("T"))]
    expected = list(store.match("n1", patterns, select=["V", "E", "T"]))
    chunks = list(store.match_chunks("n1", patterns, ["V", "E", "T"], size=size))
    assert all(len(c.rows) <= size for c in chunks) and len(chunks) == math.ceil(len(expected) / size)
    got = decoded(chunks, ["V", "E", "T"], False)
    assert [{k: typed(v) for k, v in row.items()} for row in got] == [{k: typed(v) for k, v in row.items()} for row in expected]
    assert len(got) == len(VALUES)


@pytest.mark.parametrize("size", [1, 2, 5000])
def test_grouped_chunks_collect_the_values_of_each_combination(store, size):
    facts(store)
    patterns = [TriplePattern(Var("E"), X + "value", Var("V")), TriplePattern(Var("E"), X + "tag", Var("T"))]
    expected = {row["T"]: sorted(repr(typed(v)) for v in row["V"])
                for row in store.match("n1", patterns, select=["T", "V"], group="V")}
    chunks = list(store.match_chunks("n1", patterns, ["T", "V"], group="V", size=size))
    got = decoded(chunks, ["T", "V"], True)
    assert {row["T"]: sorted(repr(typed(v)) for v in row["V"]) for row in got} == expected
    assert sorted(expected) == [X + "even", X + "odd"] and all(len(c.rows) <= size for c in chunks)


def test_chunks_of_a_match_without_solutions_or_kept_variables(store):
    facts(store)
    none = [TriplePattern(Var("E"), X + "value", X + "nothing")]
    assert list(store.match_chunks("n1", none, ["E"])) == []
    patterns = [TriplePattern(Var("E"), X + "tag", X + "odd")]
    chunks = list(store.match_chunks("n1", patterns, []))
    assert [len(c.rows) for c in chunks] == [len(VALUES) // 2] and chunks[0].rows[0] == ()


def _grouped_by_key(store, patterns, key, var):
    """The groups of match_chunks and of match, each as key -> sorted typed values."""
    expected = {repr(typed(row[key])): sorted(repr(typed(v)) for v in row[var])
                for row in store.match("n1", patterns, select=[key, var], group=var)}
    got = {repr(typed(row[key])): sorted(repr(typed(v)) for v in row[var])
           for row in decoded(list(store.match_chunks("n1", patterns, [key, var], group=var, size=2)), [key, var], True)}
    return got, expected


def test_groups_of_iris_by_one_key_are_those_of_match(store):
    # On SQLite these are grouped by SQL (integer term ids); the groups must be match's.
    facts(store)
    store.insert("n1", [Triple(X + f"e{i}", X + "seen", X + f"thing{j}") for i in range(6) for j in range(i % 3 + 1)]
                 + [Triple(X + "e0", X + "seen", X + "thing0")])  # the same triple again: a solution of its own
    patterns = [TriplePattern(Var("E"), X + "tag", Var("T")), TriplePattern(Var("E"), X + "seen", Var("S"))]
    got, expected = _grouped_by_key(store, patterns, "T", "S")
    assert got == expected and sorted(expected) == sorted(repr(typed(X + t)) for t in ("even", "odd"))
    assert sum(len(v) for v in expected.values()) == 13
    if type(store).__name__ == "SQLiteStore":  # and SQL grouped them
        assert store._matches.grouped_in_sql("n1", patterns, None, [], ["T", "S"], "S", 5000) is not None


def test_groups_keyed_by_signed_zeros_stay_apart(store):
    # GROUP BY in SQL joins 0.0 and -0.0, match on SQLite keeps them apart: such a key is
    # grouped in Python there (MongoDB's $group joins them, in match too).
    facts(store)
    store.insert("n1", [Triple(X + f"e{i}", X + "zero", v) for i, v in enumerate([0.0, -0.0, 0.0, 2.5])])
    patterns = [TriplePattern(Var("E"), X + "zero", Var("Z")), TriplePattern(Var("E"), X + "tag", Var("T"))]
    got, expected = _grouped_by_key(store, patterns, "Z", "T")
    assert got == expected
    if type(store).__name__ == "SQLiteStore":
        assert got[repr(typed(0.0))] == sorted([repr(typed(X + "even"))] * 2) and got[repr(typed(-0.0))] == [repr(typed(X + "odd"))]


def test_groups_of_integers_and_of_no_solution(store):
    facts(store)
    patterns = [TriplePattern(Var("E"), X + "value", Var("V")), TriplePattern(Var("E"), X + "tag", Var("T"))]
    got, expected = _grouped_by_key(store, patterns, "T", "V")
    assert got == expected
    ints = [TriplePattern(Var("E"), X + "count", Var("N")), TriplePattern(Var("E"), X + "tag", Var("T"))]
    store.insert("n1", [Triple(X + f"e{i}", X + "count", i * 3) for i in range(5)])
    got, expected = _grouped_by_key(store, ints, "T", "N")
    assert got == expected and sorted(len(v) for v in got.values()) == [2, 3]
    none = [TriplePattern(Var("E"), X + "count", Var("N")), TriplePattern(Var("E"), X + "nothing", Var("T"))]
    assert list(store.match_chunks("n1", none, ["T", "N"], group="N")) == []
