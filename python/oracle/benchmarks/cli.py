"""CLI figures a user meets: the fixed cost of a call, ``neems`` / ``why-not`` /
``what-next`` from start to exit, and logging throughput through ``import`` with peak memory,
at 1,000-50,000 actions, each beside a floor measured in the same run. Each ``import`` run logs a
new NEEM into a store that holds the smaller ones (the NEEM of the run before dropped first,
untimed).

Floors: the interpreter starting and exiting (``python -c pass``) for a call; for logging,
plain ``sqlite3`` inserting the very rows ``import`` wrote (same schema and indexes, one
transaction per 1,000 actions as ``--commit-every 1000``), and the same without the secondary
indexes. Every figure is min/median/max of ``REPEAT`` runs, the max being the worst a user
met (with 5 runs, what a p99 can honestly be read as). Wall time on a shared machine is mostly
waiting for a core, so the CPU seconds (user + system of the child) are printed beside it.
"""

from __future__ import annotations

from typing import Any

import json
import os
import sqlite3
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from oracle.benchmarks.figures import growth_exponent, installed_env, run_child as _run, run_measured as _run_measured, spread, spread_text

#: NEEM sizes (executed actions); quick runs use the first and a small second one.
SIZES = (1000, 10000, 50000)
QUICK_SIZES = (1000, 4000)
#: Runs per single-call figure.
REPEAT = 5
#: Runs per ``import`` figure (an import of 50,000 actions takes minutes on a shared machine).
IMPORT_REPEAT = 3
COMMIT_EVERY = 1000


def _drop(path: Path, name: str) -> None:
    """Drop the NEEM ``name`` from the store at ``path`` if it is there."""
    from oracle.errors import StoreError
    from oracle.store import open_store
    from oracle.store.ids import resolve_neem

    if not path.exists():
        return
    store = open_store(path)
    try:
        store.drop_neem(resolve_neem(store, name))
    except StoreError:
        pass  # not there yet
    finally:
        store.close()


def _calls(argvs: dict[str, list[str]], env: dict[str, str], repeat: int) -> dict[str, dict[str, dict[str, float]]]:
    """Each command ``repeat`` times, interleaved with the floor so both meet the same load."""
    walls: dict[str, list[float]] = {name: [] for name in ["floor", *argvs]}
    cpus: dict[str, list[float]] = {name: [] for name in walls}
    for _ in range(repeat):
        for name, argv in [("floor", [sys.executable, "-c", "pass"]), *argvs.items()]:
            wall, cpu, _ = _run(argv, env)
            walls[name].append(wall)
            cpus[name].append(cpu)
    return {name: {"wall_s": spread(walls[name]), "cpu_s": spread(cpus[name])} for name in walls}


def _chains(tmp: Path, n: int, env: dict[str, str]) -> list[str]:
    """``n`` chain rows of one simulated persona (~20 available tasks per decision)."""
    gen = tmp / "gen"
    days = n // 35 + 30
    subprocess.run([sys.executable, "-m", "oracle", "generate", "--personas", "1", "--days", str(days), "--seed", "3",
                    "--out", str(gen)], check=True, capture_output=True, env=env)  # fmt: skip
    rows = [line for name in ("tune.jsonl", "test.jsonl") for line in (gen / name).read_text().splitlines() if line]
    if len(rows) < n:
        raise RuntimeError(f"the simulation gave {len(rows)} actions, fewer than {n}")
    return rows


def _chain_file(tmp: Path, rows: list[str], n: int) -> Path:
    path = tmp / f"u{n}.jsonl"
    with path.open("w") as out:
        for line in rows[:n]:
            row = json.loads(line)
            row["user"] = f"u{n}"
            out.write(json.dumps(row) + "\n")
    return path


def _sqlite_floor(store: Path, neem: str, actions: int, indexes: bool) -> tuple[float, float]:
    """Wall and CPU seconds plain sqlite3 takes to insert the rows ``import`` wrote into the NEEM's triple
    tables (the triples table and, when the NEEM has one, its side table), into a fresh file with
    the same tables (and, with ``indexes``, the same indexes), in the order they were written,
    committing every COMMIT_EVERY actions' worth of rows."""
    from oracle.store import open_store
    from oracle.store.ids import resolve_neem

    with open_store(store, read_only=True) as opened:
        neem = resolve_neem(opened, neem)  # the NEEM's tables are named by its id, not its name
    source = sqlite3.connect(store)
    columns = "id, oid, s, p, o, ok, pstar, ostar, graph, since, until, sk, raw"
    names = [name for (name,) in source.execute(
        "SELECT name FROM sqlite_master WHERE type='table' AND name IN (?, ?)", (f"{neem}_triples", f"{neem}_side"))]
    schemas, index_sql, tagged = [], [], []
    for name in names:
        schemas.append(source.execute("SELECT sql FROM sqlite_master WHERE name=?", (name,)).fetchone()[0])
        index_sql += [sql for (sql,) in source.execute(
            "SELECT sql FROM sqlite_master WHERE type='index' AND tbl_name=? AND sql IS NOT NULL", (name,))]
        tagged += [(row[0], name, row) for row in source.execute(f'SELECT {columns} FROM "{name}"')]
    source.close()
    tagged.sort(key=lambda item: item[0])
    with tempfile.TemporaryDirectory() as tmp:
        conn = sqlite3.connect(Path(tmp) / "floor.sqlite", isolation_level=None)
        conn.execute("PRAGMA journal_mode=WAL")
        conn.execute("PRAGMA synchronous=NORMAL")
        for sql in schemas:
            conn.execute(sql)
        for sql in index_sql if indexes else ():
            conn.execute(sql)
        per_commit = max(1, len(tagged) * COMMIT_EVERY // max(actions, 1))
        inserts = {name: f'INSERT INTO "{name}"({columns}) VALUES ({", ".join("?" * 13)})' for name in names}
        commits = [[(inserts[name], [row for _, table, row in tagged[i:i + per_commit] if table == name]) for name in names]
                   for i in range(0, len(tagged), per_commit)]  # fmt: skip
        start, cpu = time.perf_counter(), time.process_time()
        for batches in commits:
            conn.execute("BEGIN")
            for insert, rows in batches:
                conn.executemany(insert, rows)
            conn.execute("COMMIT")
        elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu
        conn.close()
    return elapsed, cpu


def run(quick: bool = False) -> list[dict[str, Any]]:
    sizes = list(QUICK_SIZES if quick else SIZES)
    rows: list[dict[str, Any]] = []
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        # A fresh cache dir: the first call of each command fills it, as after installing.
        env = installed_env(NEEM_ORACLE_CACHE=str(tmp / "cache"))
        print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores while measuring", flush=True)

        fixed = _calls({"help": [py, "-m", "oracle", "--help"]}, env, REPEAT)
        floor = fixed["floor"]
        ratio = fixed["help"]["wall_s"]["median"] / floor["wall_s"]["median"]
        cpu_ratio = fixed["help"]["cpu_s"]["median"] / max(floor["cpu_s"]["median"], 1e-3)
        print(f"--help start to exit: wall {spread_text(fixed['help']['wall_s'], 1000, 0)} ms (min/median/max),"
              f" cpu {spread_text(fixed['help']['cpu_s'], 1000, 0)} ms; floor (python -c pass) wall"
              f" {spread_text(floor['wall_s'], 1000, 0)} ms, cpu {spread_text(floor['cpu_s'], 1000, 0)} ms;"
              f" {ratio:.1f}x floor wall, {cpu_ratio:.1f}x cpu (target < 150 ms)", flush=True)  # fmt: skip
        rows.append({"area": "cli", "name": "help", **fixed["help"], "floor": floor, "floor_ratio": ratio,
                     "cpu_floor_ratio": cpu_ratio})  # fmt: skip

        chains = _chains(tmp, max(sizes), env)
        store = tmp / "store.sqlite"
        trend: dict[str, list[float]] = {}
        for n in sizes:
            path = _chain_file(tmp, chains, n)
            walls, cpus, rss = [], [], []
            for _attempt in range(IMPORT_REPEAT):
                # Each run logs a new NEEM beside the others, as the floor inserts into new tables: the
                # NEEM of the run before is dropped first, untimed (``--replace`` would time the drop too).
                _drop(store, f"u{n}")
                wall, cpu, peak = _run_measured([py, "-m", "oracle", "import", str(path), "--store", str(store),
                                                 "--commit-every", str(COMMIT_EVERY)], env)  # fmt: skip
                walls.append(wall)
                cpus.append(cpu)
                rss.append(peak / 1024)
            neem = f"u{n}"
            floors = {indexes: [_sqlite_floor(store, neem, n, indexes) for _ in range(IMPORT_REPEAT)]
                      for indexes in (True, False)}
            with_idx, bare = (spread([w for w, _ in floors[k]]) for k in (True, False))
            with_idx_cpu, bare_cpu = (spread([c for _, c in floors[k]]) for k in (True, False))
            wall_s, cpu_s = spread(walls), spread(cpus)
            rate, cpu_rate = n / wall_s["median"], n / cpu_s["median"]
            floor_rate, bare_rate = n / with_idx["median"], n / bare["median"]
            floor_cpu_rate, bare_cpu_rate = n / with_idx_cpu["median"], n / bare_cpu["median"]
            print(f"import, {n:>6,} actions: {rate:,.0f} actions/s wall, {cpu_rate:,.0f} per cpu-second (wall"
                  f" {spread_text(wall_s)} s, cpu {spread_text(cpu_s)} s, start to exit); peak RSS {max(rss):.0f} MiB", flush=True)
            print(f"    floor, plain sqlite3 inserting the same rows: {floor_rate:,.0f}/s wall, {floor_cpu_rate:,.0f}"
                  f" per cpu-second with these indexes; {bare_rate:,.0f}/s, {bare_cpu_rate:,.0f} without;"
                  f" import/floor {rate / floor_rate:.2f} wall, {cpu_rate / floor_cpu_rate:.2f} cpu"
                  f" (target >= 4,000/s, <= 200 MiB at 50k)", flush=True)  # fmt: skip
            rows.append({"area": "cli", "name": "import", "actions": n, "wall_s": wall_s, "cpu_s": cpu_s,
                         "actions_per_s": rate, "actions_per_cpu_s": cpu_rate, "peak_rss_mib": max(rss),
                         "sqlite_floor_s": with_idx, "sqlite_floor_cpu_s": with_idx_cpu,
                         "sqlite_no_index_floor_s": bare, "sqlite_no_index_floor_cpu_s": bare_cpu,
                         "floor_ratio": rate / floor_rate, "cpu_floor_ratio": cpu_rate / floor_cpu_rate})  # fmt: skip
            trend.setdefault("import", []).append(wall_s["median"])

            task = json.loads(chains[n - 1])["action"]
            common = ["--store", str(store)]
            found = _calls({
                "neems": [py, "-m", "oracle", "neems", *common],
                "why-not": [py, "-m", "oracle", "why-not", task, *common, "--neem", neem],
                "what-next": [py, "-m", "oracle", "what-next", *common, "--neem", neem],
            }, env, REPEAT)  # fmt: skip
            base = found["floor"]["wall_s"]["median"]
            base_cpu = max(found["floor"]["cpu_s"]["median"], 1e-3)
            floor_s = found["floor"]
            print(f"    floor (python -c pass) wall {spread_text(floor_s['wall_s'])} s, cpu {spread_text(floor_s['cpu_s'])} s")
            for name in ("neems", "why-not", "what-next"):
                figure = found[name]
                limit = 0.35 if n <= 1000 else 0.6
                print(f"{name:>9} start to exit, {n:>6,} actions: wall {spread_text(figure['wall_s'])} s, cpu"
                      f" {spread_text(figure['cpu_s'])} s; {figure['wall_s']['median'] / base:.1f}x floor wall,"
                      f" {figure['cpu_s']['median'] / base_cpu:.1f}x cpu (target < {limit} s)", flush=True)  # fmt: skip
                rows.append({"area": "cli", "name": name, "actions": n, **figure, "floor": found["floor"],
                             "floor_ratio": figure["wall_s"]["median"] / base,
                             "cpu_floor_ratio": figure["cpu_s"]["median"] / base_cpu})  # fmt: skip
                trend.setdefault(name, []).append(figure["cpu_s"]["median"])
        for name, values in trend.items():
            k = growth_exponent(sizes, values)
            shown = "-" if k is None else f"{k:.2f}"
            print(f"growth exponent of {name} ({'wall' if name == 'import' else 'cpu'}) between"
                  f" {sizes[-2]:,} and {sizes[-1]:,} actions: {shown}")  # fmt: skip
            rows.append({"area": "cli", "name": f"{name} growth exponent", "sizes": sizes[-2:], "value": k})
    return rows
