"""The predictors: rank the available tasks and predict the chain that follows.

``make_predictor(name, distances, ...)`` builds one by name (``predictors.PREDICTORS``):
``personal`` (the default, ``PersonalOracle``: a per-user online logit over ``RoutineOracle``'s
evidence and the shared prior's), ``pooled`` (``RoutineOracle`` pooled with a per-user logit), ``routine``
or ``thesis`` (the thesis PreferenceOracle, chapter 4).
``PreferenceOracle`` (fast) and ``ReferenceOracle`` (literal) share parameters and results.
"""

from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS, Hyperparameters, load_settings, preset, save_settings
from oracle.algorithm.predictors import DEFAULT, PREDICTORS, THESIS, make_predictor
from oracle.algorithm.reference import ReferenceOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.records import Option, RankedTask, Ranking, RoutineTask, Situation, Step, TreeNode

__all__ = ["PreferenceOracle", "ReferenceOracle", "RoutineOracle", "RoutineTask", "make_predictor", "PREDICTORS",
           "DEFAULT", "THESIS", "Hyperparameters", "PRESETS", "preset", "load_settings",
           "save_settings", "Option", "Step", "Situation", "RankedTask", "Ranking", "TreeNode"]
