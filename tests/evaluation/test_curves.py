"""Learning curves: pooled smoothing, and a curve that covers the whole of the longest history."""

import numpy as np
import pytest

from oracle.evaluation.curves import half_window, learning_curves, smooth
from oracle.evaluation.replay import Outcome


def test_smoothing_pools_hits_over_predictions():
    hits = np.array([1.0, 0.0, 2.0, 0.0])
    counts = np.array([1.0, 1.0, 2.0, 0.0])
    # position 2 pools positions 1..3: (0 + 2 + 0) / (1 + 2 + 0); position 1 pools 0..2: 3 / 4
    assert smooth(hits, counts, 1) == pytest.approx([0.5, 0.75, 2 / 3, 1.0])


def test_curves_cover_the_whole_history_of_the_longest_user():
    outcomes = [Outcome("a", i, 4, True, {"m": 1}, {"m": 0.0}) for i in range(300)]
    outcomes += [Outcome("b", i, 4, True, {"m": 3}, {"m": 0.0}) for i in range(10)]
    curves, chance = learning_curves(outcomes, ["m"], k=1)
    assert len(curves["m"].positions) == 300 and curves["m"].positions[-1] == 300
    assert list(chance.users[:10]) == [2] * 10 and chance.users[-1] == 1
    assert curves["m"].accuracy[-1] == 1.0 and curves["m"].accuracy[0] == pytest.approx(0.5)
    assert chance.accuracy == pytest.approx(np.full(300, 0.25))
    assert half_window(300) == 6
