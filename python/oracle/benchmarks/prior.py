"""The shared prior: ``prior build`` over 100 shared NEEMs of 10,000 actions each (quick: 10 of
1,000), and the default's rank (its ranking and re-ranked chain) with a prior against without.

The store: one NEEM of the kitchen's calls logged by the import (a pause every 20 actions, so idle
actions are counted too), then copied into NEEMs of their own users by one SQL insert each (the
same triples: the count's work does not depend on what the sequence is), each shared. Timed:
``build_prior`` with k 5 and epsilon 1 as ``prior build`` runs it (wall and CPU seconds); the floor,
measured in the same run: one SQL statement reading every triple row of the same NEEMs once
(``SELECT total(since)`` over each table: a column no index holds), what no count over them can
do without.

Rank: the default predictor fitted on a persona's history of 2,000 steps with the prior built
from 40 other personas' chains (as ``evaluate --population loo`` builds one), against the same
without a prior, interleaved; each figure min/median/max of ``REPEAT`` runs of 30 decisions, in CPU
seconds (on a shared machine the wall time is mostly waiting for a core).
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.figures import spread, spread_text

REPEAT = 5
NEEMS, ACTIONS = 100, 10_000
QUICK_NEEMS, QUICK_ACTIONS = 10, 1_000


def _chains(path: Path, actions: int, seed: int = 0) -> None:
    calls = ["pick(red_mug)", "place(red_mug, counter_top)", "pick(apple)", "eat(apple)", "open(fridge)",
             "pick(thermos)", "pour(thermos, red_mug)", "drink_from(red_mug)", "pick(bread)", "turn_on(tap)"]
    rng = random.Random(seed)
    rows, clock = [], 1_700_000_000.0
    for i in range(actions):
        rows.append({"user": "bench", "time": time.strftime("%Y-%m-%dT%H:%M:%S", time.gmtime(clock)), "duration": 5,
                     "action": calls[(i + (rng.random() < 0.3)) % len(calls)]})
        clock += 3600.0 if i % 20 == 19 else 10.0
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))


def _store(folder: Path, neems: int, actions: int) -> Path:
    from oracle.neem.importing import import_chains
    from oracle.neem.sharing import set_shared
    from oracle.ontology import build_ontology
    from oracle.store import open_store
    from oracle.store.sqlite.tables import neem_table

    chains = folder / "c.jsonl"
    _chains(chains, actions)
    path = folder / "s.sqlite"
    onto = build_ontology()
    with open_store(path) as store:
        (first,) = import_chains(store, onto, chains, commit_every=1000)
        set_shared(store, first, True)
        for n in range(1, neems):
            copy = f"bench-{n}"
            store.create_neem(copy, user=f"user-{n}")
            with store.transaction():
                store._conn.execute(f"INSERT INTO {neem_table(copy, 'triples')} "  # type: ignore[attr-defined]
                                    f"SELECT * FROM {neem_table(first, 'triples')}")
            set_shared(store, copy, True)
    return path


def _build(path: Path) -> tuple[float, float, int]:
    from oracle.neem.sharing import build_prior
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    onto = build_ontology()
    with open_store(path, read_only=True) as store:
        wall, cpu = time.perf_counter(), time.process_time()
        prior = build_prior(store, onto, 5, 1.0, 3)
        return time.perf_counter() - wall, time.process_time() - cpu, prior.cells()


def _scan(path: Path) -> tuple[float, float]:
    from oracle.store import open_store
    from oracle.store.sqlite.tables import neem_table

    with open_store(path, read_only=True) as store:
        tables = [neem_table(info.id, "triples") for info in store.neems()]
        # ``since`` is in no index: every row of every table is read
        sql = " + ".join(f"(SELECT total(since) FROM {t})" for t in tables)
        wall, cpu = time.perf_counter(), time.process_time()
        store._conn.execute(f"SELECT {sql}").fetchone()  # type: ignore[attr-defined]
        return time.perf_counter() - wall, time.process_time() - cpu


def _rank_figures(folder: Path, quick: bool) -> dict[str, dict[str, float]]:
    import dataclasses

    from oracle.algorithm.chaining import Afterwards, chain_ahead
    from oracle.algorithm.personal import PersonalOracle
    from oracle.calls import option_of, step_of
    from oracle.evaluation.population import leave_one_out
    from oracle.evaluation.replay import load_users
    from oracle.ontology import build_ontology
    from oracle.algorithm.predictors import DEFAULT, make_predictor
    from oracle.calls import opening_tasks
    from oracle.timeline import seconds_of, time_of_day

    subprocess.run([sys.executable, "-m", "oracle", "generate", "--personas", "41", "--days", "3" if quick else "60",
                    "--seed", "5", "--out", str(folder / "gen")], check=True, capture_output=True)
    users = load_users(folder / "gen")
    onto = build_ontology()
    name = max(users, key=lambda u: len(users[u]))
    prior = leave_one_out(onto, users)(name)
    timed = [(row, row.time) for row in users[name][:2000] if row.time is not None]
    steps = [dataclasses.replace(step_of(onto, row.action, row.available or ()), time_of_day=time_of_day(when),
                                 time=seconds_of(when)) for row, when in timed]
    history, later = steps[: len(steps) - 30], timed[len(steps) - 30:]
    models: dict[str, PersonalOracle] = {}
    for label, shared in (("with", prior), ("without", None)):
        model = make_predictor(DEFAULT, onto.distances(), opening_tasks(onto))
        assert isinstance(model, PersonalOracle)
        models[label] = model.use_prior(shared).fit(history)
    afterwards = Afterwards(history)
    times: dict[str, list[float]] = {"with": [], "without": []}
    for _ in range(REPEAT):
        for label, model in models.items():
            started = time.process_time()  # CPU: a shared machine's wall time is mostly waiting
            for row, when in later:
                offer = [option_of(onto, call) for call in row.available or (row.action,)]
                at, part = seconds_of(when), time_of_day(when)
                ranking = model.rank(offer, part, tree_roots=0, at=at)
                chain_ahead(model, ranking, offer, afterwards, part, at, 5)
            times[label].append((time.process_time() - started) / len(later))
    return {label: spread(values) for label, values in times.items()}


def run(quick: bool = False) -> list[dict[str, Any]]:
    neems, actions = (QUICK_NEEMS, QUICK_ACTIONS) if quick else (NEEMS, ACTIONS)
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        started = time.perf_counter()
        path = _store(folder, neems, actions)
        print(f"store of {neems} shared NEEMs x {actions:,} actions made in {time.perf_counter() - started:.0f} s "
              "(untimed)", flush=True)
        builds = [_build(path) for _ in range(3)]
        scans = [_scan(path) for _ in range(3)]
        build, scan = spread([b[0] for b in builds]), spread([s[0] for s in scans])
        build_cpu, scan_cpu = spread([b[1] for b in builds]), spread([s[1] for s in scans])
        print(f"prior build, {neems} NEEMs x {actions:,} actions (k 5, epsilon 1; {builds[0][2]} counts): "
              f"{spread_text(build)} s wall, {spread_text(build_cpu)} s CPU; floor, one read of every triple: "
              f"{spread_text(scan)} s wall, {spread_text(scan_cpu)} s CPU", flush=True)
        rows.append({"area": "prior", "name": "prior_build_s", "value": round(build["median"], 3),
                     "cpu": round(build_cpu["median"], 3), "neems": neems, "actions": actions,
                     "floor_s": round(scan["median"], 3)})
        ranked = _rank_figures(folder, quick)
        ratio = ranked["with"]["median"] / ranked["without"]["median"]
        print(f"rank + chain with a prior: {spread_text(ranked['with'], 1000)} ms CPU, without: "
              f"{spread_text(ranked['without'], 1000)} ms CPU per decision (median ratio {ratio:.3f})", flush=True)
        rows.append({"area": "prior", "name": "rank_with_prior_ms", "value": round(ranked["with"]["median"] * 1000, 3),
                     "without_ms": round(ranked["without"]["median"] * 1000, 3), "ratio": round(ratio, 3)})
    return rows
