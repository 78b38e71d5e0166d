"""Claims about the online predictor (docs/algorithm.md, "Online predictor"): the routine
predictor's ranking re-weighed by a conditional logit learnt after every decision; the claims it
shares with the pooled predictor are run for both."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.evidence import DecisionClock, features
from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.predictors import make_predictor
from oracle.algorithm.records import RoutineTask, Step
from oracle.algorithm.routine import RoutineOracle
from oracle.errors import SettingsError


def _served(model, steps):
    return [[(t.option, t.probability) for t in model.rank(step)] for step in steps]


def test_with_no_learning_it_is_the_routine_predictor_exactly():
    matrix = random_matrix(0)
    steps = synthetic_history(150, 0)
    still = OnlineOracle(matrix, online_rate=0.0).fit(steps[:120])
    routine = RoutineOracle(matrix).fit(steps[:120])
    assert still.learnt_ > 0 and not np.any(still.coef_)
    for step in steps[120:]:
        assert still.rank(step) == routine.rank(step)
    # before its first decision the default serves the routine predictor's ranking too
    assert OnlineOracle(matrix).fit([]).rank(steps[0]) == RoutineOracle(matrix).fit([]).rank(steps[0])


def test_one_update_raises_the_probability_of_the_option_done():
    matrix = random_matrix(1)
    steps = synthetic_history(100, 1)
    model = OnlineOracle(matrix, online_rate=0.5).fit(steps[:80])
    step = steps[80]
    offered = list(step.options)
    truth = offered.index(step.option)
    x = features(model, offered, step.time_of_day, None)
    offset = model._served(x, model._offer_ids(offered), None)

    def chosen() -> float:
        u = offset + (x / model._spread()) @ model.coef_
        p = np.exp(u - u.max())
        return float(p[truth] / p.sum())

    before = chosen()
    model._learn(x, offset, truth)
    assert chosen() > before


def test_it_learns_a_column_the_routine_predictor_does_not_weigh():
    # two options, always the one with the higher "in-hand" flag: the weight of that column grows
    matrix = random_matrix(2)
    model = OnlineOracle(matrix, online_rate=0.3).fit(synthetic_history(40, 2))
    rng = np.random.default_rng(0)
    width = model.coef_.size
    for _ in range(200):
        x = rng.normal(size=(6, width))
        model._learn(x, np.zeros(6), int(np.argmax(x[:, 5])))
    assert int(np.argmax(model.coef_)) == 5


def test_the_gate_opens_only_once_the_combination_leads_on_the_decisions_learnt():
    matrix = random_matrix(2)
    routine = RoutineOracle(matrix).fit(synthetic_history(40, 2))
    model = OnlineOracle(matrix, online_gate=2.0).fit(synthetic_history(40, 2))
    query = synthetic_history(41, 2)[-1]
    assert not model.serves() and model.rank(query) == routine.rank(query)
    rng = np.random.default_rng(0)
    width = model.coef_.size
    for _ in range(60):  # a column the offset (flat) knows nothing of decides every time
        x = rng.normal(size=(6, width))
        model._learn(x, np.zeros(6), int(np.argmax(x[:, 5])))
    assert model.lead_ > 2.0 * np.sqrt(model.spread_) and model.serves()
    assert model.rank(query) != routine.rank(query)
    assert not OnlineOracle(matrix, online_gate=1e9).fit(synthetic_history(40, 2)).serves()


@pytest.mark.parametrize("make", [lambda m: OnlineOracle(m, online_gate=None), PooledOracle], ids=["online", "pooled"])
def test_fit_is_deterministic_and_extends_step_by_step_as_a_fresh_fit(make):
    matrix = random_matrix(3)
    steps = synthetic_history(160, 3)
    fresh = make(matrix).fit(steps)
    again = pickle.loads(pickle.dumps(make(matrix).fit(steps)))
    assert np.array_equal(fresh.coef_, again.coef_) and np.any(fresh.coef_)
    assert _served(fresh, steps[-5:]) == _served(again, steps[-5:])
    stepwise = make(matrix).fit(steps[:100])
    for n in range(101, len(steps) + 1):
        stepwise.extend(steps[:n])
    assert np.array_equal(fresh.coef_, stepwise.coef_)
    assert _served(fresh, steps[-5:]) == _served(stepwise, steps[-5:])


@pytest.mark.parametrize("name, cls, make", [("online", OnlineOracle, lambda m: OnlineOracle(m, online_gate=None)),
                                             ("pooled", PooledOracle, lambda m: PooledOracle(m, online_gate=None))],
                         ids=["online", "pooled"])
def test_it_keeps_the_routine_explanation_of_each_option(name, cls, make):
    matrix = random_matrix(4)
    steps = synthetic_history(200, 4)
    assert isinstance(make_predictor(name, matrix), cls)
    combined = make(matrix).fit(steps)
    routine = RoutineOracle(matrix).fit(steps)
    assert combined.serves()
    explained = {t.option: (t.context, t.situations, t.order, t.n_similar) for t in routine.rank(steps[-1])}
    ranked = combined.rank(steps[-1])
    assert all(isinstance(t, RoutineTask) for t in ranked)
    assert [t.rank for t in ranked] == list(range(1, len(ranked) + 1))
    assert sum(t.probability for t in ranked) == pytest.approx(1.0)
    assert {t.option: (t.context, t.situations, t.order, t.n_similar) for t in ranked} == explained


@pytest.mark.parametrize("setting, value", [("online_rate", -0.1), ("online_rate", float("nan")),
                                            ("online_l2", "1e-4"), ("online_damping", -1.0),
                                            ("online_gate", -1.0), ("online_average", 1),
                                            ("online_window", 2.5), ("online_window", True)])
def test_a_bad_setting_is_one_line_naming_it(setting, value):
    with pytest.raises(SettingsError, match=setting) as raised:
        OnlineOracle(random_matrix(0), **{setting: value}).fit([])
    assert "\n" not in str(raised.value)


def test_a_decision_is_taken_when_its_history_says():
    clock = DecisionClock()
    first = Step(synthetic_history(1, 0)[0].task, time=1000.0)
    assert clock.decided(first) == (None, None)  # the first action: no clock yet
    clock.passed(first)
    later = Step(first.task, time=99999.0)
    assert clock.decided(later)[0] == 1000.0
    clock.passed(Step(first.task, idle=True))
    assert clock.decided(later)[0] == 1020.0  # an idle step since: the gap became one 20 s after
