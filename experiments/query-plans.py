"""The SQL plan of every triple query a user's commands make, for choosing the store's indexes.

Logs a simulated persona's chains (``generate``, then ``import``), runs ``rank``, ``why-not``,
``what-next`` and ``neems`` on it with every SQL statement recorded (sqlite3's trace hook),
and prints, per distinct query shape (numbers and strings replaced), the indexes its
``EXPLAIN QUERY PLAN`` uses, with a count per index and every full scan of a triple table.
Usage: python experiments/query-plans.py [--actions 1000] [--verbose]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sqlite3
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

#: Runs one CLI call with every statement of every sqlite3 connection appended to a file.
TRACED = """
import runpy, sqlite3, sys
out = open(sys.argv[1], "a", buffering=1)
connect = sqlite3.connect
def traced(*args, **kwargs):
    conn = connect(*args, **kwargs)
    conn.set_trace_callback(lambda sql: out.write(" ".join(sql.split()) + "\\n"))
    return conn
sqlite3.connect = traced
sys.argv = ["oracle", *sys.argv[2:]]
runpy.run_module("oracle", run_name="__main__")
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--actions", type=int, default=1000)
    parser.add_argument("--verbose", action="store_true", help="print every plan")
    args = parser.parse_args()
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        env = {**os.environ, "NEEM_ORACLE_CACHE": str(tmp / "cache")}
        subprocess.run([py, "-m", "oracle", "generate", "--personas", "1", "--days", str(args.actions // 35 + 30),
                        "--seed", "3", "--out", str(tmp / "gen")], check=True, capture_output=True, env=env)  # fmt: skip
        rows = [json.loads(line) for line in (tmp / "gen" / "test.jsonl").read_text().splitlines() if line][: args.actions]
        chains = tmp / "chains.jsonl"
        chains.write_text("".join(json.dumps({**row, "user": "u"}) + "\n" for row in rows))
        store, trace = tmp / "store.sqlite", tmp / "trace.txt"
        calls = [["import", str(chains)], ["neems"], ["why-not", rows[-1]["action"], "--neem", "u"],
                 ["what-next", "--neem", "u"], ["rank", "--neem", "u"]]  # fmt: skip
        for call in calls:
            subprocess.run([py, "-c", TRACED, str(trace), *call, "--store", str(store)], check=True,
                           stdout=subprocess.DEVNULL, env=env)  # fmt: skip
        conn = sqlite3.connect(store)
        # The import built the NEEM under a staging id; the store names its tables by the id it gave.
        (table,) = conn.execute("SELECT name FROM sqlite_master WHERE type='table' AND name LIKE '%\\_triples' ESCAPE '\\'").fetchone()
        shapes: dict[str, str] = {}
        for sql in trace.read_text().splitlines():
            sql = re.sub(r'"staging-[0-9a-f]+_', '"' + table.removesuffix("triples"), sql)
            if sql.startswith("SELECT") and ('_triples"' in sql or '_side"' in sql):
                shapes.setdefault(re.sub(r"'[^']*'", "S", re.sub(r"\b\d+(\.\d+)?\b", "N", sql)), sql)
        uses: Counter[str] = Counter()
        scans: list[tuple[str, str]] = []
        for sql in shapes.values():
            plan = [row[3] for row in conn.execute("EXPLAIN QUERY PLAN " + sql)]
            for step in plan:
                found = re.search(r"INDEX \S*?_((?:triples|side)_\w+)", step)
                if found:
                    uses[found.group(1)] += 1
                if re.match(r"SCAN (t\d+|\S+_(triples|side))\b", step):
                    scans.append((step, sql))
            if args.verbose:
                print(sql[:400], *(f"    {step}" for step in plan), sep="\n")
        print(f"{len(shapes)} distinct triple query shapes over {args.actions:,} actions; index uses:",
              ", ".join(f"{name} {n}" for name, n in uses.most_common()))  # fmt: skip
        for step, sql in scans:
            print(f"  {step}: {sql[:300]}")


if __name__ == "__main__":
    main()
