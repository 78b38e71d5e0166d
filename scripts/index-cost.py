"""What the (p*, o) index's condition costs an insert: a NEEM's rows put into fresh tables with
the store's indexes, the (p*, o) index written each way in turn, runs interleaved.

Usage: python scripts/index-cost.py STORE.sqlite NEEM [--runs 3]
Prints the CPU seconds (min/median/max) plain sqlite3 takes per variant, committing in ten
transactions, with the NEEM's side table (when it has one) filled alongside.
"""

from __future__ import annotations

import argparse
import sqlite3
import statistics
import tempfile
import time
from pathlib import Path

COLUMNS = "id, oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw"
CONDITIONS = {
    "NOT IN (1, 2, 3)": "p NOT IN (1, 2, 3)",
    "<> 1, 2, 3": "p <> 1 AND p <> 2 AND p <> 3",
    "p > 3": "p > 3",
    "no condition": None,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store")
    parser.add_argument("neem")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    source = sqlite3.connect(args.store)
    tables = [name for (name,) in source.execute(
        "SELECT name FROM sqlite_master WHERE type='table' AND name IN (?, ?)", (f"{args.neem}_triples", f"{args.neem}_side"))]  # fmt: skip
    schemas = [source.execute("SELECT sql FROM sqlite_master WHERE name=?", (t,)).fetchone()[0] for t in tables]
    indexes = [sql for t in tables for (sql,) in source.execute(
        "SELECT sql FROM sqlite_master WHERE type='index' AND tbl_name=? AND sql IS NOT NULL", (t,))]  # fmt: skip
    rows = {t: source.execute(f'SELECT {COLUMNS} FROM "{t}" ORDER BY id').fetchall() for t in tables}
    source.close()
    others = [sql for sql in indexes if "_pstaro" not in sql]
    pstaro = next(sql for sql in indexes if "_pstaro" in sql).split(" WHERE")[0]
    variants = {name: others + [pstaro + ("" if cond is None else f" WHERE {cond}")] for name, cond in CONDITIONS.items()}
    variants["without the (p*, o) index"] = others
    seconds: dict[str, list[float]] = {name: [] for name in variants}
    for _ in range(args.runs):
        for name, index_sql in variants.items():
            seconds[name].append(_insert(schemas, index_sql, rows))
    for name, values in seconds.items():
        print(f"{name:>28}: {min(values):.2f}/{statistics.median(values):.2f}/{max(values):.2f} s CPU")


def _insert(schemas: list[str], index_sql: list[str], rows: dict[str, list[tuple]]) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        conn = sqlite3.connect(Path(tmp) / "cost.sqlite", isolation_level=None)
        conn.execute("PRAGMA journal_mode=WAL")
        conn.execute("PRAGMA synchronous=NORMAL")
        conn.execute("PRAGMA cache_size=-65536")
        for sql in schemas + index_sql:
            conn.execute(sql)
        inserts = {t: f'INSERT INTO "{t}"({COLUMNS}) VALUES ({", ".join("?" * 13)})' for t in rows}
        batches = [[(inserts[t], r[i * len(r) // 10:(i + 1) * len(r) // 10]) for t, r in rows.items()] for i in range(10)]
        start = time.process_time()
        for batch in batches:
            conn.execute("BEGIN")
            for insert, chunk in batch:
                conn.executemany(insert, chunk)
            conn.execute("COMMIT")
        elapsed = time.process_time() - start
        conn.close()
    return elapsed


if __name__ == "__main__":
    main()
