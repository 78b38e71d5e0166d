"""The predicted chains on the benchmark's synthetic histories: a digest of what they are (to show
a cheaper copy of the model gives the same chains) and their median time, for the pooled
predictor and for the default, the personal predictor with the bench's shared prior.

Usage: python experiments/chain-check.py [SIZE ...]   (default 300 1000 10000)
For each size N: the predictor fitted on the first N steps of a history of
`oracle.benchmarks.algorithm` (seed N; the personal one with `bench_data`'s prior of other users of
the same world, made here so that older code runs it) ranks each of the next 30 steps' offers and chains ahead of it
(`oracle.algorithm.chaining.chain_ahead`, the offers that followed each option before); printed:
N, the predictor, the median ms of a chain, and the first 12 hex digits of the SHA-256 of the
chains' texts. To run the code of another commit, put its `python` folder first on PYTHONPATH
(the pooled digests need only `history`, which every commit since 9ec0755 has).
"""

from __future__ import annotations

import hashlib
import sys
import time
from typing import Any

import numpy as np

from oracle.algorithm.chaining import Afterwards, chain_ahead
from oracle.algorithm.pooled import PooledOracle
from oracle.benchmarks.algorithm import history


def check(size: int, personal: bool = False) -> tuple[float, str]:
    """The median ms of a chain and the digest of 30 chains after ``size`` steps."""
    model: Any
    if personal:
        from oracle.algorithm.personal import PersonalOracle
        from oracle.algorithm.prior import IDLE, option_key
        from oracle.algorithm.prior_counts import Population

        # benchmarks.algorithm.bench_data's prior, made here so that older code runs it too
        matrix, steps = history(size + 200 + 5 * 2000, seed=size)
        prefix, queries, others = steps[:size], steps[size:size + 200], steps[size + 200:]
        population = Population()
        for user in range(5):
            part = others[user * 2000:(user + 1) * 2000]
            population.add(user, [[IDLE if step.idle else option_key(step.option) for step in part]])
        model = PersonalOracle(matrix).use_prior(population.prior(k=5)).fit(prefix)
    else:
        matrix, steps = history(size + 200, seed=size)
        prefix, queries = steps[:size], steps[size:]
        model = PooledOracle(matrix).fit(prefix)
    afterwards = Afterwards(prefix)
    length = 1 + int(model.event_horizon_forward)
    times, chains = [], []
    for query in queries[:30]:
        ranking = model.rank(query, tree_roots=0)
        start = time.perf_counter()
        # the pooled chains as first checked (no clock); the personal ones at the decision's time, as the service chains
        at = query.time if personal else None
        chains.append(chain_ahead(model, ranking, query.options, afterwards, query.time_of_day, at, length))
        times.append((time.perf_counter() - start) * 1000.0)
    return float(np.median(times)), hashlib.sha256(repr(chains).encode()).hexdigest()[:12]


def main(argv: list[str]) -> None:
    for size in [int(a) for a in argv] or [300, 1000, 10000]:
        for personal in (False, True):
            median, digest = check(size, personal)
            print(f"{size:>6} steps, {'personal' if personal else 'pooled  '}: chain {median:.2f} ms (median of 30),"
                  f" digest {digest}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
