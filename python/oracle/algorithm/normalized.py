"""The thesis oracle with the normalised distances of thesis 6.4 ("Remove invisible byproducts of
changes in the hyperparameters or the ontology"): an option, never the thesis default.

Two rescalings, each removing one byproduct the thesis names, and nothing else changed:
- the ontology's class distances are divided by their mean over all pairs of distinct classes
  (finite, non-zero), so that a deeper or finer taxonomy (EspressoCup under Cup) does not make
  every distance larger on average;
- the task and object factors are rescaled to sum to 3 (Table 4.2's 2 + 1), so that raising one
  factor changes how the two are weighed, not the scale of every ``dist`` the knockout and the
  penalty are compared with.
docs/algorithm.md, "Normalised distances (thesis 6.4)".
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import Hyperparameters

#: the sum of Table 4.2's task and object factors, which the rescaled factors keep
FACTOR_SUM = 3.0


def normalized_matrix(distances: Any) -> Any:
    """A copy of the DistanceMatrix ``distances`` whose values are divided by the mean of its
    finite non-zero off-diagonal values (unchanged when there are none)."""
    values = np.asarray(distances.values, dtype=np.float64)
    off = values[~np.eye(len(values), dtype=bool)]
    used = off[np.isfinite(off) & (off > 0)]
    scale = float(used.mean()) if used.size else 1.0
    return type(distances)(distances.classes, values / scale, distances.lcs_index, f"{distances.key}/normalized")


def normalized_settings(settings: Hyperparameters) -> Hyperparameters:
    """``settings`` with the task and object factors rescaled to sum to ``FACTOR_SUM`` (as given
    when both are 0)."""
    total = settings.task_factor + settings.object_factor
    if total <= 0:
        return settings
    return replace(settings, task_factor=settings.task_factor * FACTOR_SUM / total,
                            object_factor=settings.object_factor * FACTOR_SUM / total)


def normalized_oracle(distances: Any, settings: Hyperparameters, opening: frozenset[str]) -> PreferenceOracle:
    """The thesis oracle (``fast.PreferenceOracle``, unchanged) over the normalised distances."""
    return PreferenceOracle.from_settings(normalized_matrix(distances), normalized_settings(settings), opening)
