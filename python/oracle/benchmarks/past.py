"""Benchmark of the questions about the past (docs/beyond.md): each question form asked of the
live service (the real ASGI app, in process) over a simulated user's NEEM of 5 and 28 days,
median of repeated asks after the first; the floor is /api/health in the same run (a round
trip through the engine thread doing nothing). Target: every form under 100 ms. Those NEEMs are
ranked once, at their end (as ``make demo``); the third, of 28 days, is ranked at every
situation, as the live service writes a NEEM (a preference per situation: "why did you
suggest" reads back through them).

The repeated asks find the NEEM unchanged, so they read what the engine kept of it
(oracle.past.kept); the rows "after a new action" time the first ask after the robot logged
one more action through the service (the action itself not timed), which reads the history's
new action and mines the routines again."""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

from oracle.benchmarks.figures import spread, spread_text

if TYPE_CHECKING:
    import httpx

#: One question per form, as the docs' worked example asks them of the demo user.
QUESTIONS = ("when did I last open the fridge?", "how often did I open(fridge) this week?",
             "what do I usually do after open(fridge)?", "what did you do today?",
             "where is the drinking glass?", "why did you suggest open(fridge)?", "who usually does open(fridge)?",
             "Wann habe ich zuletzt pick(beer_bottle) gemacht?")


#: The NEEMs asked: days, and whether ranked at every situation (else once, at the end).
NEEMS = ((5, False), (28, False), (28, True))


def _log(path: Path, days: int, ranked: bool = False) -> None:
    from datetime import datetime

    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store import open_store
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    onto = build_ontology()
    rows, _ = simulate(make_persona(3, 0), load_world(), days + 1, 3)
    last = rows[-1].time.date() if rows[-1].time else None
    store = open_store(path)
    log = NeemLogger.create(store, onto, user="bench", neem_id="bench", commit_every=500)
    now = None
    for row in rows:
        assert isinstance(row.time, datetime)
        if row.time.date() == last:
            now = row
            break
        if ranked and row.available:
            log.available(row.available, row.time)
            log.preference([(call, float(i)) for i, call in enumerate(row.available)], row.time)
            log.action(row.action, row.time, row.end)
        else:
            log.action(row.action, row.time, row.end, available=row.available)
    if now is not None and now.time is not None:
        log.available(now.available or (), now.time)
        log.preference([(call, float(i)) for i, call in enumerate(now.available or ())], now.time)
    log.close()
    store.close()


def run(quick: bool = False) -> list[dict[str, Any]]:
    from fastapi.testclient import TestClient

    from oracle.algorithm.params import Hyperparameters
    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    rows: list[dict[str, Any]] = []
    repeats = 5 if quick else 15
    for days, ranked in (NEEMS[:1] if quick else NEEMS):
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "past.sqlite"
            _log(path, days, ranked)
            neem = f"{days}r" if ranked else days
            ctx = build_context(str(path), build_ontology(), Hyperparameters())
            try:
                with TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
                    floor = _times(lambda: client.get("/api/health"), repeats)
                    rows.append(_row(neem, "floor: /api/health", floor))
                    for question in QUESTIONS:
                        ms = _times(partial(client.get, "/api/neems/bench/ask", params={"q": question}), repeats)
                        rows.append(_row(neem, question, ms))
                    ms = _times(lambda: client.get("/api/neems/bench/summary"), repeats)
                    rows.append(_row(neem, "state summary", ms))
                    for name, ask in AFTER_ACTION:
                        ms = _after_actions(client, partial(ask, client), repeats)
                        rows.append(_row(neem, f"{name}, after a new action", ms))
            finally:
                ctx.thread.close()
    from oracle.benchmarks.pastboot import run as first_after_boot

    return rows + first_after_boot(quick)


#: The answers that read the whole history (the kept actions, the routines), timed after an action.
AFTER_ACTION: tuple[tuple[str, Callable[[httpx.Client], httpx.Response]], ...] = (
    (QUESTIONS[5], lambda client: client.get("/api/neems/bench/ask", params={"q": QUESTIONS[5]})),
    ("state summary", lambda client: client.get("/api/neems/bench/summary")),
)


def _after_actions(client: httpx.Client, call: Callable[[], httpx.Response], repeats: int) -> list[float]:
    """``call`` timed right after each of ``repeats`` + 1 actions logged through the service
    a minute apart after the NEEM's latest event (the first, which opens the session, dropped)."""
    samples = []
    for index in range(repeats + 1):
        now = client.get("/api/neems/bench/summary").json()["now"]
        logged = client.post("/api/neems/bench/actions", json={"call": "open(fridge)", "begin": now + 60, "end": now + 65})
        if logged.status_code != 200:
            raise RuntimeError(f"benchmark action failed: {logged.status_code} {logged.text}")
        started = time.perf_counter()
        answer = call()
        if answer.status_code != 200:
            raise RuntimeError(f"benchmark request failed: {answer.status_code} {answer.text}")
        if index:
            samples.append((time.perf_counter() - started) * 1000)
    return samples


def _times(call: Callable[[], httpx.Response], repeats: int) -> list[float]:
    first = call()
    if first.status_code != 200:
        raise RuntimeError(f"benchmark request failed: {first.status_code} {first.text}")
    samples = []
    for _ in range(repeats):
        started = time.perf_counter()
        call()
        samples.append((time.perf_counter() - started) * 1000)
    return samples


def _row(neem: int | str, name: str, samples: list[float]) -> dict[str, Any]:
    """``neem``: its days, with an r when ranked at every situation."""
    figure = spread(samples)
    print(f"  {neem:>3} days  {name:<52} {spread_text(figure, digits=1)} ms (min/median/max)", flush=True)
    return {"area": "past", "name": name, "days": int(str(neem).rstrip("r")), "ranked_each": str(neem).endswith("r"),
            "ms": figure}
