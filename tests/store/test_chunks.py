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
