"""Solutions of a match as compact chunks: each distinct value once, rows of positions.

A history read returns ~170,000 rows at 10,000 actions that repeat a few thousand task, role
and plan IRIs; a chunk lists each distinct value once and each row as small integers, so the
Prolog bridge writes (and Prolog reads) each IRI once per chunk instead of once per cell.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class MatchChunk:
    """Up to a chunk's worth of solutions of ``Store.match_chunks``.

    ``values`` are the distinct plain values (as ``Store.match`` gives them); each row holds,
    per kept variable in the order asked, the position of its value in ``values`` (from 0) or,
    for the grouped variable (last), the list of the positions of its values.
    """

    values: list[Any]
    rows: list[tuple[Any, ...]]


class ValueIndex:
    """Positions of distinct values, keyed so that values Python finds equal but Prolog does
    not (1, 1.0 and True; 0.0 and -0.0) stay apart."""

    def __init__(self) -> None:
        self.values: list[Any] = []
        self._keys: dict[Any, int] = {}

    def position(self, value: Any) -> int:
        kind = type(value)
        key = value if kind is str else (kind, repr(value) if kind is float and value == 0.0 else value)
        known = self._keys.get(key)
        if known is None:
            known = self._keys[key] = len(self.values)
            self.values.append(value)
        return known


def chunks_from_solutions(solutions: Iterable[dict[str, Any]], names: list[str], grouped: bool,
                          size: int) -> Iterator[MatchChunk]:
    """``Store.match`` solutions (dicts) as chunks of up to ``size`` rows (any backend)."""
    index = ValueIndex()
    rows: list[tuple[Any, ...]] = []
    keys = names[:-1] if grouped else names
    last = names[-1] if grouped else ""
    for solution in solutions:
        row: tuple[Any, ...] = tuple(index.position(solution[n]) for n in keys)
        if grouped:
            row += ([index.position(v) for v in solution[last]],)
        rows.append(row)
        if len(rows) == size:
            yield MatchChunk(index.values, rows)
            index, rows = ValueIndex(), []
    if rows:
        yield MatchChunk(index.values, rows)


#: Converts the new distinct raw values of one kind at once (a store looks its term ids up in
#: one query); ``out`` converts one value.
Convert = Callable[[int, list[Any]], list[Any]]


class _RawIndex:
    """Positions of distinct raw SQL (value, kind) cells, each converted once."""

    def __init__(self, out: Callable[[Any, int], Any], convert: Convert | None = None) -> None:
        self.out = out
        self.convert: Convert = convert or (lambda kind, values: [out(value, kind) for value in values])
        self.values: list[Any] = []
        self._by_kind: dict[int, dict[Any, int]] = {}

    def column(self, values: list[Any], kinds: list[int]) -> list[int]:
        """The positions of one column's cells."""
        distinct_kinds = set(kinds)
        if len(distinct_kinds) == 1:
            (kind,) = distinct_kinds
            distinct = dict.fromkeys(values)
            # 0.0 and -0.0 (or 1 and 1.0) are one key in Python: such a column goes cell by cell.
            if 0 not in distinct and len({type(value) for value in distinct}) <= 1:
                known = self._by_kind.setdefault(kind, {})
                new = [value for value in distinct if value not in known]
                if new:
                    start = len(self.values)
                    self.values.extend(self.convert(kind, new))
                    known.update(zip(new, range(start, start + len(new))))
                return [known[value] for value in values]
        return [self._cell(value, kind) for value, kind in zip(values, kinds)]

    def _cell(self, value: Any, kind: int) -> int:
        known = self._by_kind.setdefault(-1, {})
        key = (kind, type(value), repr(value) if value == 0 else value)
        position = known.get(key)
        if position is None:
            position = known[key] = len(self.values)
            self.values.append(self.out(value, kind))
        return position


def raw_chunks(rows: list[Sequence[Any]], where: list[int], grouped: bool, size: int,
               out: Callable[[Any, int], Any], convert: Convert | None = None) -> Iterator[MatchChunk]:
    """SQL rows of (value, kind) column pairs as chunks of up to ``size`` rows; ``where`` gives,
    per kept variable in the order asked, its column pair. Grouped: the last column's values
    are collected per distinct combination of the others (``Store.match``'s ``group``), which
    must come first in the rows; each group is one row of the chunk. ``convert(kind, values)``,
    if given, converts a column's new distinct values at once, ``out`` any other value."""
    if not grouped:
        for start in range(0, len(rows), size):
            batch = rows[start:start + size]
            index = _RawIndex(out, convert)
            columns = [index.column([r[2 * c] for r in batch], [r[2 * c + 1] for r in batch]) for c in where]
            yield MatchChunk(index.values, list(zip(*columns)) if columns else [()] * len(batch))
        return
    yield from _grouped_chunks(rows, where, size, out, convert)


def _grouped_chunks(rows: list[Sequence[Any]], where: list[int], size: int,
                    out: Callable[[Any, int], Any], convert: Convert | None) -> Iterator[MatchChunk]:
    width = 2 * (len(where) - 1)
    # Grouped here, not by SQL GROUP BY: SQLite's text forms of a REAL round it to 15 digits,
    # and the raw columns group exactly (0.0 and -0.0 apart, by their text, if a key holds one).
    signed = any(0 in {row[c] for row in rows} for c in range(0, width, 2))
    groups: defaultdict[tuple[Any, ...], list[Sequence[Any]]] = defaultdict(list)
    if signed:
        for row in rows:
            groups[tuple(row[:width]) + tuple(repr(row[c]) for c in range(0, width, 2))].append(row)
    else:
        for row in rows:
            groups[tuple(row[:width])].append(row)
    keys = list(groups)
    for start in range(0, len(keys), size):
        batch = keys[start:start + size]
        index = _RawIndex(out, convert)
        columns: list[Any] = [index.column([k[2 * c] for k in batch], [k[2 * c + 1] for k in batch])
                                    for c in where[:-1]]
        members = [groups[k] for k in batch]
        flat = index.column([r[width] for m in members for r in m], [r[width + 1] for m in members for r in m])
        collected: list[list[int]] = []
        at = 0
        for m in members:
            collected.append(flat[at:at + len(m)])
            at += len(m)
        columns.append(collected)
        yield MatchChunk(index.values, list(zip(*columns)))


def concatenated_chunks(rows: list[Sequence[Any]], width: int, keys: list[int], size: int,
                        out: Callable[[Any, int], Any], convert: Convert | None = None) -> Iterator[MatchChunk]:
    """Groups made by SQL as chunks of up to ``size`` groups: each row holds the key's (value,
    kind) column pairs (``width`` columns; ``keys`` gives, per kept key variable in the order
    asked, its pair) and then the group's integer values and their kinds, each as one
    comma-separated text (``group_concat``). Each distinct group is parsed and its values
    indexed once per chunk."""
    for start in range(0, len(rows), size):
        batch = rows[start:start + size]
        index = _RawIndex(out, convert)
        columns: list[Any] = [index.column([r[2 * c] for r in batch], [r[2 * c + 1] for r in batch]) for c in keys]
        distinct = list(dict.fromkeys((r[width], r[width + 1]) for r in batch))
        members = [(list(map(int, values.split(","))), list(map(int, kinds.split(",")))) for values, kinds in distinct]
        flat = index.column([v for values, _ in members for v in values], [k for _, kinds in members for k in kinds])
        positions: dict[tuple[str, str], list[int]] = {}
        at = 0
        for key, (values, _) in zip(distinct, members):
            positions[key] = flat[at:at + len(values)]
            at += len(values)
        columns.append([positions[r[width], r[width + 1]] for r in batch])
        yield MatchChunk(index.values, list(zip(*columns)))
