"""What keeping a fit as plain data costs against the pickle it replaced (docs/algorithm.md,
"kept fit"): for synthetic histories of 3,000, 10,000 and 30,000 steps, fits the default
predictor and prints the bytes and the best of three times to write and read it each way, and
whether the read model ranks as the original (before and after extending both).

Usage: python experiments/plainstate-cost.py [--sizes 3000 10000 30000]
"""

from __future__ import annotations

import argparse
import pickle
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "algorithm"))

from algoworld import random_matrix, synthetic_history  # noqa: E402
from oracle import plainstate  # noqa: E402
from oracle.algorithm.params import Hyperparameters  # noqa: E402
from oracle.algorithm.predictors import make_predictor  # noqa: E402
from oracle.fitcache import model_classes  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[3000, 10000, 30000])
    parser.add_argument("--method", default="pooled")
    args = parser.parse_args()
    matrix = random_matrix(5)
    print("steps  plain-bytes  pickle-bytes  plain-write  plain-read  pickle-write  pickle-read (ms)  same")
    for size in args.sizes:
        steps = synthetic_history(size, 5)
        model = make_predictor(args.method, matrix, frozenset(), Hyperparameters()).fit(steps)
        classes = model_classes(model)
        best = [float("inf")] * 4
        for _ in range(3):
            t0 = time.perf_counter()
            plain = plainstate.dumps(model, classes, shared=matrix)
            t1 = time.perf_counter()
            copy = plainstate.loads(plain, classes, shared=matrix)
            t2 = time.perf_counter()
            pickled = pickle.dumps(model, protocol=5)
            t3 = time.perf_counter()
            pickle.loads(pickled)
            t4 = time.perf_counter()
            best = [min(a, b) for a, b in zip(best, (t1 - t0, t2 - t1, t3 - t2, t4 - t3))]
        ranked = lambda m, s: [(t.option, t.probability) for t in m.rank(s)]  # noqa: E731
        more = steps + steps[:50]
        same = ranked(copy, steps[-1]) == ranked(model, steps[-1]) and \
            ranked(copy.extend(more), steps[10]) == ranked(model.extend(more), steps[10])
        print(f"{size:5d}  {len(plain):11d}  {len(pickled):12d}  " + "  ".join(f"{1000 * t:10.1f}" for t in best) + f"  {same}")


if __name__ == "__main__":
    main()
