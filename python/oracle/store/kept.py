"""What a reader keeps of a NEEM beside its triples in the SQLite file (the oracle's history
read and its fit: oracle.historycache, oracle.fitcache): one blob per NEEM and kind, which its
reader checks against the NEEM before using it. Dropped and renamed with the NEEM; never in a
dump (it is made again from the triples)."""

from __future__ import annotations

from typing import Any

from oracle.errors import StoreError

TABLE = "kept"
_CREATE = (f"CREATE TABLE IF NOT EXISTS {TABLE}(neem TEXT NOT NULL, kind TEXT NOT NULL, data BLOB NOT NULL,"
           " PRIMARY KEY(neem, kind)) WITHOUT ROWID")


def read(conn: Any, neem: str, kind: str) -> bytes | None:
    """The blob kept for ``neem`` under ``kind``, or None (none kept, or a file from before)."""
    try:
        row = conn.execute(f"SELECT data FROM {TABLE} WHERE neem=? AND kind=?", (neem, kind)).fetchone()
    except StoreError:
        return None  # no such table: nothing was ever kept in this file
    return None if row is None else bytes(row[0])


def write(conn: Any, neem: str, kind: str, data: bytes) -> None:
    """Keep ``data`` for ``neem`` under ``kind`` (replacing what was kept); in the caller's transaction."""
    conn.execute(_CREATE)
    conn.execute(f"INSERT OR REPLACE INTO {TABLE} VALUES (?, ?, ?)", (neem, kind, data))


def drop(conn: Any, neem: str) -> None:
    """Forget everything kept for ``neem`` (in the caller's transaction)."""
    conn.execute(_CREATE)
    conn.execute(f"DELETE FROM {TABLE} WHERE neem=?", (neem,))


def rename(conn: Any, neem: str, new: str) -> None:
    """What was kept for ``neem`` is ``new``'s (in the caller's transaction)."""
    conn.execute(_CREATE)
    conn.execute(f"UPDATE {TABLE} SET neem=? WHERE neem=?", (new, neem))
