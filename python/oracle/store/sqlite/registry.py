"""The NEEM registry in the SQLite file: the registry rows (openEASE's ``meta``, as BSON), each
NEEM's tables made, dropped and renamed with them in one transaction, the count of its updates
and deletions (``Store.append_mark``), what a reader kept beside it (store.kept), and the facts
of its tables the other parts ask for (its side table, the id its next triple gets)."""

from __future__ import annotations

import os
from functools import partial
from typing import Any

import bson

from oracle.errors import StoreError
from oracle.store import kept
from oracle.store.base import COLLECTION_KINDS, AppendMark, NeemInfo
from oracle.store.staging import STAGING
from oracle.store.model import TAXONOMIC
from oracle.store.sqlite.connection import Connection
from oracle.store.sqlite.sides import SideRow
from oracle.store.sqlite.tables import DEFERRED, SIDE, TRIPLE_COLUMNS, index_targets, indexes, neem_table, quote, target_of
from oracle.store.sqlite.terms import Terms


class Registry:
    """The NEEMs of one store file. ``has_sides`` is False for a schema 3 file opened
    read-only (no side tables there)."""

    def __init__(self, conn: Connection, terms: Terms, *, has_sides: bool, read_only: bool) -> None:
        self.conn = conn
        self.terms = terms
        self.location = conn.location
        self.has_sides = has_sides
        self.read_only = read_only
        #: NEEM ids seen to exist; forgotten on drop/rename (another process may drop one too,
        #: then the next statement fails with "no such table", still a StoreError).
        self.present: set[str] = set()
        #: NEEM ids whose updates and deletions are counted (revisions, append_mark).
        self.tracked: set[str] = set()
        #: NEEM ids this connection left indexes out of (defer_indexes), until make_indexes.
        self.deferred: set[str] = set()

    # -- registry rows ----------------------------------------------------------------------
    def neems(self) -> list[NeemInfo]:
        rows = self.conn.execute("SELECT id, meta FROM neems ORDER BY id").fetchall()
        infos = [NeemInfo.from_meta(neem_id, self._meta(neem_id, meta)) for neem_id, meta in rows]
        return [info for info in infos if not info.meta.get(STAGING)]  # replacements being built are hidden

    def staging_neems(self) -> list[NeemInfo]:
        # Staging ids all start with "staging-" (Store.create_staging): a range on the primary
        # key, so every new NEEM of an import of many users does not decode the whole registry.
        rows = self.conn.execute("SELECT id, meta FROM neems WHERE id >= 'staging-' AND id < 'staging.'").fetchall()
        infos = [NeemInfo.from_meta(neem_id, self._meta(neem_id, meta)) for neem_id, meta in rows]
        return [info for info in infos if info.meta.get(STAGING)]

    def _meta(self, neem_id: str, blob: bytes) -> dict[str, Any]:
        try:
            return bson.decode(blob)
        except Exception:  # noqa: BLE001 - a damaged page; the caller gets a StoreError, not a traceback
            raise StoreError(f"{self.location}: the registry entry of NEEM {neem_id!r} is corrupt") from None

    def has_neem(self, neem_id: str) -> bool:
        if neem_id in self.present:
            return True
        found = self.conn.execute("SELECT 1 FROM neems WHERE id=?", (neem_id,)).fetchone() is not None
        if found:
            self.present.add(neem_id)
        return found

    def require(self, neem_id: str) -> None:
        if not self.has_neem(neem_id):
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")

    def neem(self, neem_id: str) -> NeemInfo:
        row = self.conn.execute("SELECT meta FROM neems WHERE id=?", (neem_id,)).fetchone()
        if row is None:
            raise StoreError(f"{self.location}: no NEEM {neem_id!r}")
        return NeemInfo.from_meta(neem_id, self._meta(neem_id, row[0]))

    def update_meta(self, neem_id: str, **fields: Any) -> NeemInfo:
        meta = dict(self.neem(neem_id).meta)
        meta.update(fields)
        with self.conn.transaction():
            self.conn.execute("UPDATE neems SET meta=? WHERE id=?", (bson.encode(meta), neem_id))
        return NeemInfo.from_meta(neem_id, meta)

    # -- a NEEM's tables --------------------------------------------------------------------
    def create(self, neem_id: str, record: dict[str, Any], side_property: str | None) -> None:
        """A NEEM's tables; with ``side_property`` (a non-taxonomic property with many triples
        per subject, an imagining's plans) also its side table (store.sqlite.sides)."""
        if side_property is not None and (not isinstance(side_property, str) or side_property in TAXONOMIC):
            raise StoreError(f"a side property must be a non-taxonomic property IRI, got {side_property!r}")
        t = partial(neem_table, neem_id)
        conn = self.conn
        with conn.transaction():
            conn.execute("INSERT INTO neems VALUES (?, ?)", (neem_id, bson.encode(record)))
            conn.execute(f"CREATE TABLE {t('triples')}{TRIPLE_COLUMNS}")
            if side_property is not None:
                conn.execute(f"CREATE TABLE {t(SIDE)}{TRIPLE_COLUMNS}")
                conn.execute("INSERT INTO side_tables VALUES (?, ?, '')", (neem_id, self.terms.tid(side_property)))
            conn.execute(f"CREATE TABLE {t('annotations')}(id INTEGER PRIMARY KEY, s, p, doc BLOB NOT NULL)")
            conn.execute(f"CREATE TABLE {t('tf')}(id INTEGER PRIMARY KEY, child, stamp REAL, doc BLOB NOT NULL)")
            conn.execute(f"CREATE TABLE {t('inferred')}(id INTEGER PRIMARY KEY, doc BLOB NOT NULL)")
            taken = {name for (name,) in conn.execute("SELECT name FROM sqlite_master WHERE type='index'")}
            for _, sql in indexes(neem_id, taken, side=side_property is not None):
                conn.execute(sql)
            self._track(neem_id)

    def _present_indexes(self, neem_id: str) -> dict[str, str]:
        """{``ON ...`` target: name} of the indexes on the NEEM's tables (tables.index_targets)."""
        tables = [f"{neem_id}_{kind}" for kind in (*COLLECTION_KINDS, SIDE)]
        rows = self.conn.execute(
            f"SELECT name, sql FROM sqlite_master WHERE type='index' AND sql IS NOT NULL"
            f" AND tbl_name IN ({', '.join('?' * len(tables))})", tables).fetchall()
        return {target_of(str(sql)): str(name) for name, sql in rows}

    def defer_indexes(self, neem_id: str) -> None:
        """Drop the NEEM's indexes of ``tables.DEFERRED`` (Store.defer_indexes); ``make_indexes``
        builds them again. One transaction: a kill leaves all of them or none."""
        self.require(neem_id)
        with self.conn.transaction():
            present = self._present_indexes(neem_id)
            for kind, target in index_targets(neem_id, side=self.side_row(neem_id) is not None):
                if kind in DEFERRED and target in present:
                    self.conn.execute(f"DROP INDEX {quote(present[target])}")
        self.deferred.add(neem_id)

    def make_indexes(self, neem_id: str) -> None:
        """Build each index of the NEEM that is not there (Store.make_indexes), in one transaction."""
        self.require(neem_id)
        with self.conn.transaction():
            present = self._present_indexes(neem_id)
            taken = {name for (name,) in self.conn.execute("SELECT name FROM sqlite_master WHERE type='index'")}
            for _, sql in indexes(neem_id, taken, side=self.side_row(neem_id) is not None):
                if target_of(sql) not in present:
                    self.conn.execute(sql)
        self.deferred.discard(neem_id)

    def drop(self, neem_id: str) -> None:
        conn = self.conn
        with conn.transaction():
            for kind in (*COLLECTION_KINDS, SIDE):
                conn.execute(f"DROP TABLE IF EXISTS {neem_table(neem_id, kind)}")
            conn.execute("DELETE FROM neems WHERE id=?", (neem_id,))
            conn.execute("DELETE FROM side_tables WHERE neem=?", (neem_id,))
            conn.execute("DELETE FROM revisions WHERE neem=?", (neem_id,))
            kept.drop(conn, neem_id)
        self.present.discard(neem_id)
        self.tracked.discard(neem_id)
        self.deferred.discard(neem_id)

    def rename(self, neem_id: str, new_id: str) -> None:
        conn = self.conn
        with conn.transaction():
            for kind in COLLECTION_KINDS:
                conn.execute(f"ALTER TABLE {neem_table(neem_id, kind)} RENAME TO {neem_table(new_id, kind)}")
            if self.side_row(neem_id) is not None:
                conn.execute(f"ALTER TABLE {neem_table(neem_id, SIDE)} RENAME TO {neem_table(new_id, SIDE)}")
                conn.execute("UPDATE side_tables SET neem=? WHERE neem=?", (new_id, neem_id))
            # The indexes go with their tables under their old names (SQLite cannot rename an
            # index, and rebuilding them cost minutes and ~200 MiB at 50,000 actions): a NEEM
            # created later under an id whose names are taken gets other names (tables.indexes).
            conn.execute("UPDATE neems SET id=? WHERE id=?", (new_id, neem_id))
            conn.execute("UPDATE revisions SET neem=? WHERE neem=?", (new_id, neem_id))
            kept.rename(conn, neem_id, new_id)
        self.present.discard(neem_id)
        self.tracked.discard(neem_id)
        self.deferred.discard(neem_id)

    def side_row(self, neem_id: str) -> SideRow | None:
        """(term id of the side property, the closure ids its rows hold) of a NEEM with a side table."""
        if not self.has_sides:
            return None
        row = self.conn.execute("SELECT p, closures FROM side_tables WHERE neem=?", (neem_id,)).fetchone()
        return None if row is None else (int(row[0]), str(row[1]))

    def tables_of(self, neem_id: str) -> tuple[str, ...]:
        """The NEEM's triple tables (ids run across both: a row's id names it in either)."""
        side = () if self.side_row(neem_id) is None else (neem_table(neem_id, SIDE),)
        return (neem_table(neem_id, "triples"), *side)

    def next_id(self, neem_id: str) -> int:
        """The id the next triple of a NEEM gets: with a side table, ids run across both tables,
        so a dump reads them back in insertion order."""
        main = neem_table(neem_id, "triples")
        if self.side_row(neem_id) is None:
            return int(self.conn.execute(f"SELECT coalesce(max(id), 0) + 1 FROM {main}").fetchone()[0])
        side = neem_table(neem_id, SIDE)
        row = self.conn.execute(
            f"SELECT max((SELECT coalesce(max(id), 0) FROM {main}), (SELECT coalesce(max(id), 0) FROM {side}))"
        ).fetchone()
        return int(row[0]) + 1

    # -- revisions --------------------------------------------------------------------------
    def _track(self, neem_id: str) -> None:
        """Count every update and deletion of the NEEM's triples from now on (append_mark):
        triggers on its triple tables, under a token of their own that stays with the tables
        when the NEEM is renamed and goes when they are dropped."""
        token = os.urandom(8).hex()
        self.conn.execute("INSERT INTO revisions VALUES (?, ?, 0)", (neem_id, token))
        for table, kind in ((neem_table(neem_id, "triples"), "t"), (neem_table(neem_id, SIDE), "s")):
            if kind == "s" and self.side_row(neem_id) is None:
                continue
            for event in ("UPDATE", "DELETE"):
                name = quote(f"changes_{token}_{kind}_{event.lower()}")
                self.conn.execute(f"CREATE TRIGGER {name} AFTER {event} ON {table} BEGIN"
                                  f" UPDATE revisions SET changes = changes + 1 WHERE token = '{token}'; END")

    def ensure_tracked(self, neem_id: str) -> None:
        """Start counting the NEEM's updates and deletions unless they are counted already."""
        if neem_id in self.tracked:
            return
        if self.conn.execute("SELECT 1 FROM revisions WHERE neem=?", (neem_id,)).fetchone() is None:
            self._track(neem_id)
        self.tracked.add(neem_id)

    def append_mark(self, neem_id: str) -> AppendMark | None:
        # A NEEM made before the revisions table starts being tracked at its first mark (a
        # reader only trusts what it read after that); a read-only store cannot start it.
        self.require(neem_id)
        query = "SELECT token, changes FROM revisions WHERE neem=?"
        try:
            with self.conn.reading():
                row = self.conn.execute(query, (neem_id,)).fetchone()
                last = self.next_id(neem_id) - 1
        except StoreError:
            if self.read_only:
                return None  # a store from before the revisions table
            raise
        if row is None and not self.read_only:
            with self.conn.transaction():
                self.ensure_tracked(neem_id)
                row = self.conn.execute(query, (neem_id,)).fetchone()
                last = self.next_id(neem_id) - 1
        return None if row is None else AppendMark(str(row[0]), int(row[1]), last)

    # -- what readers keep (store.kept) -----------------------------------------------------
    def read_kept(self, neem_id: str, kind: str) -> bytes | None:
        with self.conn.reading():
            return kept.read(self.conn, neem_id, kind)

    def write_kept(self, neem_id: str, kind: str, data: bytes) -> bool:
        if self.read_only:
            return False
        with self.conn.transaction():
            kept.write(self.conn, neem_id, kind, data)
        return True
