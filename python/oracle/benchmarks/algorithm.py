"""Benchmark of the predictors: time per prediction of the thesis oracle's ``fast`` and ``reference``
and of the personal predictor, the default (with a shared prior of other users of the same
synthetic world, ``bench_data``), the pooled one and the routine predictor they build on (median
<= 1 ms at 300, <= 20 ms at 10,000); the predicted chain of the personal and pooled ones
(``perso chain``, ``poole chain``: <= 5 ms at 10,000).

Synthetic histories of 100 to 10,000 steps with ~20 available options per situation, over a
random 90-class taxonomy whose distances follow thesis eq. 4.5; a routine-like Markov chain over
60 world states decides what is available and what is done. Times are per ``rank`` call (with the
forward tree of the best option), the fastest of 3 runs per query for ``fast``; ``partial_fit``
rows time adding one step.
"""

from __future__ import annotations

import math
import time
import tracemalloc
from collections.abc import Callable, Iterable, Sequence
from typing import Any, Protocol

import numpy as np

from oracle.algorithm.chaining import Afterwards, chain_ahead
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS
from oracle.algorithm.reference import ReferenceOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.prior import Prior
from oracle.algorithm.stacked import StackedOracle
from oracle.algorithm.records import Option, Ranking, Step
from oracle.ontology.distance import DistanceMatrix
from oracle.timeline import part_of_day_at

NS = "https://example.org/bench#"
SETTINGS = ("recommended", "no_situations")


def taxonomy(rng: np.random.Generator, n_tasks: int = 30, n_objects: int = 60) -> tuple[DistanceMatrix, list[str], list[str]]:
    """Two random trees (tasks, objects) under one root; distance log(path * CSpec + 1) (eq. 4.5)."""
    names = ["Thing"]
    parent = [-1]
    leaves: dict[str, list[str]] = {"Task": [], "Object": []}
    for kind, count in (("Task", n_tasks), ("Object", n_objects)):
        top = len(names)
        names.append(kind)
        parent.append(0)
        groups = []
        for g in range(max(2, count // 6)):
            groups.append(len(names))
            names.append(f"{kind}Group{g}")
            parent.append(top)
        for i in range(count):
            names.append(f"{kind}{i}")
            parent.append(int(rng.choice(groups)))
            leaves[kind].append(NS + names[-1])
    n = len(names)
    ancestors = []
    for i in range(n):
        chain, node = [], i
        while node >= 0:
            chain.append(node)
            node = parent[node]
        ancestors.append(chain)
    depth_total = max(len(a) for a in ancestors)
    values = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1, n):
            common = next(a for a in ancestors[i] if a in ancestors[j])
            path = ancestors[i].index(common) + ancestors[j].index(common)
            cspec = 1 - len(ancestors[common]) / depth_total
            values[i, j] = values[j, i] = math.log(path * cspec + 1)
    return DistanceMatrix.from_values(tuple(NS + name for name in names), values), leaves["Task"], leaves["Object"]


#: The histories' clock: when the first step begins, and the time from one step to the next.
START_S, STEP_S = 1_700_000_000.0, 540.0


def history(n: int, seed: int = 0, n_options: int = 20, n_states: int = 60) -> tuple[DistanceMatrix, list[Step]]:
    rng = np.random.default_rng(seed)
    matrix, tasks, objects = taxonomy(rng)
    idle_task = tasks[0]
    def option() -> Option:
        kind = rng.integers(0, 3)
        target = objects[rng.integers(len(objects))] if kind >= 1 else None
        reference = objects[rng.integers(len(objects))] if kind == 2 else None
        return Option(tasks[1 + rng.integers(len(tasks) - 1)], target, reference)
    states = [tuple(dict.fromkeys(option() for _ in range(n_options))) for _ in range(n_states)]
    favourite = rng.integers(0, n_options, size=(n_states, 4))
    steps: list[Step] = []
    state = 0
    for i in range(n):
        options = states[state]
        begin = START_S + i * STEP_S  # a clock, a step every 9 min
        tod = part_of_day_at(begin)  # its part of day as the logger records it (the clock's UTC wall clock)
        if rng.random() < 0.05:
            steps.append(Step(idle_task, None, None, options, tod, True, "idle", begin))
            state = int(rng.integers(n_states))
            continue
        pick = favourite[state, rng.integers(4)] if rng.random() < 0.8 else rng.integers(n_options)
        chosen = options[int(pick) % len(options)]
        steps.append(Step(chosen.task, chosen.target, chosen.reference, options, tod, False, str(chosen), begin))
        state = (state * 5 + int(pick) + 1) % n_states
    return matrix, steps


#: The shared prior of the bench: this many other users of the same synthetic world, each
#: ``PRIOR_STEPS`` steps of it after the queries, counted as ``prior build`` counts (k = users).
PRIOR_USERS, PRIOR_STEPS = 5, 2000


def bench_data(size: int, queries: int) -> tuple[DistanceMatrix, list[Step], list[Step], Prior]:
    """The history of ``size`` steps (seed ``size``), the ``queries`` steps after it, and the
    shared prior counted from ``PRIOR_USERS`` other users of the same world (the steps after the
    queries, one slice each: what the personal predictor, the default, ranks with)."""
    from oracle.algorithm.prior import IDLE, option_key
    from oracle.algorithm.prior_counts import Population

    matrix, steps = history(size + queries + PRIOR_USERS * PRIOR_STEPS, seed=size)
    others = steps[size + queries:]
    population = Population()
    for user in range(PRIOR_USERS):
        part = others[user * PRIOR_STEPS:(user + 1) * PRIOR_STEPS]
        population.add(user, [[IDLE if step.idle else option_key(step.option) for step in part]])
    return matrix, steps[:size], steps[size:size + queries], population.prior(k=PRIOR_USERS)


class _Ranker(Protocol):
    """What the timing loops need of an oracle: the reference one has no partial_fit."""

    def fit(self, history: Iterable[Step]) -> Any: ...

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None) -> Ranking: ...


def _times(oracle: _Ranker, queries: Sequence[Step], repeats: int = 1) -> list[float]:
    """Milliseconds per query: the fastest of ``repeats`` runs, so that other processes on a
    shared machine do not show up as the algorithm's tail latency."""
    out = []
    for query in queries:
        best = math.inf
        for _ in range(repeats):
            start = time.perf_counter()
            oracle.rank(query, tree_roots=1)
            best = min(best, time.perf_counter() - start)
        out.append(best * 1000.0)
    return out


def floor_counts(steps: Sequence[Step]) -> tuple[dict[Option, int], dict[tuple[int, ...], dict[int, int]]]:
    """The work of the fits' floor (``fit_floor_ms``): each action interned (idle: -1) and counted
    after its context of up to 3 earlier tokens; the interned ids and the counts."""
    ids: dict[Option, int] = {}
    counts: dict[tuple[int, ...], dict[int, int]] = {}
    recent: tuple[int, ...] = ()
    for step in steps:
        token = -1 if step.idle else ids.setdefault(step.option, len(ids))
        followers = counts.setdefault(recent, {})
        followers[token] = followers.get(token, 0) + 1
        recent = (*recent[-2:], token)
    return ids, counts


def fit_floor_ms(steps: Sequence[Step], runs: int = 3) -> float:
    """The fits' floor, measured in the same run: milliseconds (the fastest of ``runs``) of one
    plain-Python pass over ``steps`` that does the least a per-user counting fit does
    (``floor_counts``: an order-3 n-gram's fit). A fit's figure over its floor says how much of
    it is the machine and how much the predictor."""
    best = math.inf
    for _ in range(runs):
        start = time.perf_counter()
        floor_counts(steps)
        best = min(best, time.perf_counter() - start)
    return best * 1000.0


def _peak_mb(make: Callable[[], _Ranker], prefix: Sequence[Step], queries: Sequence[Step]) -> float:
    tracemalloc.start()
    oracle = make().fit(prefix)
    for query in queries[:3]:
        oracle.rank(query, tree_roots=1)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


def run(quick: bool = False) -> list[dict[str, Any]]:
    sizes = (100, 300) if quick else (100, 300, 1000, 10000)
    reference_queries = {100: 5, 300: 3} if quick else {100: 10, 300: 5, 1000: 3}
    fast_queries = 40 if quick else 200
    rows: list[dict[str, Any]] = []
    print(f"{'history':>8} {'settings':<14} {'impl':<10} {'median ms':>10} {'p99 ms':>9} {'peak MB':>8} {'ratio':>7}")
    for size in sizes:
        matrix, prefix, queries, prior = bench_data(size, fast_queries)  # = history(size + fast_queries, seed=size)
        for name in SETTINGS:
            settings = PRESETS[name].to_dict()
            found = {}
            for impl, cls, count in (("fast", PreferenceOracle, fast_queries),
                                     ("reference", ReferenceOracle, reference_queries.get(size, 0))):
                if count == 0:
                    continue
                oracle = cls(matrix, **settings).fit(prefix)
                oracle.rank(queries[0], tree_roots=1)  # warm caches of numpy and Python
                times = _times(oracle, queries[:count], 3 if impl == "fast" else 1)
                found[impl] = median = float(np.median(times))
                p99 = float(np.percentile(times, 99))
                peak = _peak_mb(lambda: cls(matrix, **settings), prefix, queries)
                rows.append({"area": "algorithm", "name": "rank", "history": size, "impl": impl,
                             "settings": name, "median_ms": round(median, 4), "p99_ms": round(p99, 4),
                             "peak_mb": round(peak, 2)})
                ratio = f"{found['reference'] / found['fast']:.0f}x" if impl == "reference" else ""
                print(f"{size:>8} {name:<14} {impl:<10} {median:>10.3f} {p99:>9.3f} {peak:>8.1f} {ratio:>7}", flush=True)
            # adding a step (incremental state) costs this much, once per executed task
            oracle = PreferenceOracle(matrix, **settings).fit(prefix[:-20])
            adds = []
            for step in prefix[-20:]:
                start = time.perf_counter()
                oracle.partial_fit(step)
                adds.append((time.perf_counter() - start) * 1000.0)
            rows.append({"area": "algorithm", "name": "partial_fit", "history": size, "impl": "fast",
                         "settings": name, "median_ms": round(float(np.median(adds)), 4),
                         "p99_ms": round(float(np.percentile(adds, 99)), 4), "peak_mb": None})
            print(f"{size:>8} {name:<14} {'fast add':<10} {np.median(adds):>10.3f} {np.percentile(adds, 99):>9.3f}",
                  flush=True)
        floor_ms = fit_floor_ms(prefix)  # one floor per history, beside each predictor's fit on it
        for learned, impl in ((PersonalOracle, "personal"), (PooledOracle, "pooled"), (RoutineOracle, "routine"),
                              (StackedOracle, "stacked"), (OnlineOracle, "online")):
            rows.extend(_routine_rows(matrix, prefix, queries, fast_queries, size, floor_ms, learned, impl,
                                      prior if learned is PersonalOracle else None))
    return rows


def _routine_rows(matrix: DistanceMatrix, prefix: Sequence[Step], queries: Sequence[Step], count: int, size: int,
                  floor_ms: float, cls: type = RoutineOracle, impl: str = "routine",
                  prior: Prior | None = None) -> list[dict[str, Any]]:
    """The routine predictor (or ``cls``, ``impl``: the personal, pooled, stacked or online one) on the same history and
    queries (its own defaults, self-tuned; the personal one with ``prior``, the bench's shared
    prior): rank, partial_fit and one whole fit, beside the fits' floor on that history
    (``floor_ms``); the predicted chain of the personal and the pooled ones."""

    def make() -> Any:
        return cls(matrix).use_prior(prior) if prior is not None else cls(matrix)

    start = time.perf_counter()
    model = make().fit(prefix)
    fit_ms = (time.perf_counter() - start) * 1000.0
    model.rank(queries[0], tree_roots=1)
    times = _times(model, queries[:count], 3)
    median, p99 = float(np.median(times)), float(np.percentile(times, 99))
    peak = _peak_mb(make, prefix, queries)
    print(f"{size:>8} {'default':<14} {impl:<10} {median:>10.3f} {p99:>9.3f} {peak:>8.1f}   fit {fit_ms:.0f} ms"
          f" (floor {floor_ms:.1f} ms, {fit_ms / floor_ms:.0f}x)",
          flush=True)
    adds = []
    model = make().fit(prefix[:-20])
    for step in prefix[-20:]:  # adding a step also scores the variants on it: one rank
        start = time.perf_counter()
        model.partial_fit(step)
        adds.append((time.perf_counter() - start) * 1000.0)
    print(f"{size:>8} {'default':<14} {impl[:5] + ' add':<10} {np.median(adds):>10.3f} "
          f"{np.percentile(adds, 99):>9.3f}", flush=True)
    chain = _chain_rows(model, prefix, queries, size, impl, median) if cls in (PooledOracle, PersonalOracle) else []
    return chain + [{"area": "algorithm", "name": "rank", "history": size, "impl": impl, "settings": "default",
             "median_ms": round(median, 4), "p99_ms": round(p99, 4), "peak_mb": round(peak, 2)},
            {"area": "algorithm", "name": "partial_fit", "history": size, "impl": impl, "settings": "default",
             "median_ms": round(float(np.median(adds)), 4), "p99_ms": round(float(np.percentile(adds, 99)), 4),
             "peak_mb": None},
            {"area": "algorithm", "name": "fit", "history": size, "impl": impl, "settings": "default",
             "median_ms": round(fit_ms, 1), "p99_ms": None, "peak_mb": None, "floor_ms": round(floor_ms, 2),
             "floor_ratio": round(fit_ms / floor_ms, 1)}]



def _chain_rows(model: Any, prefix: Sequence[Step], queries: Sequence[Step], size: int, impl: str,
                rank_ms: float) -> list[dict[str, Any]]:
    """The predicted chain beside the ranking (oracle.algorithm.chaining): its median time per
    decision over 20 queries, and its floor, one hypothetical copy of the fitted model (what the
    chain must pay before its first re-ranking; its option tables shared until written) plus the
    ranking's own median per step. The pooled chain without the clock (as first measured), the
    personal one, the default, at the decision's time, as the service chains."""
    afterwards = Afterwards(prefix)
    length = 1 + int(model.event_horizon_forward)
    times, copies, steps = [], [], []
    for query in queries[:20]:
        ranking = model.rank(query, tree_roots=0)
        at = query.time if impl == "personal" else None
        start = time.perf_counter()
        chain = chain_ahead(model, ranking, query.options, afterwards, query.time_of_day, at, length)
        times.append((time.perf_counter() - start) * 1000.0)
        steps.append(len(chain))
        start = time.perf_counter()
        model.hypothetical()
        copies.append((time.perf_counter() - start) * 1000.0)
    median, copy = float(np.median(times)), float(np.median(copies))
    floor = copy + rank_ms * (float(np.mean(steps)) - 1)
    print(f"{size:>8} {'default':<14} {impl[:5] + ' chain':<10} {median:>10.3f} {np.percentile(times, 99):>9.3f}"
          f"   {np.mean(steps):.1f} steps; floor {floor:.1f} ms (copy of the model {copy:.1f} ms + rank per step)",
          flush=True)
    return [{"area": "algorithm", "name": "chain", "history": size, "impl": impl, "settings": "default",
             "median_ms": round(median, 4), "p99_ms": round(float(np.percentile(times, 99)), 4), "peak_mb": None,
             "steps": round(float(np.mean(steps)), 2), "floor_ms": round(floor, 3), "copy_ms": round(copy, 3)}]


if __name__ == "__main__":
    run(quick=False)
