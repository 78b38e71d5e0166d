"""Learning curves: accuracy against the position of a prediction in its user's history.

Position i pools the i-th prediction of every user who has one. The curve is smoothed by pooling
a centred window of positions (hits over predictions, so positions few users reach weigh little),
and runs over the whole history, up to the longest user's last prediction.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from oracle.evaluation.baselines import chance_hit
from oracle.evaluation.replay import Outcome


@dataclass(frozen=True)
class Curve:
    positions: np.ndarray  # 1-based position of the prediction in the user's history
    accuracy: np.ndarray   # smoothed accuracy at each position
    users: np.ndarray      # how many users have a prediction at that position


def half_window(length: int) -> int:
    """Half-width of the smoothing window: 2 % of the longest history, at least 2 positions."""
    return max(2, round(length / 50))


def smooth(hits: np.ndarray, counts: np.ndarray, half: int) -> np.ndarray:
    """Pooled moving average: sum of hits over sum of counts in [i - half, i + half]."""
    kernel = np.ones(2 * half + 1)
    num = np.convolve(hits, kernel, mode="same")
    den = np.convolve(counts, kernel, mode="same")
    return np.divide(num, den, out=np.zeros_like(num), where=den > 0)


def learning_curves(outcomes: Sequence[Outcome], methods: Sequence[str], k: int,
                    half: int | None = None) -> tuple[dict[str, Curve], Curve]:
    """Smoothed Top-k curves of each method and of chance over the whole history."""
    length = 1 + max((o.index for o in outcomes), default=-1)
    counts = np.zeros(length)
    chance = np.zeros(length)
    hits = {name: np.zeros(length) for name in methods}
    for o in outcomes:
        counts[o.index] += 1
        chance[o.index] += chance_hit(k, o.n_candidates, o.truth_offered)
        for name in methods:
            rank = o.ranks[name]
            if rank is not None and rank <= k:
                hits[name][o.index] += 1
    half = half_window(length) if half is None else half
    positions = np.arange(1, length + 1)
    curves = {name: Curve(positions, smooth(h, counts, half), counts) for name, h in hits.items()}
    return curves, Curve(positions, smooth(chance, counts, half), counts)


__all__ = ["Curve", "half_window", "learning_curves", "smooth"]
