"""The first "why did you suggest" after the service boots, on a NEEM of 10,000 actions (issue 57's
target: <= 100 ms), beside two floors of the same boot: its first ``/api/health`` and the same
question asked again (everything read kept). Half the boots ask the question first of all (it
then also pays what any first request through the app pays), half after ``/api/health``.

Each boot is a fresh process (``python -m oracle.benchmarks.pastboot STORE FIRST``), as ``serve``
starts: the context built, ``oracle.service.boot`` (what ``serve`` does before it listens), then
the requests through the real ASGI app in process. The NEEM is the Prolog bench's (``prolog._neem``: a preference
every 10 actions); one process asks first so that its history is kept, as after an import.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.figures import spread, spread_text

QUESTION = "why did you suggest pick(banana)?"


def run(quick: bool = False) -> list[dict[str, Any]]:
    from oracle.benchmarks.prolog import _neem
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    n, boots = (1000, 2) if quick else (10000, 5)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "boot.sqlite"
        store = open_store(path)
        _neem(store, build_ontology(), n)
        store.close()
        _boot(path, "health")  # the first reads the history whole and keeps it (in the store)
        found = [_boot(path, first) for _ in range(boots) for first in ("health", "why")]
    rows = []
    for name, first, key in (("floor: first /api/health after boot", "health", "health"),
                             ("first 'why did you suggest' after boot, after /api/health", "health", "why"),
                             ("first 'why did you suggest' after boot, the first request", "why", "why"),
                             ("floor: the same question again", "health", "again")):
        figure = spread([f[key] for f in found if f["first"] == first])
        print(f"  {n:>6,} actions  {name:<58} {spread_text(figure, digits=1)} ms (min/median/max of {boots} boots)"
              + (" (target <= 100 ms)" if key == "why" else ""), flush=True)
        rows.append({"area": "past", "name": name, "actions": n, "ms": figure})
    return rows


def _boot(path: Path, first: str) -> dict[str, Any]:
    done = subprocess.run([sys.executable, "-m", "oracle.benchmarks.pastboot", str(path), first],
                          capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"boot benchmark failed: {done.stderr.strip()[-400:]}")
    figures: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return figures


def _child(store: str, first: str) -> None:
    """One boot, as ``serve`` boots (``oracle.service.boot``); its requests in order (``first``:
    "health" or "why" first): the figures (ms) as a JSON line."""
    from fastapi.testclient import TestClient

    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import build_ontology
    from oracle.service import boot, build_context
    from oracle.service.app import create_app

    ctx = build_context(store, build_ontology(), Hyperparameters())
    order = ("health", "why", "again") if first == "health" else ("why", "again", "health")
    try:
        app = create_app(ctx)
        boot(ctx, app)  # as serve boots
        with TestClient(app, base_url="http://127.0.0.1") as client:
            times: dict[str, Any] = {"first": first}
            for key in order:
                started = time.perf_counter()
                answer = client.get("/api/health") if key == "health" else client.get("/api/neems/bench/ask",
                                                                                      params={"q": QUESTION})
                times[key] = (time.perf_counter() - started) * 1000
                if answer.status_code != 200:
                    raise RuntimeError(f"{key}: {answer.status_code} {answer.text}")
    finally:
        ctx.thread.close()
    print(json.dumps(times), flush=True)


if __name__ == "__main__":
    _child(sys.argv[1], sys.argv[2])
