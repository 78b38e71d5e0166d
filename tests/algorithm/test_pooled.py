"""The pooled predictor: the routine predictor and a per-user conditional logit, pooled log-linearly."""

from __future__ import annotations

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.evidence import features
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.errors import SettingsError
from oracle.evaluation.learned import Evidence, OnlineLogit


def _served(model, steps):
    return [[(t.option, t.probability) for t in model.rank(step)] for step in steps]


def test_all_weight_on_the_routine_predictor_is_the_routine_predictor():
    matrix = random_matrix(0)
    steps = synthetic_history(150, 0)
    pooled = PooledOracle(matrix, pool_weight=1.0, online_gate=None).fit(steps[:120])
    routine = RoutineOracle(matrix).fit(steps[:120])
    assert pooled.learnt_ > 0 and np.any(pooled.coef_) and not pooled.serves()
    for step in steps[120:]:
        assert pooled.rank(step) == routine.rank(step)
    # before its first decision the default serves the routine predictor's ranking
    assert PooledOracle(matrix).fit([]).rank(steps[0]) == RoutineOracle(matrix).fit([]).rank(steps[0])


def test_its_logit_learns_as_the_logit_baseline_does():
    # the same decisions, the same rows: the same weights as the replay's `logit`
    matrix = random_matrix(1)
    steps = synthetic_history(60, 1)
    pooled = PooledOracle(matrix).fit(steps[:40])
    baseline = OnlineLogit(Evidence(matrix, frozenset()))
    rng = np.random.default_rng(0)
    width = pooled.coef_.size
    start = pooled.coef_.copy()
    baseline.w, baseline.g2 = start.copy(), pooled.squared_.copy()
    for _ in range(30):
        x = rng.normal(size=(5, width))
        truth = int(np.argmax(x[:, 3]))
        pooled._learn(x, np.zeros(5), truth)
        baseline.learn(x, truth)
    np.testing.assert_allclose(pooled.coef_, baseline.w)
    assert not np.allclose(pooled.coef_, start)


def test_the_pool_is_between_its_two_rankers():
    matrix = random_matrix(2)
    steps = synthetic_history(200, 2)
    model = PooledOracle(matrix, pool_weight=0.5, online_gate=None).fit(steps[:180])
    step = steps[180]
    offered = list(step.options)
    routine = {t.option: t.probability for t in RoutineOracle(matrix).fit(steps[:180]).rank(step)}
    x = features(model, offered, step.time_of_day, model._clock.moment())
    q = np.exp(x @ model.coef_ - (x @ model.coef_).max())
    q /= q.sum()
    expected = np.sqrt(np.array([routine[o] for o in offered]) * q)
    expected /= expected.sum()
    served = {t.option: t.probability for t in model.rank(step)}
    np.testing.assert_allclose([served[o] for o in offered], expected, rtol=1e-6)


# fit against extend, and the routine predictor's explanation kept: tests/algorithm/test_online.py (both
# combinations).


@pytest.mark.parametrize("value", [-0.1, 1.5, "0.3", True, float("nan"), [], [0.5, 2.0]])
def test_a_bad_pool_weight_is_one_line_naming_it(value):
    with pytest.raises(SettingsError, match="pool_weight") as raised:
        PooledOracle(random_matrix(0), pool_weight=value).fit([])
    assert "\n" not in str(raised.value)


def test_a_gate_no_candidate_passes_serves_the_routine_predictor():
    matrix = random_matrix(3)
    steps = synthetic_history(150, 3)
    gated = PooledOracle(matrix, pool_weight="auto", online_gate=1e9).fit(steps[:120])
    routine = RoutineOracle(matrix).fit(steps[:120])
    assert gated.learnt_ > 0 and gated.leads_.shape == (4,) and np.any(gated.spreads_)
    assert gated.served_weight() is None and not gated.serves()
    for step in steps[120:130]:
        assert gated.rank(step) == routine.rank(step)


def test_the_gate_serves_the_candidate_with_the_largest_lead_over_the_routine_predictor():
    model = PooledOracle(random_matrix(4), pool_weight="auto", online_gate=1.0).fit(synthetic_history(80, 4))
    model.leads_[:] = [1.0, 9.0, 12.0, 3.0]
    model.spreads_[:] = [4.0, 16.0, 400.0, 4.0]  # 0.4 leads by 12, but by less than one standard error (20)
    assert model.served_weight() == 0.6
    model.leads_[:] = [-1.0, 0.0, 2.0, 1.0]
    model.spreads_[:] = [1.0, 1.0, 9.0, 4.0]
    assert model.served_weight() is None


def test_the_gates_evidence_is_each_weights_hit_score_minus_the_routine_predictors():
    model = PooledOracle(random_matrix(5), pool_weight=0.5, online_gate=0.0).fit(synthetic_history(40, 5))
    model.coef_ = np.eye(model.coef_.size)[0]
    model.leads_[:] = 0.0
    model.spreads_[:] = 0.0
    x = np.zeros((6, model.coef_.size))
    x[1, 0] = 3.0
    routine = np.log(np.array([0.3, 0.02, 0.2, 0.18, 0.16, 0.14]))  # the truth (1) last: hit score 0
    model._learn(x, routine, 1)  # pooled at 0.5 it ranks first: hit score 1
    assert model.leads_.tolist() == [1.0] and model.spreads_.tolist() == [1.0]


def test_with_likelihood_evidence_the_gate_sums_log_probability_differences():
    model = PooledOracle(random_matrix(5), pool_weight=0.5, online_gate=0.0,
                         pool_evidence="likelihood").fit(synthetic_history(40, 5))
    model.coef_ = np.eye(model.coef_.size)[0]
    model.leads_[:] = 0.0
    model.spreads_[:] = 0.0
    x = np.zeros((6, model.coef_.size))
    x[1, 0] = 3.0
    routine = np.log(np.array([0.3, 0.02, 0.2, 0.18, 0.16, 0.14]))
    model._learn(x, routine, 1)
    q = np.exp(x[:, 0]) / np.exp(x[:, 0]).sum()
    u = 0.5 * routine + 0.5 * np.log(q)
    expected = u[1] - np.log(np.exp(u).sum()) - np.log(0.02)
    assert model.leads_[0] == pytest.approx(expected) and expected > 0
    assert model.spreads_[0] == pytest.approx(expected * expected)


def test_a_bad_gate_evidence_is_one_line_naming_it():
    with pytest.raises(SettingsError, match="pool_evidence") as raised:
        PooledOracle(random_matrix(0), pool_evidence="accuracy").fit([])
    assert "\n" not in str(raised.value)


def test_a_list_of_weights_is_what_the_gate_chooses_from():
    model = PooledOracle(random_matrix(4), pool_weight=[0.8, 0.0], online_gate=1.0).fit(synthetic_history(80, 4))
    assert model.candidates_.tolist() == [0.8, 0.0] and model.leads_.shape == (2,)
    auto = PooledOracle(random_matrix(4)).fit(synthetic_history(80, 4))
    assert auto.candidates_.tolist() == [0.8, 0.6, 0.4, 0.2]
