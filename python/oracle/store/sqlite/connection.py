"""The store's one SQLite connection as its parts use it: sqlite3 errors (a NEEM dropped by
another process, a locked or full disk, a corrupt page) as StoreError, the whole-file check a
writer's first write waits for, write transactions and read snapshots, rows inserted in groups."""

from __future__ import annotations

import itertools
import sqlite3
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import Any

from oracle.errors import StoreError
from oracle.store.integrity import IntegrityCheck


def reason(error: sqlite3.Error) -> str:
    text = str(error)
    if isinstance(error, sqlite3.DatabaseError) and "malformed" in text:
        return f"{text}: the store file is corrupt (restore it from a backup or an export)"
    return text


class Cursor:
    """A cursor whose rows, fetched lazily, also turn sqlite3 errors (a corrupt page met while
    reading) into StoreError."""

    def __init__(self, cursor: sqlite3.Cursor, location: str) -> None:
        self.cursor = cursor
        self.location = location

    def fetchone(self) -> Any:
        try:
            return self.cursor.fetchone()
        except sqlite3.Error as error:
            raise StoreError(f"{self.location}: {reason(error)}") from None

    def fetchall(self) -> list[Any]:
        try:
            return self.cursor.fetchall()
        except sqlite3.Error as error:
            raise StoreError(f"{self.location}: {reason(error)}") from None

    def __iter__(self) -> Iterator[Any]:
        # Not ``yield from``: a generator abandoned mid-way (an export that failed on a full
        # disk) would then close the cursor when collected, after the store closed, and print
        # a traceback ("Cannot operate on a closed database") instead of staying quiet.
        try:
            for row in self.cursor:  # noqa: UP028 - see above
                yield row
        except sqlite3.Error as error:
            raise StoreError(f"{self.location}: {reason(error)}") from None

    @property
    def lastrowid(self) -> int | None:
        return self.cursor.lastrowid

    @property
    def rowcount(self) -> int:
        return self.cursor.rowcount


def inserted_id(cursor: Cursor | sqlite3.Cursor) -> int:
    """The id of the row an INSERT just made (sqlite3 types it Optional for other statements)."""
    if cursor.lastrowid is None:
        raise StoreError("SQLite reported no id for an inserted row")
    return cursor.lastrowid


#: Statements that never change the file (a deferred BEGIN starts a read snapshot; the
#: automatic_index pragma is a setting of the connection).
_READS = ("SELECT", "EXPLAIN", "COMMIT", "ROLLBACK", "END", "PRAGMA AUTOMATIC_INDEX")


def may_write(sql: str) -> bool:
    """Whether a statement may change the file (the pragmas a writer sets are before any check)."""
    head = " ".join(sql[:40].split()).upper()
    return not (head.startswith(_READS) or head == "BEGIN" or head.startswith("BEGIN DEFERRED"))


class Connection:
    """sqlite3 errors as StoreError. With ``check`` (oracle.store.integrity), the first
    statement that may write waits for the whole-file check and is refused, as every later
    one, when the file is damaged. ``forget`` is called when a write transaction rolls back:
    the parts drop what they cached of rows that are gone (interned terms, closures)."""

    def __init__(self, conn: sqlite3.Connection, location: str, check: IntegrityCheck | None = None) -> None:
        self.conn = conn
        self.location = location
        self.check = check
        self.depth = 0
        self.forget: list[Callable[[], None]] = []

    def _before_write(self) -> None:
        if self.check is not None:
            self.check.wait()   # StoreError when damaged: the check stays, so every write is refused
            self.check = None

    def execute(self, sql: str, params: Sequence[Any] | Mapping[str, Any] = ()) -> Cursor:
        if self.check is not None and may_write(sql):
            self._before_write()
        try:
            return Cursor(self.conn.execute(sql, params), self.location)
        except sqlite3.Error as error:
            raise StoreError(f"{self.location}: {reason(error)}") from None

    def executemany(self, sql: str, rows: Any) -> sqlite3.Cursor:
        self._before_write()
        try:
            return self.conn.executemany(sql, rows)
        except sqlite3.Error as error:
            raise StoreError(f"{self.location}: {error}") from None

    def insert_many(self, table: str, columns: str, rows: list[tuple[Any, ...]], per_statement: int) -> None:
        """``rows`` into ``table`` in this order, ``per_statement`` rows to one INSERT."""
        width = columns.count(",") + 1
        one = f"({', '.join('?' * width)})"
        whole = len(rows) - len(rows) % per_statement if per_statement > 1 else 0
        if whole:
            chain = itertools.chain.from_iterable
            grouped = f"INSERT INTO {table}({columns}) VALUES {', '.join([one] * per_statement)}"
            self.executemany(grouped, (list(chain(rows[i : i + per_statement])) for i in range(0, whole, per_statement)))
        if whole < len(rows):
            self.executemany(f"INSERT INTO {table}({columns}) VALUES {one}", rows[whole:])

    @contextmanager
    def transaction(self) -> Iterator[None]:
        """One write transaction (BEGIN IMMEDIATE: one writer at a time). Nested, a savepoint of
        the outer one: it commits with the outer one, and a failure inside undoes its writes
        alone (the service's group commit runs each request's writes so, oracle.service.groupcommit)."""
        nested = self.depth > 0
        point = f"nest{self.depth}"
        self.execute(f"SAVEPOINT {point}" if nested else "BEGIN IMMEDIATE")
        self.depth += 1
        try:
            yield
        except BaseException:
            self.depth -= 1
            if self.conn.in_transaction:
                self.execute(f"ROLLBACK TO {point}" if nested else "ROLLBACK")
                if nested:
                    self.execute(f"RELEASE {point}")
                for forget in self.forget:
                    forget()
            raise
        self.depth -= 1
        if nested:
            self.execute(f"RELEASE {point}")
            return
        try:
            self.execute("COMMIT")
        except StoreError:
            if self.conn.in_transaction:  # not committed (an I/O error): the next BEGIN must not fail too
                self.conn.rollback()
                for forget in self.forget:
                    forget()
            raise

    @contextmanager
    def reading(self) -> Iterator[None]:
        """One read transaction (one snapshot of the file) that takes no write lock; inside a
        transaction already, that one."""
        if self.depth > 0 or self.conn.in_transaction:
            yield
            return
        self.execute("BEGIN")
        try:
            yield
        finally:
            if self.conn.in_transaction:
                self.execute("COMMIT")

    def close(self) -> None:
        if self.check is not None:
            self.check.cancel()
        self.conn.close()
