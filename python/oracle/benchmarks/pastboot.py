"""The first "why did you suggest" after the service boots, on a NEEM of 10,000 actions (issue 57's
target: <= 100 ms), beside two floors of the same boot: its first ``/api/health`` and the same
question asked again (everything read kept).

Each boot is a fresh process (``python -m oracle.benchmarks.pastboot STORE``), as ``serve`` starts:
the context built, ``Engine.warm_up`` (what ``serve`` does before it listens), then the requests
through the real ASGI app in process. The NEEM is the Prolog bench's (``prolog._neem``: a preference
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
        _boot(path)  # the first reads the history whole and keeps it (in the store)
        found = [_boot(path) for _ in range(boots)]
    rows = []
    for name, key in (("floor: first /api/health after boot", "health"),
                      ("first 'why did you suggest' after boot", "first"),
                      ("floor: the same question again", "again")):
        figure = spread([f[key] for f in found])
        print(f"  {n:>6,} actions  {name:<44} {spread_text(figure, digits=1)} ms (min/median/max of {boots} boots)"
              + (" (target <= 100 ms)" if key == "first" else ""), flush=True)
        rows.append({"area": "past", "name": name, "actions": n, "ms": figure})
    return rows


def _boot(path: Path) -> dict[str, float]:
    done = subprocess.run([sys.executable, "-m", "oracle.benchmarks.pastboot", str(path)],
                          capture_output=True, text=True, timeout=600, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"boot benchmark failed: {done.stderr.strip()[-400:]}")
    figures: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
    return figures


def _child(store: str) -> None:
    """One boot: the figures (ms) as a JSON line."""
    from fastapi.testclient import TestClient

    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    ctx = build_context(store, build_ontology(), Hyperparameters())
    try:
        ctx.thread.call(ctx.engine.warm_up)
        with TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
            times: dict[str, float] = {}
            for key, where in (("health", "/api/health"), ("first", "/api/neems/bench/ask"), ("again", "/api/neems/bench/ask")):
                started = time.perf_counter()
                answer = client.get(where, params={"q": QUESTION} if key != "health" else None)
                times[key] = (time.perf_counter() - started) * 1000
                if answer.status_code != 200:
                    raise RuntimeError(f"{key}: {answer.status_code} {answer.text}")
    finally:
        ctx.thread.close()
    print(json.dumps(times), flush=True)


if __name__ == "__main__":
    _child(sys.argv[1])
