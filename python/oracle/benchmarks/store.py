"""Store figures: logging throughput into the embedded store, export/load of a 10,000-action NEEM."""

from __future__ import annotations

import random
import shutil
import tempfile
import time
from datetime import datetime, timedelta, timezone
from pathlib import Path

from oracle.chains import TaskCall


def _calls(onto, rng: random.Random, n: int) -> list[TaskCall]:
    """Random but valid calls: each task with as many afforded objects as it takes."""
    objects = sorted(name for name, obj in onto.objects.items() if not obj.abstract)
    calls: list[TaskCall] = []
    tasks = sorted(onto.tasks)
    while len(calls) < n:
        task = rng.choice(tasks)
        arity = 2 if onto.tasks[task].ref_role and onto.tasks[task].target_role else 1
        calls.append(TaskCall(task, tuple(rng.sample(objects, arity))))
    return calls


def _log(logger, rng: random.Random, pool: list[TaskCall], count: int) -> float:
    moment = datetime(2024, 3, 1, 7, 0, tzinfo=timezone.utc)
    t0 = time.perf_counter()
    for _ in range(count):
        end = moment + timedelta(seconds=rng.uniform(3, 15))
        logger.action(rng.choice(pool), moment, end, available=rng.sample(pool, 20))
        moment = end + timedelta(seconds=rng.choice((2, 5, 30)))
    logger.flush()
    return time.perf_counter() - t0


def run(quick: bool = False) -> list[dict]:
    from oracle.logger import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store.dump import export_neem, load_dump
    from oracle.store.sqlite import SQLiteStore
    from oracle.store.tbox import tbox_from_graph

    onto = build_ontology()
    tbox = tbox_from_graph(onto.graph)
    rng = random.Random(7)
    pool = _calls(onto, rng, 60)
    n_actions = 1_000 if quick else 10_000
    rows: list[dict] = []
    work = Path(tempfile.mkdtemp(prefix="neem-bench-"))
    try:
        store = SQLiteStore(work / "bench.sqlite")
        for commit_every, count in ((1, n_actions // 5), (100, n_actions)):
            logger = NeemLogger.create(store, onto, user=f"bench-{commit_every}", tbox=tbox, commit_every=commit_every)
            elapsed = _log(logger, rng, pool, count)
            rate = count / elapsed
            triples = store.count(logger.neem_id)
            print(f"logging: {count} actions (roles, times, 20 available tasks each), commit every {commit_every}:"
                  f" {elapsed:.2f} s = {rate:,.0f} actions/s; NEEM has {triples:,} triples")  # fmt: skip
            rows.append({"area": "store", "name": f"logging_actions_per_s_commit_{commit_every}",
                         "value": round(rate, 1), "actions": count, "triples": triples})  # fmt: skip

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
    return rows
