"""The learned predictors' fits on the benchmark's synthetic histories: a digest of what they
rank (to show a cheaper fit is the same fit) and the seconds of whole fits at 10,000 steps.

Usage: python experiments/bench-fit.py [--runs 3] [--digest-only]
The digest: `routine`, `pooled`, `online` and `stacked`, each fitted on the first 300, 1,200 and
2,500 steps of a history of `oracle.benchmarks.algorithm` (seeds 1-3), rank the next 10 steps'
offers (with their forward trees), learn the next 20 with `partial_fit` and rank 10 more; the
SHA-256 runs over every ranked option's rank, score and option (and its tree and evidence at
first). The timing: `routine` and `pooled` fitted on 10,000 steps (seed 0), `--runs` times each,
alternating, wall seconds (min and median), beside the fits' floor measured in the same rounds
(an order-3 count pass over the same steps, ``oracle.benchmarks.algorithm.fit_floor_ms``). To
time code from another commit, put its `python` folder first on PYTHONPATH; the script uses only
what both sides export (``fit_floor_ms`` exists from the commit that added it on).
"""

from __future__ import annotations

import argparse
import hashlib
import time
from typing import Any

import numpy as np

from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.stacked import StackedOracle
from oracle.benchmarks.algorithm import fit_floor_ms, history

PREDICTORS: tuple[type[Any], ...] = (RoutineOracle, PooledOracle, OnlineOracle, StackedOracle)


def digest() -> str:
    """SHA-256 of the rankings described in the module docstring."""
    sha = hashlib.sha256()
    for size, seed in ((300, 1), (1200, 2), (2500, 3)):
        matrix, steps = history(size + 40, seed=seed)
        for cls in PREDICTORS:
            model = cls(matrix).fit(steps[:size])
            for query in steps[size:size + 10]:
                ranking = model.rank(query, tree_roots=1)
                sha.update(repr([(t.rank, t.score, t.option, t.n_similar, t.nearest, t.successors)
                                 for t in ranking]).encode())
            for step in steps[size:size + 20]:
                model.partial_fit(step)
            for query in steps[size + 20:size + 30]:
                sha.update(repr([(t.rank, t.score, t.option) for t in model.rank(query, tree_roots=1)]).encode())
    return sha.hexdigest()


def fit_seconds(runs: int) -> dict[str, list[float]]:
    """Wall seconds of whole fits at 10,000 steps, ``runs`` of each predictor, alternating, and
    of the fits' floor (``oracle.benchmarks.algorithm.fit_floor_ms``) after each round."""
    matrix, steps = history(10050, seed=0)
    times: dict[str, list[float]] = {"routine": [], "pooled": [], "floor": []}
    for _ in range(runs):
        for name, cls in (("routine", RoutineOracle), ("pooled", PooledOracle)):
            start = time.perf_counter()
            cls(matrix).fit(steps[:10000])
            times[name].append(time.perf_counter() - start)
        times["floor"].append(fit_floor_ms(steps[:10000], runs=1) / 1000.0)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="whole fits per predictor (default 3)")
    parser.add_argument("--digest-only", action="store_true", help="print the digest only")
    args = parser.parse_args()
    if args.runs < 1:
        parser.error("--runs must be 1 or more")
    print(f"digest {digest()}", flush=True)
    if args.digest_only:
        return
    times = fit_seconds(args.runs)
    floor = float(np.median(times["floor"]))
    for name, seconds in times.items():
        ratio = f", {float(np.median(seconds)) / floor:.0f}x the floor" if name != "floor" else ""
        print(f"{name:8} fit at 10,000 steps: min {min(seconds):.3f} s, median {float(np.median(seconds)):.3f} s"
              f" ({', '.join(f'{s:.3f}' for s in seconds)}){ratio}", flush=True)


if __name__ == "__main__":
    main()
