"""The embedded default backend: one SQLite file holding KnowRob documents, indexed.

Each NEEM gets the four KnowRob collections as tables ``"<id>_triples"`` and so on. A triple
row keeps the exact BSON document (so dumps round-trip byte for byte) beside the columns the
indexes need. ``p*``/``o*`` are stored by reference to a content-addressed closure table: all
``rdf:type dul:Action`` triples share one closure row, so the closure costs one integer per
triple and ``o* contains C`` is an indexed lookup. IRIs and strings are interned in a ``terms`` table so
rows and index entries hold small integers (half the cost of indexing the IRI text).

Why this module is large: the schema, term and closure interning, the insert path and the
closure propagation share the connection and three caches (terms, closures, scopes) that must
stay consistent within one transaction; split across modules they would share private state.
The query compiler, which needs none of it but term ids, lives in ``store.sql``.
"""

from __future__ import annotations

import heapq
import math
import os
import struct
import time
from collections.abc import Callable, Collection, Iterable, Iterator, Mapping, Sequence
from contextlib import AbstractContextManager
from functools import partial
from operator import itemgetter
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import bson
from bson.decimal128 import Decimal128
from bson.codec_options import DEFAULT_CODEC_OPTIONS, DatetimeConversion
from bson.int64 import Int64
from bson.objectid import ObjectId

from oracle.errors import StoreError
from oracle.store.base import COLLECTION_KINDS, STAGING, Appended, AppendMark, Closed, NeemInfo, Store
from oracle.store.model import (
    HIERARCHY,
    TAXONOMIC,
    Annotation,
    DocumentBuilder,
    Hierarchy,
    NumberFormat,
    Scope,
    TriplePattern,
    TripleRow,
    encode_number,
    encode_value,
    extend_closure,
    unix_seconds,
)
from oracle.store.chunks import MatchChunk, concatenated_chunks, raw_chunks
from oracle.store import kept
from oracle.store.sqlite.closures import Closures
from oracle.store.sqlite.compiler import SqlCompiler, match_sql
from oracle.store.sqlite.sides import Side, held, note_closures, side_of
from oracle.store.sqlite.terms import K_DATE, K_DECIMAL, K_DOUBLE, K_LONG, K_STR, Terms
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.opening import open_read_only, open_writer
from oracle.store.sqlite.tables import (
    DOC_COLUMNS,
    GROUPED_ROWS,
    HIERARCHY_SQL,
    TAXONOMIC_SQL,
    INSERT_COLUMNS,
    SIDE,
    TRIPLE_COLUMNS,
    indexes,
    quote,
    neem_table,
    non_taxonomic,
)

def _blob(doc: Mapping[str, Any]) -> bytes:
    """A document's BSON: the bytes it was read with when it came from a dump."""
    raw = getattr(doc, "raw", None)
    return raw if raw is not None else bson.encode(doc, codec_options=_CODEC)


def _grouped(rows: list[Any], names: list[str], out: Callable[[Any, int], Any]) -> Iterator[dict[str, Any]]:
    """Rows of (value, kind) column pairs grouped by all but the last pair, whose values are
    collected (store.chunks.raw_chunks: each distinct value converted once)."""
    for chunk in raw_chunks(rows, list(range(len(names))), True, max(len(rows), 1), out):
        values = chunk.values
        for row in chunk.rows:
            solution = {name: values[p] for name, p in zip(names[:-1], row)}
            solution[names[-1]] = [values[p] for p in row[-1]]
            yield solution


SK_DECIMAL, SK_DOUBLE = 1, 2
_CODEC = DEFAULT_CODEC_OPTIONS.with_options(datetime_conversion=DatetimeConversion.DATETIME_AUTO)

class SQLiteStore(Store):
    """A NEEM store in one SQLite file (WAL, synchronous=FULL: an action committed survives a
    killed process and a power loss, docs/security.md)."""

    def __init__(
        self,
        path: str | os.PathLike[str],
        number_format: NumberFormat = "decimal128",
        *,
        create: bool = True,
        read_only: bool = False,
        check_while_reading: bool = False,
    ) -> None:
        super().__init__(number_format)
        self.path = Path(path).expanduser()
        self.location = str(self.path)
        self.read_only = read_only
        if (read_only or not create) and not self.path.is_file():
            raise StoreError(f"{self.path}: no NEEM store there (check --store; 'import' or 'load' creates one)")
        #: False for a schema 3 file opened read-only (no side tables there).
        self._has_sides = True
        # the whole-file check a writer's first write waits for (None: done at open, or nothing to check)
        if read_only:
            conn, self._has_sides = open_read_only(self.path)
            check = None
        else:
            conn, check = open_writer(self.path, check_while_reading)
        self._conn = Connection(conn, self.location, check)
        self._terms = Terms(self._conn)
        self._closures = Closures(self._conn, self._terms)
        self._conn.forget += [self._terms.forget, self._closures.forget]
        self._time_cache: dict[bytes, float] = {}
        self._scopes: dict[tuple[Any, ...], dict[str, Any]] = {}
        #: NEEM ids seen to exist; forgotten on drop/rename (another process may drop one too,
        #: then the next statement fails with "no such table", still a StoreError).
        self._present: set[str] = set()
        #: NEEM ids whose updates and deletions are counted (revisions, append_mark).
        self._tracked: set[str] = set()
        self._random = os.urandom(5)
        self._counter = int.from_bytes(os.urandom(3), "big")

    def known_term_id(self, value: str) -> int:
        """The id of a term for a query; -1 (matching nothing) when the store never saw it."""
        return self._terms.known_id(value)

    def closures_containing(self, term_id: int) -> list[int]:
        """Ids of the closures holding a term (what ``SqlCompiler`` inlines into ordered queries)."""
        return self._closures.containing(term_id)

    def _side(self, neem_id: str) -> Side | None:
        return side_of(self._conn, self._closures, neem_id, self._side_row(neem_id))

    def close(self) -> None:
        self._conn.close()

    def transaction(self) -> AbstractContextManager[None]:
        return self._conn.transaction()

    # -- registry ---------------------------------------------------------------------------
    def _registry(self) -> list[NeemInfo]:
        rows = self._conn.execute("SELECT id, meta FROM neems ORDER BY id").fetchall()
        return [NeemInfo.from_meta(neem_id, self._meta(neem_id, meta)) for neem_id, meta in rows]

    def neems(self) -> list[NeemInfo]:
        return [info for info in self._registry() if not info.meta.get(STAGING)]  # replacements being built are hidden

    def staging_neems(self) -> list[NeemInfo]:
        # Staging ids all start with "staging-" (Store.create_staging): a range on the primary
        # key, so every new NEEM of an import of many users does not decode the whole registry.
        rows = self._conn.execute("SELECT id, meta FROM neems WHERE id >= 'staging-' AND id < 'staging.'").fetchall()
        infos = [NeemInfo.from_meta(neem_id, self._meta(neem_id, meta)) for neem_id, meta in rows]
        return [info for info in infos if info.meta.get(STAGING)]

    def _meta(self, neem_id: str, blob: bytes) -> dict[str, Any]:
        try:
            return bson.decode(blob)
        except Exception:  # noqa: BLE001 - a damaged page; the caller gets a StoreError, not a traceback
            raise StoreError(f"{self.location}: the registry entry of NEEM {neem_id!r} is corrupt") from None

    def has_neem(self, neem_id: str) -> bool:
        if neem_id in self._present:
            return True
        found = self._conn.execute("SELECT 1 FROM neems WHERE id=?", (neem_id,)).fetchone() is not None
        if found:
            self._present.add(neem_id)
        return found

    def neem(self, neem_id: str) -> NeemInfo:
        row = self._conn.execute("SELECT meta FROM neems WHERE id=?", (neem_id,)).fetchone()
        if row is None:
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        return NeemInfo.from_meta(neem_id, self._meta(neem_id, row[0]))

    def _create_neem(self, neem_id: str, record: dict[str, Any], side_property: str | None) -> None:
        """A NEEM's tables; with ``side_property`` (a non-taxonomic property with many triples
        per subject, an imagining's plans) also its side table (docs/store.md): its triples are
        kept apart with one index, every query and dump sees the same documents."""
        if side_property is not None and (not isinstance(side_property, str) or side_property in TAXONOMIC):
            raise StoreError(f"a side property must be a non-taxonomic property IRI, got {side_property!r}")
        t = partial(neem_table, neem_id)
        with self.transaction():
            self._conn.execute("INSERT INTO neems VALUES (?, ?)", (neem_id, bson.encode(record)))
            self._conn.execute(f"CREATE TABLE {t('triples')}{TRIPLE_COLUMNS}")
            if side_property is not None:
                self._conn.execute(f"CREATE TABLE {t(SIDE)}{TRIPLE_COLUMNS}")
                self._conn.execute("INSERT INTO side_tables VALUES (?, ?, '')", (neem_id, self._terms.tid(side_property)))
            self._conn.execute(f"CREATE TABLE {t('annotations')}(id INTEGER PRIMARY KEY, s, p, doc BLOB NOT NULL)")
            self._conn.execute(
                f"CREATE TABLE {t('tf')}(id INTEGER PRIMARY KEY, child, stamp REAL, doc BLOB NOT NULL)"
            )
            self._conn.execute(f"CREATE TABLE {t('inferred')}(id INTEGER PRIMARY KEY, doc BLOB NOT NULL)")
            taken = {name for (name,) in self._conn.execute("SELECT name FROM sqlite_master WHERE type='index'")}
            for _, sql in indexes(neem_id, taken, side=side_property is not None):
                self._conn.execute(sql)
            self._track(neem_id)

    def _drop_neem(self, neem_id: str) -> None:
        with self.transaction():
            for kind in (*COLLECTION_KINDS, SIDE):
                self._conn.execute(f"DROP TABLE IF EXISTS {neem_table(neem_id, kind)}")
            self._conn.execute("DELETE FROM neems WHERE id=?", (neem_id,))
            self._conn.execute("DELETE FROM side_tables WHERE neem=?", (neem_id,))
            self._conn.execute("DELETE FROM revisions WHERE neem=?", (neem_id,))
            kept.drop(self._conn, neem_id)
        self._present.discard(neem_id)
        self._tracked.discard(neem_id)

    def _rename_neem(self, neem_id: str, new_id: str, info: NeemInfo) -> None:
        with self.transaction():
            for kind in COLLECTION_KINDS:
                self._conn.execute(f"ALTER TABLE {neem_table(neem_id, kind)} RENAME TO {neem_table(new_id, kind)}")
            if self._side_row(neem_id) is not None:
                self._conn.execute(f"ALTER TABLE {neem_table(neem_id, SIDE)} RENAME TO {neem_table(new_id, SIDE)}")
                self._conn.execute("UPDATE side_tables SET neem=? WHERE neem=?", (new_id, neem_id))
            # The indexes go with their tables under their old names (SQLite cannot rename an
            # index, and rebuilding them cost minutes and ~200 MiB at 50,000 actions): a NEEM
            # created later under an id whose names are taken gets other names (_indexes).
            self._conn.execute("UPDATE neems SET id=? WHERE id=?", (new_id, neem_id))
            self._conn.execute("UPDATE revisions SET neem=? WHERE neem=?", (new_id, neem_id))
            kept.rename(self._conn, neem_id, new_id)
        self._present.discard(neem_id)
        self._tracked.discard(neem_id)

    def _track(self, neem_id: str) -> None:
        """Count every update and deletion of the NEEM's triples from now on (append_mark):
        triggers on its triple tables, under a token of their own that stays with the tables
        when the NEEM is renamed and goes when they are dropped."""
        token = os.urandom(8).hex()
        self._conn.execute("INSERT INTO revisions VALUES (?, ?, 0)", (neem_id, token))
        for table, kind in ((neem_table(neem_id, "triples"), "t"), (neem_table(neem_id, SIDE), "s")):
            if kind == "s" and self._side_row(neem_id) is None:
                continue
            for event in ("UPDATE", "DELETE"):
                name = quote(f"changes_{token}_{kind}_{event.lower()}")
                self._conn.execute(f"CREATE TRIGGER {name} AFTER {event} ON {table} BEGIN"
                                   f" UPDATE revisions SET changes = changes + 1 WHERE token = '{token}'; END")

    def _ensure_tracked(self, neem_id: str) -> None:
        """Start counting the NEEM's updates and deletions unless they are counted already."""
        if neem_id in self._tracked:
            return
        if self._conn.execute("SELECT 1 FROM revisions WHERE neem=?", (neem_id,)).fetchone() is None:
            self._track(neem_id)
        self._tracked.add(neem_id)

    def append_mark(self, neem_id: str) -> AppendMark | None:
        # A NEEM made before the revisions table starts being tracked at its first mark (a
        # reader only trusts what it read after that); a read-only store cannot start it.
        self._require(neem_id)
        query = "SELECT token, changes FROM revisions WHERE neem=?"
        try:
            with self._conn.reading():
                row = self._conn.execute(query, (neem_id,)).fetchone()
                last = self._next_id(neem_id) - 1
        except StoreError:
            if self.read_only:
                return None  # a store from before the revisions table
            raise
        if row is None and not self.read_only:
            with self.transaction():
                self._ensure_tracked(neem_id)
                row = self._conn.execute(query, (neem_id,)).fetchone()
                last = self._next_id(neem_id) - 1
        return None if row is None else AppendMark(str(row[0]), int(row[1]), last)

    def read_kept(self, neem_id: str, kind: str) -> bytes | None:
        with self._conn.reading():
            return kept.read(self._conn, neem_id, kind)

    def write_kept(self, neem_id: str, kind: str, data: bytes) -> bool:
        if self.read_only:
            return False
        with self.transaction():
            kept.write(self._conn, neem_id, kind, data)
        return True

    def appended(self, neem_id: str, last: int) -> Appended | None:
        self._require(neem_id)
        tables = self._tables_of(neem_id)
        with self._conn.reading():
            cursors = [self._conn.execute(f"SELECT t0.id, {DOC_COLUMNS} FROM {t} AS t0 WHERE id > ? ORDER BY id", (last,))
                       for t in tables]
            docs = [self._document(row[1:]) for row in heapq.merge(*cursors, key=itemgetter(0))]
            new = " UNION ".join(f"SELECT s FROM {t} WHERE id > :last" for t in tables)
            # Each subject looked up by the (s, p) and (o, p) indexes of the main table and the
            # (s) index of the side table; the side table's objects (plans) in one scan.
            known = " OR ".join(
                [f"EXISTS (SELECT 1 FROM {t} WHERE s = n.s AND id <= :last)" for t in tables]
                + [f"EXISTS (SELECT 1 FROM {tables[0]} WHERE o = n.s AND ok = {K_STR} AND id <= :last)"]
            )
            stale = self._conn.execute(
                f"SELECT 1 FROM ({new}) AS n WHERE n.s IS NULL OR {known} LIMIT 1", {"last": last}
            ).fetchone()
            if stale is None and len(tables) > 1:
                stale = self._conn.execute(
                    f"SELECT 1 FROM {tables[1]} WHERE id <= :last AND ok = {K_STR} AND o IN ({new}) LIMIT 1",
                    {"last": last},
                ).fetchone()
        return Appended(docs, stale is None)

    def update_meta(self, neem_id: str, **fields: Any) -> NeemInfo:
        meta = dict(self.neem(neem_id).meta)
        meta.update(fields)
        with self.transaction():
            self._conn.execute("UPDATE neems SET meta=? WHERE id=?", (bson.encode(meta), neem_id))
        return NeemInfo.from_meta(neem_id, meta)

    # -- the side table ---------------------------------------------------------------------
    def _side_row(self, neem_id: str) -> tuple[int, str] | None:
        """(term id of the side property, the closure ids its rows hold) of a NEEM with a side table."""
        if not self._has_sides:
            return None
        row = self._conn.execute("SELECT p, closures FROM side_tables WHERE neem=?", (neem_id,)).fetchone()
        return None if row is None else (int(row[0]), str(row[1]))

    def _next_id(self, neem_id: str) -> int:
        """The id the next triple of a NEEM gets: with a side table, ids run across both tables,
        so a dump reads them back in insertion order."""
        main = neem_table(neem_id, "triples")
        if self._side_row(neem_id) is None:
            return int(self._conn.execute(f"SELECT coalesce(max(id), 0) + 1 FROM {main}").fetchone()[0])
        side = neem_table(neem_id, SIDE)
        row = self._conn.execute(
            f"SELECT max((SELECT coalesce(max(id), 0) FROM {main}), (SELECT coalesce(max(id), 0) FROM {side}))"
        ).fetchone()
        return int(row[0]) + 1

    def _insert_rows(self, neem_id: str, rows: list[tuple[Any, ...]], columns: str) -> None:
        """Rows of documents (``columns`` without ``id``) into the triples table, those of the
        side property into the side table; ids run across both (``_next_id``)."""
        side = self._side_row(neem_id)
        side_p = -1 if side is None else side[0]
        main_rows: list[tuple[Any, ...]] = []
        side_rows: list[tuple[Any, ...]] = []
        for i, row in enumerate(rows, start=self._next_id(neem_id)):
            (side_rows if row[2] == side_p else main_rows).append((i, *row))
        self._write_rows(neem_id, side, f"id, {columns}", main_rows, side_rows)

    def _write_rows(self, neem_id: str, side: tuple[int, str] | None, columns: str,
                    main_rows: list[tuple[Any, ...]], side_rows: list[tuple[Any, ...]],
                    side_closures: Collection[int | None] | None = None) -> None:  # fmt: skip
        """Rows (id first, then the rest of ``columns``) into the triples table and the side
        table; the closures the side rows hold (``side_closures`` when the caller knows them)
        are recorded (``sides.note_closures``)."""
        self._ensure_tracked(neem_id)  # a NEEM made before the revisions table: from its first write on
        if main_rows:
            self._conn.insert_many(neem_table(neem_id, "triples"), columns, main_rows, 1)
        if side is not None and side_rows:
            self._conn.insert_many(neem_table(neem_id, SIDE), columns, side_rows, GROUPED_ROWS)
            if side_closures is None:
                side_closures = {cid for row in side_rows for cid in row[6:8]}
            note_closures(self._conn, neem_id, side, side_closures)

    # -- writing ----------------------------------------------------------------------------
    def _seconds(self, value: Any) -> float | None:
        if isinstance(value, Decimal128):
            cached = self._time_cache.get(value.bid)
            if cached is None:
                cached = float(value.to_decimal())
                if len(self._time_cache) < 4096:
                    self._time_cache[value.bid] = cached
            return cached
        return unix_seconds(value)

    def _insert_closed(self, neem_id: str, triples: Iterable[TripleRow], hierarchy: Hierarchy,
                       builder: DocumentBuilder) -> int:  # fmt: skip
        """A batch without subClassOf/subPropertyOf triples (every batch the logger writes)
        goes straight to rows, each closure looked up once per distinct property and class;
        a batch that changes the taxonomy takes the general path (``Store._insert_closed``)."""
        batch = triples if type(triples) is list else list(triples)
        if not batch:
            return 0
        if not HIERARCHY.isdisjoint({triple[1] for triple in batch}):
            return super()._insert_closed(neem_id, batch, hierarchy, builder)
        closure = hierarchy.closure
        with self.transaction():
            self._write_triples(neem_id, batch, closure, lambda o: closure(o) if type(o) is str else (o,), builder)
        return len(batch)

    def _insert_triples(self, neem_id: str, closed: list[Closed], builder: DocumentBuilder) -> None:
        """Triples with their closures (the general path): within one such list, a property or
        class has one closure (Store._insert_closed writes the list out before a change)."""
        pstars = {triple[1]: pstar for triple, pstar, _ in closed}
        ostars = {(type(triple[2]), triple[2]): ostar for triple, _, ostar in closed if triple[1] in TAXONOMIC}
        self._write_triples(neem_id, [triple for triple, _, _ in closed], pstars.__getitem__,
                            lambda o: ostars[(type(o), o)], builder)  # fmt: skip

    def _write_triples(self, neem_id: str, batch: list[TripleRow], pstar_of: Callable[[str], tuple[Any, ...]],
                       ostar_of: Callable[[Any], tuple[Any, ...]], builder: DocumentBuilder) -> None:  # fmt: skip
        """Rows straight from triples (a document is rebuilt from its columns when read), in one
        pass: ``pstar_of(p)`` (non-taxonomic ``p``) and ``ostar_of(o)`` (the object of a
        taxonomic triple) are asked once per distinct term, as are their closure and term ids."""
        self._require(neem_id)
        decimal = builder.number_format == "decimal128"
        float_kind, scope_kind = (K_DECIMAL, SK_DECIMAL) if decimal else (K_DOUBLE, SK_DOUBLE)
        # New terms numbered in sorted order: event IRIs of one kind then grow with time, as
        # the logger mints them, and their index entries land near the end of the indexes.
        strings = set(map(itemgetter(0), batch))
        strings.update(o for o in set(map(itemgetter(2), batch)) if type(o) is str)
        ids = self._terms.tids(sorted(strings))
        cid = self._closures.cid
        side = self._side_row(neem_id)
        side_p = -1 if side is None else side[0]
        main_rows: list[tuple[Any, ...]] = []
        side_rows: list[tuple[Any, ...]] = []
        # Per property: its id, its p* closure id, whether it is taxonomic, the table it goes to.
        props: dict[str, tuple[int, int, bool, Callable[[tuple[Any, ...]], None]]] = {}
        # The o* closure id of a taxonomic triple's object: an IRI, or another value by
        # (type, value), so that 1, 1.0 and True are not one key.
        classes: dict[str, int] = {}
        values: dict[tuple[type, Any], int] = {}
        first = self._next_id(neem_id)
        # ObjectId bytes: this second, the store's random part, then a counter per row.
        prefix = struct.pack(">I", int(time.time())) + self._random
        offset = self._counter + 1 - first  # row ``first`` gets the counter after the last one
        sql_o: Any
        for row_id, triple in enumerate(batch, first):
            s_, p, o, graph, since, until = triple
            if since > until:
                raise ValueError(f"scope of {triple} ends before it starts")
            prop = props.get(p)
            if prop is None:
                p_id = self._terms.tid(p)
                taxonomic = p in TAXONOMIC
                prop = props[p] = (p_id, cid((p,) if taxonomic else pstar_of(p)), taxonomic,
                                   side_rows.append if p_id == side_p else main_rows.append)  # fmt: skip
            p_id, pstar_cid, taxonomic, append = prop
            ostar_cid = 0
            if type(o) is str:
                sql_o, kind = ids[o], K_STR
                if taxonomic:
                    ostar_cid = classes.get(o, 0) or classes.setdefault(o, cid(ostar_of(o)))
            else:
                if type(o) is float:
                    sql_o, kind = o, float_kind
                else:
                    sql_o, kind = self._terms.sql(encode_value(o, builder.number_format))
                if taxonomic:
                    key = (type(o), o)
                    ostar_cid = values.get(key, 0) or values.setdefault(key, cid(ostar_of(o)))
            append((row_id, prefix + ((offset + row_id) & 0xFFFFFF).to_bytes(3, "big"), ids[s_], p_id, sql_o, kind,
                    pstar_cid, ostar_cid, graph, since, until, scope_kind))  # fmt: skip
        self._counter = (offset + first + len(batch) - 1) & 0xFFFFFF
        side_closures = {prop[1] for prop in props.values() if prop[0] == side_p}
        self._write_rows(neem_id, side, INSERT_COLUMNS, main_rows, side_rows,
                         side_closures)  # fmt: skip

    def _triple_row(self, doc: Mapping[str, Any]) -> tuple[Any, ...]:
        """Columns of a document stored as given (kept whole in ``raw`` for an exact dump)."""
        raw = getattr(doc, "raw", None)  # bytes kept by the dump reader
        if "_id" not in doc:
            doc = {"_id": ObjectId(), **doc}
            raw = None
        p = doc.get("p")
        o = doc.get("o")
        sql_o, kind = self._terms.sql(o)
        s = doc.get("s")
        pstar = doc.get("p*")
        ostar = doc.get("o*")
        pstar_cid = None if pstar is None else self._closures.cid(pstar)
        if ostar is None:
            ostar_cid = None
        elif p not in TAXONOMIC and len(ostar) == 1 and type(ostar[0]) is type(o) and ostar[0] == o:
            ostar_cid = 0  # the trivial [o] of a non-taxonomic triple needs no closure row
        else:
            ostar_cid = self._closures.cid(ostar)
        time_ = (doc.get("scope") or {}).get("time") or {}
        since = self._seconds(time_.get("since"))
        until = self._seconds(time_.get("until"))
        oid = doc["_id"].binary if isinstance(doc["_id"], ObjectId) else b""
        row = (oid, self._terms.tid(s) if type(s) is str else None, self._terms.tid(p) if type(p) is str else None, sql_o, kind,
               pstar_cid, ostar_cid, doc.get("graph"), since, until, None, raw or bson.encode(doc, codec_options=_CODEC))  # fmt: skip
        return self._without_raw(row)

    def _without_raw(self, row: tuple[Any, ...]) -> tuple[Any, ...]:
        """The row without its BSON copy when the columns rebuild the very same bytes (every
        document this program wrote): a loaded NEEM then takes the space an imported one does."""
        oid, s, p, _o, _ok, pstar, ostar, graph, since, until, _sk, raw = row
        if len(oid) != 12 or s is None or p is None or pstar is None or ostar is None or since is None or until is None:
            return row
        if graph is not None and type(graph) is not str:
            return row
        for sk in (SK_DECIMAL, SK_DOUBLE):
            lean = (*row[:10], sk, None)
            try:
                same = bson.encode(self._document(lean), codec_options=_CODEC) == raw
            except Exception:  # noqa: BLE001 - any value the columns cannot rebuild: keep the copy
                return row
            if same:
                return lean
        return row

    def _insert_documents(self, neem_id: str, kind: str, docs: list[dict[str, Any]]) -> None:
        self._require(neem_id)
        table = neem_table(neem_id, kind)
        try:
            if kind == "triples":
                rows = [self._triple_row(doc) for doc in docs]
                self._insert_rows(neem_id, rows, "oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw")
            elif kind == "annotations":
                self._conn.executemany(
                    f"INSERT INTO {table}(s, p, doc) VALUES (?, ?, ?)",
                    [(d.get("s"), d.get("p"), _blob(d)) for d in docs],
                )
            elif kind == "tf":
                self._conn.executemany(
                    f"INSERT INTO {table}(child, stamp, doc) VALUES (?, ?, ?)",
                    [
                        (d.get("child_frame_id"), unix_seconds((d.get("header") or {}).get("stamp")), _blob(d))
                        for d in docs
                    ],
                )
            else:
                self._conn.executemany(f"INSERT INTO {table}(doc) VALUES (?)", [(_blob(d),) for d in docs])
        except (bson.errors.InvalidDocument, OverflowError) as error:
            raise StoreError(f"{self.location}: NEEM {neem_id!r}: cannot store a {kind} document ({error})") from None

    def _require(self, neem_id: str) -> None:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")

    def _propagate(self, neem_id: str, subject: str, gained: tuple[Any, ...]) -> None:
        side = self._side_row(neem_id)
        for table in (neem_table(neem_id, "triples"), *(() if side is None else (neem_table(neem_id, SIDE),))):
            self._propagate_in(table, subject, gained)
        if side is not None:
            lists = [self._closures.members(cid) for cid in held(side)]
            grown = {self._closures.cid(extend_closure(members, gained)) for members in lists if subject in members}
            note_closures(self._conn, neem_id, side, grown)

    def _propagate_in(self, table: str, subject: str, gained: tuple[Any, ...]) -> None:
        subject_id = self.known_term_id(subject)
        cids = [row[0] for row in self._conn.execute("SELECT DISTINCT cid FROM closure_member WHERE value=?", (subject_id,))]
        for cid in cids:
            new_cid = self._closures.cid(extend_closure(self._closures.members(cid), gained))
            for column, field, taxonomic in (("ostar", "o*", True), ("pstar", "p*", False)):
                which = f"p IN {TAXONOMIC_SQL}" if taxonomic else f"p NOT IN {TAXONOMIC_SQL} AND {non_taxonomic('p')}"
                self._conn.execute(
                    f"UPDATE {table} SET {column}=? WHERE {column}=? AND raw IS NULL AND {which}",
                    (new_cid, cid),
                )
                rows = self._conn.execute(
                    f"SELECT id, raw FROM {table} WHERE {column}=? AND raw IS NOT NULL AND {which}",
                    (cid,),
                ).fetchall()
                updates = []
                for rowid, blob in rows:
                    doc = bson.decode(blob, codec_options=_CODEC)
                    doc[field] = list(extend_closure(doc[field], gained))
                    updates.append((new_cid, bson.encode(doc, codec_options=_CODEC), rowid))
                self._conn.executemany(f"UPDATE {table} SET {column}=?, raw=? WHERE id=?", updates)

    def _overlapping(
        self, neem_id: str, s: Any, p: Any, o: Any, scope: Scope | None, graph: str | None = None
    ) -> list[tuple[Any, float, float]]:
        self._require(neem_id)
        query = SqlCompiler(self, neem_table(neem_id, "triples"), scope, self._side(neem_id))
        query.add(TriplePattern(s, p, o, graph), exact=True)
        sql = f"SELECT t0.id, t0.since, t0.until FROM {query.from_clause()} WHERE {query.where()} ORDER BY t0.id"
        return [(rowid, 0.0 if since is None else since, math.inf if until is None else until)
                for rowid, since, until in self._conn.execute(sql, query.params).fetchall()]  # fmt: skip

    def _tables_of(self, neem_id: str) -> tuple[str, ...]:
        """The NEEM's triple tables (ids run across both: a row's id names it in either)."""
        side = () if self._side_row(neem_id) is None else (neem_table(neem_id, SIDE),)
        return (neem_table(neem_id, "triples"), *side)

    def _rescope(self, neem_id: str, key: Any, since: float, until: float) -> None:
        for table in self._tables_of(neem_id):
            found = self._conn.execute(f"SELECT raw FROM {table} WHERE id=?", (key,)).fetchone()
            if found is not None:
                break
        else:
            raise StoreError(f"{self.location}: no stored fact {key!r} in NEEM {neem_id!r}")
        (raw,) = found
        if raw is not None:  # a loaded document keeps its bytes: its scope changes in them too
            doc = bson.decode(raw, codec_options=_CODEC)
            time_ = doc.setdefault("scope", {}).setdefault("time", {})
            kind: NumberFormat = "double" if isinstance(time_.get("since"), float) else "decimal128"
            time_["since"], time_["until"] = encode_number(since, kind), encode_number(until, kind)
            raw = bson.encode(doc, codec_options=_CODEC)
        self._conn.execute(f"UPDATE {table} SET since=?, until=?, raw=? WHERE id=?", (since, until, raw, key))

    def _delete_triples(self, neem_id: str, keys: Sequence[Any]) -> None:
        for table in self._tables_of(neem_id):
            self._conn.executemany(f"DELETE FROM {table} WHERE id=?", [(key,) for key in keys])

    def _hierarchy_source(self, neem_id: str) -> tuple[list[tuple[str, tuple[Any, ...]]], set[Any]]:
        table = neem_table(neem_id, "triples")
        edges = [
            (self._terms.value(s), self._closures.members(cid))
            for s, cid in self._conn.execute(
                f"SELECT s, ostar FROM {table} WHERE p IN {HIERARCHY_SQL} AND ostar > 0 AND s IS NOT NULL ORDER BY id"
            ).fetchall()
        ]
        used = {
            self._terms.value(value)
            for (value,) in self._conn.execute(
                f"SELECT DISTINCT value FROM closure_member WHERE value IS NOT NULL AND cid IN"
                f" (SELECT ostar FROM {table} UNION SELECT pstar FROM {table})"
            ).fetchall()
        }
        side = self._side_row(neem_id)
        if side is not None:  # the closures its rows hold are recorded: no scan of the side table
            used.update(v for cid in held(side) for v in self._closures.members(cid) if type(v) is str)
        return edges, used

    # -- reading ----------------------------------------------------------------------------
    def read_documents(self, neem_id: str, kind: str) -> Iterator[dict[str, Any]]:
        if kind not in COLLECTION_KINDS:
            raise StoreError(f"unknown collection kind {kind!r}")
        self._require(neem_id)
        if kind == "triples":
            tables = [neem_table(neem_id, kind)]
            if self._side_row(neem_id) is not None:
                tables.append(neem_table(neem_id, SIDE))
            # Each table in id order, merged: the documents in the order they were inserted.
            cursors = [self._conn.execute(f"SELECT t0.id, {DOC_COLUMNS} FROM {t} AS t0 ORDER BY id") for t in tables]
            for row in heapq.merge(*cursors, key=itemgetter(0)):
                yield self._document(row[1:])
            return
        cursor = self._conn.execute(f"SELECT doc FROM {neem_table(neem_id, kind)} ORDER BY id")
        for (blob,) in cursor:
            yield bson.decode(blob, codec_options=_CODEC)

    def _count(self, neem_id: str, kind: str) -> int:
        self._require(neem_id)
        count = int(self._conn.execute(f"SELECT count(*) FROM {neem_table(neem_id, kind)}").fetchone()[0])
        if kind == "triples" and self._side_row(neem_id) is not None:
            count += int(self._conn.execute(f"SELECT count(*) FROM {neem_table(neem_id, SIDE)}").fetchone()[0])
        return count

    def write_mark(self, neem_id: str) -> int:
        # The last rowid grows with every insert and is read from the end of the table's
        # b-tree, not by counting; a scope merge (store.project) deletes only copies of a fact
        # it keeps, and kb_unproject drops the kept summary itself.
        self._require(neem_id)
        return self._next_id(neem_id) - 1

    def _find(
        self, neem_id: str, pattern: TriplePattern, scope: Scope | None, limit: int | None, exact: bool
    ) -> Iterator[dict[str, Any]]:
        self._require(neem_id)
        query = SqlCompiler(self, neem_table(neem_id, "triples"), scope, self._side(neem_id))
        query.add(pattern, exact=exact)
        sql = f"SELECT {DOC_COLUMNS} FROM {query.from_clause()} WHERE {query.where()} ORDER BY t0.id"
        if limit is not None:
            sql += f" LIMIT {int(limit)}"
        for row in self._conn.execute(sql, query.params).fetchall():
            yield self._document(row)

    def _scope_doc(self, since: float, until: float, sk: int) -> dict[str, Any]:
        key = (since, until, sk)
        cached = self._scopes.get(key)
        if cached is None:
            fmt: NumberFormat = "decimal128" if sk == SK_DECIMAL else "double"
            cached = {"time": {"since": encode_number(since, fmt), "until": encode_number(until, fmt)}}
            if len(self._scopes) < 4096:
                self._scopes[key] = cached
        return {"time": dict(cached["time"])}

    def _document(self, row: Sequence[Any]) -> dict[str, Any]:
        """A stored document: the raw one when loaded, else rebuilt from the columns."""
        oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw = row
        if raw is not None:
            return bson.decode(raw, codec_options=_CODEC)
        if ok in (K_DECIMAL, K_DOUBLE) and o is None:
            o = math.nan  # SQLite keeps NaN as NULL
        if ok == K_DECIMAL:
            value: Any = encode_number(o, "decimal128")
        elif ok == K_LONG:
            value = Int64(o)
        elif ok == K_DATE:
            value = datetime.fromtimestamp(o, timezone.utc).replace(tzinfo=None)  # as pymongo decodes Dates
        else:
            value = self._terms.out(o, ok)
        return {
            "_id": ObjectId(oid),
            "s": self._terms.value(s),
            "p": self._terms.value(p),
            "o": value,
            "p*": list(self._closures.members(pstar)),
            "o*": [value] if ostar == 0 else list(self._closures.members(ostar)),
            "graph": graph,
            "scope": self._scope_doc(since, until, sk),
        }

    def _match(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        select: Sequence[str] | None = None,
        group: str | None = None,
        written_order: bool = False,
    ) -> Iterator[dict[str, Any]]:
        names, rows = self._match_rows(neem_id, patterns, scope, limit, order, select, group, written_order)
        out = self._terms.out
        if group is not None:
            yield from _grouped(rows, names, out)
            return
        for row in rows:
            yield {name: out(row[2 * i], row[2 * i + 1]) for i, name in enumerate(names)}

    def _match_chunks(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        kept: list[str],
        group: str | None,
        written_order: bool,
        size: int,
    ) -> Iterator[MatchChunk]:
        # The raw (value, kind) columns are indexed as they come from SQL: each distinct term
        # id becomes its IRI once per chunk, not once per cell.
        if group is not None and limit is None and not written_order:
            grouped = self._grouped_in_sql(neem_id, patterns, scope, order, kept, group, size)
            if grouped is not None:
                return grouped
        names, rows = self._match_rows(neem_id, patterns, scope, limit, order, kept, group, written_order)
        where = [names.index(name) for name in kept]
        return raw_chunks(rows, where, group is not None, size, self._terms.out, self._terms.convert)

    def _grouped_in_sql(self, neem_id: str, patterns: Sequence[TriplePattern], scope: Scope | None,
                        order: Sequence[tuple[str, bool]], kept: list[str], group: str,
                        size: int) -> Iterator[MatchChunk] | None:
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
        names, columns, rest, params = self._match_sql(neem_id, patterns, scope, None, order, kept, group, False)
        width = len(columns) - 2
        keys = [f"c{i}" for i in range(width)]
        inner = f"SELECT {', '.join(f'{expr} AS c{i}' for i, expr in enumerate(columns))} {rest}"
        # Checks: a grouped value that is no integer, a key that is a REAL zero.
        checks = [f"sum(typeof(c{width}) != 'integer' OR typeof(c{width + 1}) != 'integer')"]
        checks += [f"sum(typeof(c{i}) = 'real' AND c{i} = 0)" for i in range(0, width, 2)]
        sql = (f"SELECT {', '.join(keys + [f'group_concat(c{width})', f'group_concat(c{width + 1})'] + checks)}"
               f" FROM ({inner}) GROUP BY {', '.join(keys)}")
        rows = self._conn.execute(sql, params).fetchall()
        if any(any(row[width + 2:]) for row in rows):
            return None
        where = [names.index(name) for name in kept]
        return concatenated_chunks(rows, width, where[:-1], size, self._terms.out, self._terms.convert)

    def _match_rows(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        select: Sequence[str] | None,
        group: str | None,
        written_order: bool,
    ) -> tuple[list[str], list[Any]]:
        """The kept variables (``group`` last) and the rows of one SQL join, each row a
        (value, kind) pair per variable."""
        names, columns, rest, params = self._match_sql(neem_id, patterns, scope, limit, order, select, group,
                                                       written_order)
        sql = f"SELECT {', '.join(columns) or '1'} {rest}"
        if written_order:
            # The plan is the caller's: no automatic index (SQLite without statistics would build
            # one over the whole table for a lookup the (o, p) index answers).
            self._conn.execute("PRAGMA automatic_index = OFF")
            try:
                rows = self._conn.execute(sql, params).fetchall()
            finally:
                self._conn.execute("PRAGMA automatic_index = ON")
        else:
            rows = self._conn.execute(sql, params).fetchall()
        return names, rows

    def _match_sql(
        self,
        neem_id: str,
        patterns: Sequence[TriplePattern],
        scope: Scope | None,
        limit: int | None,
        order: Sequence[tuple[str, bool]],
        select: Sequence[str] | None,
        group: str | None,
        written_order: bool,
    ) -> tuple[list[str], list[str], str, Any]:
        self._require(neem_id)
        query = SqlCompiler(self, neem_table(neem_id, "triples"), scope, self._side(neem_id))
        return match_sql(query, patterns, limit, order, select, group, written_order)

    def annotations(self, neem_id: str, s: str | None = None, p: str | None = None) -> Iterator[Annotation]:
        self._require(neem_id)
        conds, params = ["1"], []
        if s is not None:
            conds.append("s=?")
            params.append(s)
        if p is not None:
            conds.append("p=?")
            params.append(p)
        sql = f"SELECT doc FROM {neem_table(neem_id, 'annotations')} WHERE {' AND '.join(conds)} ORDER BY id"
        for (blob,) in self._conn.execute(sql, params):
            doc = bson.decode(blob)
            yield Annotation(doc["s"], doc["p"], doc.get("v"))
