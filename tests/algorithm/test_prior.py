"""The shared prior: counts with k users, clipping and noise, its file, and the personal predictor."""

from __future__ import annotations

import json
from collections import Counter

import numpy as np
import pytest

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.prior import IDLE, Prior, PriorError, load_prior, option_key
from oracle.algorithm.prior_counts import Population, cells_of, released
from oracle.errors import SettingsError


def _sequences(seed: int, users: int = 12, length: int = 120) -> dict[str, list[str]]:
    rng = np.random.default_rng(seed)
    tasks = [f"t{i}(o{i % 3})" for i in range(8)]
    out = {}
    for u in range(users):
        habit = rng.permutation(len(tasks))  # each user their own favourite order
        seq: list[str] = []
        for i in range(length):
            seq.append(IDLE if i % 25 == 24 else tasks[habit[i % 5]] if rng.random() < 0.7 else tasks[rng.integers(8)])
        out[f"user{u}"] = seq
    return out


def _users_per_cell(sequences: dict[str, list[str]]) -> Counter:
    users: Counter = Counter()
    for seq in sequences.values():
        users.update(cells_of(seq).keys())
    return users


def test_cells_are_the_tasks_after_each_context_of_orders_0_to_3():
    cells = cells_of(["a", "b", IDLE, "c"])
    assert cells[((), "a")] == 1 and cells[(("a",), "b")] == 1
    assert cells[(("a", "b", IDLE), "c")] == 1 and cells[((IDLE,), "c")] == 1
    assert not any(task == IDLE for _, task in cells)  # idle is a context, never a task that followed
    assert sum(1 for context, _ in cells if len(context) > 3) == 0


@pytest.mark.parametrize("k", [2, 5])
def test_every_count_of_a_prior_has_at_least_k_users(k):
    sequences = _sequences(0)
    population = Population(clip=3)
    for user, seq in sequences.items():
        population.add(user, [seq])
    prior = population.prior(k)
    users = _users_per_cell(sequences)
    assert prior.cells() > 0
    for context, followers in prior.tables.items():
        for task in followers:
            assert users[(context, task)] >= k, (context, task)
    # and nothing that k users gave is left out
    kept = {(c, t) for c, f in prior.tables.items() for t in f}
    assert kept == {cell for cell, n in users.items() if n >= k}


def test_clipping_bounds_what_one_user_adds_to_any_count():
    sequences = _sequences(1)
    sequences["heavy"] = ["t0(o0)"] * 500  # one user doing one thing very often
    population = Population(clip=3)
    for user, seq in sequences.items():
        population.add(user, [seq])
    full = population.prior(k=1)
    without = population.without("heavy", k=1)
    # the sensitivity: removing one user moves any count by at most clip
    cells = {(c, t) for c, f in full.tables.items() for t in f}
    for context, task in cells:
        before = full.tables[context][task]
        after = without.tables.get(context, {}).get(task, 0.0)
        assert 0 <= before - after <= 3


def test_leaving_a_user_out_is_building_without_them():
    sequences = _sequences(2)
    population = Population(clip=3)
    for user, seq in sequences.items():
        population.add(user, [seq])
    others = Population(clip=3)
    for user, seq in sequences.items():
        if user != "user3":
            others.add(user, [seq])
    assert population.without("user3", k=2).tables == others.prior(k=2).tables


def test_the_noise_is_laplace_of_scale_clip_over_epsilon():
    # counts far from the cut at 0, so the noise is seen whole
    cells = {((f"c{i}",), "t"): 1000.0 for i in range(4000)}
    noisy = released(cells, {cell: 5 for cell in cells}, 5, 0.5, 2, np.random.default_rng(0))
    deviations = np.array([noisy[context]["t"] - 1000.0 for context, _ in cells])
    # Laplace(b): mean 0, mean absolute deviation b = clip / epsilon = 4
    assert abs(deviations.mean()) < 0.3
    assert 3.8 < np.abs(deviations).mean() < 4.2
    assert released(cells, {cell: 4 for cell in cells}, 5, 0.5, 2, np.random.default_rng(0)) == {}
    with pytest.raises(SettingsError):
        Population(clip=2).prior(k=1, epsilon=0.0)


def test_the_file_holds_counts_only_and_says_what_it_was_counted_under(tmp_path):
    population = Population()
    sequences = _sequences(4)
    for user, seq in sequences.items():
        population.add(user, [seq])
    prior = population.prior(k=3, fingerprint="abc123")
    path = tmp_path / "prior.json"
    prior.save(path)
    data = json.loads(path.read_text())
    assert data["format"] == "neem-oracle-prior" and data["version"] == 1 and data["fingerprint"] == "abc123"
    assert set(data) == {"format", "version", "fingerprint", "k", "epsilon", "clip", "users", "max_order", "idle",
                         "contexts"}
    assert all(set(row) == {"context", "next"} for row in data["contexts"])
    assert not any(user in path.read_text() for user in sequences)  # no user id
    assert load_prior(path, "abc123").tables == prior.tables
    with pytest.raises(PriorError, match="another ontology"):
        load_prior(path, "other")
    data["version"] = 2
    path.write_text(json.dumps(data))
    with pytest.raises(PriorError, match="version"):
        load_prior(path)


def test_probabilities_back_off_as_ppm_c():
    prior = Prior({(): {"a": 3.0, "b": 1.0}, ("a",): {"b": 2.0}})
    backed, unigram = prior.probabilities(["x", "a"], ["a", "b", "c"])
    # order 0: (n + kinds / 3) / (4 + 2); order 1 after "a": (n + 1 * lower) / (2 + 1)
    lower = np.array([(3 + 2 / 3) / 6, (1 + 2 / 3) / 6, (2 / 3) / 6])
    np.testing.assert_allclose(unigram, lower)
    np.testing.assert_allclose(backed, (np.array([0, 2, 0]) + lower) / 3)
    np.testing.assert_allclose(backed.sum(), 1.0)


def test_without_a_prior_the_personal_predictor_is_the_pooled_logit_alone():
    matrix = random_matrix(3)
    steps = synthetic_history(160, 3)
    personal = PersonalOracle(matrix).fit(steps[:140])
    logit = PooledOracle(matrix, pool_weight=0.0, online_gate=None).fit(steps[:140])
    np.testing.assert_allclose(personal.coef_[:logit.coef_.size], logit.coef_, atol=1e-9)
    for step in steps[140:]:
        assert [t.option for t in personal.rank(step)] == [t.option for t in logit.rank(step)]


def test_with_a_prior_it_starts_as_the_others_habits_and_learns_its_own():
    matrix = random_matrix(4)
    steps = [s for s in synthetic_history(200, 4) if not s.idle and len(s.options) > 2]
    # other people mostly did the option the first offer lists last
    prior = Prior({(): {option_key(steps[0].options[-1]): 50.0}})
    fresh = PersonalOracle(matrix).use_prior(prior).fit([])
    assert fresh.rank(steps[0]).tasks[0].option == steps[0].options[-1]
    # the prior is the process's: never kept with the fit, shared by the chain's copies
    assert fresh.__getstate__()["_prior"] is None
    assert fresh.fit(steps[:5]).hypothetical().prior is prior


def test_the_explanation_says_what_other_people_usually_do_after_the_same_tasks():
    from oracle.algorithm.records import Ranking
    from oracle.ranking import people_words

    matrix = random_matrix(5)
    steps = [s for s in synthetic_history(80, 5) if not s.idle]
    model = PersonalOracle(matrix).fit(steps[:40])
    last = option_key(steps[39].option)
    offer = list(steps[40].options)
    chosen, other = offer[0], offer[1]
    model.use_prior(Prior({(last,): {option_key(chosen): 9.0, "x": 1.0}, (): {option_key(other): 5.0}}))
    assert model.usually(chosen) == (1, 0.9)
    assert model.usually(other) == (0, 1.0)
    ranking = model.rank(offer)
    words = dict(zip([t.option for t in ranking.tasks], people_words(model, ranking)))
    assert words[chosen] == f"people usually do this after {last} (90%)"
    assert words[other].startswith("people often do this")
    assert people_words(PersonalOracle(matrix).fit(steps[:40]), ranking) == [None] * len(offer)
    assert people_words(PooledOracle(matrix).fit(steps[:40]), Ranking(())) == []
