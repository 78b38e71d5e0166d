"""The whole history read where nothing is kept (oracle.slicedread): one call vs slices of
``SLICE_ACTIONS`` actions, at 10,000 and 50,000 actions, each read in a process of its own (its
peak RSS is the read's), beside two floors measured in the same run: the same process answering
one small question (Prolog loaded, no history read) and the rows read with plain SQL. Then what
a robot's job on the engine thread waits while /explore reads such a NEEM: the read as one job
(before) or one job per slice (oracle.service.sliced_jobs).

Run alone: ``python -m oracle.benchmarks.slices [--quick]``."""

from __future__ import annotations

import asyncio
import json
import resource
import shutil
import sqlite3
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

#: The child's modes: the one-call read, the sliced read, the floor (Prolog loaded, one question).
MODES = ("one call", "sliced", "floor")


def _child(store_path: str, neem: str, mode: str) -> None:
    """Read the history of ``neem`` as ``mode`` says; print wall, cpu and peak RSS as JSON."""
    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.slicedread import sliced_view
    from oracle.store import open_store

    store = open_store(store_path)
    bridge = Bridge(store, neem, build_ontology())
    bridge.latest_situation()  # Prolog loaded and pointed at the NEEM before the clock starts
    wall, cpu = time.perf_counter(), time.process_time()
    if mode == "one call":
        rows = len(bridge.history_view().rows)
    elif mode == "sliced":
        rows = len(sliced_view(bridge).rows)
    else:
        rows = 0
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"wall_s": wall, "cpu_s": cpu, "peak_mib": peak, "rows": rows}))


def _measure(store: Path, neem: str, mode: str) -> dict[str, Any]:
    out = subprocess.run([sys.executable, "-m", "oracle.benchmarks.slices", "child", str(store), neem, mode],
                         check=True, capture_output=True, text=True)
    result: dict[str, Any] = json.loads(out.stdout.strip().splitlines()[-1])
    return result


def _robot_wait(store: Path, big: str, small: str, sliced: bool) -> dict[str, Any]:
    """A job every 50 ms on the engine thread (the latest situation of NEEM ``small``: the bridge
    switches NEEM as for a robot's call) while NEEM ``big`` is read for /explore: its latency
    from submit to answer, min/median/max, and how long the read took."""
    from types import SimpleNamespace

    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.service.engine import EngineThread
    from oracle.service.sliced_jobs import view_in_jobs
    from oracle.store import open_store

    opened = open_store(str(store))
    onto = build_ontology()
    bridges = {neem: Bridge(opened, neem, onto) for neem in (big, small)}
    engine = SimpleNamespace(store=opened, bridge=lambda neem: bridges[neem])
    thread = EngineThread()

    async def main() -> dict[str, Any]:
        await thread.run(lambda: bridges[small].latest_situation())
        waits: list[float] = []
        started = time.perf_counter()
        if sliced:
            read = asyncio.ensure_future(view_in_jobs(thread, engine, big))  # type: ignore[arg-type]
        else:
            read = asyncio.ensure_future(thread.run(lambda: bridges[big].history_view()))
        while not read.done():
            sent = time.perf_counter()
            await thread.run(lambda: bridges[small].latest_situation())
            waits.append(time.perf_counter() - sent)
            await asyncio.sleep(0.05)
        took = time.perf_counter() - started
        return {"read_s": took, "robot_jobs": len(waits), "robot_wait_ms": {
            "min": min(waits) * 1000, "median": statistics.median(waits) * 1000, "max": max(waits) * 1000}}

    return asyncio.run(main())


def _robot_child(store_path: str, big: str, small: str, mode: str) -> None:
    print(json.dumps(_robot_wait(Path(store_path), big, small, mode == "sliced")))


def slice_figures(quick: bool = False) -> list[dict[str, Any]]:
    """The rows: per size, each mode's read (median of 3 processes; 1 when quick), and the robot's wait."""
    from oracle.benchmarks.readfloor import chains_store as _chains_store
    from oracle.benchmarks.readfloor import sql_floor as _sql_floor
    from oracle.store import open_store
    from oracle.store.ids import resolve_neem

    sizes = [1000] if quick else [10_000, 50_000]
    repeat = 1 if quick else 3
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp:
        store = _chains_store(Path(tmp), [*sizes, 1000] if 1000 not in sizes else sizes)
        opened = open_store(str(store))
        ids = {n: resolve_neem(opened, f"u{n}") for n in [*sizes, 1000]}
        opened.close()
        for n in sizes:
            row: dict[str, Any] = {"area": "prolog", "name": "whole read in slices", "actions": n}
            for mode in MODES:
                runs = [_measure(store, ids[n], mode) for _ in range(repeat)]
                row[mode] = {key: statistics.median(r[key] for r in runs) for key in ("wall_s", "cpu_s", "peak_mib")}
                row[mode]["rows"] = runs[0]["rows"]
            sql = min(_timed_cpu(lambda: _sql_floor(store, ids[n])) for _ in range(repeat))
            row["sql_floor_cpu_s"] = sql
            print(f"  whole read at {n:,} actions: one call {_said(row['one call'])}; sliced {_said(row['sliced'])};"
                  f" floor (Prolog loaded, no read) peak {row['floor']['peak_mib']:.0f} MiB; SQL floor cpu {sql:.2f} s",
                  flush=True)
            for mode in ("one call", "sliced"):
                copy = Path(tmp) / "robot.sqlite"
                shutil.copy(store, copy)  # the sliced read keeps the view it read: each run on a fresh copy
                with sqlite3.connect(copy) as conn:  # nothing kept, as a MongoDB store or a lost entry
                    conn.execute("DELETE FROM kept WHERE kind='history'")
                out = subprocess.run([sys.executable, "-m", "oracle.benchmarks.slices", "robot", str(copy), ids[n], ids[1000],
                                      mode], check=True, capture_output=True, text=True)
                wait = json.loads(out.stdout.strip().splitlines()[-1])
                row[f"robot {mode}"] = wait
                w = wait["robot_wait_ms"]
                print(f"  a robot's job while /explore reads {n:,} actions ({mode}): waits min/median/max"
                      f" {w['min']:.0f}/{w['median']:.0f}/{w['max']:.0f} ms over {wait['robot_jobs']} jobs;"
                      f" the read took {wait['read_s']:.1f} s", flush=True)
                copy.unlink()
            rows.append(row)
    return rows


def _timed_cpu(fn: Any) -> float:
    cpu = time.process_time()
    fn()
    return time.process_time() - cpu


def _said(figures: dict[str, Any]) -> str:
    return f"{figures['wall_s']:.2f} s wall, {figures['cpu_s']:.2f} s cpu, peak {figures['peak_mib']:.0f} MiB"


if __name__ == "__main__":
    if sys.argv[1:2] == ["child"]:
        _child(*sys.argv[2:5])
    elif sys.argv[1:2] == ["robot"]:
        _robot_child(*sys.argv[2:6])
    else:
        slice_figures(quick="--quick" in sys.argv)
