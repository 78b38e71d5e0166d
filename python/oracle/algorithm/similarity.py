"""Thesis Algorithm 2 (``reference.overall_distance``) between many options at once, for the routine predictor.

The thesis oracle keeps its own vectorised copy inside ``fast.py`` so that it stays bit-identical
to ``reference``; this one serves the new predictor and is held equal to ``reference`` by
tests/algorithm/test_routine.py. Options become rows of class indices (task, target, reference;
-1 for an empty slot) so that a whole table of distances is one numpy expression.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from oracle.algorithm.reference import class_row
from oracle.algorithm.records import DistanceTable, Option


def class_rows(matrix: DistanceTable, options: Sequence[Option]) -> np.ndarray:
    """The (k, 3) class indices of ``options`` in the distance matrix; -1 for an empty role slot."""
    rows = np.empty((len(options), 3), dtype=np.int64)
    for i, option in enumerate(options):
        rows[i, 0] = class_row(matrix, option.task)
        rows[i, 1] = -1 if option.target is None else class_row(matrix, option.target)
        rows[i, 2] = -1 if option.reference is None else class_row(matrix, option.reference)
    return rows


def option_distances(values: np.ndarray, a: np.ndarray, b: np.ndarray, task_factor: float,
                     object_factor: float, penalty: float) -> np.ndarray:
    """Algorithm 2 between every row of ``a`` and every row of ``b``: an (len(a), len(b)) table.

    ``task_factor * dist(task) + object_factor * avg(slot distances)``, a slot filled on one side
    only costing ``penalty``, a slot empty on both sides left out of the average.
    """
    task = values[a[:, 0][:, None], b[:, 0][None, :]]
    total = np.zeros(task.shape)
    count = np.zeros(task.shape, dtype=np.int64)
    for slot in (1, 2):
        mine, theirs = a[:, slot][:, None], b[:, slot][None, :]
        both = (mine >= 0) & (theirs >= 0)
        one = (mine >= 0) ^ (theirs >= 0)
        total = total + np.where(both, values[np.maximum(mine, 0), np.maximum(theirs, 0)], 0.0)
        total = total + np.where(one, penalty, 0.0)
        count += both | one
    average = np.divide(total, count, out=np.zeros(task.shape), where=count > 0)
    result: np.ndarray = task_factor * task + object_factor * average
    return result
