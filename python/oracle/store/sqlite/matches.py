"""Conjunctions of patterns answered by one SQL join (``Store.match``, the queries Prolog
asks): solutions as dicts, or as chunks for the Prolog bridge (store.chunks), grouped by
SQLite where that is exact."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any

from oracle.store.chunks import MatchChunk, concatenated_chunks, raw_chunks
from oracle.store.model import Scope, TriplePattern
from oracle.store.sqlite.compiler import match_sql
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.reads import Reads
from oracle.store.sqlite.terms import Terms

Order = Sequence[tuple[str, bool]]


def grouped(rows: list[Any], names: list[str], out: Callable[[Any, int], Any]) -> Iterator[dict[str, Any]]:
    """Rows of (value, kind) column pairs grouped by all but the last pair, whose values are
    collected (store.chunks.raw_chunks: each distinct value converted once)."""
    for chunk in raw_chunks(rows, list(range(len(names))), True, max(len(rows), 1), out):
        values = chunk.values
        for row in chunk.rows:
            solution = {name: values[p] for name, p in zip(names[:-1], row)}
            solution[names[-1]] = [values[p] for p in row[-1]]
            yield solution


class Matches:
    """The match path of one store file (its compiler from ``reads``)."""

    def __init__(self, conn: Connection, terms: Terms, reads: Reads) -> None:
        self.conn = conn
        self.terms = terms
        self.reads = reads

    def solutions(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
                  order: Order, select: Sequence[str] | None = None, group: str | None = None,
                  written_order: bool = False) -> Iterator[dict[str, Any]]:  # fmt: skip
        """``Store._match``: one dict per solution (per group with ``group``)."""
        names, rows = self.rows(neem_id, patterns, scope, limit, order, select, group, written_order)
        out = self.terms.out
        if group is not None:
            yield from grouped(rows, names, out)
            return
        for row in rows:
            yield {name: out(row[2 * i], row[2 * i + 1]) for i, name in enumerate(names)}

    def chunks(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
               order: Order, kept: list[str], group: str | None, written_order: bool,
               size: int) -> Iterator[MatchChunk]:  # fmt: skip
        """``Store._match_chunks``: the raw (value, kind) columns are indexed as they come from
        SQL, so each distinct term id becomes its IRI once per chunk, not once per cell."""
        if group is not None and limit is None and not written_order:
            done = self.grouped_in_sql(neem_id, patterns, scope, order, kept, group, size)
            if done is not None:
                return done
        names, rows = self.rows(neem_id, patterns, scope, limit, order, kept, group, written_order)
        where = [names.index(name) for name in kept]
        return raw_chunks(rows, where, group is not None, size, self.terms.out, self.terms.convert)

    def grouped_in_sql(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, order: Order,
                       kept: list[str], group: str, size: int) -> Iterator[MatchChunk] | None:  # fmt: skip
        """A grouped match grouped by SQLite (GROUP BY over the join, ``group_concat`` of the
        grouped column): one row per group reaches Python instead of one per solution (the
        imaginings of a history read: 10,000 groups, not 212,000 rows). Exact only where the
        grouped values are all integers (term ids, integers) and no key is a REAL zero (GROUP BY
        would join 0.0 and -0.0): otherwise None, and the caller groups in Python. Only for a
        key of one variable: its groups are few and large, while a wide key (an action with its
        task and interval, two types each) makes groups of ~2 values that Python groups faster
        than SQLite sorts the rows by eight columns (0.39 s against 0.44 s at 10,000 actions)."""
        if len(kept) != 2 or kept[-1] != group:
            return None
        names, columns, rest, params = self._sql(neem_id, patterns, scope, None, order, kept, group, False)
        width = len(columns) - 2
        keys = [f"c{i}" for i in range(width)]
        inner = f"SELECT {', '.join(f'{expr} AS c{i}' for i, expr in enumerate(columns))} {rest}"
        # Checks: a grouped value that is no integer, a key that is a REAL zero.
        checks = [f"sum(typeof(c{width}) != 'integer' OR typeof(c{width + 1}) != 'integer')"]
        checks += [f"sum(typeof(c{i}) = 'real' AND c{i} = 0)" for i in range(0, width, 2)]
        # "LIMIT -1" (no limit) keeps SQLite from flattening the join into the GROUP BY (its
        # flattening rule: a subquery with a LIMIT is not flattened into an aggregate), where
        # it would plan the join anew and start from every interval rather than a slice's
        # range of begins (a slice's imaginings at 50,000 actions: 0.25 -> 0.07 s; a whole
        # read's the same, 1.7 s).
        sql = (f"SELECT {', '.join(keys + [f'group_concat(c{width})', f'group_concat(c{width + 1})'] + checks)}"
               f" FROM ({inner} LIMIT -1) GROUP BY {', '.join(keys)}")
        rows = self.conn.execute(sql, params).fetchall()
        if any(any(row[width + 2:]) for row in rows):
            return None
        where = [names.index(name) for name in kept]
        return concatenated_chunks(rows, width, where[:-1], size, self.terms.out, self.terms.convert)

    def rows(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
             order: Order, select: Sequence[str] | None, group: str | None,
             written_order: bool) -> tuple[list[str], list[Any]]:  # fmt: skip
        """The kept variables (``group`` last) and the rows of one SQL join, each row a
        (value, kind) pair per variable."""
        names, columns, rest, params = self._sql(neem_id, patterns, scope, limit, order, select, group, written_order)
        sql = f"SELECT {', '.join(columns) or '1'} {rest}"
        if written_order:
            # The plan is the caller's: no automatic index (SQLite without statistics would build
            # one over the whole table for a lookup the (o, p) index answers).
            self.conn.execute("PRAGMA automatic_index = OFF")
            try:
                rows = self.conn.execute(sql, params).fetchall()
            finally:
                self.conn.execute("PRAGMA automatic_index = ON")
        else:
            rows = self.conn.execute(sql, params).fetchall()
        return names, rows

    def _sql(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None, limit: int | None,
             order: Order, select: Sequence[str] | None, group: str | None,
             written_order: bool) -> tuple[list[str], list[str], str, list[Any]]:  # fmt: skip
        self.reads.registry.require(neem_id)
        query = self.reads.compiler(neem_id, scope)
        return match_sql(query, patterns, limit, order, select, group, written_order)
