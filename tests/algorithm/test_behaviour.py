"""Claims about the algorithm's behaviour, each checked on a small world (thesis chapter 4)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from algoworld import IDLE, OBJECTS, OPEN, TASKS, option_strategy, random_matrix
from oracle.ontology.distance import DistanceMatrix
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS, Hyperparameters
from oracle.algorithm.reference import (
    ReferenceOracle, importance_weights, overall_distance, situation_distance,
)
from oracle.algorithm.records import Option, Step, canonical_options
from oracle.algorithm.tree import Successions, TreeShape, occurrence_value, successor_tree
from oracle.errors import OntologyError, SettingsError

PICK, PLACE, POUR, OPEN_, CLOSE, DRINK = TASKS
RED, BLUE, THERMOS, DRAWER, TABLE, SPOON, PLATE = OBJECTS


def step(task, target=None, reference=None, options=(), tod=None, idle=False):
    return Step(task, target, reference, tuple(options), tod, idle)


def idle(tod=None):
    return Step(IDLE, idle=True, time_of_day=tod)


def oracles(matrix, **params):
    return (ReferenceOracle(matrix, **params), PreferenceOracle(matrix, **params))


# -- eq. 4.12 / 4.13 -----------------------------------------------------------------------

def test_eq_4_13_worked_example():
    a, c, x = 0.5, 0.4, 0.7
    assert occurrence_value(a + c, 2, x) == pytest.approx(0.28, abs=0.005)
    assert occurrence_value(0.3, 1, x) == pytest.approx(0.3, abs=1e-3)


def test_table_4_1_place_beats_drink_unless_counts_dominate():
    place, drink = [0.0, 0.1, 0.4, 0.9], [0.5, 0.9, 1.3, 1.5, 1.9]
    def v(ds, x):
        return occurrence_value(math.fsum(ds), len(ds), x)
    assert v(place, 0.25) < v(drink, 0.25)          # low average wins at the recommended x
    assert v(place, 0.0) < v(drink, 0.0)
    assert v([0.5] * 8, 1.0) < v([0.1], 1.0)        # x = 1: many hits beat one good one


def test_fig_4_6_tree_scores_and_order():
    """Situations A, B, C at distances 0.5, 0.3, 0.4; B -> pick plate -> transport plate,
    A -> pick mug -> transport mug, C -> pick mug -> close drawer."""
    options = [Option(OPEN_, DRAWER), Option(PICK, PLATE), Option(PICK, RED), Option(PLACE, PLATE),
               Option(PLACE, RED), Option(CLOSE, DRAWER)]
    # positions: A=0, B=3, C=6 (open drawer), successors follow; idle between
    executed = np.array([0, 2, 4, 0, 1, 3, 0, 2, 5])
    next_position = np.array([1, 2, -1, 4, 5, -1, 7, 8, -1])
    roots, dists = np.array([0, 3, 6]), np.array([0.5, 0.3, 0.4])
    present = frozenset({DRAWER, PLATE, RED})
    history = Successions(next_position, executed, options)
    tree = successor_tree(roots, dists, history, TreeShape(3, 0.7, present, frozenset()), True)
    assert [n.option for n in tree] == [Option(PICK, RED), Option(PICK, PLATE)]
    assert tree[0].score == pytest.approx(0.28, abs=0.005) and tree[0].support == 2
    assert tree[1].score == pytest.approx(0.3, abs=1e-3)
    assert [n.option for n in tree[0].children] == [Option(CLOSE, DRAWER), Option(PLACE, RED)]
    # Fig. 4.7: without the plate present, the plate branch disappears ...
    pruned = successor_tree(roots, dists, history, TreeShape(3, 0.7, frozenset({DRAWER, RED}), frozenset()), True)
    assert [n.option for n in pruned] == [Option(PICK, RED)]
    # ... unless the candidate opens something, which may reveal it
    unchecked = successor_tree(roots, dists, history, TreeShape(3, 0.7, frozenset({DRAWER, RED}), frozenset({OPEN_})), False)
    assert len(unchecked) == 2


# -- eq. 4.11 ------------------------------------------------------------------------------

@given(st.floats(0.01, 1.0), st.integers(0, 30))
def test_importance_weights_decrease_and_sum_below_one(f, n):
    w = importance_weights(f, n)
    assert w[0] == f
    assert all(a >= b for a, b in zip(w, w[1:]))
    assert math.fsum(w) == pytest.approx(1 - (1 - f) ** (n + 1), abs=1e-12)


# -- Algorithms 2 and 3 ---------------------------------------------------------------------

@settings(max_examples=40, deadline=None)
@given(st.integers(0, 5), option_strategy(), option_strategy())
def test_overall_distance_symmetric_and_zero_on_identity(seed, a, b):
    matrix, p = random_matrix(seed), Hyperparameters()
    assert overall_distance(p, matrix, a, a) == 0.0
    assert overall_distance(p, matrix, a, b) == overall_distance(p, matrix, b, a)


def test_penalty_is_symmetric_in_the_slots():
    matrix, p = random_matrix(0), Hyperparameters(penalty=3.7, task_factor=2.0, object_factor=1.0)
    with_object, without = Option(PICK, RED), Option(PICK)
    assert overall_distance(p, matrix, with_object, without) == pytest.approx(3.7)
    assert overall_distance(p, matrix, without, with_object) == pytest.approx(3.7)
    assert overall_distance(p, matrix, without, without) == 0.0   # no object on either side: average 0


def test_situation_comparison_adds_option_set_distance_and_respects_the_skips():
    matrix = random_matrix(1)
    a, b = Option(PICK, RED), Option(PICK, BLUE)
    mine, theirs = canonical_options([a, Option(POUR, RED, THERMOS)]), canonical_options([b])
    p = Hyperparameters(knockout=100.0)
    base = overall_distance(p, matrix, a, b)
    extra = (min(overall_distance(p, matrix, mine[0], b), math.inf) + overall_distance(p, matrix, mine[1], b)) / 2
    assert situation_distance(p, matrix, a, mine, b, theirs) == pytest.approx(base + extra * p.compare_situations)
    assert situation_distance(Hyperparameters(knockout=100.0, compare_situations=0.0), matrix, a, mine, b, theirs) == base
    low = Hyperparameters(knockout=base)   # already at knockout: the situation is not compared
    assert situation_distance(low, matrix, a, mine, b, theirs) == base


# -- ranking -------------------------------------------------------------------------------

def two_class_matrix():
    classes = TASKS + OBJECTS + (IDLE,)
    values = np.full((len(classes), len(classes)), 3.0)
    np.fill_diagonal(values, 0.0)
    return DistanceMatrix.from_values(classes, values)


def test_identity_history_ranks_the_repeated_task_first_with_known_score():
    matrix = two_class_matrix()
    offered = (Option(PLACE, TABLE, RED), Option(PICK, RED), Option(DRINK, RED))
    history = [step(PICK, RED, options=offered), step(PLACE, TABLE, RED, options=offered)] * 3
    for oracle in oracles(matrix, **PRESETS["A"].to_dict()):
        ranking = oracle.fit(history).rank(offered)
        assert ranking[0].option == Option(PICK, RED)   # after a place comes a pick, every time
        assert ranking[0].n_similar == 3
        # identical chains give distance 0 except where they run into the history start (penalty)
        assert ranking[0].score < ranking[1].score
        assert ranking[-1].option == Option(DRINK, RED) and ranking[-1].n_similar == 0
        assert ranking[-1].score == math.inf


def test_knockout_zero_keeps_only_identical_tasks_and_large_knockout_keeps_all():
    matrix = random_matrix(2)
    offered = (Option(PICK, RED), Option(PICK, BLUE))
    history = [step(PICK, RED, options=offered), step(PLACE, TABLE, RED, options=offered)]
    for oracle in oracles(matrix, **PRESETS["L"].to_dict()):
        ranking = oracle.fit(history).rank(offered)
        assert {t.option: t.n_similar for t in ranking} == {Option(PICK, RED): 1, Option(PICK, BLUE): 0}
    for oracle in oracles(matrix, **PRESETS["M"].to_dict()):
        assert all(t.n_similar == 2 for t in oracle.fit(history).rank(offered))


def test_unknown_candidates_follow_by_nearest_distance_then_offered_order():
    matrix = two_class_matrix()
    history = [step(PICK, RED)]
    offered = (Option(CLOSE, DRAWER), Option(DRINK, BLUE), Option(PICK, BLUE), Option(PICK, RED))
    for oracle in oracles(matrix, **PRESETS["L"].to_dict()):
        ranking = oracle.fit(history).rank(offered)
        assert [t.option for t in ranking] == [Option(PICK, RED), Option(PICK, BLUE), Option(CLOSE, DRAWER),
                                              Option(DRINK, BLUE)]
        assert [t.rank for t in ranking] == [1, 2, 3, 4]
    empty = PreferenceOracle(matrix).fit([]).rank(offered)
    assert [t.option for t in empty] == list(offered)


def test_predecessors_decide_between_equal_main_matches():
    """Both candidates were done once; only the spoon followed the chain that is running now."""
    matrix = two_class_matrix()
    history = [idle(), step(OPEN_, DRAWER), step(DRINK, RED), step(PICK, SPOON),
               idle(), step(OPEN_, DRAWER), step(PICK, PLATE), step(PICK, BLUE),
               idle(), step(OPEN_, DRAWER), step(DRINK, RED)]
    offered = (Option(PICK, BLUE), Option(PICK, SPOON))
    p = PRESETS["A"]
    w = importance_weights(p.decreasing_importance_factor, p.event_horizon_backwards)
    knocked = 0.0
    for n in range(1, p.event_horizon_backwards + 1):
        knocked += w[n] * p.penalty
    expected_blue = occurrence_value(knocked / (w[0] + math.fsum(w[1:])), 1, p.multiple_occurrences_factor)
    for oracle in oracles(matrix, **p.to_dict()):
        ranking = oracle.fit(history).rank(offered)
        assert [t.option for t in ranking] == [Option(PICK, SPOON), Option(PICK, BLUE)]
        assert ranking[0].score == pytest.approx(0.0001)       # identical chain back to the idle step
        assert ranking[1].score == pytest.approx(expected_blue)  # knocked out at the first predecessor
        assert oracle.rank(offered)[0].successors == ()           # the spoon ended its chain


def test_idle_steps_delimit_chains():
    """Steps before an idle step are never compared as predecessors: changing them (to steps not
    similar to any candidate themselves) changes nothing, although they differ from the current chain."""
    matrix = two_class_matrix()
    tail = [idle(), step(OPEN_, DRAWER), step(PICK, RED)]
    offered = (Option(PLACE, TABLE, RED), Option(POUR, RED, THERMOS))
    a = [step(DRINK, BLUE), step(CLOSE, DRAWER)] + tail + [step(PLACE, TABLE, RED)] + tail
    b = [step(CLOSE, PLATE), step(DRINK, SPOON)] + tail + [step(PLACE, TABLE, RED)] + tail
    for cls in (ReferenceOracle, PreferenceOracle):
        ra = cls.from_settings(matrix, "A").fit(a).rank(offered)
        rb = cls.from_settings(matrix, "A").fit(b).rank(offered)
        assert [(t.option, t.score) for t in ra] == [(t.option, t.score) for t in rb]
        # identical back to the idle step, where both chains start: distance 0, nothing earlier counts
        assert ra[0].option == Option(PLACE, TABLE, RED) and ra[0].score == pytest.approx(0.0001, abs=1e-15)


def test_time_of_day_penalty_multiplies_distances_of_other_parts_of_day():
    matrix = random_matrix(5)
    offered = (Option(PICK, RED),)
    history = [step(PICK, BLUE, tod="Morning")]
    for factor in (1.0, 10.0):
        params = dict(PRESETS["A"].to_dict(), knockout=5.0, time_of_day_penalty=factor, event_horizon_backwards=0)
        for oracle in oracles(matrix, **params):
            oracle.fit(history)
            same = oracle.rank(offered, "Morning")[0].score
            other = oracle.rank(offered, "Evening")[0].score
            unknown = oracle.rank(offered, None)[0].score
            assert unknown == same
            assert other - 0.0001 == pytest.approx((same - 0.0001) * factor)


def test_rank_does_not_mutate_and_params_roundtrip():
    matrix = random_matrix(6)
    history = [step(PICK, RED, options=[Option(PICK, RED)]), step(PLACE, TABLE, RED)]
    oracle = PreferenceOracle(matrix, knockout=2.0).fit(history)
    before = {k: (v.copy() if isinstance(v, np.ndarray) else v) for k, v in vars(oracle).items()
              if not k.startswith("_")}
    first = oracle.rank([Option(PICK, BLUE), Option(DRINK, SPOON)], "Night")
    assert oracle.rank([Option(PICK, BLUE), Option(DRINK, SPOON)], "Night") == first
    after = {k: v for k, v in vars(oracle).items() if not k.startswith("_")}
    assert before.keys() == after.keys() and oracle.n_steps_ == 2
    assert oracle.get_params()["knockout"] == 2.0
    oracle.set_params(knockout=1.0)
    with pytest.raises(SettingsError, match="fit"):
        oracle.rank([Option(PICK, BLUE)])
    assert oracle.fit(history).rank([Option(PICK, BLUE)])


def test_unknown_class_is_a_user_error():
    with pytest.raises(OntologyError, match="NoSuchThing"):
        PreferenceOracle(random_matrix(0)).fit([step("odb#NoSuchThing")])
    with pytest.raises(OntologyError, match="NoSuchThing"):
        ReferenceOracle(random_matrix(0)).fit([]).rank([Option(PICK, "odb#NoSuchThing")])


def test_duplicate_options_are_ranked_once():
    oracle = PreferenceOracle(random_matrix(0)).fit([step(PICK, RED)])
    assert len(oracle.rank([Option(PICK, RED), Option(PICK, RED), Option(OPEN, DRAWER)])) == 2
