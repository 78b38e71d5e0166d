"""The fast oracle is the reference algorithm: same ranking, same scores, same trees."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from algoworld import OPEN, histories, options_strategy, random_matrix, synthetic_history
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS
from oracle.algorithm.reference import ReferenceOracle
from oracle.timeline import TIME_OF_DAY_NAMES

PRESET_NAMES = "ABCDEFGHIJKLMN"


def assert_same(a, b) -> None:
    assert [t.option for t in a] == [t.option for t in b]
    assert [t.n_similar for t in a] == [t.n_similar for t in b]
    for x, y in zip(a, b):
        assert x.score == pytest.approx(y.score, abs=1e-9, rel=0) or x.score == y.score
        assert x.nearest == pytest.approx(y.nearest, abs=1e-9, rel=0) or x.nearest == y.nearest
    assert [t.successors for t in a] == [t.successors for t in b]


def both(matrix, preset_name, history, **overrides):
    settings_ = PRESETS[preset_name].to_dict() | overrides
    kwargs = dict(opening_tasks=frozenset({OPEN}), **settings_)
    return (ReferenceOracle(matrix, **kwargs).fit(history), PreferenceOracle(matrix, **kwargs).fit(history))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 5), preset_name=st.sampled_from(PRESET_NAMES), history=histories(25),
       options=options_strategy(6), now=st.sampled_from((None,) + TIME_OF_DAY_NAMES),
       knockout=st.sampled_from((None, 0.0, 0.5, 1.16, 2.5)), horizon=st.integers(0, 6))
def test_fast_ranks_like_reference(seed, preset_name, history, options, now, knockout, horizon):
    matrix = random_matrix(seed)
    overrides = {"event_horizon_backwards": horizon}
    if knockout is not None:
        overrides["knockout"] = knockout
    reference, fast = both(matrix, preset_name, history, **overrides)
    assert_same(reference.rank(options, now, tree_roots=None), fast.rank(options, now, tree_roots=None))


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 3), history=histories(20), extra=histories(6), options=options_strategy(5))
def test_partial_fit_equals_fit(seed, history, extra, options):
    matrix = random_matrix(seed)
    grown = PreferenceOracle.from_settings(matrix, "A").fit(history)
    for step in extra:
        grown.partial_fit(step)
    whole = ReferenceOracle.from_settings(matrix, "A").fit(history + extra)
    assert_same(whole.rank(options, "Morning", tree_roots=None), grown.rank(options, "Morning", tree_roots=None))


@pytest.mark.parametrize("preset_name", PRESET_NAMES)
def test_every_fig_5_5_setting_on_a_routine(preset_name):
    matrix = random_matrix(7)
    history = synthetic_history(90, seed=11, n_options=8, n_states=12)
    reference, fast = both(matrix, preset_name, history[:-1])
    assert_same(reference.rank(history[-1], tree_roots=None), fast.rank(history[-1], tree_roots=None))
