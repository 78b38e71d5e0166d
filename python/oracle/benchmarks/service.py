"""The live service under load: N simulated robots posting situations and actions (no tablet
choices) to a real server process
on a free loopback port, each into its own NEEM of 1,000 logged actions. Bounded by request
counts and a wall-clock cap; it stops by itself.

Printed per phase: round-trip p50/p99 (client side, over HTTP), the server's own ranking time,
and the floors measured in the same run: GET /api/health, a round trip through the HTTP stack and
the engine thread doing nothing, and a durable commit (a plain SQLite WAL commit with
synchronous=FULL, one fsync: what every acknowledged situation waits for at the least).
"""

from __future__ import annotations

from typing import Any

import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from pathlib import Path

from oracle.service.robot import Drive, drive, percentile, persona_rows

#: The robots stop after this long even if their steps are not all posted (the load is bounded).
CAP_S = 300.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _prepare(store: Path, robots: int, actions: int, steps: int) -> list[tuple[str, str, list[Any]]]:
    """One NEEM per robot holding ``actions`` logged actions; the next ``steps`` rows to post."""
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    onto = build_ontology()
    db = open_store(store)
    plans = []
    for robot in range(robots):
        user, rows = robot_rows(robot, actions + steps)
        logger = NeemLogger.create(db, onto, user=user, neem_id=f"bench-{robot}", commit_every=500)
        for row in rows[:actions]:
            logger.action(row.action, row.time, row.end, available=row.available)
        logger.flush()
        plans.append((f"bench-{robot}", user, rows[actions:actions + steps]))
    db.close()
    return plans


def robot_rows(robot: int, count: int) -> tuple[str, list[Any]]:
    """Robot ``robot``'s user and at least ``count`` rows of its persona's days (the same each call)."""
    days = 2 + count // 30
    user, rows = persona_rows(robot, 3, days)
    while len(rows) < count:  # personas differ in how much they do a day
        days = days * 3 // 2
        user, rows = persona_rows(robot, 3, days)
    return user, rows


def booted_copy(store: Path, work: Path) -> Any:
    """A service context (booted, no HTTP) over a fresh copy of ``store`` at ``work``: what the
    engine-only experiments (experiments/hub-engine.py, situation-parts.py) time."""
    import shutil

    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import build_ontology
    from oracle.service import boot, build_context

    for suffix in ("", "-wal", "-shm"):
        if os.path.exists(f"{work}{suffix}"):
            os.remove(f"{work}{suffix}")
    shutil.copy(store, work)
    ctx = build_context(str(work), build_ontology(), Hyperparameters())
    boot(ctx)
    return ctx


def _serve(store: Path, *extra: str) -> tuple[subprocess.Popen[bytes], str]:
    port = _free_port()
    process = subprocess.Popen([sys.executable, "-m", "oracle", "serve", "--store", str(store), "--port", str(port), *extra],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        try:
            urllib.request.urlopen(url + "/api/health", timeout=2).read()
            return process, url
        except OSError:
            if process.poll() is not None:
                break
            time.sleep(0.3)
    process.kill()
    raise RuntimeError("the service did not start")


def _floor(url: str, n: int) -> list[float]:
    from oracle.service.client import Client

    client = Client(url)
    try:
        return sorted(client.request("GET", "/api/health")[1] for _ in range(n))
    finally:
        client.close()


def _fsync_floor(folder: Path, n: int) -> list[float]:
    """What acknowledging a durable write costs at the least on this disk: plain SQLite commits of
    one small row each, in WAL with synchronous=FULL as the store commits (each an fsync of the
    WAL), in the store's folder (ms each, sorted)."""
    import sqlite3

    path = folder / "fsync-floor.sqlite"
    conn = sqlite3.connect(path, isolation_level=None)
    try:
        conn.execute("PRAGMA journal_mode=WAL")
        conn.execute("PRAGMA synchronous=FULL")
        conn.execute("CREATE TABLE t(a INTEGER, b TEXT)")
        times = []
        for i in range(n):
            started = time.perf_counter()
            conn.execute("BEGIN IMMEDIATE")
            conn.execute("INSERT INTO t VALUES (?, ?)", (i, "x" * 200))
            conn.execute("COMMIT")
            times.append((time.perf_counter() - started) * 1000)
        return sorted(times)
    finally:
        conn.close()


def _row(phase: str, kind: str, values: list[float], robots: int, errors: int) -> dict[str, Any]:
    values = sorted(values)
    row = {"area": "service", "name": f"{phase} {kind}", "robots": robots, "n": len(values), "errors": errors,
           "p50_ms": round(percentile(values, 50), 3), "p99_ms": round(percentile(values, 99), 3)}
    print(f"  {phase:22s} {kind:10s} n={len(values):5d} p50 {row['p50_ms']:7.2f} ms  p99 {row['p99_ms']:7.2f} ms"
          f"  errors {errors}", flush=True)
    return row


def _open_sessions(url: str, plans: list[tuple[str, str, list[Any]]]) -> float:
    """First request per NEEM: one history read through Prolog and one fit (reported apart)."""
    from oracle.service.client import Client

    client = Client(url, timeout=600)
    started = time.perf_counter()
    for neem, _, _ in plans:
        client.get(f"/api/neems/{neem}/situation")
    client.close()
    return (time.perf_counter() - started) * 1000 / len(plans)


def run(quick: bool = False) -> list[dict[str, Any]]:
    actions, steps, robots = (200, 30, 2) if quick else (1000, 150, 3)
    rows: list[dict[str, Any]] = []
    import importlib.util

    print(f"  load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores (other work inflates every figure);"
          f" niceness {os.nice(0)}; uvicorn's HTTP parser:"
          f" {'httptools' if importlib.util.find_spec('httptools') else 'h11 (pure Python)'}", flush=True)
    with tempfile.TemporaryDirectory(prefix="neem-bench-service-") as folder:
        store = Path(folder) / "bench.sqlite"
        plans = _prepare(store, robots, actions, steps * 3)
        process, url = _serve(store)
        stop = threading.Event()
        timer = threading.Timer(CAP_S, stop.set)
        try:
            opened = _open_sessions(url, plans)
            print(f"  session open (history read + fit at {actions} actions): {opened:.0f} ms per NEEM", flush=True)
            timer.start()  # the cap bounds the load, not the preparation
            rows.append({"area": "service", "name": "session open", "ms": round(opened, 1), "actions": actions})
            rows.append(_row("floor (GET /api/health)", "round trip", _floor(url, 300), 1, 0))
            rows.append(_row("floor (a durable commit)", "fsync", _fsync_floor(Path(folder), 300), 1, 0))

            neem, user, todo = plans[0]
            alone = drive(url, user, todo[:steps], neem, stop=stop, choices=False)
            for kind in ("situation", "server", "engine", "rank", "action"):
                rows.append(_row("1 robot", kind, alone.latencies.get(kind, []), 1, len(alone.errors)))

            results: list[Drive] = [Drive() for _ in plans]

            def one(index: int) -> None:
                neem_i, user_i, todo_i = plans[index]
                start = steps if index == 0 else 0
                results[index] = drive(url, user_i, todo_i[start:start + steps], neem_i, stop=stop, choices=False)

            threads = [threading.Thread(target=one, args=(i,)) for i in range(len(plans))]
            started = time.perf_counter()
            for thread in threads:
                thread.start()
            for thread in threads:
                thread.join()
            seconds = time.perf_counter() - started
            errors = sum(len(r.errors) for r in results)
            for kind in ("situation", "server", "engine", "rank", "action"):
                values = [v for r in results for v in r.latencies.get(kind, [])]
                rows.append(_row(f"{len(plans)} robots at once", kind, values, len(plans), errors))
            posted = sum(len(r.latencies.get("situation", [])) + len(r.latencies.get("action", [])) for r in results)
            print(f"  {len(plans)} robots: {posted} requests in {seconds:.1f} s ({posted / seconds:.0f}/s)"
                  f"{'; stopped by the time cap' if stop.is_set() else ''}", flush=True)
        finally:
            timer.cancel()
            _stop(process)
        rows.extend(_write_behind(store, plans[0], steps))
        rows.extend(_hub(Path(folder) / "hub.sqlite", *((4, 200, 8) if quick else (HUB_ROBOTS, actions, HUB_STEPS))))
    return rows


#: The hub phase: this many robots, each posting a situation and its action about once a second
#: (after ``HUB_STEPS`` steps each, it ends), into NEEMs of the same size as the phases above.
HUB_ROBOTS = 20
HUB_STEPS = 20


def _hub(store: Path, robots: int, actions: int, steps: int) -> list[dict[str, Any]]:
    """``robots`` robots at once, each posting one situation and one action a second (started
    spread over the first second), against one service process: the hub's load (docs/service.md,
    "Many robots on one hub")."""
    import random

    plans = _prepare(store, robots, actions, steps)
    process, url = _serve(store)
    rows: list[dict[str, Any]] = []
    try:
        opened = _open_sessions(url, plans)
        print(f"  {robots} robots at 1 situation/s: session open {opened:.0f} ms per NEEM", flush=True)
        results: list[Drive] = [Drive() for _ in plans]
        offsets = random.Random(0).sample(range(1000), robots)

        def one(index: int) -> None:
            neem, user, todo = plans[index]
            time.sleep(offsets[index] / 1000)
            results[index] = drive(url, user, todo[:steps], neem, delay=1.0, choices=False)

        threads = [threading.Thread(target=one, args=(i,)) for i in range(robots)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        errors = sum(len(r.errors) for r in results)
        for kind in ("situation", "server", "engine", "action"):
            rows.append(_row(f"{robots} robots, 1/s each", kind, [v for r in results for v in r.latencies.get(kind, [])],
                             robots, errors))
    finally:
        _stop(process)
    return rows


def _stop(process: subprocess.Popen[bytes]) -> None:
    process.terminate()
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        process.kill()


def _write_behind(store: Path, plan: tuple[str, str, list[Any]], steps: int) -> list[dict[str, Any]]:
    """The same robot against a service started with --write-behind (answer before the commit):
    what acknowledging only committed situations (the default) costs."""
    neem, user, todo = plan
    process, url = _serve(store, "--write-behind")
    try:
        _open_sessions(url, [plan])
        later = todo[2 * steps:] or todo[steps:]
        done = drive(url, user, later[: max(10, steps // 3)], neem, choices=False)
        return [_row("1 robot, --write-behind", kind, done.latencies.get(kind, []), 1, len(done.errors))
                for kind in ("situation", "action")]
    finally:
        _stop(process)
