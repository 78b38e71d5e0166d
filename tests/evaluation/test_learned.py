"""The learned baselines (docs/evaluation.md, "Learned baselines")."""

from __future__ import annotations

import numpy as np

from oracle.algorithm.records import Option, Step
from oracle.evaluation.learned import GBDT_FIRST, Evidence, Gbdt, OnlineLogit, fit_ranker, learned_baselines
from oracle.ontology import build_ontology
from oracle.calls import opening_tasks, option_of
from oracle.chains import parse_call


def test_lambdarank_learns_which_column_decides():
    rng = np.random.default_rng(0)
    decisions = []
    for _ in range(80):
        x = rng.normal(size=(6, 4))
        decisions.append((x, int(np.argmax(x[:, 3]))))
    model = fit_ranker(decisions)
    test = rng.normal(size=(200, 6, 4))
    hits = sum(int(np.argmax(model.predict(x)) == np.argmax(x[:, 3])) for x in test)
    assert hits >= 150


class FixedRows(Evidence):
    """Evidence whose rows are given: column 1 marks the option the user takes."""

    def rows(self, candidates, time_of_day, at):
        return np.array([[0.0, 1.0 if c.task == "b" else 0.0, float(i)] for i, c in enumerate(candidates)])

    def observe(self, step):
        self.history.append(step)


def test_logit_and_gbdt_learn_online_from_the_rows_they_ranked():
    kitchen = build_ontology()
    offer = [Option("a"), Option("b"), Option("c")]
    for method in (OnlineLogit(FixedRows(kitchen.distances(), frozenset())),
                   Gbdt(FixedRows(kitchen.distances(), frozenset()))):
        for _ in range(GBDT_FIRST + 1):
            method.rank(offer)
            method.observe(Step("b", options=tuple(offer)))
        assert method.rank(offer)[0] == Option("b"), method.name
    gbdt = Gbdt(FixedRows(kitchen.distances(), frozenset()))
    for _ in range(GBDT_FIRST - 1):
        gbdt.rank(offer)
        gbdt.observe(Step("b", options=tuple(offer)))
    assert gbdt.model is None  # not fitted before GBDT_FIRST decisions


def test_the_learned_baselines_share_one_evidence_and_add_each_step_once():
    kitchen = build_ontology()
    logit, gbdt = learned_baselines(kitchen.distances(), opening_tasks(kitchen))
    assert logit.evidence is gbdt.evidence
    pick = option_of(kitchen, parse_call("pick(red_mug)"))
    history = [Step(pick.task, pick.target, pick.reference, (pick,)) for _ in range(3)]
    for step in history:
        for method in (logit, gbdt):
            method.observe(step)
    assert len(logit.evidence.history) == 3 and logit.evidence.model.n_steps_ == 3
    logit.reset()
    gbdt.reset()
    assert logit.evidence.history == [] and logit.evidence.model.n_steps_ == 0
