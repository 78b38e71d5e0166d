"""The learned predictor of the usual mode: a logit fitted to the user's counts."""

from __future__ import annotations

import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from oracle.past.autonomy import TIE_ORDER, ModeCounts, Performed, fit
from oracle.past.modelogit import fit_modes, ranked_modes

CALLS = ("pick(red_mug)", "pick(apple)", "pour(thermos, red_mug)", "open(fridge)", "eat(apple)")
PARTS = ("Morning", "Midday", "Evening")


def test_what_is_shared_between_tasks_carries_to_a_task_never_seen_then():
    # Every task the user does by hand in the morning and leaves to the robot in the evening;
    # open(fridge) was only ever seen in the morning. Its own counts say the user; the evening says the robot.
    seen = [Performed(call, "Morning", "user") for call in CALLS[:3] for _ in range(6)]
    seen += [Performed(call, "Evening", "robot") for call in CALLS[:3] for _ in range(6)]
    seen += [Performed("open(fridge)", "Morning", "user")] * 2
    counts = fit(seen)
    assert counts.predict("open(fridge)", "Evening")[0] == "user"
    assert fit_modes(counts).predict("open(fridge)", "Evening") == "robot"
    assert fit_modes(counts).predict("open(fridge)", "Morning") == "user"


def test_a_call_with_many_counts_keeps_its_own_mode():
    seen = [Performed("pour(thermos, red_mug)", "Morning", "together")] * 12
    seen += [Performed(call, "Morning", "user") for call in CALLS if "pour" not in call for _ in range(4)]
    assert fit_modes(fit(seen)).predict("pour(thermos, red_mug)", "Morning") == "together"


def test_nothing_seen_is_a_tie_and_the_user_takes_it():
    model = fit_modes(ModeCounts())
    assert model.predict("pick(apple)", "Morning") == "user"


def test_the_ranking_cites_the_counts_and_says_nothing_of_unknown_tasks():
    counts = fit([Performed("pick(red_mug)", "Morning", "robot")] * 3 + [Performed("pick(red_mug)", "Morning", "user")])
    usual, chain = ranked_modes(counts, ["pick(red_mug)", "cut(bread)"], ["pick(red_mug)", "cut(bread)"], "Morning")
    assert usual[0].to_json() == {"mode": "robot", "context": "call and part",
                                  "counts": {"robot": 3, "user": 1, "together": 0}}
    assert usual[1].mode is None and chain == ["robot", None]
    (none,), _ = ranked_modes(counts, ["pick(red_mug)"], [], None)  # no clock: the part "none"
    assert none.context == "call" and none.mode == "robot"


performed = st.lists(st.tuples(st.sampled_from(CALLS), st.sampled_from(PARTS), st.sampled_from(TIE_ORDER)),
                     min_size=1, max_size=60)


@settings(max_examples=25, deadline=None)
@given(performed)
def test_the_fit_is_the_penalised_likelihoods_minimum_whatever_the_order(actions):
    from scipy.optimize import minimize

    forward = fit_modes(fit(Performed(*a) for a in actions))
    shuffled = list(actions)
    random.Random(len(actions)).shuffle(shuffled)
    backward = fit_modes(fit(Performed(*a) for a in shuffled))
    for call in CALLS:
        for part in PARTS:
            assert forward.predict(call, part) == backward.predict(call, part)
            np.testing.assert_allclose(forward.scores(call, part), backward.scores(call, part), atol=1e-4)
    # an independent solver finds the same penalised log-likelihood
    counts = fit(Performed(*a) for a in actions)
    cells = [(k[1], k[2], c) for k, c in counts.counts.items() if k[0] == "cp"]
    rows = forward.rows
    index = np.array([[rows["b"], rows[f"t:{counts.task_of(c)}"], rows[f"c:{c}"], rows[f"p:{p}"]] for c, p, _ in cells])
    seen = np.array([[n.get(m, 0) for m in TIE_ORDER] for _, _, n in cells], float)

    def loss(flat: np.ndarray) -> float:
        scores = flat.reshape(len(rows), 3)[index].sum(axis=1)
        top = scores.max(axis=1, keepdims=True)
        log_p = scores - top - np.log(np.exp(scores - top).sum(axis=1, keepdims=True))
        return float(-(seen * log_p).sum() + 5.0 * flat @ flat)

    best = minimize(loss, np.zeros(len(rows) * 3), method="BFGS", options={"gtol": 1e-8})
    assert loss(forward.weights.ravel()) == pytest.approx(best.fun, rel=1e-6, abs=1e-6)


def test_a_call_done_the_same_way_three_times_keeps_its_mode():
    # the robot does most things; the user poured twice, then three times, by hand
    robot = [Performed(call, "Morning", "robot") for call in CALLS if "pour" not in call for _ in range(5)]
    twice = fit(robot + [Performed("pour(thermos, red_mug)", "Morning", "user")] * 2)
    thrice = fit(robot + [Performed("pour(thermos, red_mug)", "Morning", "user")] * 3)
    (two,), _ = ranked_modes(twice, ["pour(thermos, red_mug)"], [], "Morning")
    (three,), _ = ranked_modes(thrice, ["pour(thermos, red_mug)"], [], "Morning")
    assert two.mode == "robot"  # two of its own weigh less than what everything else shares
    assert three.mode == "user" and three.counts == {"robot": 0, "user": 3, "together": 0}
    mixed = fit(robot + [Performed("pour(thermos, red_mug)", "Morning", "user")] * 3
                + [Performed("pour(thermos, red_mug)", "Morning", "together")])
    (four,), _ = ranked_modes(mixed, ["pour(thermos, red_mug)"], [], "Morning")
    assert four.mode == fit_modes(mixed).predict("pour(thermos, red_mug)", "Morning")  # not unanimous: the logit
