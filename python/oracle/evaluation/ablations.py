"""Thesis Fig. 5.5 settings A-N replayed side by side, each compared with A on the same predictions.

One replay ranks every step with all fourteen settings, so the comparisons are paired: per-user
differences with bootstrap intervals and Holm-corrected Wilcoxon signed-rank tests (statistics.py).
"""

from __future__ import annotations

from typing import Any

from collections.abc import Callable

from oracle.algorithm.params import PRESETS
from oracle.chains import ChainRow
from oracle.evaluation.replay import KS, OracleMethod, replay, summarize
from oracle.evaluation.statistics import comparison_summary
from oracle.ontology import OdbOntology


def run_ablations(
    ontology: OdbOntology,
    users: dict[str, list[ChainRow]],
    seed: int = 0,
    progress: Callable[[int, int, str], None] | None = None,
) -> dict[str, Any]:
    """Per setting: accuracies, per-user accuracies, timing, the settings, and ``vs_A`` (paired, per k)."""
    letters = [k for k in PRESETS if len(k) == 1]
    methods = [OracleMethod(ontology, PRESETS[letter], name=letter) for letter in letters]
    result = replay(ontology, users, methods, seed, progress)
    summary = summarize(result)["methods"]
    paired = comparison_summary(result.outcomes, "A", [x for x in letters if x != "A"], seed)
    table: dict[str, dict[str, Any]] = {}
    for letter in letters:
        entry = summary[letter]
        row = {f"top{k}": entry[f"top{k}"] for k in KS}
        row["ms_per_prediction"] = entry["ms_per_prediction"]
        row["settings"] = PRESETS[letter].to_dict()
        if letter != "A":
            row["vs_A"] = paired["methods"][letter]
        row["per_user"] = entry["per_user"]
        table[letter] = row
    return {"unit": paired["unit"], "units": paired["units"], "test": paired["test"], "settings": table}
