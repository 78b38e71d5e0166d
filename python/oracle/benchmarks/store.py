"""Store figures: logging throughput into the embedded store, export/load of a 10,000-action NEEM,
and ``import`` of 10,000 and 50,000 actions with the first rank after it (benchmarks.importbench)."""

from __future__ import annotations

import random
import shutil
import tempfile
import time
from datetime import datetime, timedelta, timezone
from pathlib import Path
from typing import TYPE_CHECKING, Any

from oracle.chains import TaskCall

if TYPE_CHECKING:
    from oracle.neem.writer import NeemLogger
    from oracle.ontology.model import OdbOntology
    from oracle.store.base import Store
    from oracle.store.tbox import TBox


def _calls(onto: OdbOntology, rng: random.Random, n: int) -> list[TaskCall]:
    """Random but valid calls: each task with as many afforded objects as it takes."""
    objects = sorted(name for name, obj in onto.objects.items() if not obj.abstract)
    calls: list[TaskCall] = []
    tasks = sorted(onto.tasks)
    while len(calls) < n:
        task = rng.choice(tasks)
        arity = 2 if onto.tasks[task].ref_role and onto.tasks[task].target_role else 1
        calls.append(TaskCall(task, tuple(rng.sample(objects, arity))))
    return calls


WorkItem = tuple[TaskCall, datetime, datetime, list[TaskCall]]


def _workload(rng: random.Random, pool: list[TaskCall], count: int) -> list[WorkItem]:
    """Actions to log, drawn before the clock starts: (call, begin, end, 20 available calls).

    Gaps of 2, 5 or 30 s, so a third of the actions also write an idle action."""
    moment = datetime(2024, 3, 1, 7, 0, tzinfo=timezone.utc)
    steps: list[WorkItem] = []
    for _ in range(count):
        end = moment + timedelta(seconds=rng.uniform(3, 15))
        steps.append((rng.choice(pool), moment, end, rng.sample(pool, 20)))
        moment = end + timedelta(seconds=rng.choice((2, 5, 30)))
    return steps


def _log(logger: NeemLogger, steps: list[WorkItem]) -> float:
    t0 = time.perf_counter()
    for call, begin, end, available in steps:
        logger.action(call, begin, end, available=available)
    logger.flush()
    return time.perf_counter() - t0


def _python_share(store: Store, onto: OdbOntology, tbox: TBox | None, steps: list[WorkItem]) -> float:
    """Microseconds of CPU per action spent outside SQLite's row insert (logger, closures,
    commits of nothing): what the logger and the shared insert path cost, whatever the disk."""
    from oracle.neem.writer import NeemLogger

    logger = NeemLogger.create(store, onto, user="bench-python", tbox=tbox, commit_every=100)
    store._writes._insert_flat = lambda *args: None  # type: ignore[attr-defined] # rows built, never written: this store is not used for anything else
    t0 = time.process_time()
    for call, begin, end, available in steps:
        logger.action(call, begin, end, available=available)
    logger.flush()
    return (time.process_time() - t0) / len(steps) * 1e6


#: (commit_every, label, what a killed process can lose), see docs/store.md "Crash safety".
SETTINGS = (
    (1, "default logger, commit_every=1", "each action durable when action() returns"),
    (100, "grouped commits, commit_every=100", "a crash loses up to the last 100 actions, those not yet committed"),
)


def run(quick: bool = False) -> list[dict[str, Any]]:
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store.dump import export_neem, load_dump
    from oracle.store.sqlite import SQLiteStore
    from oracle.store.tbox import tbox_from_graph

    onto = build_ontology()
    tbox = tbox_from_graph(onto.graph)
    rng = random.Random(7)
    pool = _calls(onto, rng, 60)
    n_actions = 1_000 if quick else 10_000
    rows: list[dict[str, Any]] = []
    work = Path(tempfile.mkdtemp(prefix="neem-bench-"))
    try:
        store = SQLiteStore(work / "bench.sqlite")
        for commit_every, label, durability in SETTINGS:
            count = n_actions // 5 if commit_every == 1 else n_actions
            logger = NeemLogger.create(store, onto, user=f"bench-{commit_every}", tbox=tbox, commit_every=commit_every)
            elapsed = _log(logger, _workload(rng, pool, count))
            rate = count / elapsed
            triples = store.count(logger.neem_id)
            print(f"logging, {label}: {rate:,.0f} actions/s ({count:,} actions with roles, times and 20 available"
                  f" tasks each in {elapsed:.2f} s; NEEM has {triples:,} triples; {durability})")  # fmt: skip
            rows.append({"area": "store", "name": f"logging_actions_per_s_commit_{commit_every}",
                         "value": round(rate, 1), "actions": count, "triples": triples})  # fmt: skip

        scratch = SQLiteStore(work / "python-share.sqlite")
        share = min(_python_share(scratch, onto, tbox, _workload(rng, pool, 2_000)) for _ in range(3))
        scratch.close()
        print(f"logging, Python share (SQLite's row insert left out, CPU time, best of 3): {share:.0f} us per action")
        rows.append({"area": "store", "name": "logging_python_us_per_action", "value": round(share, 1)})

        t0 = time.perf_counter()
        export_neem(store, logger.neem_id, work / "dump")  # the 10,000-action NEEM
        export_s = time.perf_counter() - t0
        target = SQLiteStore(work / "load.sqlite")
        t0 = time.perf_counter()
        load_dump(target, work / "dump", neem_id="loaded")
        load_s = time.perf_counter() - t0
        size = sum(f.stat().st_size for f in (work / "dump").rglob("*.bson"))
        print(f"export of the {n_actions}-action NEEM: {export_s:.2f} s ({size / 1e6:.1f} MB BSON); load: {load_s:.2f} s")
        rows.append({"area": "store", "name": "export_s", "value": round(export_s, 3), "actions": n_actions})
        rows.append({"area": "store", "name": "load_s", "value": round(load_s, 3), "actions": n_actions})
        store.close()
        target.close()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    from oracle.benchmarks import importbench

    return rows + importbench.run(quick)
