"""SQLite's whole-file check before a writer's first write, run beside the writer's reads.

``PRAGMA quick_check`` reads every page of the file: ~0.6 s for a 340 MB store, paid by every
call that writes, however little it writes (a ranking written back). A writer that asks for it
(``check_while_reading``) and opens an existing, complete store starts the check on a connection of its own, in a thread (SQLite runs
without the GIL), and goes on reading; its first write waits for the check and is refused when
the file is damaged, so nothing is ever written into a damaged file. docs/store.md, "Durability".
"""

from __future__ import annotations

import sqlite3
import threading
import urllib.parse
from pathlib import Path

from oracle.errors import CorruptStoreError


def problems_of(conn: sqlite3.Connection) -> list[str]:
    """What ``PRAGMA quick_check`` finds (at most 3 problems), or ``[]`` for a sound file."""
    try:
        found = [str(row[0]) for row in conn.execute("PRAGMA quick_check(3)").fetchall()]
    except sqlite3.DatabaseError as error:
        found = [str(error)]
    return [] if found == ["ok"] else found


def damaged(path: Path, problems: list[str]) -> CorruptStoreError:
    """The one-line error of a damaged store file (SQLite's report spans lines: one here)."""
    found = " ".join("; ".join(problems).split())[:200]
    return CorruptStoreError(f"{path}: the store file is corrupt ({found}); nothing was written"
                      " (restore it from a backup or an export)")


class IntegrityCheck:
    """``problems_of`` the file at ``path``, run in a thread on a read-only connection of its own."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._problems: list[str] = []
        self._conn: sqlite3.Connection | None = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="neem-store-check", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            uri = "file:" + urllib.parse.quote(str(self.path.resolve())) + "?mode=ro"
            self._conn = sqlite3.connect(uri, uri=True, check_same_thread=False)
            try:
                self._conn.execute("PRAGMA busy_timeout=10000")
                if not self._stop.is_set():
                    self._problems = problems_of(self._conn)
            finally:
                self._conn.close()
        except Exception as error:  # noqa: BLE001 - anything that stops the check refuses the writes
            self._problems = [str(error) or type(error).__name__]

    def wait(self) -> None:
        """Block until the check is done; StoreError when the file is damaged."""
        self._thread.join()
        if self._problems:
            raise damaged(self.path, self._problems)

    def cancel(self) -> None:
        """Stop a check still running (the store is closing without having written)."""
        self._stop.set()
        conn = self._conn
        if self._thread.is_alive() and conn is not None:
            try:
                conn.interrupt()
            except sqlite3.ProgrammingError:
                pass  # closed meanwhile: the check has finished
        self._thread.join()
