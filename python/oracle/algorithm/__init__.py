"""PreferenceOracle (thesis chapter 4): rank the available tasks and predict the chain that follows.

``PreferenceOracle`` (fast) and ``ReferenceOracle`` (literal) share parameters and results.
"""

from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import PRESETS, Hyperparameters, load_settings, preset, save_settings
from oracle.algorithm.reference import ReferenceOracle
from oracle.algorithm.records import Option, RankedTask, Ranking, Situation, Step, TreeNode

__all__ = ["PreferenceOracle", "ReferenceOracle", "Hyperparameters", "PRESETS", "preset", "load_settings",
           "save_settings", "Option", "Step", "Situation", "RankedTask", "Ranking", "TreeNode"]
