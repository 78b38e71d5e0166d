"""Predictors by name: the CLI's ``--method``, the replay and the Python API all choose here.

``personal`` (the default, ``personal.PersonalOracle``: a per-user online logit over the routine
predictor's evidence and, given one, the shared prior's), ``pooled`` (``pooled.PooledOracle``: the
routine predictor pooled with a per-user logit where that leads), ``routine``
(``routine.RoutineOracle``; ``routine-fixed`` and ``routine-mixture`` are its self-tuning
ablations) and ``thesis`` (``fast.PreferenceOracle`` with the given Table 4.2 settings, exactly
as the thesis defines it). Every predictor has the same
estimator interface: ``fit(history) -> self``, ``partial_fit(step) -> self`` and
``rank(options, time_of_day, tree_roots=..., present_objects=..., at=...) -> Ranking`` whose scores are
lower-is-better (thesis: eq. 4.12 distance; routine: -log2 of the probability).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any, Protocol

from oracle.algorithm.fast import PreferenceOracle
from oracle.algorithm.params import Hyperparameters
from oracle.algorithm.normalized import normalized_oracle
from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.personal import PersonalOracle
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.routine import RoutineOracle
from oracle.algorithm.stacked import StackedOracle
from oracle.algorithm.records import Option, Ranking, Step
from oracle.errors import SettingsError


class Predictor(Protocol):
    #: Steps fitted so far.
    n_steps_: int

    def fit(self, history: Iterable[Step]) -> Any: ...

    def partial_fit(self, step: Step) -> Any: ...

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None) -> Ranking: ...


@dataclass(frozen=True)
class PredictorSpec:
    """A named predictor: what it is, and how to build it (unfitted) from the ontology's distances."""

    name: str
    summary: str
    build: Callable[[Any, frozenset[str], Hyperparameters], Predictor]


def _routine(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    # the thesis settings tune the thesis oracle; the routine predictor tunes itself (selftune)
    return RoutineOracle(distances, opening_tasks=opening)


def _routine_tuned(tuning: str) -> Callable[[Any, frozenset[str], Hyperparameters], Predictor]:
    def build(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
        return RoutineOracle(distances, opening_tasks=opening, tuning=tuning)
    return build


def _stacked(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return StackedOracle(distances, opening_tasks=opening)


def _online(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return OnlineOracle(distances, opening_tasks=opening)


def _pooled(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return PooledOracle(distances, opening_tasks=opening)


def _personal(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return PersonalOracle(distances, opening_tasks=opening)


def _thesis_normalized(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return normalized_oracle(distances, settings, opening)


def _thesis(distances: Any, opening: frozenset[str], settings: Hyperparameters) -> Predictor:
    return PreferenceOracle.from_settings(distances, settings, opening)


PREDICTORS: dict[str, PredictorSpec] = {
    "routine": PredictorSpec("routine", "exact-context counts backed off to ontology similarity, self-tuned "
                             "(docs/algorithm.md, 'Routine predictor')", _routine),
    # the self-tuning ablations of docs/results.md: the first variant alone, and the posterior mixture
    "routine-fixed": PredictorSpec("routine-fixed", "the routine predictor without self-tuning (its first variant)",
                                   _routine_tuned("fixed")),
    "routine-mixture": PredictorSpec("routine-mixture", "the routine predictor, variants mixed by their likelihood",
                                     _routine_tuned("mixture")),
    "stacked": PredictorSpec("stacked", "the routine predictor's evidence combined by a per-user conditional logit "
                             "(docs/algorithm.md, 'Stacked predictor')", _stacked),
    "online": PredictorSpec("online", "the routine predictor re-weighed by a per-user conditional logit over its "
                            "evidence, learnt after every decision (docs/algorithm.md, 'Online predictor')", _online),
    "pooled": PredictorSpec("pooled", "the routine predictor and a per-user conditional logit over its evidence, "
                            "pooled log-linearly (docs/algorithm.md, 'Pooled predictor')", _pooled),
    "personal": PredictorSpec("personal", "a per-user online conditional logit over the routine predictor's "
                              "evidence and, given one, the shared prior's (docs/algorithm.md, 'Personal predictor')",
                              _personal),
    "thesis": PredictorSpec("thesis", "the thesis PreferenceOracle (chapter 4) with the given settings", _thesis),
    "thesis-normalized": PredictorSpec("thesis-normalized", "the thesis oracle over the normalised distances of "
                                       "thesis 6.4 (docs/algorithm.md)", _thesis_normalized),
}
DEFAULT = "personal"
THESIS = "thesis"


def predictor_spec(name: str) -> PredictorSpec:
    """The predictor called ``name``; SettingsError listing the known names otherwise."""
    spec = PREDICTORS.get(name.strip().lower()) if isinstance(name, str) else None
    if spec is None:
        raise SettingsError(f"unknown method {name!r} (known: {', '.join(PREDICTORS)})")
    return spec


def make_predictor(name: str, distances: Any, opening_tasks: frozenset[str] = frozenset(),
                   settings: Hyperparameters | None = None) -> Predictor:
    """An unfitted predictor by name; ``settings`` (default: Table 4.2) apply to ``thesis``."""
    return predictor_spec(name).build(distances, frozenset(opening_tasks), settings or Hyperparameters())
