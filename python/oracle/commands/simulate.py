"""``python -m oracle simulate --serve URL --persona N``: a simulated robot driving the service.

The robot lives in the kitchen world (oracle.world) with one persona: each simulated step it
posts what it perceives, the tasks available, and the action the persona then chose, as EDAN's
framework would. ``--robots N`` runs N robots at once (one NEEM each) for a load test.
"""

from __future__ import annotations

import argparse
import threading
import time
from dataclasses import dataclass, field
from urllib.parse import quote


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("simulate", help="a simulated robot (kitchen world + persona) driving a running service")
    parser.add_argument("--serve", required=True, metavar="URL", help="the service, e.g. http://127.0.0.1:8765")
    parser.add_argument("--persona", type=int, default=0, help="which persona of the world's generator (default 0)")
    parser.add_argument("--seed", type=int, default=3, help="the generator's seed (default 3, as make demo)")
    parser.add_argument("--days", type=int, default=2, help="simulated days to drive (default 2)")
    parser.add_argument("--neem", help="NEEM to log into (default: a new one named after the persona)")
    parser.add_argument("--robots", type=int, default=1, help="robots at once, one NEEM each (default 1)")
    parser.add_argument("--delay", type=float, default=0.0, help="seconds between steps, to watch the page (default 0)")
    parser.add_argument("--token", help="the service's token, if it has one")
    parser.set_defaults(handler=run)


@dataclass
class Drive:
    """What one robot did: request latencies per kind (ms) and errors."""

    latencies: dict[str, list[float]] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)
    steps: int = 0


def persona_rows(persona: int, seed: int, days: int) -> tuple[str, list]:  # noqa: ANN001
    """The persona's file name and the ChainRows of its simulated days."""
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.rules import load_world

    who = make_persona(seed, persona)
    return who.file_name, simulate(who, load_world(), days, seed)[0]


def drive(url: str, user: str, rows: list, neem: str | None, token: str | None = None,
          delay: float = 0.0, stop: threading.Event | None = None) -> Drive:
    """Create (or reuse) the NEEM and post the rows step by step: perception of objects not
    seen before, the situation, the action the persona chose."""
    from oracle.service.client import Client, ServiceError

    client = Client(url, token)
    result = Drive()
    try:
        existing = {n["id"] for n in client.get("/api/neems")}
        if neem is None or neem not in existing:
            neem = client.post("/api/neems", {"user": user, "neem": neem})["id"]
        base = f"/api/neems/{quote(neem, safe='')}"
        seen: set[str] = set()
        for row in rows:
            if stop is not None and stop.is_set():
                break
            at = row.time.isoformat()
            available = [str(c) for c in row.available or (row.action,)]
            objects = sorted({a for c in (row.available or (row.action,)) for a in c.args} - seen)
            try:
                if objects:
                    _, ms = client.request("POST", f"{base}/perception", {"objects": [{"name": o} for o in objects], "at": at})
                    result.latencies.setdefault("perception", []).append(ms)
                    seen.update(objects)
                answer, ms = client.request("POST", f"{base}/situation", {"available": available, "at": at})
                result.latencies.setdefault("situation", []).append(ms)
                result.latencies.setdefault("rank", []).append(float(answer["ms"]))
                end = row.end.isoformat() if row.end is not None else None
                _, ms = client.request("POST", f"{base}/actions", {"call": str(row.action), "begin": at, "end": end})
                result.latencies.setdefault("action", []).append(ms)
            except ServiceError as error:
                result.errors.append(str(error))
            result.steps += 1
            if delay:
                time.sleep(delay)
    finally:
        client.close()
    return result


def run(args: argparse.Namespace) -> int:
    from oracle.errors import NeemOracleError

    if args.robots < 1 or args.days < 1:
        raise NeemOracleError("--robots and --days must be at least 1")
    results: list[Drive] = [Drive() for _ in range(args.robots)]

    def one(index: int) -> None:
        neem = args.neem if args.robots == 1 else (f"{args.neem}-{index}" if args.neem else None)
        user, rows = persona_rows(args.persona + index, args.seed, args.days)
        results[index] = drive(args.serve, user, rows, neem, args.token, args.delay)

    started = time.perf_counter()
    threads = [threading.Thread(target=one, args=(i,)) for i in range(args.robots)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    seconds = time.perf_counter() - started
    steps = sum(r.steps for r in results)
    errors = [e for r in results for e in r.errors]
    print(f"{args.robots} robot(s) drove {steps} steps in {seconds:.1f} s; {len(errors)} errors")
    for kind in ("perception", "situation", "rank", "action"):
        values = sorted(v for r in results for v in r.latencies.get(kind, []))
        if values:
            print(f"  {kind:10s} n={len(values):5d}  p50 {percentile(values, 50):6.2f} ms  p99 {percentile(values, 99):6.2f} ms")
    for error in errors[:5]:
        print(f"  error: {error}")
    return 1 if errors else 0


def percentile(sorted_values: list[float], q: float) -> float:
    """Nearest-rank percentile of already sorted values."""
    if not sorted_values:
        return float("nan")
    rank = max(1, -(-len(sorted_values) * q // 100))
    return sorted_values[int(rank) - 1]
