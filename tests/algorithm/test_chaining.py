"""The predicted chain by re-ranking (oracle.algorithm.chaining): what is feasible after an option,
a model left as it was, each step among what followed its predecessor before, and who chains how."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from algoworld import IDLE, OBJECTS, TASKS, random_matrix, synthetic_history
from oracle.algorithm.chaining import Afterwards, chain_ahead, rankings_ahead, reranks
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.prior import Prior, option_key
from oracle.algorithm.records import Option, Step
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.stacked import StackedOracle

A, B, C, D = (Option(TASKS[i], OBJECTS[i], None) for i in range(4))


def _step(option: Option, offer: tuple[Option, ...], idle: bool = False) -> Step:
    if idle:
        return Step(IDLE, None, None, offer, "Morning", True, "idle")
    return Step(option.task, option.target, option.reference, offer, "Morning", False, str(option))


def test_what_followed_an_option_is_the_offer_of_the_next_decision_and_a_break_ends_it():
    after = Afterwards([_step(A, (A, C)), _step(B, (B, D)), _step(C, (C,)), _step(A, (A,), idle=True), _step(D, (D, A))])
    assert after.feasible(A) == (B, D)      # the decision after A offered B and D
    assert after.feasible(B) == (C,)
    assert after.feasible(C) == ()          # a break followed C: nothing is known to follow it
    assert after.feasible(D) == ()          # nothing followed D yet
    # the latest execution counts
    after.add(_step(A, (A,)))
    after.add(_step(C, (C, D)))
    assert after.feasible(A) == (C, D)


def test_the_chain_leaves_the_model_as_it_was():
    matrix = random_matrix(3)
    steps = synthetic_history(300, 3)
    model = PooledOracle(matrix).fit(steps[:250])
    step = steps[250]
    ranking = model.rank(step)
    before = pickle.dumps(model)  # after the ranking: ranking keeps what it worked out per state
    chain = chain_ahead(model, ranking, step.options, Afterwards(steps[:250]), step.time_of_day, None, 4)
    assert len(chain) == 4 and chain[0] == ranking.tasks[0].option
    assert model.n_steps_ == 250 and pickle.dumps(model) == before
    assert model.rank(step) == ranking


def test_each_step_is_among_what_followed_the_step_before_it():
    matrix = random_matrix(4)
    steps = synthetic_history(400, 4)
    model = RoutineOracle(matrix).fit(steps[:300])
    after = Afterwards(steps[:300])
    checked = 0
    for step in steps[300:340]:
        if step.idle:
            continue
        ranking = model.rank(step)
        later = rankings_ahead(model, ranking, step.options, after, step.time_of_day, None, 3)
        previous = ranking.tasks[0].option
        for following in later:
            assert set(following.options()) == set(after.feasible(previous))
            previous = following.tasks[0].option
            checked += 1
        assert len(later) == 2 or not after.feasible(previous)  # it ends only where nothing is known to follow
    assert checked > 40


def test_a_step_not_offered_now_but_always_after_the_first_leads_the_chain_on():
    # A was always followed by B, which is never offered together with A
    history = [_step(x, offer) for _ in range(6) for x, offer in ((A, (A, C)), (B, (B, D)), (D, (D, C)))]
    model = RoutineOracle(random_matrix(5)).fit(history)
    ranking = model.rank([A, C], "Morning")
    assert ranking.tasks[0].option == A
    chain = chain_ahead(model, ranking, (A, C), Afterwards(history), "Morning", None, 3)
    assert chain == (A, B, D)


def test_the_chain_ends_where_each_activity_ended_before():
    # B always ended the activity (a break after it): the chain says no more than A, B
    history = []
    for _ in range(5):
        history += [_step(A, (A, C)), _step(B, (B, D)), _step(A, (A,), idle=True)]
    model = RoutineOracle(random_matrix(8)).fit(history)
    ranking = model.rank([A, C], "Morning")
    assert chain_ahead(model, ranking, (A, C), Afterwards(history), "Morning", None, 4) == (A, B)


def test_the_chain_stops_where_nothing_more_is_asked_or_ranked():
    matrix = random_matrix(6)
    steps = synthetic_history(120, 6)
    model = RoutineOracle(matrix).fit(steps[:100])
    ranking = model.rank(steps[100])
    after = Afterwards(steps[:100])
    assert chain_ahead(model, ranking, steps[100].options, after, None, None, 1) == (ranking.tasks[0].option,)
    assert rankings_ahead(model, ranking, steps[100].options, after, None, None, 1) == []
    empty = model.rank([], None)
    assert chain_ahead(model, empty, (), after, None, None, 4) == ()


def test_the_routine_predictors_chain_by_re_ranking_the_thesis_oracle_by_its_tree():
    matrix = random_matrix(7)
    assert reranks(RoutineOracle(matrix)) and reranks(PooledOracle(matrix))
    assert not reranks(PreferenceOracle(matrix))


def _unseen(model: RoutineOracle) -> tuple[Option, ...]:
    """Six options the model has not interned."""
    every = (Option(task, target, reference) for task in TASKS for target in OBJECTS for reference in (None, *OBJECTS))
    options = tuple(option for option in every if option not in model.options_)[:6]
    assert len(options) == 6
    return options


def test_a_hypothetical_copy_learns_as_a_pickled_copy_and_the_model_stays_as_it_was():
    matrix = random_matrix(5)
    steps = synthetic_history(300, 5)
    model = PooledOracle(matrix).fit(steps[:260])
    for step in steps[260:263]:
        model.rank(step)  # the kept exponentials filled, as a served model has them
    before = pickle.dumps(model)
    table, kept = model._known.table.copy(), {tau: k.copy() for tau, (k, _) in model._known._decayed.items()}
    twin, plain = model.hypothetical(), pickle.loads(before)
    unseen = _unseen(model)
    for step in steps[263:270]:  # the twin learns new options, then ranks them
        offer = step.options + unseen
        chosen = unseen[len(step.options) % len(unseen)]
        learnt = Step(chosen.task, chosen.target, chosen.reference, offer, step.time_of_day, False, str(chosen))
        twin.partial_fit(learnt)
        plain.partial_fit(learnt)
        assert twin.rank(list(offer), step.time_of_day) == plain.rank(list(offer), step.time_of_day)
    assert pickle.dumps(model) == before
    assert np.array_equal(model._known.table, table)
    assert all(np.array_equal(model._known._decayed[tau][0], k) for tau, k in kept.items())
    assert model.rank(steps[270]) == pickle.loads(before).rank(steps[270])
    # the model learns on while the copy lives: neither sees the other's steps
    after = twin.rank(list(steps[280].options), steps[280].time_of_day)
    original = pickle.loads(before)
    for step in steps[270:280]:
        model.partial_fit(step)
        original.partial_fit(step)
        assert model.rank(steps[280]) == original.rank(steps[280])
    assert twin.rank(list(steps[280].options), steps[280].time_of_day) == after
    for one, other in ((model, original), (twin, plain)):
        for name, stream in one._streams.items():
            mine, theirs = stream.counts, other._streams[name].counts
            assert mine.tokens == theirs.tokens
            assert [(level.tables, level.totals, level.once, level.twice) for level in mine.levels + mine.timed] == \
                [(level.tables, level.totals, level.once, level.twice) for level in theirs.levels + theirs.timed]


def test_a_fork_of_the_option_table_copies_only_what_it_changes():
    matrix = random_matrix(6)
    model = RoutineOracle(matrix).fit(synthetic_history(120, 6))
    known = model._known
    known.decayed(0.5)
    fork = known.fork()
    assert fork.table is known.table and fork.decayed(0.5) is not None and fork._decayed[0.5][0] is known._decayed[0.5][0]
    fork.intern(_unseen(model)[0])
    fork.decayed(0.5)
    assert fork.table is not known.table and fork._decayed[0.5][0] is not known._decayed[0.5][0]
    assert len(fork.options) == len(known.options) + 1 and fork.options is not known.options


def _with_prior(steps: list[Step]) -> PersonalOracle:
    prior = Prior({(): {option_key(steps[0].options[-1]): 40.0, option_key(steps[3].options[0]): 10.0}})
    return PersonalOracle(random_matrix(9)).use_prior(prior)


@pytest.mark.parametrize("make", [lambda steps: RoutineOracle(random_matrix(9)), lambda steps: OnlineOracle(random_matrix(9)),
                                  lambda steps: StackedOracle(random_matrix(9)), _with_prior],
                         ids=["routine", "online", "stacked", "personal-with-prior"])
def test_every_re_ranking_predictors_copy_learns_as_a_pickled_copy_and_shares_nothing_it_changes(make):
    # the copy forks each part of the state: a part it shared and changed would show in the model
    steps = synthetic_history(260, 9)
    model = make(steps).fit(steps[:200])
    model.rank(steps[200])
    before = pickle.dumps(model)
    twin, plain = model.hypothetical(), pickle.loads(before)
    if isinstance(model, PersonalOracle):
        plain.use_prior(model.prior)  # the prior is the process's, never pickled
    for step in steps[200:215]:
        twin.partial_fit(step)
        plain.partial_fit(step)
        assert twin.rank(step) == plain.rank(step)
    assert pickle.dumps(model) == before
    model.partial_fit(steps[215])  # and the model learns on without reaching the copy
    assert twin.rank(steps[216]) == plain.rank(steps[216])


def test_a_fork_of_the_context_counts_copies_nothing_and_neither_sees_the_others_counts():
    from oracle.algorithm.contexts import ContextCounts

    counts = ContextCounts(2, 0)
    for token in (1, 2, 1, 3, 1, 2):
        counts.add(token, 0)
    copy = pickle.loads(pickle.dumps(counts))
    fork = counts.fork()
    assert fork.levels[2].tables.base is counts.levels[2].tables  # shared, nothing copied
    # both count on: a context each had, a new one each, one of them the same new context
    for token in (4, 1, 2):
        counts.add(token, 1)
        copy.add(token, 1)
    for token in (2, 5, 4):
        fork.add(token, 2)
    grown = pickle.loads(pickle.dumps(copy))
    again = pickle.loads(pickle.dumps(counts))
    forked = pickle.loads(pickle.dumps(fork))  # written out whole
    state = lambda c: [(dict(level.tables), dict(level.totals), level.once, level.twice) for level in c.levels + c.timed]
    assert state(counts) == state(grown) == state(again)
    reference = pickle.loads(pickle.dumps(ContextCounts(2, 0)))
    for token in (1, 2, 1, 3, 1, 2):
        reference.add(token, 0)
    for token in (2, 5, 4):
        reference.add(token, 2)
    assert state(fork) == state(reference) == state(forked)
    assert [list(level.tables) for level in fork.levels] == [list(level.tables) for level in reference.levels]
    twin = fork.fork()  # a fork of a fork
    twin.add(1, 3)
    fork.add(3, 2)
    reference.add(3, 2)
    assert state(fork) == state(reference)


@pytest.mark.parametrize("cls", [RoutineOracle, OnlineOracle, PooledOracle, PersonalOracle, StackedOracle])
def test_a_ranking_without_its_explanation_orders_as_the_explained_one_and_the_chain_reads_it(cls):
    matrix = random_matrix(10)
    steps = synthetic_history(260, 10)
    model = cls(matrix).fit(steps[:200])
    after = Afterwards(steps[:200])
    for step in steps[200:230]:
        for at in (None, step.time):
            full = model.rank(list(step.options), step.time_of_day, at=at)
            bare = model.rank(list(step.options), step.time_of_day, at=at, explain=False)
            assert [(t.option, t.probability) for t in bare.tasks] == [(t.option, t.probability) for t in full.tasks]
        ranking = model.rank(step)
        later = rankings_ahead(model, ranking, step.options, after, step.time_of_day, step.time, 4)
        chain = chain_ahead(model, ranking, step.options, after, step.time_of_day, step.time, 4)
        assert chain == ((ranking.tasks[0].option, *(r.tasks[0].option for r in later)) if ranking.tasks else ())


class _Afresh(PersonalOracle):
    """The personal predictor without the kept evidence and rows: each made anew when asked."""

    def _evidence(self, offered, now):  # type: ignore[no-untyped-def]
        self._evidence_at = None
        return super()._evidence(offered, now)

    def _rows(self, offered, time_of_day, at):  # type: ignore[no-untyped-def]
        self._rows_at = None
        return super()._rows(offered, time_of_day, at)


def test_the_kept_evidence_and_rows_rank_learn_and_chain_as_made_afresh():
    """What ranking a decision computes is kept for learning it next (the predicted chain's steps,
    at the decision's time and at the part of day it will be learnt at): the same rankings, the
    same weights learnt, the same chains, and the kept rows cannot be changed in place."""
    from oracle.benchmarks.algorithm import bench_data

    matrix, prefix, queries, prior = bench_data(400, 40)
    kept, afresh = (cls(matrix).use_prior(prior).fit(prefix) for cls in (PersonalOracle, _Afresh))
    afterwards = Afterwards(prefix)
    for query in queries:
        ranked = kept.rank(query, tree_roots=0)
        assert ranked == afresh.rank(query, tree_roots=0)
        chains = [chain_ahead(m, ranked, query.options, afterwards, query.time_of_day, query.time, 6) for m in (kept, afresh)]
        assert chains[0] == chains[1]
        kept.partial_fit(query)
        afresh.partial_fit(query)
        afterwards.add(query)
        assert np.array_equal(kept.coef_, afresh.coef_)
    rows = kept._rows(list(queries[-1].options), queries[-1].time_of_day, queries[-1].time)
    with pytest.raises(ValueError):
        rows[0, 0] = 1.0


def test_a_fork_shares_the_followers_sets_and_neither_changes_the_others():
    from oracle.algorithm.focus import Resumption

    base = Resumption()
    for action in (1, 2, 1, 3):
        base.follow(action)
    fork = base.fork()
    fork.follow(4)  # 3 -> 4 in the fork only
    base.follow(5)  # 3 -> 5 in the base only
    assert base.followers[3] == {5} and fork.followers[3] == {4}
    assert base.followers[1] == fork.followers[1] == {2, 3} and base.followers[1] is fork.followers[1]
