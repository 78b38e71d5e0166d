"""The routine predictor's clock: how long ago each offered option was last done, the user's own
odds per bucket, and the gate that lets them rank only once they lead on Top-1
(docs/algorithm.md, "How long ago")."""

from __future__ import annotations

import math
import pickle
from dataclasses import replace

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.clock import EDGES, ClockGate, SinceDone, reweighted
from oracle.algorithm.records import Step
from oracle.algorithm.routine import RoutineOracle
from oracle.answers import ago, lifts
from oracle.errors import SettingsError


def timed(steps: list[Step], seed: int = 0) -> list[Step]:
    """The steps with begins: gaps of 30 s to 2 h, drawn once per seed."""
    rng = np.random.default_rng(seed)
    gaps = rng.choice([30.0, 200.0, 2000.0, 7200.0], size=len(steps))
    times = 1_700_000_000.0 + np.cumsum(gaps)
    return [replace(step, time=float(t)) for step, t in zip(steps, times)]


def test_buckets_weights_and_counts_by_hand():
    clock = SinceDone((60.0, 3600.0))
    clock.done(1, 1000.0)
    clock.done(2, 3000.0)
    # ids 1, 2, 3 at 3030 s: 2030 s ago (bucket 1), 30 s ago (bucket 0), never (bucket 3)
    assert clock.buckets([1, 2, 3], 3030.0) == [1, 0, 3]
    assert clock.buckets([1, 2], None) is None               # no clock: nothing
    assert clock.buckets([3, 4], 3030.0) is None             # all never done: nothing to tell apart
    assert np.allclose(clock.weights([1, 0, 3]), [1.0, 1.0, 1.0])   # one pseudo-step a side
    clock.observe([1, 0, 3], 1)                              # the option done 30 s ago was chosen
    assert clock.hits == [1.0, 0.0, 0.0, 0.0] and np.allclose(clock.share, [1 / 3, 1 / 3, 0.0, 1 / 3])
    assert np.allclose(clock.weights([0, 1, 3]), [2 / (4 / 3), 1 / (4 / 3), 1 / (4 / 3)])
    clock.observe(None, 0)                                   # a decision the clock cannot tell apart counts nothing
    assert clock.hits == [1.0, 0.0, 0.0, 0.0]
    assert clock.ages([1, 3], 3030.0, True) == [2030.0, None] and clock.ages([1], 3030.0, False) == [None]


def test_the_gate_opens_on_a_clear_top1_lead_and_recuts_to_a_window():
    gate = ClockGate(kept=[])
    plain, lifted = np.array([0.6, 0.4]), np.array([0.3, 0.7])
    assert not gate.open(2.0)
    for position in range(5):                               # the lifted ranking is right five times
        gate.update(plain, lifted, 1, position)
    assert (gate.lead, gate.spread) == (5.0, 5.0) and gate.open(2.0)   # 5 > 2 sqrt(5)
    gate.update(plain, lifted, 0, 5)                         # and wrong once
    assert (gate.lead, gate.spread) == (4.0, 6.0) and not gate.open(2.0)
    gate.update(plain, plain, 0, 6)                          # both right: no difference
    assert (gate.lead, gate.spread) == (4.0, 6.0)
    gate.keep_from(3)
    assert (gate.lead, gate.spread) == (1.0, 3.0) and [at for at, _ in gate.kept] == [3, 4, 5, 6]
    assert np.allclose(reweighted(np.array([0.5, 0.5]), np.array([3.0, 1.0])), [0.75, 0.25])


def test_without_a_clock_or_with_the_gate_shut_the_ranking_is_the_one_before():
    matrix = random_matrix(1)
    steps = synthetic_history(240, 1)
    clocked = timed(steps)
    now = clocked[-1].time + 60.0

    def ranked(model, query, at=None):
        return [(t.option, t.probability, t.since) for t in model.rank(query, at=at)]

    before = RoutineOracle(matrix, recency=()).fit(steps)
    untimed = RoutineOracle(matrix).fit(steps)                       # no step has a time
    shut = RoutineOracle(matrix, recency_gate=1e9).fit(clocked)  # the gate never opens
    off = RoutineOracle(matrix, recency=()).fit(clocked)
    for query in steps[-8:]:
        assert ranked(untimed, query) == ranked(before, query)
        assert ranked(shut, query, now) == ranked(off, query, now)


def test_an_open_gate_weighs_the_ranking_by_the_users_odds(monkeypatch):
    matrix = random_matrix(2)
    steps = timed(synthetic_history(300, 2), 2)
    model = RoutineOracle(matrix).fit(steps)
    now = steps[-1].time + 120.0
    offered = list(dict.fromkeys(steps[-1].options))
    shut = RoutineOracle(matrix, recency_gate=1e9).fit(steps)
    before = {t.option: t.probability for t in shut.rank(offered, "Morning", at=now, tree_roots=0)}
    monkeypatch.setattr(ClockGate, "open", lambda self, margin: True)
    weights = model.clock_.weights(model.clock_.buckets([model._known.ids[o] for o in offered], now))
    assert weights is not None and not np.allclose(weights, weights[0])
    expected = reweighted(np.array([before[o] for o in offered]), weights)
    got = {t.option: t for t in model.rank(offered, "Morning", at=now, tree_roots=0)}
    assert np.allclose([got[o].probability for o in offered], expected)
    for option in offered:
        last = model.clock_.last.get(model._known.ids[option])
        assert got[option].since == (None if last is None else now - last)


@pytest.mark.parametrize("window", [0, 5, 40, 1000])
def test_extend_equals_a_fresh_fit_with_the_clock(window):
    matrix = random_matrix(3)
    steps = timed(synthetic_history(180, 3), 3)
    fresh = RoutineOracle(matrix, tuning_window=window, recency_gate=0.0).fit(steps)
    for cut in (0, 1, 60, 179, 180):
        grown = pickle.loads(pickle.dumps(RoutineOracle(matrix, tuning_window=window, recency_gate=0.0).fit(steps[:cut])))
        grown.extend(steps)
        assert (grown.gate_.lead, grown.gate_.spread) == (fresh.gate_.lead, fresh.gate_.spread)
        assert (grown.clock_.hits, grown.clock_.share, grown.clock_.last) == \
            (fresh.clock_.hits, fresh.clock_.share, fresh.clock_.last)
        query = steps[-1]
        assert [(t.option, t.probability, t.since) for t in grown.rank(query, at=query.time + 30)] == \
            [(t.option, t.probability, t.since) for t in fresh.rank(query, at=query.time + 30)]


def test_fit_scores_the_gate_as_partial_fit_does():
    matrix = random_matrix(4)
    steps = timed(synthetic_history(120, 4), 4)
    whole = RoutineOracle(matrix, recency_gate=0.0).fit(steps)
    one_by_one = RoutineOracle(matrix, recency_gate=0.0).fit([])
    for step in steps:
        one_by_one.partial_fit(step)
    assert (whole.gate_.lead, whole.gate_.spread) == (one_by_one.gate_.lead, one_by_one.gate_.spread)
    assert whole.gate_.spread > 0      # the clock did tell the ranking's first option apart somewhere


@pytest.mark.parametrize("params", [{"recency": (600.0, 60.0)}, {"recency": (0.0, 60.0)}, {"recency": (True,)},
                                    {"recency": (math.inf,)}, {"recency": "60"}, {"recency_gate": -1.0},
                                    {"recency_gate": math.nan}])
def test_bad_clock_settings_are_refused(params):
    with pytest.raises(SettingsError, match="recency"):
        RoutineOracle(random_matrix(0), **params).fit([])


@pytest.mark.parametrize("bad", [math.nan, math.inf, True, "10"])
def test_a_step_time_must_be_finite_seconds(bad):
    with pytest.raises(ValueError, match="time"):
        Step("t", time=bad)


def test_tiny_histories_and_the_words_of_the_reason():
    matrix = random_matrix(5)
    one = timed(synthetic_history(1, 5), 5)
    model = RoutineOracle(matrix).fit(one)
    assert len(model.rank(one[0], at=one[0].time + 10)) == len(set(one[0].options))
    assert RoutineOracle(matrix).fit([]).rank(one[0], at=1e9)[0].since is None
    assert EDGES == (60.0, 600.0, 3600.0, 14400.0, 43200.0, 129600.0)
    assert [ago(s) for s in (40, 300, 3 * 3600, 3 * 86400)] == ["40 s ago", "5 min ago", "3 h ago", "3 days ago"]
    assert lifts([], False, False, 300.0) == ["last done 5 min ago"] and lifts([], False) == []


def test_history_steps_carry_their_begin_only_where_the_neem_has_a_clock():
    from pathlib import Path

    from oracle.calls import steps_before, steps_from_history
    from oracle.ontology import build_ontology

    examples = Path(__file__).resolve().parents[2] / "docs" / "examples"
    onto = build_ontology(examples / "odb", examples / "mapping.yaml")
    offer = ["pick(teapot)", "pick(mug)"]
    rows = [{"begin": 100.0, "end": 110.0, "call": "pick(teapot)", "part": "Morning", "available": offer},
            {"begin": 200.0, "end": 210.0, "call": "idle", "part": "Morning", "available": None},
            {"begin": 300.0, "end": 310.0, "call": "pick(mug)", "part": "Morning", "available": offer},
            {"begin": 400.0, "end": 410.0, "call": "pick(teapot)", "part": "Morning", "available": offer}]
    clocked = steps_from_history(onto, rows)
    assert [s.time for s in clocked] == [100.0, None, 300.0, 400.0]      # idle steps carry none
    assert clocked[0].options is clocked[3].options                      # offers still shared
    assert [s.time for s in steps_from_history(onto, rows, clocked=False)] == [None] * 4
    assert [s.time for s in steps_before(onto, rows, 350.0, clocked=False)] == [None] * 4   # and the idle gap


def test_a_step_begun_at_a_time_is_the_step_made_with_it():
    from oracle.algorithm.records import Option

    step = Step("t", "a", None, (Option("t", "a"), Option("u")), "Morning", False, "t(a)")
    later = step.began(1234.5)
    assert later == Step("t", "a", None, (Option("t", "a"), Option("u")), "Morning", False, "t(a)", 1234.5)
    assert later.options is step.options and step.time is None and hash(later) == hash(replace(step, time=1234.5))
    for bad in (math.nan, True, "1"):
        with pytest.raises(ValueError, match="time"):
            step.began(bad)


@pytest.mark.parametrize("bad", [math.nan, math.inf, True, "now"])
def test_a_decision_time_must_be_finite_seconds(bad):
    steps = timed(synthetic_history(20, 6), 6)
    with pytest.raises(SettingsError, match="at must be finite"):
        RoutineOracle(random_matrix(6)).fit(steps).rank(steps[-1], at=bad)
