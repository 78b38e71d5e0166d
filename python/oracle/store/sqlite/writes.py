"""Writing a NEEM's documents: triples straight to rows (the logger's batches), documents as
given (a load; annotations, poses and inferred documents as BSON), closures extended through
the stored rows when the taxonomy grows, and a stored fact's scope changed or the fact deleted
(store.project). Every write runs in the caller's transaction."""

from __future__ import annotations

import os
import struct
import time
from collections.abc import Callable, Collection, Sequence
from itertools import compress
from operator import gt, itemgetter
from typing import Any

import bson

from oracle.errors import StoreError
from oracle.store.base import Closed
from oracle.store.model import (
    TAXONOMIC,
    DocumentBuilder,
    Hierarchy,
    NumberFormat,
    TripleRow,
    encode_number,
    encode_value,
    extend_closure,
    unix_seconds,
)
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.documents import CODEC, SK_DECIMAL, SK_DOUBLE, Documents, blob
from oracle.store.sqlite.registry import Registry
from oracle.store.sqlite.sides import SideRow, held, note_closures
from oracle.store.sqlite.tables import DOCUMENT_COLUMNS, GROUPED_ROWS, INSERT_COLUMNS, SIDE, TAXONOMIC_SQL, neem_table, non_taxonomic
from oracle.store.sqlite.terms import K_DECIMAL, K_DOUBLE, K_STR, Terms

Rows = list[tuple[Any, ...]]


class Writes:
    """The write path of one store file."""

    def __init__(self, conn: Connection, registry: Registry, terms: Terms, closures: Closures,
                 documents: Documents) -> None:  # fmt: skip
        self.conn = conn
        self.registry = registry
        self.terms = terms
        self.closures = closures
        self.documents = documents
        # ObjectIds of the rows this process writes: the second, this random part, a counter.
        self._random = os.urandom(5)
        self._counter = int.from_bytes(os.urandom(3), "big")

    def closed(self, neem_id: str, batch: list[TripleRow], hierarchy: Hierarchy, builder: DocumentBuilder) -> None:
        """A batch without subClassOf/subPropertyOf triples, each closure looked up once per
        distinct property and class (``SQLiteStore._insert_closed``)."""
        closure = hierarchy.closure
        with self.conn.transaction():
            self.triples(neem_id, batch, closure, lambda o: closure(o) if type(o) is str else (o,), builder)

    def with_closures(self, neem_id: str, closed: list[Closed], builder: DocumentBuilder) -> None:
        """Triples with their closures (the general path): within one such list, a property or
        class has one closure (Store._insert_closed writes the list out before a change)."""
        pstars = {triple[1]: pstar for triple, pstar, _ in closed}
        ostars = {(type(triple[2]), triple[2]): ostar for triple, _, ostar in closed if triple[1] in TAXONOMIC}
        self.triples(neem_id, [triple for triple, _, _ in closed], pstars.__getitem__,
                     lambda o: ostars[(type(o), o)], builder)  # fmt: skip

    def triples(self, neem_id: str, batch: list[TripleRow], pstar_of: Callable[[str], tuple[Any, ...]],
                ostar_of: Callable[[Any], tuple[Any, ...]], builder: DocumentBuilder) -> None:  # fmt: skip
        """Rows straight from triples (a document is rebuilt from its columns when read), in one
        pass: ``pstar_of(p)`` (non-taxonomic ``p``) and ``ostar_of(o)`` (the object of a
        taxonomic triple) are asked once per distinct term, as are their closure and term ids.

        Everything that does not change from row to row is settled per batch first (the scopes
        checked, the terms interned, each property's ids and table, each class's closure), so
        the loop only looks up and lays out columns, one row after another in one flat list per
        table: a grouped INSERT's parameters are then a slice of it (``write_flat``), not a
        list chained anew from 80 row tuples (CPU of a 10,000-action import's writes 1.68 ->
        1.59 s)."""
        self.registry.require(neem_id)
        bad = next(compress(batch, map(gt, map(itemgetter(4), batch), map(itemgetter(5), batch))), None)
        if bad is not None:
            raise ValueError(f"scope of {bad} ends before it starts")
        decimal = builder.number_format == "decimal128"
        float_kind, scope_kind = (K_DECIMAL, SK_DECIMAL) if decimal else (K_DOUBLE, SK_DOUBLE)
        properties = set(map(itemgetter(1), batch))
        # New terms numbered in sorted order: event IRIs of one kind then grow with time, as
        # the logger mints them, and their index entries land near the end of the indexes.
        strings = set(map(itemgetter(0), batch))
        strings.update(o for o in set(map(itemgetter(2), batch)) if type(o) is str)
        ids = self.terms.tids(sorted(strings | properties))
        cid = self.closures.cid
        side = self.registry.side_row(neem_id)
        side_p = -1 if side is None else side[0]
        main_flat: list[Any] = []
        side_flat: list[Any] = []
        # Per property: its id, its p* closure id, whether it is taxonomic, the table it goes to.
        props = {p: (ids[p], cid((p,) if p in TAXONOMIC else pstar_of(p)), p in TAXONOMIC,
                     side_flat.extend if ids[p] == side_p else main_flat.extend) for p in properties}  # fmt: skip
        # The o* closure id of a taxonomic triple's IRI object (a class), once per class.
        classes = {o: cid(ostar_of(o)) for o in {o for _, p, o, _, _, _ in batch if p in TAXONOMIC and type(o) is str}}
        first = self.registry.next_id(neem_id)
        # ObjectId bytes: this second, the store's random part, then a counter per row (row
        # ``first`` gets the counter after the last one), as one 96-bit number.
        stamp = int.from_bytes(struct.pack(">I", int(time.time())) + self._random, "big") << 24
        offset = self._counter + 1 - first
        row_ids = range(first, first + len(batch))
        oids = [(stamp | ((offset + row_id) & 0xFFFFFF)).to_bytes(12, "big") for row_id in row_ids]
        sql_o: Any
        for row_id, oid, (s_, p, o, graph, since, until) in zip(row_ids, oids, batch):
            p_id, pstar_cid, taxonomic, extend = props[p]
            if type(o) is str:
                sql_o, kind, ostar_cid = ids[o], K_STR, classes[o] if taxonomic else 0
            else:
                if type(o) is float:
                    sql_o, kind = o, float_kind
                else:
                    sql_o, kind = self.terms.sql(encode_value(o, builder.number_format))
                ostar_cid = cid(ostar_of(o)) if taxonomic else 0
            extend((row_id, oid, ids[s_], p_id, sql_o, kind, pstar_cid, ostar_cid, graph, since, until, scope_kind))
        self._counter = (offset + first + len(batch) - 1) & 0xFFFFFF
        side_closures = {prop[1] for prop in props.values() if prop[0] == side_p}
        self.write_flat(neem_id, side, main_flat, side_flat, side_closures)

    def write_flat(self, neem_id: str, side: SideRow | None, main_flat: list[Any], side_flat: list[Any],
                   side_closures: Collection[int]) -> None:  # fmt: skip
        """``triples``' rows, each the ``INSERT_COLUMNS`` laid out one after another in one list
        per table, written as ``write_rows`` writes rows (grouped where it groups them)."""
        self.registry.ensure_tracked(neem_id)  # a NEEM made before the revisions table: from its first write on
        width = INSERT_COLUMNS.count(",") + 1
        if main_flat:
            # Grouped too while the partial indexes are left out (Registry.deferred): 13 % less
            # CPU then, more with them (tables.GROUPED_ROWS)
            grouped = GROUPED_ROWS if neem_id in self.registry.deferred else 1
            self._insert_flat(neem_table(neem_id, "triples"), width, main_flat, grouped)
        if side is not None and side_flat:
            self._insert_flat(neem_table(neem_id, SIDE), width, side_flat, GROUPED_ROWS)
            note_closures(self.conn, neem_id, side, side_closures)

    def _insert_flat(self, table: str, width: int, flat: list[Any], per_statement: int) -> None:
        """Rows of ``width`` values laid out in ``flat``, in this order, ``per_statement`` rows
        to one INSERT (the statement's parameters are then a slice of ``flat``)."""
        one = f"({', '.join('?' * width)})"
        step = width * per_statement if per_statement > 1 else 0
        whole = len(flat) - len(flat) % step if step else 0
        if whole:
            grouped = f"INSERT INTO {table}({INSERT_COLUMNS}) VALUES {', '.join([one] * per_statement)}"
            self.conn.executemany(grouped, (flat[i : i + step] for i in range(0, whole, step)))
        if whole < len(flat):
            rest = iter(flat[whole:])
            self.conn.executemany(f"INSERT INTO {table}({INSERT_COLUMNS}) VALUES {one}", zip(*[rest] * width))

    def write_rows(self, neem_id: str, side: SideRow | None, columns: str, main_rows: Rows, side_rows: Rows,
                   side_closures: Collection[int | None] | None = None) -> None:  # fmt: skip
        """Rows (id first, then the rest of ``columns``) into the triples table and the side
        table; the closures the side rows hold (``side_closures`` when the caller knows them)
        are recorded (``sides.note_closures``)."""
        self.registry.ensure_tracked(neem_id)  # a NEEM made before the revisions table: from its first write on
        if main_rows:
            # Grouped too while the partial indexes are left out (Registry.deferred): 13 % less
            # CPU then, more with them (tables.GROUPED_ROWS)
            grouped = GROUPED_ROWS if neem_id in self.registry.deferred else 1
            self.conn.insert_many(neem_table(neem_id, "triples"), columns, main_rows, grouped)
        if side is not None and side_rows:
            self.conn.insert_many(neem_table(neem_id, SIDE), columns, side_rows, GROUPED_ROWS)
            if side_closures is None:
                side_closures = {cid for row in side_rows for cid in row[6:8]}
            note_closures(self.conn, neem_id, side, side_closures)

    def documents_as_given(self, neem_id: str, kind: str, docs: list[dict[str, Any]]) -> None:
        """Documents of one collection stored as given (``Store.write_documents``)."""
        self.registry.require(neem_id)
        table = neem_table(neem_id, kind)
        try:
            if kind == "triples":
                self._document_rows(neem_id, [self.documents.row(doc) for doc in docs])
            elif kind == "annotations":
                self.conn.executemany(
                    f"INSERT INTO {table}(s, p, doc) VALUES (?, ?, ?)",
                    [(d.get("s"), d.get("p"), blob(d)) for d in docs],
                )
            elif kind == "tf":
                self.conn.executemany(
                    f"INSERT INTO {table}(child, stamp, doc) VALUES (?, ?, ?)",
                    [(d.get("child_frame_id"), unix_seconds((d.get("header") or {}).get("stamp")), blob(d)) for d in docs],
                )
            else:
                self.conn.executemany(f"INSERT INTO {table}(doc) VALUES (?)", [(blob(d),) for d in docs])
        except (bson.errors.InvalidDocument, OverflowError) as error:
            raise StoreError(f"{self.conn.location}: NEEM {neem_id!r}: cannot store a {kind} document ({error})") from None

    def _document_rows(self, neem_id: str, rows: Rows) -> None:
        """Rows of documents (``DOCUMENT_COLUMNS``) into the triples table, those of the side
        property into the side table; ids run across both (``Registry.next_id``)."""
        side = self.registry.side_row(neem_id)
        side_p = -1 if side is None else side[0]
        main_rows: Rows = []
        side_rows: Rows = []
        for i, row in enumerate(rows, start=self.registry.next_id(neem_id)):
            (side_rows if row[2] == side_p else main_rows).append((i, *row))
        self.write_rows(neem_id, side, f"id, {DOCUMENT_COLUMNS}", main_rows, side_rows)

    def propagate(self, neem_id: str, subject: str, gained: tuple[Any, ...]) -> None:
        """Append ``gained`` to ``o*`` of taxonomic and ``p*`` of other rows containing ``subject``."""
        side = self.registry.side_row(neem_id)
        for table in self.registry.tables_of(neem_id):
            self._propagate_in(table, subject, gained)
        if side is not None:
            lists = [self.closures.members(cid) for cid in held(side)]
            grown = {self.closures.cid(extend_closure(members, gained)) for members in lists if subject in members}
            note_closures(self.conn, neem_id, side, grown)

    def _propagate_in(self, table: str, subject: str, gained: tuple[Any, ...]) -> None:
        for cid in self.closures.containing(self.terms.known_id(subject)):
            new_cid = self.closures.cid(extend_closure(self.closures.members(cid), gained))
            for column, field, taxonomic in (("ostar", "o*", True), ("pstar", "p*", False)):
                which = f"p IN {TAXONOMIC_SQL}" if taxonomic else f"p NOT IN {TAXONOMIC_SQL} AND {non_taxonomic('p')}"
                self.conn.execute(
                    f"UPDATE {table} SET {column}=? WHERE {column}=? AND raw IS NULL AND {which}",
                    (new_cid, cid),
                )
                rows = self.conn.execute(
                    f"SELECT id, raw FROM {table} WHERE {column}=? AND raw IS NOT NULL AND {which}",
                    (cid,),
                ).fetchall()
                updates = []
                for key, raw in rows:
                    doc = bson.decode(raw, codec_options=CODEC)
                    doc[field] = list(extend_closure(doc[field], gained))
                    updates.append((new_cid, bson.encode(doc, codec_options=CODEC), key))
                self.conn.executemany(f"UPDATE {table} SET {column}=?, raw=? WHERE id=?", updates)

    def rescope(self, neem_id: str, key: Any, since: float, until: float) -> None:
        """A stored fact's scope (``Store._rescope``), in its raw BSON too when it keeps one."""
        for table in self.registry.tables_of(neem_id):
            found = self.conn.execute(f"SELECT raw FROM {table} WHERE id=?", (key,)).fetchone()
            if found is not None:
                break
        else:
            raise StoreError(f"{self.conn.location}: no stored fact {key!r} in NEEM {neem_id!r}")
        (raw,) = found
        if raw is not None:  # a loaded document keeps its bytes: its scope changes in them too
            doc = bson.decode(raw, codec_options=CODEC)
            time_ = doc.setdefault("scope", {}).setdefault("time", {})
            kind: NumberFormat = "double" if isinstance(time_.get("since"), float) else "decimal128"
            time_["since"], time_["until"] = encode_number(since, kind), encode_number(until, kind)
            raw = bson.encode(doc, codec_options=CODEC)
        self.conn.execute(f"UPDATE {table} SET since=?, until=?, raw=? WHERE id=?", (since, until, raw, key))

    def delete(self, neem_id: str, keys: Sequence[Any]) -> None:
        """Stored facts by their keys (``Store._delete_triples``)."""
        for table in self.registry.tables_of(neem_id):
            self.conn.executemany(f"DELETE FROM {table} WHERE id=?", [(key,) for key in keys])
