"""Hyperparameter tuning by coordinate search (thesis 4.5).

Starting from the recommended settings, each trainable hyperparameter in turn is tried at
neighbouring values (a step up and down, relative to its current value); a change is kept when it
improves the chosen metric on the tuning chains. When a full pass improves nothing, the step
halves. ``event horizon forward`` does not change rankings and is not tuned. The search stops when
the budget of replays is spent or the step is below 1/16 of its start.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from oracle.algorithm.params import Hyperparameters
from oracle.chains import ChainRow
from oracle.errors import SettingsError
from oracle.evaluation.replay import OracleMethod, replay, summarize
from oracle.ontology import OdbOntology

TUNED = ("knockout", "penalty", "task_factor", "object_factor", "compare_situations", "time_of_day_penalty",
         "decreasing_importance_factor", "multiple_occurrences_factor", "event_horizon_backwards")


@dataclass(frozen=True)
class TuningStep:
    evaluation: int
    parameter: str
    value: float
    score: float
    kept: bool


def _neighbours(settings: Hyperparameters, name: str, step: float) -> list[Hyperparameters]:
    value = getattr(settings, name)
    values: list[float]
    if name == "event_horizon_backwards":
        delta = max(1, round(value * step))
        candidates = [value - delta, value + delta]
        values = [int(v) for v in candidates if v >= 0]
    elif name == "decreasing_importance_factor":
        values = [min(1.0, max(0.01, value * (1 - step))), min(1.0, value * (1 + step))]
    elif name in ("compare_situations", "multiple_occurrences_factor") and value == 0:
        values = [step]
    else:
        values = [value * (1 - step), value * (1 + step)]
        if name == "time_of_day_penalty":
            values = [max(1.0, v) for v in values]
    out = []
    for v in values:
        if v == value:
            continue
        try:
            changed: dict[str, Any] = {name: v}
            out.append(replace(settings, **changed))
        except SettingsError:
            continue
    return out


def tune(
    ontology: OdbOntology,
    users: dict[str, list[ChainRow]],
    metric: str = "top5",
    budget: int = 40,
    start: Hyperparameters | None = None,
    seed: int = 0,
    progress: Callable[[TuningStep, Hyperparameters], None] | None = None,
) -> tuple[Hyperparameters, float, list[TuningStep]]:
    if metric not in ("top1", "top3", "top5"):
        raise SettingsError(f"unknown metric {metric!r}; use top1, top3 or top5")
    if budget < 1:
        raise SettingsError("budget must be at least 1 replay")

    def score(settings: Hyperparameters) -> float:
        summary = summarize(replay(ontology, users, [OracleMethod(ontology, settings)], seed))
        return float(summary["methods"]["oracle"][metric])

    best = start or Hyperparameters()
    best_score = score(best)
    spent = 1
    history = [TuningStep(spent, "start", 0.0, best_score, True)]
    step = 0.5
    while spent < budget and step >= 0.5 / 16:
        improved = False
        for name in TUNED:
            for candidate in _neighbours(best, name, step):
                if spent >= budget:
                    break
                value = score(candidate)
                spent += 1
                kept = value > best_score
                history.append(TuningStep(spent, name, float(getattr(candidate, name)), value, kept))
                if progress is not None:
                    progress(history[-1], candidate)
                if kept:
                    best, best_score, improved = candidate, value, True
                    break
        if not improved:
            step /= 2
    return best, best_score, history
