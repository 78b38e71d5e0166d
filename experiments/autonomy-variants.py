"""Development replay of the autonomy-mode predictors on the persona tune split (docs/beyond.md,
"Autonomy mode": how the learned predictor was chosen). Each persona's actions are replayed in
order, each mode predicted from the earlier ones only, as ``routines-eval`` does; printed: the
share predicted right by the per-task majority, the weighted contexts, the logit fitted to the
counts at each L2 strength, the logit with a call's own unanimous counts kept at 2, 3 and 5
actions (the call-and-part context alone, or the call's too), and an online AdaGrad logit
(features bias, task, call and part of the day, or with the objects).

usage: python experiments/autonomy-variants.py [--split tune]
Development use only: never run it on the test split to choose.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from oracle.past.autonomy import TIE_ORDER, ModeCounts, Performed, majority  # noqa: E402
from oracle.past.modelogit import fit_modes  # noqa: E402
from oracle.timeline import part_of_day_at, seconds_of  # noqa: E402
from oracle.world.autonomy import modes_of  # noqa: E402
from oracle.world.generate import simulate_entries  # noqa: E402
from oracle.world.personas import make_personas  # noqa: E402
from oracle.world.worldfile import load_world  # noqa: E402

SHRINKS = (1.0, 3.0, 10.0, 20.0, 40.0)
KEPT = ((2, 1), (3, 1), (5, 1), (2, 2), (3, 2), (5, 2))  # (actions, contexts: 1 call and part, 2 also the call)
ONLINE = (("bias task call part", "tcp", 0.1), ("bias task call part", "tcp", 0.3),
          ("bias task objects part", "top", 0.1), ("bias task call objects part", "tcop", 0.1))


class Online:
    """A multinomial logit over one-hot features, one AdaGrad step (L2 0.001) per action."""

    def __init__(self, kinds: str, rate: float) -> None:
        self.kinds, self.rate = kinds, rate
        self.w: dict[str, np.ndarray] = {}
        self.g: dict[str, np.ndarray] = {}

    def features(self, task: str, call: str, objects: tuple[str, ...], part: str) -> list[str]:
        names = ["b"] + ([f"t:{task}"] if "t" in self.kinds else []) + ([f"c:{call}"] if "c" in self.kinds else [])
        return names + ([f"o:{o}" for o in objects] if "o" in self.kinds else []) + [f"p:{part}"]

    def scores(self, names: list[str]) -> np.ndarray:
        return sum((self.w[n] for n in names if n in self.w), np.zeros(len(TIE_ORDER)))

    def predict(self, names: list[str]) -> str:
        s = self.scores(names)
        return TIE_ORDER[int(np.argmax(s >= s.max() - 1e-12))]

    def learn(self, names: list[str], mode: str) -> None:
        s = self.scores(names)
        p = np.exp(s - s.max())
        p /= p.sum()
        for n in names:
            w = self.w.setdefault(n, np.zeros(len(TIE_ORDER)))
            g = self.g.setdefault(n, np.full(len(TIE_ORDER), 1e-8))
            grad = p - (np.array(TIE_ORDER) == mode) + 1e-3 * w
            g += grad * grad
            w -= self.rate * grad / np.sqrt(g)


def kept(counts: ModeCounts, call: str, part: str, actions: int, contexts: int) -> str | None:
    """The mode of the call's own counts where they are unanimous over ``actions`` or more."""
    for _, key in counts.contexts(call, part)[:contexts]:
        seen = counts.counts.get(key)
        if seen:
            total = sum(seen.values())
            top, n = seen.most_common(1)[0]
            return top if total >= actions and n == total else None
    return None


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--split", choices=("tune",), default="tune")
    args = parser.parse_args()
    right: Counter[str] = Counter()
    total = 0
    for persona in make_personas(105, 0):
        if persona.split != args.split:
            continue
        rows, _ = simulate_entries(persona, load_world(), 7, 0)
        counts, by_task = ModeCounts(), {}
        online = [Online(kinds, rate) for _, kinds, rate in ONLINE]
        for row, mode in zip(rows, modes_of(persona, rows, 0)):
            call, task, objects = str(row.action), row.action.task, tuple(row.action.args)
            part = part_of_day_at(seconds_of(row.time)) if row.time else "Midday"
            known = counts.predict(call, part)[1] != "none"
            right["per-task majority"] += (majority(by_task[task]) if task in by_task else "user") == mode
            right["weighted contexts"] += counts.predict(call, part)[0] == mode
            for shrink in SHRINKS:
                guess = fit_modes(counts, shrink).predict(call, part) if known else "user"
                right[f"logit on the counts, L2 {shrink:g}"] += guess == mode
                if shrink == 10.0:
                    for actions, contexts in KEPT:
                        own = kept(counts, call, part, actions, contexts)
                        label = f"L2 10, own mode kept at {actions} ({'call and part' if contexts == 1 else 'or call'})"
                        right[label] += (own or guess) == mode
            for (label, _, rate), model in zip(ONLINE, online):
                names = model.features(task, call, objects, part)
                right[f"online AdaGrad {rate:g}, {label}"] += model.predict(names) == mode
                model.learn(names, mode)
            counts.add(Performed(call, part, mode))
            by_task.setdefault(task, Counter())[mode] += 1
            total += 1
    print(f"{args.split} split: {total} actions")
    for label, n in right.items():
        print(f"  {label:55s} {n / total:.2%}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
