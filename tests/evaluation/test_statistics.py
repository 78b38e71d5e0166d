"""Paired statistics: Holm by hand, Wilcoxon against scipy, the bootstrap on cases with known answers."""

import numpy as np
import pytest
from scipy.stats import wilcoxon

from oracle.evaluation.replay import Outcome
from oracle.evaluation.statistics import BLOCK, MIN_USERS, bootstrap_interval, compare, holm, units_of, wilcoxon_p


def outcome(user, index, a, b):
    return Outcome(user, index, 10, True, {"a": a, "b": b}, {"a": 0.0, "b": 0.0})


def test_holm_by_hand():
    # sorted 0.005 0.01 0.03 0.04 -> x4 x3 x2 x1 = 0.02 0.03 0.06 0.04, made monotone: 0.02 0.03 0.06 0.06
    assert holm([0.01, 0.04, 0.03, 0.005]) == pytest.approx([0.03, 0.06, 0.06, 0.02])
    assert holm([0.5, 0.9]) == pytest.approx([1.0, 1.0])
    assert holm([]) == []


def test_wilcoxon_drops_zero_differences_and_matches_scipy():
    d = np.array([0.1, -0.05, 0.2, 0.0, 0.3, 0.15, -0.02, 0.25])
    assert wilcoxon_p(d) == pytest.approx(wilcoxon(d[d != 0]).pvalue)
    assert wilcoxon_p(np.zeros(5)) == 1.0


def test_bootstrap_of_two_equal_units_spans_both():
    # units of equal size with differences 0.1 and 0.3: resampled means are 0.1, 0.2 or 0.3
    low, high = bootstrap_interval(np.array([1.0, 3.0]), np.array([10.0, 10.0]), seed=1)
    assert (low, high) == pytest.approx((0.1, 0.3))
    # a constant difference has a zero-width interval, and the seed makes it reproducible
    assert bootstrap_interval(np.array([2.0] * 5), np.array([10.0] * 5), seed=3) == pytest.approx((0.2, 0.2))
    diffs, sizes = np.arange(6.0), np.full(6, 9.0)
    assert bootstrap_interval(diffs, sizes, 5) == bootstrap_interval(diffs, sizes, 5)


def test_units_are_users_or_blocks_of_one_users_predictions():
    many = [outcome(f"u{i}", j, 1, 2) for i in range(MIN_USERS) for j in range(3)]
    assert units_of(many, ["a", "b"]).kind == "user"
    assert len(units_of(many, ["a", "b"]).labels) == MIN_USERS
    one = [outcome("solo", j, 1, 2) for j in range(2 * BLOCK + 1)]
    units = units_of(one, ["a", "b"])
    assert len(units.labels) == 3 and list(units.sizes) == [BLOCK, BLOCK, 1]
    assert list(units.hits[("a", 1)]) == [BLOCK, BLOCK, 1] and list(units.hits[("b", 1)]) == [0, 0, 0]


def test_a_method_better_on_every_user_has_an_interval_above_zero():
    outcomes = []
    for i in range(12):
        for j in range(20):
            better = 1 if j % 4 else 2      # a: top-1 three times in four
            worse = 1 if j % 4 == 0 or (i % 3 == 0 and j % 4 == 1) else 4
            outcomes.append(outcome(f"u{i}", j, better, worse))
    _, found = compare(outcomes, "b", ["a"], seed=0)
    top1 = next(c for c in found if c.k == 1)
    pooled = (sum(o.ranks["a"] == 1 for o in outcomes) - sum(o.ranks["b"] == 1 for o in outcomes)) / len(outcomes)
    assert top1.difference == pytest.approx(pooled)
    assert 0 < top1.low <= top1.difference <= top1.high
    assert top1.p < 0.01 and top1.p_holm == top1.p  # a family of one comparison
    top5 = next(c for c in found if c.k == 5)
    assert top5.difference == 0 and top5.p == 1.0


def test_cold_start_uses_only_each_users_first_predictions():
    from oracle.evaluation.replay import ReplayResult
    from oracle.evaluation.statistics import cold_start_summary

    # a is right only late in the history, b only early
    outcomes = [outcome(f"u{i}", j, 1 if j >= 30 else 5, 1 if j < 30 else 5) for i in range(MIN_USERS) for j in range(40)]
    cold = cold_start_summary(ReplayResult(outcomes))
    assert cold["n_predictions"] == 30 * MIN_USERS
    assert cold["methods"]["a"]["top1"] == 0.0 and cold["methods"]["b"]["top1"] == 1.0
    paired = cold["comparisons"]["methods"]["b"]["top1"]
    assert paired["difference"] == 1.0 and paired["low"] == paired["high"] == 1.0
