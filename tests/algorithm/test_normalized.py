"""The thesis oracle over normalised distances (thesis 6.4): an option that removes the byproducts."""

from __future__ import annotations

import numpy as np

from algoworld import random_matrix, synthetic_history
from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.normalized import normalized_matrix, normalized_oracle, normalized_settings
from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.predictors import make_predictor
from oracle.ontology.distance import DistanceMatrix


def test_a_finer_taxonomy_or_a_larger_task_factor_leaves_the_normalised_ranking_alone():
    matrix = random_matrix(4)
    deeper = DistanceMatrix.from_values(matrix.classes, matrix.values * 2.5)  # every distance larger on average
    steps = synthetic_history(120, 4)
    a = normalized_oracle(matrix, Hyperparameters(), frozenset()).fit(steps[:100])
    b = normalized_oracle(deeper, Hyperparameters(), frozenset()).fit(steps[:100])
    for step in steps[100:]:
        assert [(t.option, round(t.score, 9)) for t in a.rank(step)] == [(t.option, round(t.score, 9))
                                                                         for t in b.rank(step)]
    doubled = normalized_settings(Hyperparameters(task_factor=4.0, object_factor=2.0))
    assert (doubled.task_factor, doubled.object_factor) == (2.0, 1.0)
    off = normalized_matrix(matrix).values[~np.eye(len(matrix.classes), dtype=bool)]
    assert np.mean(off[off > 0]) == np.float64(1.0) or abs(np.mean(off[off > 0]) - 1.0) < 1e-12


def test_the_thesis_oracle_is_unchanged_and_the_option_is_selectable_by_name():
    matrix = random_matrix(5)
    steps = synthetic_history(80, 5)
    thesis = make_predictor("thesis", matrix).fit(steps[:70])
    assert thesis.rank(steps[75]) == PreferenceOracle.from_settings(matrix, Hyperparameters()).fit(steps[:70]).rank(
        steps[75])
    normalized = make_predictor("thesis-normalized", matrix).fit(steps[:70])
    assert normalized.rank(steps[75]) == normalized_oracle(matrix, Hyperparameters(), frozenset()).fit(
        steps[:70]).rank(steps[75])
