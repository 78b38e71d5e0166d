"""Opening the store file: read-only (nothing written on open), or as a writer (a private
file, WAL, synchronous=FULL, the store's own tables made or upgraded in one transaction), and
never writing into a damaged file (store.integrity)."""

from __future__ import annotations

import os
import sqlite3
import stat
import time
import urllib.parse
from pathlib import Path
from typing import Any

from oracle.errors import StoreError
from oracle.files import private_folder
from oracle.store.integrity import IntegrityCheck, damaged, problems_of
from oracle.store.sqlite.tables import RESERVED_TERMS

SCHEMA_VERSION = "4"
#: Schemas this version reads: 3 is 4 without side tables (opened for writing, it becomes 4,
#: so an older version, which would not see side tables, refuses it from then on).
READS_SCHEMAS = ("3", SCHEMA_VERSION)
#: The store's own tables, made (or upgraded from schema 3) in one transaction when a writer opens
#: the file: a process killed meanwhile leaves no half-made store that readers would refuse.
SCHEMA_STATEMENTS = (
    "CREATE TABLE IF NOT EXISTS store_info(key TEXT PRIMARY KEY, value TEXT)",
    "CREATE TABLE IF NOT EXISTS neems(id TEXT PRIMARY KEY, meta BLOB NOT NULL)",
    "CREATE TABLE IF NOT EXISTS closure(cid INTEGER PRIMARY KEY, key BLOB UNIQUE NOT NULL)",
    "CREATE TABLE IF NOT EXISTS closure_member(cid INTEGER NOT NULL, pos INTEGER NOT NULL, value, PRIMARY KEY(cid, pos)) WITHOUT ROWID",
    "CREATE INDEX IF NOT EXISTS closure_member_value ON closure_member(value, cid)",
    "CREATE TABLE IF NOT EXISTS terms(id INTEGER PRIMARY KEY, value TEXT NOT NULL UNIQUE)",
    "CREATE TABLE IF NOT EXISTS side_tables(neem TEXT PRIMARY KEY, p INTEGER NOT NULL, closures TEXT NOT NULL)",
    # A NEEM's update and delete count (Store.append_mark), kept by triggers on its tables.
    "CREATE TABLE IF NOT EXISTS revisions(neem TEXT PRIMARY KEY, token TEXT NOT NULL UNIQUE, changes INTEGER NOT NULL)",
    "INSERT OR IGNORE INTO store_info VALUES ('schema', '4')",
    "UPDATE store_info SET value='4' WHERE key='schema' AND value='3'",
)

#: How long a writer opening the store keeps asking for WAL mode while others open it too.
WAL_SWITCH_WAIT_S = 10.0


def open_read_only(path: Path) -> tuple[sqlite3.Connection, bool]:
    """A connection that writes nothing on open (no pragma that changes the file, no schema),
    so ``neems`` or ``why-not`` never wait for, nor block, an ``import`` or ``load``; and
    whether the file has side tables (False for schema 3)."""
    try:
        uri = "file:" + urllib.parse.quote(str(path.resolve())) + "?mode=ro"
        try:
            conn, row = _open_read_only(uri)
        except sqlite3.OperationalError:
            if os.access(path.parent, os.W_OK):
                raise
            # A store on read-only media (a mounted backup): SQLite cannot make the WAL's
            # shared-memory file there, and nobody can change the file, so it is read as is.
            conn, row = _open_read_only(uri + "&immutable=1")
    except sqlite3.DatabaseError as error:
        reason = "not a NEEM store" if "no such table" in str(error) or "not a database" in str(error) else str(error)
        raise StoreError(f"{path}: cannot open the NEEM store ({reason})") from None
    version = None if row is None else row[0]
    if row is None:  # tables without the schema row: an older version was stopped making the file
        raise StoreError(f"{path}: the store was never completed (its maker was stopped); a writing command"
                         " such as import completes it")  # fmt: skip
    if version not in READS_SCHEMAS:
        raise StoreError(f"{path}: store schema {version}, this version reads {SCHEMA_VERSION}")
    return conn, version == SCHEMA_VERSION


def _open_read_only(uri: str) -> tuple[sqlite3.Connection, Any]:
    conn = sqlite3.connect(uri, uri=True, isolation_level=None, check_same_thread=False)
    try:
        conn.execute("PRAGMA busy_timeout=10000")
        conn.execute("PRAGMA query_only=1")
        conn.execute("PRAGMA cache_size=-65536")
        return conn, conn.execute("SELECT value FROM store_info WHERE key='schema'").fetchone()
    except BaseException:
        conn.close()
        raise


def open_writer(path: Path, check_while_reading: bool) -> tuple[sqlite3.Connection, IntegrityCheck | None]:
    """A writer's connection, and the whole-file check its first write waits for (None: done
    at open, or nothing to check)."""
    checked = True  # nothing to check until a connection is open
    try:
        private_folder(path.parent)  # each missing folder 0700 whatever the umask (~/.local/share too)
        existed = path.exists()
        if existed and not stat.S_ISREG(path.stat().st_mode):
            raise StoreError(f"{path}: not a regular file (a NEEM store is one SQLite file)")
        # Create the file 0600 before SQLite does; its -wal and -shm files copy the mode.
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o600)
        try:
            if existed and stat.S_IMODE(os.fstat(fd).st_mode) & 0o077:
                os.fchmod(fd, 0o600)  # a store copied in as 0644 is private from now on
        finally:
            os.close(fd)
        conn = sqlite3.connect(path, isolation_level=None, check_same_thread=False)
        # The whole-file check runs before anything is written. With check_while_reading,
        # when opening writes nothing (a complete store of this schema, in WAL mode), it runs
        # beside the reads that follow and the first write waits for it (store/integrity.py).
        checked = not (existed and path.stat().st_size > 0)
        if not checked and not check_while_reading:
            _check_integrity(conn, path)
            checked = True
        conn.execute("PRAGMA busy_timeout=10000")  # concurrent writers wait instead of failing
        if not checked and str(conn.execute("PRAGMA journal_mode").fetchone()[0]).lower() != "wal":
            _check_integrity(conn, path)   # switching to WAL writes the header
            checked = True
        _use_wal(conn)
        # FULL: a commit returns once its WAL frames are on disk, so a committed action
        # survives a power loss too (NORMAL survives a killed process only; docs/security.md)
        conn.execute("PRAGMA synchronous=FULL")
        # temp_store stays FILE: with MEMORY, dropping a NEEM (import --replace) kept its
        # statement journal in memory, +270 MiB at 50,000 actions; sorts are as fast.
        # A dropped or wiped NEEM's pages are overwritten, not just freed: its documents
        # cannot be read back from the file (most builds default to it; this one need not).
        conn.execute("PRAGMA secure_delete=ON")
        # Fewer, larger checkpoints: each one fsyncs, commits themselves do not.
        conn.execute("PRAGMA wal_autocheckpoint=8192")
        conn.execute("PRAGMA cache_size=-65536")
        version, check = _make_schema(conn, path, checked)
    except sqlite3.DatabaseError as error:
        if not checked:
            _check_integrity(conn, path)   # a damaged file: say so, not what failed first
        raise StoreError(f"{path}: cannot open the NEEM store ({error})") from None
    except (OSError, sqlite3.Error) as error:
        raise StoreError(f"{path}: cannot open the NEEM store ({error})") from None
    if version != SCHEMA_VERSION:
        raise StoreError(f"{path}: store schema {version}, this version reads {SCHEMA_VERSION}")
    return conn, check


def _use_wal(conn: sqlite3.Connection) -> None:
    """Put the file in WAL mode. SQLite refuses the switch at once ("database is locked", no busy
    wait) while another process opening the same new file switches it: ask again, briefly."""
    deadline = time.monotonic() + WAL_SWITCH_WAIT_S
    while True:
        try:
            conn.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as error:
            if "locked" not in str(error) and "busy" not in str(error) or time.monotonic() > deadline:
                raise
            time.sleep(0.005 + 0.02 * int.from_bytes(os.urandom(1), "big") / 255)


def _make_schema(conn: sqlite3.Connection, path: Path, checked: bool) -> tuple[str, IntegrityCheck | None]:
    """Make or upgrade the store's own tables (``SCHEMA_STATEMENTS``) in one transaction:
    each statement would otherwise commit on its own, and a kill in between left tables
    without the schema row (every reader then refused the file). On a file not checked yet,
    a transaction that would change something is rolled back and made again after the
    check; one that changes nothing leaves the check to run beside the reads. Returns the
    schema version and that check (None when the file was checked)."""
    while True:
        conn.execute("BEGIN IMMEDIATE")
        try:
            before = (conn.total_changes, conn.execute("PRAGMA schema_version").fetchone()[0])
            for statement in SCHEMA_STATEMENTS:
                conn.execute(statement)
            conn.executemany("INSERT OR IGNORE INTO terms VALUES (?, ?)", RESERVED_TERMS)
            version = str(conn.execute("SELECT value FROM store_info WHERE key='schema'").fetchone()[0])
            after = (conn.total_changes, conn.execute("PRAGMA schema_version").fetchone()[0])
            changes = after != before
            conn.execute("ROLLBACK" if changes and not checked else "COMMIT")
        except BaseException:
            if conn.in_transaction:
                conn.execute("ROLLBACK")
            raise
        if changes and not checked:
            _check_integrity(conn, path)   # closes conn and raises when damaged
            checked = True
            continue
        return version, None if checked else IntegrityCheck(path)


def _check_integrity(conn: sqlite3.Connection, path: Path) -> None:
    """Refuse to write into a damaged file: writing would spread the damage, and a later
    reader would answer from it. ``quick_check`` reads every page once (no index cross-check)."""
    problems = problems_of(conn)
    if problems:
        conn.close()
        raise damaged(path, problems)
