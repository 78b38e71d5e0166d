"""Import figures of the store area: ``python -m oracle import`` of 10,000 and 50,000 actions
(quick: 1,000 and 4,000), start to exit, with its peak RSS, and the first ``rank`` after it,
each beside the floor measured in the same run.

The floor of an import is plain ``sqlite3`` inserting the very rows that import wrote, into a
fresh file with the same tables and indexes (and, as a second figure, without the secondary
indexes), one transaction per 1,000 actions as ``--commit-every 1000`` (benchmarks.cli
``_sqlite_floor``). Import and floor runs alternate, so both meet the same load; each import
logs a new NEEM beside the other sizes' (the one of the run before dropped first, untimed).
The floor of a rank is the interpreter starting and exiting (``python -c pass``). Wall time on
a shared machine is mostly waiting for a core: the CPU seconds (user + system of the child)
are printed beside it, and the load average before each size.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any

from oracle.benchmarks.figures import installed_env, run_child, run_measured, spread, spread_text

SIZES = (10_000, 50_000)
QUICK_SIZES = (1_000, 4_000)
#: Alternated runs per size (an import of 50,000 actions takes a minute on a shared machine).
REPEAT = 2
COMMIT_EVERY = 1000
#: The issue's targets, printed beside the figures.
TARGET_RATE = 4_000
TARGET_RSS_MIB = 250
TARGET_RANK_S = {10_000: 1.0, 50_000: 2.0}


def run(quick: bool = False) -> list[dict[str, Any]]:
    from oracle.benchmarks.cli import _chain_file, _chains, _drop, _sqlite_floor

    sizes = QUICK_SIZES if quick else SIZES
    py = sys.executable
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        env = installed_env(NEEM_ORACLE_CACHE=str(tmp / "cache"))
        chains = _chains(tmp, max(sizes), env)
        store = tmp / "store.sqlite"
        for n in sizes:
            path, neem = _chain_file(tmp, chains, n), f"u{n}"
            load = os.getloadavg()[0]
            walls: list[float] = []
            cpus: list[float] = []
            rss: list[float] = []
            floor: list[tuple[float, float]] = []
            bare: list[tuple[float, float]] = []
            rank_walls: list[float] = []
            rank_cpus: list[float] = []
            pass_walls: list[float] = []
            pass_cpus: list[float] = []
            for _ in range(REPEAT):
                _drop(store, neem)
                wall, cpu, peak = run_measured([py, "-m", "oracle", "import", str(path), "--store", str(store),
                                                "--commit-every", str(COMMIT_EVERY)], env)  # fmt: skip
                walls.append(wall)
                cpus.append(cpu)
                rss.append(peak / 1024)
                # the first rank after the import, on a copy (it writes its ranking back)
                ranked = tmp / "ranked.sqlite"
                shutil.copyfile(store, ranked)
                if Path(f"{store}-wal").exists():
                    shutil.copyfile(f"{store}-wal", f"{ranked}-wal")
                wall, cpu, _ = run_child([py, "-m", "oracle", "rank", "--store", str(ranked), "--neem", neem], env)
                rank_walls.append(wall)
                rank_cpus.append(cpu)
                for leftover in (ranked, Path(f"{ranked}-wal"), Path(f"{ranked}-shm")):
                    leftover.unlink(missing_ok=True)
                wall, cpu, _ = run_child([py, "-c", "pass"], env)
                pass_walls.append(wall)
                pass_cpus.append(cpu)
                floor.append(_sqlite_floor(store, neem, n, True))
                bare.append(_sqlite_floor(store, neem, n, False))
            wall_s, cpu_s = spread(walls), spread(cpus)
            floor_s, floor_cpu = spread([w for w, _ in floor]), spread([c for _, c in floor])
            bare_s, bare_cpu = spread([w for w, _ in bare]), spread([c for _, c in bare])
            rate, cpu_rate = n / wall_s["median"], n / cpu_s["median"]
            print(f"import, {n:>6,} actions (load average {load:.1f}): {rate:,.0f} actions/s wall, {cpu_rate:,.0f} per"
                  f" cpu-second (wall {spread_text(wall_s)} s, cpu {spread_text(cpu_s)} s, start to exit); peak RSS"
                  f" {max(rss):.0f} MiB (targets >= {TARGET_RATE:,}/s, <= {TARGET_RSS_MIB} MiB at 50,000)", flush=True)
            print(f"    floor, plain sqlite3 inserting the same rows: {n / floor_s['median']:,.0f}/s wall,"
                  f" {n / floor_cpu['median']:,.0f} per cpu-second with these indexes; {n / bare_s['median']:,.0f}/s,"
                  f" {n / bare_cpu['median']:,.0f} per cpu-second without; import/floor"
                  f" {floor_s['median'] / wall_s['median']:.2f} wall, {floor_cpu['median'] / cpu_s['median']:.2f} cpu",
                  flush=True)  # fmt: skip
            rank_s, rank_cpu = spread(rank_walls), spread(rank_cpus)
            target = TARGET_RANK_S.get(n)
            print(f"first rank after the import, {n:>6,} actions: wall {spread_text(rank_s)} s, cpu"
                  f" {spread_text(rank_cpu)} s; floor (python -c pass) wall {spread_text(spread(pass_walls))} s"
                  + (f" (target <= {target:g} s)" if target else ""), flush=True)  # fmt: skip
            rows.append({"area": "store", "name": "import", "actions": n, "load": load, "wall_s": wall_s,
                         "cpu_s": cpu_s, "actions_per_s": rate, "actions_per_cpu_s": cpu_rate, "peak_rss_mib": max(rss),
                         "sqlite_floor_s": floor_s, "sqlite_floor_cpu_s": floor_cpu, "sqlite_no_index_floor_s": bare_s,
                         "sqlite_no_index_floor_cpu_s": bare_cpu})  # fmt: skip
            rows.append({"area": "store", "name": "first_rank_after_import", "actions": n, "wall_s": rank_s,
                         "cpu_s": rank_cpu, "floor_wall_s": spread(pass_walls), "floor_cpu_s": spread(pass_cpus)})  # fmt: skip
    return rows
