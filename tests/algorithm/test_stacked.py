"""Claims about the routine predictor's evidence rows and the stacked predictor (docs/algorithm.md,
"Stacked predictor")."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.evidence import feature_names, features
from oracle.algorithm.records import Option, RoutineTask, Step
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.stacked import StackedOracle, chosen_shrink, fit_logit
from oracle.errors import SettingsError


def test_evidence_rows_hold_each_variants_log_probability_and_the_context_counts():
    matrix = random_matrix(0)
    steps = synthetic_history(120, 0)
    model = RoutineOracle(matrix).fit(steps[:100])
    offered = list(steps[100].options)
    x = features(model, offered, steps[100].time_of_day, None)
    names = feature_names(model)
    assert x.shape == (len(offered), len(names)) == (len(offered), len(model.variants_) + 16 + len(model.recency))
    ids = model._offer_ids(offered)
    new, resumed = model._offer_flags(ids)
    probabilities = model._variant_probabilities(offered, ids, steps[100].time_of_day, None,
                                                 model._in_focus(offered), new, resumed)[0]
    for v, p in enumerate(probabilities):
        assert np.allclose(np.exp(x[:, v]), np.maximum(p, 1e-12))
    counts = model._streams["idle"].counts
    followers = counts.levels[1].tables.get(counts.context(1)) or {}
    share = x[:, names.index("share1")]
    assert np.allclose(share * counts.levels[1].totals.get(counts.context(1), 1),
                       [followers.get(i, 0) for i in ids])
    assert x[:, names.index("no-clock")].tolist() == [1.0] * len(offered)  # no decision time given
    assert set(x[:, names.index("never")].tolist()) <= {0.0, 1.0}


def test_the_logit_recovers_a_deciding_column_and_the_gate_keeps_it_only_where_it_helps():
    rng = np.random.default_rng(1)
    rows = []
    for _ in range(90):
        x = rng.normal(size=(8, 3))
        rows.append((x, int(np.argmax(x[:, 2]))))  # column 2 decides, column 0 (the offset) is noise
    w, spread = fit_logit(rows, 1.0)
    assert np.argmax(np.abs(w)) == 2 and w[2] > 0
    assert chosen_shrink(rows, (1.0, 100.0), 2.0) is not None
    decided = [(x, int(np.argmax(x[:, 0]))) for x, _ in rows]  # the offset already decides: nothing to add
    assert chosen_shrink(decided, (1.0, 100.0), 2.0) is None
    assert chosen_shrink(rows[:20], (1.0,), 2.0) is None  # too few decisions


def _same(a: StackedOracle, b: StackedOracle, queries) -> None:
    assert (a.coef_ is None) == (b.coef_ is None) and a.refit_at_ == b.refit_at_
    if a.coef_ is not None:
        assert np.array_equal(a.coef_, b.coef_)
    for step in queries:
        assert [(t.option, t.probability) for t in a.rank(step)] == [(t.option, t.probability) for t in b.rank(step)]


@pytest.mark.parametrize("seed", [0, 1])
def test_stacked_extend_and_step_by_step_equal_a_fresh_fit(seed):
    matrix = random_matrix(seed)
    steps = synthetic_history(220, seed)
    settings = {"combine_window": 60, "combine_every": 10, "tuning_window": 50}
    fresh = StackedOracle(matrix, **settings).fit(steps)
    grown = pickle.loads(pickle.dumps(StackedOracle(matrix, **settings).fit(steps[:97]))).extend(steps)
    _same(fresh, grown, steps[-6:])
    # one step at a time over the last 70 steps: seven refits of the combination (every 10 steps)
    stepwise = StackedOracle(matrix, **settings).fit(steps[:150])
    for n in range(151, len(steps) + 1):
        stepwise.extend(steps[:n])
    _same(fresh, stepwise, steps[-6:])


def test_stacked_keeps_the_routine_explanation_and_serves_routine_until_it_has_evidence():
    matrix = random_matrix(2)
    steps = synthetic_history(200, 2)
    routine = RoutineOracle(matrix).fit(steps[:20])
    stacked = StackedOracle(matrix).fit(steps[:20])
    assert stacked.coef_ is None
    assert stacked.rank(steps[20]) == routine.rank(steps[20])
    stacked = StackedOracle(matrix, combine_window=120, combine_every=20).fit(steps)
    routine = RoutineOracle(matrix).fit(steps)
    explained = {t.option: (t.context, t.situations, t.order) for t in routine.rank(steps[-1])}
    ranked = stacked.rank(steps[-1])
    assert all(isinstance(t, RoutineTask) for t in ranked)
    assert [t.rank for t in ranked] == list(range(1, len(ranked) + 1))
    assert sum(t.probability for t in ranked) == pytest.approx(1.0)
    assert {t.option: (t.context, t.situations, t.order) for t in ranked} == explained


def test_stacked_refuses_bad_settings():
    with pytest.raises(SettingsError, match="combine_window"):
        StackedOracle(random_matrix(0), combine_window=0).fit([])
    with pytest.raises(SettingsError, match="combine_shrink"):
        StackedOracle(random_matrix(0), combine_shrink=(float("nan"),)).fit([])
    with pytest.raises(TypeError, match="Step"):
        StackedOracle(random_matrix(0)).fit([Option("x")])  # type: ignore[list-item]


def test_a_past_decision_is_taken_when_its_history_says_not_when_the_action_began():
    matrix = random_matrix(0)
    model = StackedOracle(matrix).fit([])
    first = Step(synthetic_history(1, 0)[0].task, time=1000.0)
    assert model._decided(first) == (None, None)  # the first action: no clock yet
    model._previous = (1000.0, False)
    later = Step(first.task, time=99999.0)
    assert model._decided(later)[0] == 1000.0
    model._previous = (1000.0, True)  # an idle step since: the gap became one 20 s after
    assert model._decided(later)[0] == 1020.0
