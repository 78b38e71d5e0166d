"""Prolog figures: crossing cost, a 5-goal conjunction compiled vs goal-by-goal, why_not latency."""

from __future__ import annotations

import tempfile
import time
from datetime import datetime, timedelta
from pathlib import Path


#: Goal-by-goal evaluation costs one store query per solution of the goals before; on the
#: 10,000-action NEEM it takes minutes, so it is timed on a NEEM of this many actions.
STEPWISE_ACTIONS = 1000


def _neem(store, onto, n_actions: int, neem_id: str = "bench") -> None:
    from oracle.neem.writer import NeemLogger

    log = NeemLogger.create(store, onto, user="bench", neem_id=neem_id, commit_every=500)
    tasks = ["pick(apple)", "pour(thermos, green_mug)", "pick(banana)", "open(fridge)"]
    for obj in ("apple", "thermos", "green_mug", "banana", "fridge"):
        log.perceive(obj, datetime(2024, 1, 1, 6))
    t = datetime(2024, 1, 1, 7)
    for i in range(n_actions):
        if i % 10 == 0:
            log.available(tasks[:3], t)
            log.preference([(tasks[(i // 10) % 3], 0.1), (tasks[(i // 10 + 1) % 3], 0.5)], t)
        log.action(tasks[i % 3], t + timedelta(seconds=1), t + timedelta(seconds=5))
        t += timedelta(seconds=10)
    log.flush()


def _time(fn, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def run(quick: bool = False) -> list[dict]:
    from oracle.bridge import Bridge
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    n = 1000 if quick else 10000
    rows: list[dict] = []
    onto = build_ontology()
    with tempfile.TemporaryDirectory() as tmp:
        store = open_store(Path(tmp) / "bench.sqlite")
        start = time.perf_counter()
        _neem(store, onto, n)
        print(f"logged a {n}-action NEEM in {time.perf_counter() - start:.1f} s")
        bridge = Bridge(store, "bench", onto)

        calls = 2000
        t = _time(lambda: bridge.query(f"forall(between(1, {calls}, _), \\+ neem_store:store_match([t(x, y, _)], any))"))
        per = t / calls * 1e6
        print(f"Prolog->Python->store round trip (1-pattern store_match, no answer):{per:8.1f} us")
        rows.append({"area": "prolog", "name": "crossing", "us_per_call": per})
        t = _time(lambda: bridge.query("true"), 50) * 1e6
        print(f"Python->Prolog query('true'):                                      {t:8.1f} us")
        rows.append({"area": "prolog", "name": "python_to_prolog", "us_per_call": t})

        goal = ("executes_task(A, T), instance_of(T, odb:pick), has_participant(A, O),"
                " has_time_interval(A, I), has_interval_begin(I, B)")
        small = min(n, STEPWISE_ACTIONS)
        if small < n:
            _neem(store, onto, small, "bench-small")
        for label, stepwise, neem, size in (("compiled (one query)", False, "bench", n),
                                            ("compiled (one query)", False, "bench-small", small),
                                            ("goal-by-goal", True, "bench-small", small)):  # fmt: skip
            if neem == "bench-small" and small == n:
                neem = "bench"
                if not stepwise:
                    continue
            b = bridge if neem == "bench" else Bridge(store, neem, onto)
            result: list = []
            t = _time(lambda: result.append(len(b.solutions(goal, ["A", "O", "B"], stepwise=stepwise))), 1)
            print(f"5-goal conjunction, {label:22s} on {size:,} actions: {t * 1000:8.1f} ms  ({result[-1]} solutions)")
            rows.append({"area": "prolog", "name": f"conjunction {label}", "ms": t * 1000,
                         "solutions": result[-1], "actions": size})
        bridge = Bridge(store, "bench", onto)

        latest = bridge.query("aggregate_all(max(B), odb_decisions:decision(situation, _, B), M)")[0]["M"]
        for label, at in (("lately", None), ("at a time", latest - 1000)):
            t = _time(lambda: bridge.why_not("pick", ["banana"], at), 3)
            print(f"why_not(pick(banana)) {label:10s}: {t * 1000:8.1f} ms (target < 100 ms)")
            rows.append({"area": "prolog", "name": f"why_not {label}", "ms": t * 1000, "actions": n})
        bridge.close()
        store.close()
    return rows
