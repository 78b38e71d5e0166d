"""Reading a NEEM's documents: every document of a collection in insertion order (dumps,
poses, annotations), counts and the write mark, one pattern's documents (``Store.find`` and
the facts store.project changes), the triples added since an append mark (the history read),
and the taxonomy's source (hierarchy edges, the terms closures use)."""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Iterator
from functools import partial
from operator import itemgetter
from typing import Any

import bson

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, Appended
from oracle.store.model import Annotation, Scope, Term, TriplePattern
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.compiler import SqlCompiler, TermIds
from oracle.store.sqlite.connection import Connection, Cursor
from oracle.store.sqlite.documents import CODEC, Documents
from oracle.store.sqlite.registry import Registry
from oracle.store.sqlite.sides import held, side_of
from oracle.store.sqlite.tables import DOC_COLUMNS, HIERARCHY_SQL, SIDE, neem_table
from oracle.store.sqlite.terms import K_STR, Terms


class Reads:
    """The read path of one store file; ``ids`` is what the query compiler asks (the store)."""

    def __init__(self, conn: Connection, registry: Registry, terms: Terms, closures: Closures, documents: Documents,
                 ids: TermIds) -> None:  # fmt: skip
        self.conn = conn
        self.registry = registry
        self.terms = terms
        self.closures = closures
        self.documents = documents
        self.ids = ids

    def compiler(self, neem_id: str, scope: Scope | None) -> SqlCompiler:
        """A query compiler over the NEEM's triples (and its side table)."""
        side = side_of(self.conn, self.closures, neem_id, self.registry.side_row(neem_id))
        return SqlCompiler(self.ids, neem_table(neem_id, "triples"), scope, side)

    def _in_order(self, cursors: list[Cursor]) -> Iterator[dict[str, Any]]:
        """Documents of rows (id, then ``DOC_COLUMNS``) of each table in id order, merged: in
        the order they were inserted."""
        document = self.documents.document
        for row in heapq.merge(*cursors, key=itemgetter(0)):
            yield document(row[1:])

    def documents_of(self, neem_id: str, kind: str) -> Iterator[dict[str, Any]]:
        """Every document of one collection, in insertion order (``Store.read_documents``)."""
        if kind not in COLLECTION_KINDS:
            raise StoreError(f"unknown collection kind {kind!r}")
        self.registry.require(neem_id)
        if kind == "triples":
            tables = [neem_table(neem_id, kind)]
            if self.registry.side_row(neem_id) is not None:
                tables.append(neem_table(neem_id, SIDE))
            yield from self._in_order([self.conn.execute(f"SELECT t0.id, {DOC_COLUMNS} FROM {t} AS t0 ORDER BY id")
                                       for t in tables])  # fmt: skip
            return
        cursor = self.conn.execute(f"SELECT doc FROM {neem_table(neem_id, kind)} ORDER BY id")
        for (blob,) in cursor:
            yield bson.decode(blob, codec_options=CODEC)

    def count(self, neem_id: str, kind: str) -> int:
        self.registry.require(neem_id)
        count = int(self.conn.execute(f"SELECT count(*) FROM {neem_table(neem_id, kind)}").fetchone()[0])
        if kind == "triples" and self.registry.side_row(neem_id) is not None:
            count += int(self.conn.execute(f"SELECT count(*) FROM {neem_table(neem_id, SIDE)}").fetchone()[0])
        return count

    def write_mark(self, neem_id: str) -> int:
        # The last rowid grows with every insert and is read from the end of the table's
        # b-tree, not by counting; a scope merge (store.project) deletes only copies of a fact
        # it keeps, and kb_unproject drops the kept summary itself.
        self.registry.require(neem_id)
        return self.registry.next_id(neem_id) - 1

    def find(self, neem_id: str, pattern: TriplePattern, scope: Scope | None, limit: int | None,
             exact: bool) -> Iterator[dict[str, Any]]:  # fmt: skip
        self.registry.require(neem_id)
        query = self.compiler(neem_id, scope)
        query.add(pattern, exact=exact)
        sql = f"SELECT {DOC_COLUMNS} FROM {query.from_clause()} WHERE {query.where()} ORDER BY t0.id"
        if limit is not None:
            sql += f" LIMIT {int(limit)}"
        for row in self.conn.execute(sql, query.params).fetchall():
            yield self.documents.document(row)

    def overlapping(self, neem_id: str, s: Term, p: Term, o: Term, scope: Scope | None,
                    graph: str | None = None) -> list[tuple[Any, float, float]]:  # fmt: skip
        """(row id, since, until) of the facts with these asserted s, p, o (``Store._overlapping``)."""
        self.registry.require(neem_id)
        query = self.compiler(neem_id, scope)
        query.add(TriplePattern(s, p, o, graph), exact=True)
        sql = f"SELECT t0.id, t0.since, t0.until FROM {query.from_clause()} WHERE {query.where()} ORDER BY t0.id"
        return [(rowid, 0.0 if since is None else since, math.inf if until is None else until)
                for rowid, since, until in self.conn.execute(sql, query.params).fetchall()]  # fmt: skip

    def appended(self, neem_id: str, last: int) -> Appended:
        """The triples added after id ``last``, and whether all their subjects are new."""
        self.registry.require(neem_id)
        tables = self.registry.tables_of(neem_id)
        with self.conn.reading():
            docs = list(self._in_order([self.conn.execute(f"SELECT t0.id, {DOC_COLUMNS} FROM {t} AS t0 WHERE id > ? ORDER BY id",
                                                          (last,)) for t in tables]))  # fmt: skip
            new = " UNION ".join(f"SELECT s FROM {t} WHERE id > :last" for t in tables)
            # Each subject looked up by the (s, p) and (o, p) indexes of the main table and the
            # (s) index of the side table; the side table's objects (plans) by its (o) index (a
            # scan in a file from before it).
            known = " OR ".join(
                [f"EXISTS (SELECT 1 FROM {t} WHERE s = n.s AND id <= :last)" for t in tables]
                + [f"EXISTS (SELECT 1 FROM {tables[0]} WHERE o = n.s AND ok = {K_STR} AND id <= :last)"]
            )
            stale = self.conn.execute(
                f"SELECT 1 FROM ({new}) AS n WHERE n.s IS NULL OR {known} LIMIT 1", {"last": last}
            ).fetchone()
            if stale is None and len(tables) > 1:
                stale = self.conn.execute(
                    f"SELECT 1 FROM {tables[1]} WHERE id <= :last AND ok = {K_STR} AND o IN ({new}) LIMIT 1",
                    {"last": last},
                ).fetchone()
        return Appended(docs, stale is None)

    def hierarchy_source(self, neem_id: str) -> tuple[list[tuple[str, tuple[Any, ...]]], Callable[[], set[Any]]]:
        """(subject, o*) of every hierarchy edge, and how to find every term used in a stored
        closure (a scan of the NEEM's rows: read only when a new edge needs it, model.Hierarchy)."""
        table = neem_table(neem_id, "triples")
        value, members = self.terms.value, self.closures.members
        edges = [
            (value(s), members(cid))
            for s, cid in self.conn.execute(
                f"SELECT s, ostar FROM {table} WHERE p IN {HIERARCHY_SQL} AND ostar > 0 AND s IS NOT NULL ORDER BY id"
            ).fetchall()
        ]
        return edges, partial(self._used_terms, neem_id)

    def _used_terms(self, neem_id: str) -> set[Any]:
        table = neem_table(neem_id, "triples")
        value, members = self.terms.value, self.closures.members
        used = {
            value(term)
            for (term,) in self.conn.execute(
                f"SELECT DISTINCT value FROM closure_member WHERE value IS NOT NULL AND cid IN"
                f" (SELECT ostar FROM {table} UNION SELECT pstar FROM {table})"
            ).fetchall()
        }
        side = self.registry.side_row(neem_id)
        if side is not None:  # the closures its rows hold are recorded: no scan of the side table
            used.update(v for cid in held(side) for v in members(cid) if type(v) is str)
        return used

    def annotations(self, neem_id: str, s: str | None = None, p: str | None = None) -> Iterator[Annotation]:
        self.registry.require(neem_id)
        conds, params = ["1"], []
        if s is not None:
            conds.append("s=?")
            params.append(s)
        if p is not None:
            conds.append("p=?")
            params.append(p)
        sql = f"SELECT doc FROM {neem_table(neem_id, 'annotations')} WHERE {' AND '.join(conds)} ORDER BY id"
        for (blob,) in self.conn.execute(sql, params):
            doc = bson.decode(blob)
            yield Annotation(doc["s"], doc["p"], doc.get("v"))
