"""Thesis Fig. 5.5 settings A-N replayed against A, with Mann-Whitney U p-values and timing."""

from __future__ import annotations

from collections.abc import Callable

from scipy.stats import mannwhitneyu

from oracle.algorithm.params import PRESETS
from oracle.chains import ChainRow
from oracle.evaluation.replay import KS, OracleMethod, replay, summarize
from oracle.ontology import OdbOntology


def run_ablations(
    ontology: OdbOntology,
    users: dict[str, list[ChainRow]],
    seed: int = 0,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """Replay every preset; per preset: accuracies, per-user lists, p-values against A, timing."""
    summaries: dict[str, dict] = {}
    for letter, settings in ((k, v) for k, v in PRESETS.items() if len(k) == 1):
        if progress is not None:
            progress(letter)
        result = replay(ontology, users, [OracleMethod(ontology, settings, name=letter)], seed)
        summaries[letter] = summarize(result)["methods"][letter]
    base = summaries["A"]["per_user"]
    table: dict[str, dict] = {}
    for letter, entry in summaries.items():
        row = {f"top{k}": entry[f"top{k}"] for k in KS}
        row["ms_per_prediction"] = entry["ms_per_prediction"]
        row["settings"] = PRESETS[letter].to_dict()
        for k in KS:
            mine = [entry["per_user"][u][f"top{k}"] for u in base]
            theirs = [base[u][f"top{k}"] for u in base]
            if letter == "A" or len(base) < 2 or mine == theirs:
                row[f"p_top{k}"] = 1.0
            else:
                row[f"p_top{k}"] = float(mannwhitneyu(mine, theirs, alternative="two-sided").pvalue)
        row["per_user"] = entry["per_user"]
        table[letter] = row
    return table
