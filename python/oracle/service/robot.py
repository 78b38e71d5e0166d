"""A simulated robot for the service: the kitchen world and one persona (oracle.world) posted
step by step as EDAN's framework would (perception of new objects, the situation, the action the
persona chose), with each request's round trip recorded. For the demo and the load test."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import quote


@dataclass
class Drive:
    """What one robot did: request latencies per kind (ms) and errors."""

    latencies: dict[str, list[float]] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)
    steps: int = 0
    #: The task executed at each step (the person's choice where the robot followed the tablet).
    executed: list[str] = field(default_factory=list)


def persona_rows(persona: int, seed: int, days: int) -> tuple[str, list[Any]]:
    """The persona's file name and the ChainRows of its simulated days."""
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    who = make_persona(seed, persona)
    return who.file_name, simulate(who, load_world(), days, seed)[0]


def drive(url: str, user: str, rows: list[Any], neem: str | None, token: str | None = None,
          delay: float = 0.0, stop: threading.Event | None = None, choices: bool = True,
          announce: Callable[[str], None] | None = None, follow: float | None = None) -> Drive:
    """Create (or reuse) the NEEM (``announce`` is told its id) and post the rows step by step:
    perception of objects not seen before, the situation, the persona's choice as the tablet
    posts it (``choices``), and the action the robot then executes. With ``follow`` (seconds)
    the robot follows the tablet instead: after each situation it waits that long for the
    person's choice and executes it (the persona's when none comes)."""
    from oracle.service.client import Client, ServiceError

    client = Client(url, token)
    result = Drive()
    try:
        try:
            listed = client.get("/api/neems")
            # an existing NEEM is reused whether ``neem`` is its id or its name
            existing = {n["name"]: n["id"] for n in listed if n.get("name")} | {n["id"]: n["id"] for n in listed}
            if neem is not None and neem in existing:
                neem = existing[neem]
            else:
                neem = client.post("/api/neems", {"user": user, "neem": neem})["id"]
        except ServiceError as error:
            result.errors.append(str(error))
            return result
        assert neem is not None
        if announce is not None:
            announce(neem)
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
                timing = client.server_timing
                if "engine" in timing:
                    result.latencies.setdefault("server", []).append(timing["engine"] + timing.get("queue", 0.0))
                    result.latencies.setdefault("engine", []).append(timing["engine"])
                chosen = str(row.action)
                if follow is not None:
                    chosen = wait_for_choice(client, base, follow, available, stop) or chosen
                elif choices:
                    _, ms = client.request("POST", f"{base}/choice", {"task": str(row.action), "at": at})
                    result.latencies.setdefault("choice", []).append(ms)
                end = row.end.isoformat() if row.end is not None else None
                _, ms = client.request("POST", f"{base}/actions", {"call": chosen, "begin": at, "end": end})
                result.latencies.setdefault("action", []).append(ms)
                result.executed.append(chosen)
            except ServiceError as error:
                result.errors.append(str(error))
            result.steps += 1
            if delay:
                time.sleep(delay)
    finally:
        client.close()
    return result


def wait_for_choice(client: Any, base: str, seconds: float, available: list[str],
                    stop: threading.Event | None = None) -> str | None:
    """The task the person chooses on the tablet within ``seconds`` (a decision newer than the
    one there now, among ``available``); None when none comes."""
    before = client.get(f"{base}/choice").get("decision")
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and not (stop is not None and stop.is_set()):
        made = client.get(f"{base}/choice")
        if made.get("decision") not in (None, before) and made.get("task") in available:
            return str(made["task"])
        time.sleep(POLL_S)
    return None


#: How often a robot following the tablet asks for the person's choice.
POLL_S = 0.25


def percentile(sorted_values: list[float], q: float) -> float:
    """Nearest-rank percentile of already sorted values."""
    if not sorted_values:
        return float("nan")
    rank = max(1, -(-len(sorted_values) * q // 100))
    return sorted_values[int(rank) - 1]
