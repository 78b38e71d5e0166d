"""Claims about the routine predictor (docs/algorithm.md, "Routine predictor") and the registry."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from algoworld import IDLE, OBJECTS, TASKS, histories, option_strategy, random_matrix, synthetic_history
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS, Hyperparameters
from oracle.algorithm.predictors import DEFAULT, PREDICTORS, make_predictor, predictor_spec
from oracle.algorithm.reference import overall_distance
from oracle.algorithm.contexts import ContextCounts
from oracle.algorithm.records import RoutineTask
from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.selftune import VariantWeights
from oracle.algorithm.similarity import class_rows, option_distances
from oracle.algorithm.records import Option, Step
from oracle.errors import SettingsError
from oracle.ontology.distance import DistanceMatrix

PICK, PLACE, POUR, OPEN_, CLOSE, DRINK = TASKS
RED, BLUE, THERMOS, DRAWER, TABLE, SPOON, PLATE = OBJECTS


def kitchen() -> DistanceMatrix:
    """Mugs are close to each other and far from the drawer; pick is close to place."""
    classes = TASKS + OBJECTS + (IDLE,)
    values = np.full((len(classes), len(classes)), 1.5)
    near = {(RED, BLUE): 0.1, (PICK, PLACE): 0.4, (RED, THERMOS): 0.6, (BLUE, THERMOS): 0.6}
    for (a, b), d in near.items():
        i, j = classes.index(a), classes.index(b)
        values[i, j] = values[j, i] = d
    np.fill_diagonal(values, 0.0)
    return DistanceMatrix.from_values(classes, values)


def act(option: Option, options=(), tod=None) -> Step:
    return Step(option.task, option.target, option.reference, tuple(options), tod, False, str(option))


def idle() -> Step:
    return Step(IDLE, idle=True, label="idle")


ROUTINE = (Option(PICK, RED), Option(POUR, THERMOS, RED), Option(DRINK, RED), Option(PLACE, RED, TABLE))
OFFERED = tuple(reversed(ROUTINE)) + (Option(OPEN_, DRAWER),)


def test_empty_history_keeps_the_offered_order_with_equal_probabilities():
    ranking = RoutineOracle(kitchen()).fit([]).rank(OFFERED)
    assert ranking.options() == OFFERED
    assert all(isinstance(t, RoutineTask) and t.order == -1 and t.n_similar == 0 for t in ranking)
    assert [t.probability for t in ranking] == pytest.approx([1 / len(OFFERED)] * len(OFFERED))
    assert all(math.isinf(t.nearest) for t in ranking)
    assert RoutineOracle(kitchen()).fit([]).rank(()).tasks == ()


def test_one_step_history_ranks_the_repeated_action_first():
    ranking = RoutineOracle(kitchen()).fit([act(ROUTINE[1], OFFERED)]).rank(OFFERED)
    assert ranking[0].option == ROUTINE[1] and ranking[0].order == 0 and ranking[0].n_similar == 1
    assert sum(t.probability for t in ranking) == pytest.approx(1.0)
    assert [t.score for t in ranking] == sorted(t.score for t in ranking)  # -log2 p: lower is better


def test_a_history_of_idle_steps_only_knows_no_action():
    model = RoutineOracle(kitchen()).fit([idle(), idle()])
    ranking = model.rank(OFFERED)
    assert ranking.options() == OFFERED and all(t.order == -1 for t in ranking)
    assert [t.probability for t in ranking] == pytest.approx([1 / len(OFFERED)] * len(OFFERED))
    after = model.partial_fit(act(ROUTINE[0], OFFERED)).rank(OFFERED)
    assert after[0].option == ROUTINE[0] and after[0].situations == (2,)  # history position after the gaps


def test_many_exact_repetitions_outrank_one_closer_looking_match():
    # after pick(red) the user poured 5 times and placed once; the single place is the latest
    a, b, _, d = ROUTINE
    history = [s for _ in range(5) for s in (act(a), act(b))] + [act(a), act(d)]
    ranking = RoutineOracle(kitchen()).fit(history + [act(a)]).rank((d, b))
    assert ranking.options() == (b, d)
    assert (ranking[0].order, ranking[0].n_similar, ranking[0].situations) == (1, 5, (1, 3, 5, 7, 9))
    assert (ranking[1].order, ranking[1].n_similar, ranking[1].situations) == (1, 1, (11,))
    assert ranking[0].context == ranking[1].context == (str(a),)
    assert ranking[0].probability > 4 * ranking[1].probability


def test_a_repeated_routine_is_learned_exactly_with_its_context_and_chain():
    history = [act(o, OFFERED) for _ in range(4) for o in ROUTINE] + [act(o, OFFERED) for o in ROUTINE[:3]]
    ranking = RoutineOracle(kitchen()).fit(history).rank(OFFERED)
    best = ranking[0]
    assert best.option == ROUTINE[3]
    assert best.order == 3 and best.n_similar == 4
    assert best.context == tuple(str(o) for o in ROUTINE[:3])
    assert best.situations == (3, 7, 11, 15)          # every past PLACE after pick, pour, drink
    assert ranking.chain()[:2] == (ROUTINE[3], ROUTINE[0])  # what followed it in the past


def test_a_never_seen_action_is_ranked_by_its_similarity_to_what_the_user_did():
    history = [act(Option(PICK, RED), (Option(PICK, RED),)) for _ in range(5)]
    offered = (Option(OPEN_, DRAWER), Option(PICK, BLUE), Option(CLOSE, DRAWER))
    ranking = RoutineOracle(kitchen()).fit(history).rank(offered)
    assert ranking[0].option == Option(PICK, BLUE)    # the blue mug is like the red one
    assert ranking[0].order == -1 and ranking[0].n_similar == 0
    assert ranking[0].nearest == pytest.approx(2 * 0.0 + 0.1)


def test_what_follows_an_idle_gap_is_a_context_of_its_own():
    a, b, c, d = ROUTINE
    history = []
    for _ in range(3):
        history += [act(a), act(b), act(d), act(a), act(b), idle(), act(c)]
    model = RoutineOracle(kitchen()).fit(history)
    assert model.rank((c, d)).options() == (d, c)  # after pick, pour: place (no gap since the last action) ...
    after_gap = model.partial_fit(act(a)).partial_fit(act(b)).partial_fit(idle()).rank((d, c))
    assert after_gap[0].option == c and "idle" in after_gap[0].context  # ... but drink after a gap


def test_the_time_of_day_moves_similar_evidence():
    morning, evening = Option(DRINK, RED), Option(DRINK, BLUE)
    history = [act(morning, tod="Morning"), act(evening, tod="Evening")] * 3
    model = RoutineOracle(kitchen(), orders=(0,), time_of_day_penalty=3.0).fit(history)
    offered = (Option(PICK, RED), Option(PICK, BLUE))
    assert model.rank(offered, "Morning")[0].option == offered[0]
    assert model.rank(offered, "Evening")[0].option == offered[1]


def test_rank_changes_nothing_and_fit_equals_partial_fit():
    steps = synthetic_history(80, seed=4)
    model = RoutineOracle(random_matrix(4)).fit(steps[:60])
    before = (model.n_steps_, model.weights_.hits.copy(), len(model.options_))
    first = model.rank(steps[60])
    assert model.rank(steps[60]) == first
    assert (model.n_steps_, len(model.options_)) == before[::2] and (model.weights_.hits == before[1]).all()
    for step in steps[60:]:
        model.partial_fit(step)
    fresh = RoutineOracle(random_matrix(4)).fit(steps)
    assert fresh.rank(steps[0]) == model.rank(steps[0])


@settings(max_examples=25, deadline=None)
@given(histories(max_size=20), st.lists(option_strategy(), min_size=1, max_size=5).map(tuple))
def test_rankings_are_deterministic_permutations_of_the_offer(history, offered):
    one = RoutineOracle(random_matrix(1)).fit(history).rank(offered)
    two = RoutineOracle(random_matrix(1)).fit(history).rank(offered)
    assert one == two
    assert sorted(map(str, one.options())) == sorted(map(str, dict.fromkeys(offered)))
    assert [t.rank for t in one] == list(range(1, len(one) + 1))
    assert sum(t.probability for t in one) == pytest.approx(1.0)


@settings(max_examples=40, deadline=None)
@given(option_strategy(), option_strategy())
def test_vectorised_algorithm_2_equals_the_reference(a, b):
    matrix = random_matrix(2)
    values = option_distances(matrix.values, class_rows(matrix, [a]), class_rows(matrix, [b]), 2.0, 1.0, 3.7)
    assert values[0, 0] == pytest.approx(overall_distance(Hyperparameters(), matrix, a, b))


def test_self_tuning_follows_the_variant_that_predicted_the_user_best():
    steps = synthetic_history(200, seed=6)
    model = RoutineOracle(random_matrix(6), orders=(0, 3), temperatures=(1.0,), lowest_orders=(0,),
                          novelty=(False,)).fit(steps)
    assert model.variants_ == (("idle", 0, 1.0, 0, True, True, False), ("idle", 3, 1.0, 0, True, True, False))
    assert model.weights_.hits[1] > model.weights_.hits[0]  # the routine is sequential
    assert model.weights_.weights("leader").tolist() == [0.0, 1.0]
    assert model.weights_.weights("leader", 2.0).tolist() == [0.0, 1.0]  # clearly better: it leads
    assert model.weights_.weights("leader", 1e6).tolist() == [1.0, 0.0]  # not by a million errors
    assert model.weights_.weights("fixed").tolist() == [1.0, 0.0]


def test_a_variant_must_beat_the_first_by_the_margin_to_lead():
    weights = VariantWeights(2)
    even = [np.array([0.6, 0.4]), np.array([0.4, 0.6])]
    weights.update(even, 1)   # the second variant was right once, the first not: a lead of 2/3
    weights.update(even, 0)   # ... then the first was right: no lead
    weights.update(even, 1)
    assert weights.hits[1] - weights.hits[0] == pytest.approx(1 / 3)
    assert weights.weights("leader").tolist() == [0.0, 1.0]
    # lead 1/3 against sqrt(3 * (1/3)^2) = 0.577 standard units: one, not two, margins ahead
    assert weights.weights("leader", 0.5).tolist() == [0.0, 1.0]
    assert weights.weights("leader", 2.0).tolist() == [1.0, 0.0]


def test_parameters_follow_the_estimator_contract():
    model = RoutineOracle(kitchen(), orders=(2,))
    assert model.get_params()["orders"] == (2,)
    assert model.set_params(tuning="fixed") is model and model.tuning == "fixed"
    with pytest.raises(SettingsError, match="unknown parameter"):
        model.set_params(nope=1)
    for bad in ({"orders": ()}, {"temperatures": (0.0,)}, {"streams": ("sideways",)}, {"tuning": "best"},
                {"penalty": -1.0}, {"context_depth": 1.5}, {"lowest_orders": (2,)},
                {"timed": ()}, {"timed": (1,)}, {"timed_from": -1}, {"discounts": ("yes",)}, {"discount_from": -1},
                {"discount_from": True}, {"discount_evidence": -1}, {"discount_evidence": 1.5},
                {"timed_discount_from": -1}, {"timed_discount_from": 1.0}, {"timed_shrink": 1},
                {"switch_margin": -1.0}):
        with pytest.raises(SettingsError):
            RoutineOracle(kitchen(), **bad).fit([])
    fitted = RoutineOracle(kitchen()).fit([])
    fitted.set_params(orders=(1,))
    with pytest.raises(SettingsError, match="changed since fit"):
        fitted.rank(OFFERED)
    with pytest.raises(SettingsError, match="not fitted"):
        RoutineOracle(kitchen()).rank(OFFERED)


def test_the_registry_names_the_default_and_the_exact_thesis_oracle():
    assert DEFAULT == "personal" and set(PREDICTORS) >= {"personal", "pooled", "routine", "thesis"}
    assert isinstance(make_predictor(DEFAULT, kitchen()), PersonalOracle)
    assert isinstance(make_predictor("pooled", kitchen()), PooledOracle)
    assert isinstance(make_predictor("routine", kitchen()), RoutineOracle)
    assert make_predictor("routine-fixed", kitchen()).tuning == "fixed"
    steps = synthetic_history(60, seed=3)
    matrix = random_matrix(3)
    for name in ("recommended", "L"):
        thesis = make_predictor("thesis", matrix, frozenset({TASKS[3]}), PRESETS[name]).fit(steps[:50])
        direct = PreferenceOracle.from_settings(matrix, PRESETS[name], frozenset({TASKS[3]})).fit(steps[:50])
        assert thesis.rank(steps[55]) == direct.rank(steps[55])
    assert predictor_spec(" Thesis ").name == "thesis"
    with pytest.raises(SettingsError, match="known: routine, routine-fixed, routine-mixture, stacked, online, pooled, "
                                            "personal, thesis, thesis-normalized"):
        make_predictor("bayes", matrix)


def test_timed_contexts_refine_a_context_by_the_part_of_day():
    counts = ContextCounts(1, timed_from=1)
    for token, part in ((7, 0), (1, 0), (7, 2), (2, 2), (7, 0), (1, 0), (7, 2), (2, 2), (7, 0)):
        counts.add(token, part)
    base = np.full(2, 0.5)
    plain = counts.blend([1, 2], base, 1, 1).probabilities
    assert plain[0] == pytest.approx(plain[1])  # after 7: once 1, once 2 ... twice each
    morning = counts.blend([1, 2], base, 1, 1, part=0).probabilities
    evening = counts.blend([1, 2], base, 1, 1, part=2).probabilities
    assert morning[0] > morning[1] and evening[1] > evening[0]
    assert counts.blend([1, 2], base, 1, 1, part=3).probabilities.tolist() == plain.tolist()  # never at night
    untimed = ContextCounts(1)
    for token, part in ((7, 0), (1, 0), (7, 2), (2, 2)):
        untimed.add(token, part)
    assert untimed.blend([1, 2], base, 1, 1, part=0).probabilities.tolist() == \
        untimed.blend([1, 2], base, 1, 1).probabilities.tolist()


def test_the_discounted_blend_is_absolute_discounting_with_the_estimated_discount():
    counts = ContextCounts(1)
    for token in (5, 1, 5, 1, 5, 2, 5, 3, 5):
        counts.add(token)
    base = np.array([0.1, 0.1, 0.1, 0.7])   # candidates 1, 2, 3 and 4 (never seen after 5)
    ppm = counts.blend([1, 2, 3, 4], base, 1, 1).probabilities
    discounted = counts.blend([1, 2, 3, 4], base, 1, 1, discount=True).probabilities
    # D = n1 / (n1 + 2 n2) over the order-1 pairs: (5,2), (2,5), (5,3), (3,5) once, (5,1), (1,5) twice
    d = 4 / (4 + 2 * 2)
    assert counts.levels[1].discount() == pytest.approx(d)
    assert discounted == pytest.approx([(2 - d + d * 3 * 0.1) / 4, (1 - d + d * 3 * 0.1) / 4,
                                        (1 - d + d * 3 * 0.1) / 4, d * 3 * 0.7 / 4])
    assert float(discounted.sum()) == pytest.approx(float(ppm.sum())) == pytest.approx(1.0)
    assert discounted.tolist() != ppm.tolist()


def _order_2_counts() -> tuple[ContextCounts, np.ndarray, list[int]]:
    """Counts of order 2 whose latest context (1, 5) was followed by 1 and by 2, a base, the candidates."""
    counts = ContextCounts(2)
    for token in (5, 1, 5, 1, 5, 2, 5, 3, 5, 1, 5):
        counts.add(token)
    return counts, np.array([0.1, 0.1, 0.1, 0.7]), [1, 2, 3, 4]


def test_discounting_applies_from_its_order_and_ppm_c_below():
    counts, base, candidates = _order_2_counts()
    ppm = counts.blend(candidates, base, 2).probabilities
    everywhere = counts.blend(candidates, base, 2, discount=True).probabilities
    # from order 3 (above the maximum order 2): no level is discounted, the blend is PPM-C
    assert counts.blend(candidates, base, 2, discount=True, discount_from=3).probabilities.tolist() == ppm.tolist()
    assert counts.blend(candidates, base, 2, discount=True, discount_from=0).probabilities.tolist() == everywhere.tolist()
    # from order 2: orders 0 and 1 as PPM-C, then the order-2 level discounted on top of them
    below = counts.blend(candidates, base, 1).probabilities
    seen = np.array([counts.levels[2].tables[(1, 5)].get(c, 0) for c in candidates], dtype=float)
    d, kinds, total = counts.levels[2].discount(), len(counts.levels[2].tables[(1, 5)]), counts.levels[2].totals[(1, 5)]
    expected = (np.maximum(seen - d, 0.0) + d * kinds * below) / total
    assert counts.blend(candidates, base, 2, discount=True, discount_from=2).probabilities == pytest.approx(expected)
    assert expected.tolist() != everywhere.tolist()


def test_discounting_waits_for_the_evidence_of_its_estimate():
    counts, base, candidates = _order_2_counts()
    ppm = counts.blend(candidates, base, 2).probabilities.tolist()
    everywhere = counts.blend(candidates, base, 2, discount=True).probabilities.tolist()
    pairs = [counts.levels[n].evidence() for n in range(3)]
    assert pairs == [counts.levels[n].once + counts.levels[n].twice for n in range(3)] and min(pairs) > 0
    # below every order's evidence: discounted as without the threshold; above all of it: PPM-C
    assert counts.blend(candidates, base, 2, discount=True, discount_evidence=min(pairs)).probabilities.tolist() == everywhere
    assert counts.blend(candidates, base, 2, discount=True, discount_evidence=max(pairs) + 1).probabilities.tolist() == ppm


def test_the_part_of_day_levels_can_be_discounted_from_their_own_order():
    counts = ContextCounts(2, timed_from=1)
    for token in (5, 1, 5, 1, 5, 2, 5, 3, 5, 1, 5):
        counts.add(token, 0)
    base, candidates = np.array([0.1, 0.1, 0.1, 0.7]), [1, 2, 3, 4]
    same = counts.blend(candidates, base, 2, part=0, discount=True, discount_from=2).probabilities
    # None: the part-of-day levels follow discount_from (order 1 PPM-C, timed or not)
    assert counts.blend(candidates, base, 2, part=0, discount=True, discount_from=2,
                        timed_discount_from=None).probabilities.tolist() == same.tolist()
    # from order 1: the untimed order-1 level stays PPM-C, its part-of-day level is discounted by its own D
    untimed_1 = counts.blend(candidates, base, 1, discount=True, discount_from=2).probabilities
    level = counts.timed[1]
    seen = np.array([level.tables[(0, 5)].get(c, 0) for c in candidates], dtype=float)
    d, kinds, total = level.discount(), len(level.tables[(0, 5)]), level.totals[(0, 5)]
    assert counts.blend(candidates, base, 1, part=0, discount=True, discount_from=2,
                        timed_discount_from=1).probabilities == pytest.approx(
        (np.maximum(seen - d, 0.0) + d * kinds * untimed_1) / total)
    # without a part of day, or without discounting, the option changes nothing
    for kwargs in ({"part": -1, "discount": True}, {"part": 0, "discount": False}):
        assert counts.blend(candidates, base, 2, discount_from=2, timed_discount_from=1, **kwargs).probabilities.tolist() \
            == counts.blend(candidates, base, 2, discount_from=2, **kwargs).probabilities.tolist()


def test_a_shrunk_part_of_day_level_escapes_by_the_followers_of_its_context():
    counts = ContextCounts(1, timed_from=1)
    for token, part in ((5, 0), (1, 0), (5, 1), (2, 1), (5, 1), (3, 1), (5, 0), (1, 0), (5, 0)):
        counts.add(token, part)
    base, candidates = np.array([0.1, 0.2, 0.3, 0.4]), [1, 2, 3, 4]
    untimed = counts.blend(candidates, base, 1).probabilities     # P_1: context (5,) followed by 1, 2, 3, 1
    level = counts.timed[1].tables[(0, 5)]                        # at part 0: followed by 1 twice
    seen = np.array([level.get(c, 0) for c in candidates], dtype=float)
    n_t, u_n = sum(level.values()), len(counts.levels[1].tables[(5,)])
    assert (n_t, len(level), u_n) == (2, 1, 3)
    # PPM-C with the context's distinct followers at any time as the escape count
    assert counts.blend(candidates, base, 1, part=0, timed_shrink=True).probabilities == pytest.approx(
        (seen + u_n * untimed) / (n_t + u_n))
    own = counts.blend(candidates, base, 1, part=0).probabilities
    assert own == pytest.approx((seen + 1 * untimed) / (n_t + 1))
    # shrunk: between the untimed estimate and the part-of-day one
    assert untimed[0] < counts.blend(candidates, base, 1, part=0, timed_shrink=True).probabilities[0] < own[0]
    # without a part of day the option changes nothing
    assert counts.blend(candidates, base, 1, timed_shrink=True).probabilities.tolist() == untimed.tolist()


def test_at_order_0_the_counts_of_this_part_of_day_replace_the_overall_counts():
    counts = ContextCounts(0, timed_from=0)
    for token, part in ((1, 0), (1, 0), (1, 0), (2, 2)):
        counts.add(token, part)
    base = np.full(2, 0.5)
    plain = counts.blend([1, 2], base, 0).probabilities
    evening = counts.blend([1, 2], base, 0, part=2)
    assert plain[0] > plain[1] and evening.probabilities[1] > evening.probabilities[0]
    assert evening.probabilities == pytest.approx([0.25, 0.75])   # (0 + 1 * 0.5) / 2, (1 + 0.5) / 2
    assert evening.order.tolist() == [0, 0] and evening.count.tolist() == [3, 1]   # explained untimed
    assert counts.blend([1, 2], base, 0, part=3).probabilities.tolist() == plain.tolist()  # nothing at night yet


def test_the_routine_predictor_counts_what_the_user_does_at_this_part_of_day():
    morning, evening = Option(POUR, THERMOS, RED), Option(OPEN_, DRAWER)
    steps = [act(morning, (morning, evening), "Morning") for _ in range(6)]
    steps += [act(evening, (morning, evening), "Evening") for _ in range(3)]
    only_counts = {"orders": (0,), "lowest_orders": (0,)}
    timed = RoutineOracle(kitchen(), **only_counts).fit(steps)
    untimed = RoutineOracle(kitchen(), timed=(False,), **only_counts).fit(steps)
    assert timed.rank((morning, evening), "Evening").options()[0] == evening
    assert timed.rank((morning, evening), "Morning").options()[0] == morning
    assert untimed.rank((morning, evening), "Evening").options()[0] == morning   # done twice as often


def test_the_gate_tells_a_part_of_day_that_changes_the_followers_from_noise():
    from oracle.algorithm.contexts import differs
    assert differs({1: 8}, {1: 8, 2: 8}, 1.645)            # 8 x 1 here, 8 x 2 elsewhere: clearly different
    assert not differs({1: 1}, {1: 1, 2: 1}, 1.645)        # once each: could be chance
    assert not differs({1: 4, 2: 4}, {1: 8, 2: 8}, 0.0)    # the same shares here and elsewhere
    assert not differs({1: 3, 2: 1}, {1: 3, 2: 1}, 0.0)    # never followed at another part of day
    assert not differs({}, {1: 3, 2: 1}, 0.0) and not differs({1: 3}, {1: 5}, 0.0)   # nothing here / one follower
    # a stricter gate needs more evidence for the same shares
    assert differs({1: 5, 2: 1}, {1: 6, 2: 6}, 0.0) and not differs({1: 5, 2: 1}, {1: 6, 2: 6}, 3.0)


def test_a_gated_part_of_day_refines_only_where_it_differs():
    counts = ContextCounts(1, timed_from=0)
    alike = ((7, 0), (1, 0), (7, 0), (2, 0), (7, 2), (1, 2), (7, 2), (2, 2)) * 3   # after 7: 1 or 2 at either part
    for token, part in (*alike, (7, 0)):
        counts.add(token, part)
    base = np.full(2, 0.5)
    untimed = counts.blend([1, 2], base, 1, 0).probabilities
    assert counts.blend([1, 2], base, 1, 0, part=0, gate=1.645).probabilities.tolist() == untimed.tolist()
    assert counts.blend([1, 2], base, 1, 0, part=0).probabilities.tolist() != untimed.tolist()  # ungated: refined
    apart = ContextCounts(1, timed_from=1)
    for token, part in (*((7, 0), (1, 0), (7, 2), (2, 2)) * 6, (7, 0)):   # after 7: 1 in the morning, 2 in the evening
        apart.add(token, part)
    gated = apart.blend([1, 2], base, 1, 1, part=0, gate=1.645).probabilities
    assert gated.tolist() == apart.blend([1, 2], base, 1, 1, part=0).probabilities.tolist()
    assert gated[0] > 0.8


def test_exclusion_gives_the_never_done_options_the_estimate_of_a_novel_action():
    counts = ContextCounts(1)
    for token in (1, 1, 2):
        counts.add(token)
    base = np.array([0.45, 0.45, 0.05, 0.05])   # candidates 1, 2 and two never done, 3 and 4
    plain = counts.blend([1, 2, 3, 4], base, 0).probabilities
    excluded = counts.blend([1, 2, 3, 4], base, 0, exclusion=True).probabilities
    # order 0: N = 3 actions, u = 2 distinct; the escape 2/5 goes to 3 and 4 alone, shared by base
    assert excluded == pytest.approx([2 / 5, 1 / 5, 1 / 5, 1 / 5])
    assert plain == pytest.approx([(2 + 2 * 0.45) / 5, (1 + 2 * 0.45) / 5, 2 * 0.05 / 5, 2 * 0.05 / 5])
    # only the lowest level excludes: order 1 above it blends as before
    above = counts.blend([1, 2, 3, 4], base, 1, exclusion=True).probabilities   # context (2,): never followed yet
    assert above.tolist() == excluded.tolist()
    # nothing left to exclude to: the base is kept
    assert counts.blend([1, 2], np.full(2, 0.5), 0, exclusion=True).probabilities.tolist() == \
        counts.blend([1, 2], np.full(2, 0.5), 0).probabilities.tolist()


@pytest.mark.parametrize("options", [{"timed_gate": 1.645}, {"exclusion": True}, {"timed_gate": 0.0, "exclusion": True},
                                     {"novelty": (True,)}, {"novelty": (False, True), "timed_gate": 1.645},
                                     {"focus": 0}, {"focus": 1, "focus_odds": False}, {"focus_level": "top"},
                                     {"timed_blend": 0.5}, {"fresh": False}, {"fresh_level": "base"}, {"resume": False}])
def test_the_new_options_on_empty_and_tiny_histories(options):
    empty = RoutineOracle(kitchen(), **options).fit([]).rank(OFFERED)
    assert empty.options() == OFFERED
    assert [t.probability for t in empty] == pytest.approx([1 / len(OFFERED)] * len(OFFERED))
    one = RoutineOracle(kitchen(), **options).fit([act(ROUTINE[1], OFFERED, "Morning")]).rank(OFFERED, "Morning")
    assert one[0].option == ROUTINE[1] and sum(t.probability for t in one) == pytest.approx(1.0)
    steps = [s for _ in range(5) for s in (idle(), *(act(o, OFFERED, "Morning") for o in ROUTINE))] + [idle()]
    model = RoutineOracle(kitchen(), **options).fit(steps)
    after = model.rank(OFFERED, "Morning")
    assert after.options()[0] == ROUTINE[0] and after[0].context[-1] == "idle"   # the routine starts after a gap
    assert RoutineOracle(kitchen(), **options).fit(steps[:-1]).partial_fit(steps[-1]).rank(OFFERED, "Morning") == after


def test_the_new_options_are_validated():
    for bad in ({"timed_gate": True}, {"timed_gate": "high"}, {"timed_gate": math.inf}, {"exclusion": 1},
                {"novelty": True}, {"novelty": ()}, {"novelty": (1,)}, {"focus": -1}, {"focus": True},
                {"focus_odds": 1}, {"focus_level": "all"}, {"timed_blend": 2}, {"timed_blend": True},
                {"fresh": 1}, {"fresh": "yes"}, {"fresh_level": "all"}, {"resume": 1}):
        with pytest.raises(SettingsError):
            RoutineOracle(kitchen(), **bad).fit([])


def test_novelty_gives_the_never_done_options_the_estimate_of_a_novel_action_and_keeps_q_among_the_rest():
    counts = ContextCounts(1)
    for token in (1, 1, 2):
        counts.add(token)
    base = np.array([0.45, 0.45, 0.05, 0.05])   # candidates 1, 2 done; 3, 4 never done
    # order 0: q = u / (N + u) = 2 / 5; the done part escapes to base restricted to the done ones
    novel = counts.blend([1, 2, 3, 4], base, 0, novelty=True).probabilities
    assert novel == pytest.approx([0.6 * (2 + 2 * 0.5) / 5, 0.6 * (1 + 2 * 0.5) / 5, 0.4 * 0.5, 0.4 * 0.5])
    # without the order-0 level the split sits under the first context (here unseen: it stays)
    assert counts.blend([1, 2, 3, 4], base, 1, 1, novelty=True).probabilities == pytest.approx([0.3, 0.3, 0.2, 0.2])
    # an offer of done options only, or of never-done options only, is blended as without novelty
    for offer, b in (([1, 2], np.array([0.7, 0.3])), ([3, 4], np.array([0.7, 0.3]))):
        assert counts.blend(offer, b, 1, novelty=True).probabilities.tolist() == counts.blend(offer, b, 1).probabilities.tolist()
    assert ContextCounts(1).blend([1, 2], np.full(2, 0.5), 1, novelty=True).probabilities.tolist() == [0.5, 0.5]


def test_the_default_has_novelty_variants_after_the_plain_ones():
    model = RoutineOracle(kitchen()).fit([])
    assert len(model.variants_) == 16 and model.variants_[0][-1] is False
    assert [v[-1] for v in model.variants_[:2]] == [False, True]


@settings(max_examples=60, deadline=None)
@given(tokens=st.lists(st.tuples(st.sampled_from([-1, 0, 1, 2, 3, 4]), st.integers(-1, 3)), max_size=60),
       candidates=st.lists(st.integers(-3, 6), min_size=1, max_size=6, unique=True),
       lowest=st.sampled_from([0, 1]), timed_from=st.sampled_from([-1, 0, 1]), part=st.integers(-1, 3),
       discount=st.booleans(), exclusion=st.booleans(), novelty=st.booleans(),
       gate=st.sampled_from([None, 1.0]), discount_from=st.integers(0, 3), evidence=st.sampled_from([0, 3, 10]),
       timed_discount=st.sampled_from([None, 1, 2]), shrink=st.booleans())
def test_blends_of_several_maximum_orders_equal_the_blend_of_each(tokens, candidates, lowest, timed_from, part,
                                                                  discount, exclusion, novelty, gate, discount_from,
                                                                  evidence, timed_discount, shrink):
    # The self-tuning's variants that differ in their maximum order only share one blend pass:
    # each order's result must be exactly the blend computed alone.
    counts = ContextCounts(5, timed_from)
    for token, token_part in tokens:
        counts.add(token, token_part)
    base = np.random.default_rng(len(tokens)).random(len(candidates)) + 0.01
    base /= base.sum()
    stops = (3, 5, 1, 7)
    together = counts.blends(candidates, base, stops, lowest, part, discount, gate, exclusion, novelty, {}, discount_from,
                             evidence, timed_discount, shrink)
    for stop in stops:
        alone = counts.blend(candidates, base, stop, lowest, part, discount, gate, exclusion, novelty,
                             discount_from=discount_from, discount_evidence=evidence, timed_discount_from=timed_discount,
                             timed_shrink=shrink)
        assert np.array_equal(together[stop].probabilities, alone.probabilities)
        assert np.array_equal(together[stop].order, alone.order) and np.array_equal(together[stop].count, alone.count)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 5), st.integers(-1, 3)), min_size=0, max_size=60),
       st.lists(st.floats(0.0, 1.0), min_size=12, max_size=12), st.booleans(), st.booleans(), st.booleans(),
       st.integers(0, 1))
def test_a_stack_of_bases_blends_each_row_bit_for_bit_as_alone(tokens, weights, novelty, exclusion, discount, lowest):
    counts = ContextCounts(3, timed_from=0)
    for token, part in tokens:
        counts.add(token if token < 5 else -1, part)   # 5 stands for the idle token
    candidates = [0, 1, 2, 3, 4, 7]                     # 7: never counted
    rows = np.array(weights).reshape(2, 6)
    rows[1, :3] = 0.0                                   # a row without mass on the done candidates
    kwargs = dict(min_order=lowest, part=tokens[-1][1] if tokens else -1, discount=discount,
                  exclusion=exclusion, novelty=novelty, discount_from=1, discount_evidence=2)
    stacked = counts.blends(candidates, rows, (1, 3), **kwargs)
    for row in range(2):
        alone = counts.blends(candidates, rows[row], (1, 3), **kwargs)
        for order in (1, 3):
            assert stacked[order].probabilities[row].tolist() == alone[order].probabilities.tolist()
            assert stacked[order].order.tolist() == alone[order].order.tolist()


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 5), st.integers(-1, 3)), min_size=0, max_size=60),
       st.lists(st.floats(0.0, 1.0), min_size=24, max_size=24),
       st.lists(st.tuples(st.sampled_from([0, 0, 1, 1, 2]), st.booleans(), st.booleans()), min_size=1, max_size=4),
       st.booleans(), st.booleans(), st.sampled_from([-1, 0, 1]), st.booleans())
def test_lanes_blended_in_one_pass_equal_each_lane_alone(tokens, weights, lanes, exclusion, discount, timed_from,
                                                         shrink):
    # The self-tuning's variants that differ in their lowest order and novelty share the levels
    # from order 1 on: each lane's rows, flat or stacked, must come out exactly as alone.
    counts = ContextCounts(3, timed_from=timed_from)
    for token, part in tokens:
        counts.add(token if token < 5 else -1, part)   # 5 stands for the idle token
    candidates = [0, 1, 2, 3, 4, 7]                     # 7: never counted
    rows = np.array(weights).reshape(4, 6)
    rows[1, :3] = 0.0                                   # a row without mass on the done candidates
    bases = [rows[i] if flat else rows[i:i + 2] for i, (_, _, flat) in enumerate(lanes)]
    kwargs = dict(part=tokens[-1][1] if tokens else -1, discount=discount, exclusion=exclusion,
                  discount_from=1, discount_evidence=2, timed_shrink=shrink)
    together = counts.lane_blends(candidates, [(base, lowest, novelty) for base, (lowest, novelty, _) in zip(bases, lanes)],
                                  (3, 1, 2), **kwargs)
    for base, (lowest, novelty, _), found in zip(bases, lanes, together):
        alone = counts.blends(candidates, base, (3, 1, 2), lowest, novelty=novelty, **kwargs)
        for order in (1, 2, 3):
            assert found[order].probabilities.shape == alone[order].probabilities.shape
            assert found[order].probabilities.tobytes() == alone[order].probabilities.tobytes()
            assert found[order].order.tolist() == alone[order].order.tolist()
            assert found[order].count.tolist() == alone[order].count.tolist()


def test_the_part_of_day_levels_stop_at_timed_to():
    counts = ContextCounts(2, timed_from=0)
    for token, part in ((7, 0), (1, 0), (7, 2), (2, 2), (7, 0), (1, 0), (7, 2), (2, 2), (7, 0)):
        counts.add(token, part)
    base = np.full(3, 1 / 3)
    candidates = [1, 2, 7]
    untimed = counts.blend(candidates, base, 2, 1).probabilities.tolist()
    morning = counts.blend(candidates, base, 2, 1, part=0).probabilities.tolist()
    assert morning != untimed
    # timed_to 0: no part-of-day level at orders 1 and 2 (the order-0 level is below min_order 1)
    assert counts.blend(candidates, base, 2, 1, part=0, timed_to=0).probabilities.tolist() == untimed
    # timed_to 1: order 1 refined, order 2 not: the blend up to order 1 equals the fully timed one
    assert counts.blend(candidates, base, 1, 1, part=0, timed_to=1).probabilities.tolist() == \
        counts.blend(candidates, base, 1, 1, part=0).probabilities.tolist()
    assert counts.blend(candidates, base, 2, 1, part=0, timed_to=1).probabilities.tolist() != morning


def test_timed_to_is_checked():
    with pytest.raises(SettingsError, match="timed_to"):
        RoutineOracle(kitchen(), timed_to=-1).fit([])


def _handled_then_used(objects, rounds):
    """A user who picks an object and then drinks from that object, for changing objects."""
    offered = tuple(Option(t, o) for o in objects for t in (PICK, DRINK))
    return [act(Option(task, o), offered) for _ in range(rounds) for o in objects for task in (PICK, DRINK)]


def test_the_objects_in_hand_lift_the_never_done_options_that_use_them():
    history = _handled_then_used((RED, BLUE, THERMOS), 3) + [act(Option(PICK, SPOON))]
    offered = (Option(DRINK, PLATE), Option(DRINK, SPOON))      # neither was ever done
    plain = RoutineOracle(kitchen(), focus=0).fit(history).rank(offered)
    assert plain[0].probability == pytest.approx(plain[1].probability)   # alike by similarity: offered order
    model = RoutineOracle(kitchen(), focus=1).fit(history)
    handled = model.rank(offered)
    lift, rest = model.hand_.lift(model.focus_odds)
    assert lift > 1 > rest   # this user goes on with what they just picked
    # both escape to the lowest level alike, so their odds are the lift's
    assert handled[0].probability / handled[1].probability == pytest.approx(lift / rest)
    assert handled.options()[0] == Option(DRINK, SPOON) and handled[0].focus == (SPOON,)
    assert handled[1].focus == () and handled[0].probability > handled[1].probability


def test_the_lift_is_the_users_own_rate_of_using_an_object_in_hand_against_the_offer():
    history = _handled_then_used((RED, BLUE), 1)     # pick red, drink red, pick blue, drink blue
    model = RoutineOracle(kitchen(), focus=1).fit(history)
    # with the latest action's objects in focus, half the 4 offered options use them at steps 2-4
    # (the first step has no focus): drink red yes, pick blue no, drink blue yes
    assert (model.hand_.steps, model.hand_.hits, model.hand_.share) == (3, 2.0, 1.5)
    assert model.hand_.lift(True) == pytest.approx(((2 + 1) / (1.5 + 1), (3 - 2 + 1) / (3 - 1.5 + 1)))
    assert model.hand_.lift(False) == pytest.approx(((2 + 1) / (1.5 + 1), 1.0))
    fitted = RoutineOracle(kitchen(), focus=1).fit(history[:2])
    for step in history[2:]:
        fitted.partial_fit(step)
    assert fitted.hand_ == model.hand_


def _takes_what_is_new():
    """A user who takes, each time, the option the latest action made available (offers by hand)."""
    offers = [((PICK, RED), (PICK, BLUE)), ((PICK, BLUE), (DRINK, RED)),
              ((PICK, BLUE), (DRINK, RED), (PICK, THERMOS)), ((PICK, BLUE), (DRINK, THERMOS))]
    chosen = [(PICK, RED), (DRINK, RED), (PICK, THERMOS), (DRINK, THERMOS)]
    return [act(Option(*done), tuple(Option(*o) for o in offer)) for offer, done in zip(offers, chosen)]


def test_the_lift_of_the_newly_offered_options_is_counted_against_the_offer_of_the_previous_decision():
    history = _takes_what_is_new()
    model = RoutineOracle(kitchen(), fresh=True).fit(history)
    # the first decision has no previous offer; then 1 of 2, 1 of 3 and 1 of 2 options were new, each taken
    assert (model.fresh_.lift.steps, model.fresh_.lift.hits) == (3, 3.0)
    assert model.fresh_.lift.share == pytest.approx(1 / 2 + 1 / 3 + 1 / 2)
    assert model.fresh_.lift.lift(True) == pytest.approx((4 / (4 / 3 + 1), 1 / (3 - 4 / 3 + 1)))
    stepwise = RoutineOracle(kitchen(), fresh=True).fit(history[:1])
    for step in history[1:]:
        stepwise.partial_fit(step)
    assert stepwise.fresh_ == model.fresh_
    assert RoutineOracle(kitchen(), fresh=False).fit(history).fresh_.lift.steps == 0   # not counted when off


@pytest.mark.parametrize("level", ["top", "base"])
def test_the_newly_offered_options_are_lifted_by_the_users_own_odds(level):
    history = _takes_what_is_new()
    offered = (Option(PICK, BLUE), Option(DRINK, SPOON))   # neither done; blue offered before, the spoon new
    plain = RoutineOracle(kitchen(), fresh=False).fit(history).rank(offered)
    model = RoutineOracle(kitchen(), fresh=True, fresh_level=level).fit(history)
    lifted = model.rank(offered)
    w_new, w_old = model.fresh_.lift.lift(True)
    assert w_new > 1 > w_old
    ratio = {r: {t.option: t.probability for t in r} for r in (plain, lifted)}
    before = ratio[plain][Option(DRINK, SPOON)] / ratio[plain][Option(PICK, BLUE)]
    after = ratio[lifted][Option(DRINK, SPOON)] / ratio[lifted][Option(PICK, BLUE)]
    # on the blend, or on Q where both escape to the lowest level alike: the odds move by the lift's
    assert after == pytest.approx(before * w_new / w_old)
    assert after > before
    assert {t.option: t.new for t in lifted} == {Option(DRINK, SPOON): True, Option(PICK, BLUE): False}
    assert not any(t.new for t in plain)


def test_an_offer_that_never_changes_leaves_the_newly_offered_lift_out():
    # every step offers the same options (as a replay without available sets does): nothing is new
    history = _handled_then_used((RED, BLUE, THERMOS), 3)
    offered = history[0].options
    plain = RoutineOracle(kitchen(), fresh=False).fit(history)
    model = RoutineOracle(kitchen(), fresh=True).fit(history)
    assert model.fresh_.lift.steps == 0
    assert model.rank(offered) == plain.rank(offered)


def _picks_then_breaks_then_drinks(rounds):
    """A user who picks a mug, pauses, then drinks from it, for two mugs (the same four offered)."""
    offered = tuple(Option(t, o) for o in (RED, BLUE) for t in (PICK, DRINK))
    return [s for _ in range(rounds) for o in (RED, BLUE)
            for s in (act(Option(PICK, o), offered), idle(), act(Option(DRINK, o), offered))]


def test_after_a_break_the_lift_counts_the_options_that_once_followed_the_last_action():
    history = _picks_then_breaks_then_drinks(2)
    model = RoutineOracle(kitchen()).fit(history)
    # after each break the last action was a pick; only in the second round had its drink followed
    # it before (1 of the 4 offered options), and each time it was taken
    assert (model.resume_.lift.steps, model.resume_.lift.hits, model.resume_.lift.share) == (2, 2.0, 0.5)
    stepwise = RoutineOracle(kitchen()).fit(history[:1])
    for step in history[1:]:
        stepwise.partial_fit(step)
    assert stepwise.resume_.lift == model.resume_.lift
    assert RoutineOracle(kitchen(), resume=False).fit(history).resume_.lift.steps == 0


def test_after_a_break_the_option_that_goes_on_from_the_last_action_is_lifted():
    history = _picks_then_breaks_then_drinks(3)
    offered = history[0].options
    now = history + [act(Option(PICK, RED), offered), idle()]
    plain = {t.option: t for t in RoutineOracle(kitchen(), resume=False).fit(now).rank(offered)}
    model = RoutineOracle(kitchen()).fit(now)
    lifted = {t.option: t for t in model.rank(offered)}
    w_in, w_out = model.resume_.lift.lift(True)
    assert w_in > 1 > w_out
    assert lifted[Option(DRINK, RED)].probability > plain[Option(DRINK, RED)].probability
    assert [o for o, t in lifted.items() if t.resumed] == [Option(DRINK, RED)]
    # without a break right before now nothing is lifted, and nothing is said
    for resume in (True, False):
        after = RoutineOracle(kitchen(), resume=resume).fit(now[:-1]).rank(offered)
        assert not any(t.resumed for t in after)
    assert RoutineOracle(kitchen()).fit(now[:-1]).rank(offered) == \
        RoutineOracle(kitchen(), resume=False).fit(now[:-1]).rank(offered)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 4), st.integers(-2, 3), st.integers(-1, 3)), min_size=1, max_size=60),
       st.sampled_from([0.5, 2.0]), st.integers(-1, 3))
def test_the_similarity_mass_by_kinds_equals_it_per_action_bit_for_bit(actions, tau, now_code):
    """Q weighs each kind of past action (its predecessors and part of day) once and hands the
    weight to its actions: the same numbers, summed in the same order, as per action."""
    from oracle.algorithm.kernel import context_distance, similarity_mass

    rng = np.random.default_rng(len(actions))
    table = rng.uniform(0.0, 2.0, (5, 5))
    cand = rng.uniform(0.0, 2.0, (3, 5))
    executed = np.array([a for a, _, _ in actions])
    before = np.array([[b, (b + 1) % 3, -2] for _, b, _ in actions])
    tod = np.array([t for _, _, t in actions])
    now = (1, -1, 2)
    kinds: dict[tuple[int, ...], int] = {}
    kind_of = np.array([kinds.setdefault((*row, t), len(kinds)) for row, t in zip(before.tolist(), tod.tolist())])
    first = {k: i for i, k in reversed(list(enumerate(kind_of.tolist())))}
    order = [first[k] for k in range(len(kinds))]
    differs = (tod >= 0) & (tod != now_code) if now_code >= 0 else np.zeros(tod.size, dtype=bool)
    alone = similarity_mass(cand, executed, context_distance(table, now, before, 1.5, 0.5), differs, tau, 2.0)
    grouped = similarity_mass(cand, executed, context_distance(table, now, before[order], 1.5, 0.5), differs[order],
                              tau, 2.0, kind_of)
    assert alone.tobytes() == grouped.tobytes()


def test_the_variants_scores_count_ties_as_rank_orders_them():
    # every variant scored at once equals each scored alone: ties go to the option offered first
    rng = np.random.default_rng(7)
    for _ in range(200):
        size = int(rng.integers(1, 9))
        probabilities = [rng.integers(0, 4, size) / 4.0 for _ in range(5)]
        truth = int(rng.integers(0, size))
        weights = VariantWeights(5)
        weights.update(probabilities, truth)
        hits = []
        for p in probabilities:
            better = sum(1 for i, q in enumerate(p) if q > p[truth] or (q == p[truth] and i < truth))
            hits.append(((better < 1) + (better < 3) + (better < 5)) / 3.0)
        assert weights.hits.tolist() == hits
        assert weights.spread.tolist() == [(h - hits[0]) ** 2 for h in hits]
        assert weights.scores.tolist() == [math.log(max(float(p[truth]), 1e-12)) for p in probabilities]
