"""What a NEEM's rows cost SQLite to insert, written the ways the logger could write them.

Usage: python experiments/row-cost.py STORE.sqlite NEEM_ID [--runs 3]
The NEEM's triple and side rows go into fresh tables with the store's indexes, in their order,
committed in ten transactions, runs interleaved; printed: CPU seconds (min/median/max) of all
the inserts and commits, and of the INSERTs into each table alone, for
  - one row per INSERT in both tables (what plain ``executemany`` does, the bench's floor),
  - 80 rows per INSERT in the side table (what the store does),
  - 80 rows per INSERT in both tables,
  - the ``rdf:type owl:NamedIndividual`` rows moved from the triples table to the side table
    (a layout the query compiler would have to know; here only its insert cost),
  - the side rows packed, one row per subject (an imagining) whose object holds all its plans'
    term ids as one blob, 80 rows per INSERT (the layout docs/store.md weighs for the import
    target; the query compiler and the dump would have to unpack it; here only its insert cost).
"""

from __future__ import annotations

import argparse
import itertools
import sqlite3
import statistics
import struct
import tempfile
import time
from pathlib import Path

COLUMNS = "id, oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw"
NAMED_INDIVIDUAL = "http://www.w3.org/2002/07/owl#NamedIndividual"
GROUP = 80


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store")
    parser.add_argument("neem")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    source = sqlite3.connect(args.store)
    main_table, side_table = f"{args.neem}_triples", f"{args.neem}_side"
    tables = [main_table, side_table]
    schemas = [source.execute("SELECT sql FROM sqlite_master WHERE name=?", (t,)).fetchone()[0] for t in tables]
    indexes = [sql for t in tables for (sql,) in source.execute(
        "SELECT sql FROM sqlite_master WHERE type='index' AND tbl_name=? AND sql IS NOT NULL", (t,))]  # fmt: skip
    rows = {t: source.execute(f'SELECT {COLUMNS} FROM "{t}" ORDER BY id').fetchall() for t in tables}
    named = source.execute("SELECT id FROM terms WHERE value=?", (NAMED_INDIVIDUAL,)).fetchone()[0]
    source.close()
    moved = {main_table: [r for r in rows[main_table] if not (r[3] == 1 and r[4] == named)]}
    moved[side_table] = sorted(rows[side_table] + [r for r in rows[main_table] if r[3] == 1 and r[4] == named])
    print(f"{len(rows[main_table]):,} triple rows, {len(rows[side_table]):,} side rows;"
          f" {len(rows[main_table]) - len(moved[main_table]):,} of them rdf:type owl:NamedIndividual")  # fmt: skip
    packed = {main_table: rows[main_table], side_table: _packed(rows[side_table])}
    variants = {
        "one row per INSERT": (rows, ()),
        "side rows 80 per INSERT": (rows, (side_table,)),
        "both tables 80 per INSERT": (rows, (main_table, side_table)),
        "NamedIndividual rows in the side table": (moved, (side_table,)),
        "side rows packed, one per imagining": (packed, (side_table,)),
    }
    seconds: dict[str, list[dict[str, float]]] = {name: [] for name in variants}
    for _ in range(args.runs):
        for name, (data, grouped) in variants.items():
            seconds[name].append(_insert(schemas, indexes, data, grouped))
    for name, runs in seconds.items():
        shown = [f"{part} {_spread([run[part] for run in runs])}" for part in ("all", main_table, side_table)]
        print(f"{name:>40}: " + "; ".join(shown).replace(main_table, "triples").replace(side_table, "side") + " s CPU")


def _packed(side: list[tuple]) -> list[tuple]:
    """One row per subject, the first row's columns with the object the blob of every object
    id of that subject's rows (in their order)."""
    objects: dict[object, list[int]] = {}
    first: dict[object, tuple] = {}
    for row in side:
        objects.setdefault(row[2], []).append(row[4])
        first.setdefault(row[2], row)
    return [(*row[:4], struct.pack(f"<{len(objects[s])}q", *objects[s]), *row[5:]) for s, row in first.items()]


def _spread(values: list[float]) -> str:
    return f"{min(values):.2f}/{statistics.median(values):.2f}/{max(values):.2f}"


def _insert(schemas: list[str], index_sql: list[str], rows: dict[str, list[tuple]], grouped: tuple[str, ...]) -> dict[str, float]:
    one = f"({', '.join('?' * 13)})"
    with tempfile.TemporaryDirectory() as tmp:
        conn = sqlite3.connect(Path(tmp) / "cost.sqlite", isolation_level=None)
        conn.execute("PRAGMA journal_mode=WAL")
        conn.execute("PRAGMA synchronous=NORMAL")
        conn.execute("PRAGMA cache_size=-65536")
        for sql in schemas + index_sql:
            conn.execute(sql)
        batches = [[(t, r[i * len(r) // 10:(i + 1) * len(r) // 10]) for t, r in rows.items()] for i in range(10)]
        spent = dict.fromkeys(rows, 0.0)
        start = time.process_time()
        for batch in batches:
            conn.execute("BEGIN")
            for table, chunk in batch:
                began = time.process_time()
                whole = len(chunk) - len(chunk) % GROUP if table in grouped else 0
                if whole:
                    sql = f'INSERT INTO "{table}"({COLUMNS}) VALUES {", ".join([one] * GROUP)}'
                    conn.executemany(sql, (list(itertools.chain.from_iterable(chunk[i:i + GROUP])) for i in range(0, whole, GROUP)))
                conn.executemany(f'INSERT INTO "{table}"({COLUMNS}) VALUES {one}', chunk[whole:])
                spent[table] += time.process_time() - began
            conn.execute("COMMIT")
        spent["all"] = time.process_time() - start
        conn.close()
    return spent


if __name__ == "__main__":
    main()
