"""Time nltk.lm's interpolated Kneser-Ney against oracle.evaluation.smoothing.KneserNey on one replay.

usage: python experiments/nltk-speed.py CHAINS.jsonl [STEPS]
Replays the first user's first STEPS rows (default 200): before each row both models score the
row's candidates from the earlier actions, then the action is added (nltk: counts.update with the
new n-grams, no refit). Idle gaps are left out here; both models see the same tokens. Prints the
mean milliseconds per prediction of each and checks that they rank alike.
"""

import sys
import time

from nltk.lm import KneserNeyInterpolated

from oracle.algorithm.records import Step
from oracle.evaluation.replay import load_users
from oracle.evaluation.smoothing import KN_DISCOUNT, KneserNey

ORDER = 3


def main() -> None:
    users = load_users(sys.argv[1])
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    rows = next(iter(users.values()))[:steps]
    everyone = sorted({str(r.action) for r in rows} | {str(c) for r in rows for c in (r.available or ())})
    reference = KneserNeyInterpolated(ORDER, discount=KN_DISCOUNT)
    reference.vocab.update(everyone)
    ours = KneserNey(ORDER)
    history: list[str] = []
    spent = {"nltk": 0.0, "ours": 0.0}
    agree = 0
    for row in rows:
        candidates = [str(c) for c in row.available] if row.available else everyone
        start = time.perf_counter()
        try:
            theirs = [reference.score(c, history[-(ORDER - 1):]) if history else 0.0 for c in candidates]
        except ZeroDivisionError:
            theirs = [0.0] * len(candidates)
        spent["nltk"] += time.perf_counter() - start
        start = time.perf_counter()
        mine = ours.probabilities([Step(c).option for c in candidates])
        spent["ours"] += time.perf_counter() - start
        best = range(len(candidates))
        agree += max(best, key=theirs.__getitem__) == max(best, key=mine.__getitem__)
        action = str(row.action)
        history.append(action)
        reference.counts.update([[tuple(history[-n:]) for n in range(1, ORDER + 1) if len(history) >= n]])
        ours.observe(Step(action))
    n = len(rows)
    print(f"{n} predictions, {sum(len(r.available or everyone) for r in rows) / n:.1f} candidates each")
    for name, seconds in spent.items():
        print(f"{name:5s} {1000 * seconds / n:8.3f} ms per prediction")
    print(f"same top candidate in {agree}/{n} predictions")


if __name__ == "__main__":
    main()
