"""Terms and values in SQLite columns: IRIs and strings interned as small integers (the
``terms`` table: rows and index entries hold an id, half the cost of indexing the text), and
the kind stored beside a value so it reads back with its BSON type."""

from __future__ import annotations

import json
from collections.abc import Collection
from datetime import datetime, timezone
from typing import Any

from bson.decimal128 import Decimal128
from bson.int64 import Int64

from oracle.store.model import unix_seconds
from oracle.store.sqlite.connection import Connection, inserted_id
from oracle.store.sqlite.tables import GROUPED_ROWS

# Kinds of the ``o`` column, so a value reads back with its BSON type.
K_STR, K_DOUBLE, K_DECIMAL, K_INT, K_LONG, K_BOOL, K_DATE, K_OTHER = range(8)

#: Terms whose ids a writer keeps in memory (about 100 bytes each) before it starts over.
TERM_CACHE = 50_000
#: Term ids looked up one at a time before ``Terms.value`` reads the whole terms table instead.
TERM_SCAN_AFTER = 2000


def sql_value(value: Any) -> tuple[Any, int]:
    """A BSON value as (SQLite value, kind)."""
    if isinstance(value, str):
        return value, K_STR
    if isinstance(value, bool):
        return int(value), K_BOOL
    if isinstance(value, Int64):
        return int(value), K_LONG
    if isinstance(value, int):
        return value, K_INT
    if isinstance(value, float):
        return value, K_DOUBLE
    if isinstance(value, Decimal128):
        return float(value.to_decimal()), K_DECIMAL
    if isinstance(value, datetime):
        return unix_seconds(value), K_DATE
    return None, K_OTHER


def python_value(value: Any, kind: int) -> Any:
    """A column value of a kind other than a term, as the plain Python value a match yields."""
    if kind == K_BOOL:
        return bool(value)
    if kind == K_DATE and value is not None:
        return datetime.fromtimestamp(value, timezone.utc)
    if kind in (K_DOUBLE, K_DECIMAL) and value is not None:
        return float(value)
    return value


class Terms:
    """The ids of IRIs and strings, interned on first use, and the terms of ids, both cached
    (``forget``: after a rollback, the ids it cached may name no row)."""

    def __init__(self, conn: Connection) -> None:
        self.conn = conn
        self.ids: dict[str, int] = {}
        self.values: dict[int, str] = {}
        #: Every term of the table is in ``values`` (read in one scan).
        self.all_read = False
        self.misses = 0
        #: Whether ``value`` may read every term in one scan (``forget`` says when no longer).
        self.scan = True

    def forget(self) -> None:
        if self.all_read and len(self.values) > TERM_CACHE:
            # the table outgrew the cache: a scan would be thrown away by the next new term
            # (20 robots' NEEMs logging at once scanned it every few requests), so look up
            self.scan = False
        self.ids.clear()
        self.values.clear()
        self.all_read = False

    def tid(self, value: str) -> int:
        """The id of an IRI or string, interned on first use."""
        tid = self.ids.get(value)
        if tid is None:
            cursor = self.conn.execute("INSERT OR IGNORE INTO terms(value) VALUES (?)", (value,))
            if cursor.rowcount == 1:
                tid = inserted_id(cursor)
            else:
                tid = self.conn.execute("SELECT id FROM terms WHERE value=?", (value,)).fetchone()[0]
            if len(self.ids) >= TERM_CACHE:
                # Every event is a new term: an import of a million rows would otherwise keep
                # millions of them in memory. The cache starts over (ids are in the table).
                self.forget()
            self.ids[value] = tid
            self.values[tid] = value
        return tid

    def tids(self, values: Collection[str]) -> dict[str, int]:
        """The ids of many terms at once (a logged action brings ~8 new event IRIs), as a dict
        of exactly these: the cached ones from memory, the stored ones read in chunks, the new
        ones numbered after the last and inserted in one statement, where ``tid`` would run
        two statements per term. The dict stays valid when the cache starts over meanwhile
        (``tid`` of a closure's member). New terms are numbered in the order given. Only
        inside a write transaction (BEGIN IMMEDIATE: no other writer numbers terms meanwhile)."""
        cached = self.ids
        ids = {value: cached[value] for value in values if value in cached}
        missing = [value for value in values if value not in ids]
        found: dict[str, int] = {}
        for i in range(0, len(missing), 500):
            chunk = missing[i : i + 500]
            marks = ", ".join("?" * len(chunk))
            found.update(self.conn.execute(f"SELECT value, id FROM terms WHERE value IN ({marks})", chunk).fetchall())
        new = [value for value in missing if value not in found]
        if new:
            first = int(self.conn.execute("SELECT coalesce(max(id), 0) + 1 FROM terms").fetchone()[0])
            numbered = list(enumerate(new, start=first))
            self.conn.insert_many("terms", "id, value", numbered, GROUPED_ROWS)
            found.update((value, key) for key, value in numbered)
        if found:
            if len(cached) + len(found) > TERM_CACHE:
                self.forget()  # as in tid: memory stays bounded over a long import
            cached.update(found)
            self.values.update((key, value) for value, key in found.items())
            ids.update(found)
        return ids

    def known_id(self, value: str) -> int:
        """The id of a term for a query; -1 (matching nothing) when the store never saw it."""
        tid = self.ids.get(value)
        if tid is None:
            row = self.conn.execute("SELECT id FROM terms WHERE value=?", (value,)).fetchone()
            if row is None:
                return -1
            tid = self.ids[value] = row[0]
            self.values[tid] = value
        return tid

    def value(self, tid: int) -> str:
        """The IRI or string of an id."""
        value = self.values.get(tid)
        if value is None:
            self.misses += 1
            if not self.all_read and self.misses > TERM_SCAN_AFTER and self.scan:
                # Reading a NEEM touches most of its terms: one scan beats many lookups. A
                # question touches a few hundred of a table of every NEEM's terms: it looks
                # them up one by one (the scan cost 0.2-0.3 s at 50,000 actions).
                for key, text in self.conn.execute("SELECT id, value FROM terms"):
                    self.values[key] = text
                    self.ids[text] = key
                self.all_read = True
                value = self.values.get(tid)
            if value is None:
                value = self.conn.execute("SELECT value FROM terms WHERE id=?", (tid,)).fetchone()[0]
                self.values[tid] = value
        return value

    def sql(self, value: Any) -> tuple[Any, int]:
        """A BSON value as (column value, kind) with strings interned."""
        if type(value) is str:
            return self.tid(value), K_STR
        return sql_value(value)

    def out(self, value: Any, kind: int) -> Any:
        """A (column value, kind) pair as the plain value a match yields."""
        return self.value(value) if kind == K_STR and value is not None else python_value(value, kind)

    def convert(self, kind: int, values: list[Any]) -> list[Any]:
        """Raw values of one kind as plain values; term ids looked up at once, in id order (a
        chunk brings up to ~20,000 new ones: one query instead of one each, or a scan of every
        NEEM's terms)."""
        if kind in (K_DOUBLE, K_DECIMAL):
            return [None if value is None else float(value) for value in values]
        if kind != K_STR:
            return [self.out(value, kind) for value in values]
        known = self.values
        missing = sorted(v for v in values if type(v) is int and v not in known)
        for start in range(0, len(missing), 5000):
            batch = json.dumps(missing[start:start + 5000])
            for key, text in self.conn.execute("SELECT id, value FROM terms WHERE id IN (SELECT value FROM json_each(?))",
                                               (batch,)):
                known[key] = text
        return [known[value] if value in known else self.out(value, kind) for value in values]
