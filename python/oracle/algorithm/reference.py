"""The PreferenceOracle as a literal, readable transcription of thesis chapter 4 (the oracle of truth).

Every formula is written out once, in the order of the thesis, with plain loops; ``fast.py`` must
return the same ranking and scores. docs/algorithm.md states each formula and each choice.
Floating-point sums are written as explicit left-to-right loops on purpose: ``fast`` performs the
same operations in the same order, so the two agree to the last bit.
"""

from __future__ import annotations

import math
from functools import partial
from dataclasses import dataclass
from collections.abc import Callable, Iterable, Sequence

import numpy as np

from oracle.algorithm.params import Hyperparameters, OracleParams
from oracle.algorithm.records import (
    DistanceTable, Option, RankedTask, Ranking, Step, TreeNode, canonical_options,
)
from oracle.algorithm.tree import Successions, TreeShape, occurrence_value, successor_tree
from oracle.errors import OntologyError, SettingsError


# ---------------------------------------------------------------------------------------------
# Algorithm 1 comes precomputed: a DistanceMatrix with .index (IRI -> row) and .values.

def class_distance(matrix: DistanceTable, a: str, b: str) -> float:
    """Algorithm 1 distance between two classes, looked up in the precomputed matrix."""
    return float(matrix.values[class_row(matrix, a), class_row(matrix, b)])


def class_row(matrix: DistanceTable, iri: str) -> int:
    try:
        return matrix.index[iri]
    except KeyError:
        raise OntologyError(f"class {iri!r} is not in the distance matrix; "
                            "was the history logged against another ontology?") from None


# ---------------------------------------------------------------------------------------------
# Algorithm 2: overall distance between two executed (or available) tasks.

def overall_distance(p: Hyperparameters, matrix: DistanceTable, a: Option, b: Option) -> float:
    """``task factor * dist(task) + object factor * avg(object distances)``.

    Objects are compared slot by slot (target with target, reference with reference). A slot
    filled on exactly one side contributes ``penalty`` (symmetric; the thesis only penalises the
    current side). A slot empty on both sides contributes nothing; with no slot left the average
    is 0 (both tasks agree that they use no object).
    """
    dist_task = class_distance(matrix, a.task, b.task)
    dist_objects: list[float] = []
    for mine, theirs in ((a.target, b.target), (a.reference, b.reference)):
        if mine is not None and theirs is not None:
            dist_objects.append(class_distance(matrix, mine, theirs))
        elif mine is not None or theirs is not None:
            dist_objects.append(p.penalty)
    total = 0.0
    for value in dist_objects:
        total += value
    average = total / len(dist_objects) if dist_objects else 0.0
    return p.task_factor * dist_task + p.object_factor * average


# ---------------------------------------------------------------------------------------------
# Algorithm 3: situation distance, adding the comparison of the available options.

def option_set_distance(p: Hyperparameters, matrix: DistanceTable, mine: Sequence[Option], theirs: Sequence[Option]) -> float:
    """Average over ``mine`` of the smallest Algorithm 2 distance to any option in ``theirs``.

    Both are canonical option sets. When either set is empty (not recorded) there is nothing to
    compare and the distance is 0: missing information is not evidence of a different situation.
    """
    if not mine or not theirs:
        return 0.0
    best_distances: list[float] = []
    for option in mine:
        best = math.inf
        for other in theirs:
            d = overall_distance(p, matrix, option, other)
            if d <= best:
                best = d
        best_distances.append(best)
    total = 0.0
    for value in best_distances:
        total += value
    return total / len(best_distances)


def situation_distance(p: Hyperparameters, matrix: DistanceTable, a: Option, a_options: Sequence[Option],
                       b: Option, b_options: Sequence[Option]) -> float:
    """Algorithm 3: Algorithm 2, plus ``compare situations * option set distance`` unless skipped."""
    dist = overall_distance(p, matrix, a, b)
    if dist >= p.knockout or p.compare_situations <= 0:
        return dist
    return dist + option_set_distance(p, matrix, a_options, b_options) * p.compare_situations


# ---------------------------------------------------------------------------------------------
# Eq. 4.11: weights of the main situation (n = 0) and its predecessors.

def importance_weights(factor: float, horizon: int) -> list[float]:
    """``w_0 = f``, ``w_n = f * (1 - sum_{k<n} w_k)`` for n = 0..horizon (i.e. ``f (1 - f)^n``)."""
    weights: list[float] = []
    used = 0.0
    for _ in range(horizon + 1):
        weight = factor * (1.0 - used)
        weights.append(weight)
        used += weight
    return weights


def is_chain_start(history: Sequence[Step], position: int) -> bool:
    """Before the first step, or at an odb:IdleTask: nothing earlier belongs to the chain."""
    return position < 0 or history[position].idle


def predecessor_distance(p: Hyperparameters, matrix: DistanceTable, history: Sequence[Step], j: int,
                         weights: Sequence[float]) -> tuple[float, float]:
    """Weighted distances of the predecessors: ``p_n(s_c)`` against ``p_n(s_h)`` for n = 1..horizon.

    The candidate's chain is the current one: ``p_n(s_c)`` is ``history[L - n]``; the historic
    situation ``s_h = history[j]`` has ``p_n(s_h) = history[j - n]``. Returns the weighted sum
    and the sum of the weights used.

    * Both chains start (idle step or history start) at the same level: stop, nothing more.
    * Only one chain starts there: the chains differ in length, which counts as a knockout.
    * Situation distance (Algorithm 3) above ``knockout``: knocked out.
    * From a knocked-out level up to the horizon every level counts ``penalty``.
    """
    current = len(history)
    total = 0.0
    weight_sum = 0.0
    knocked_out = False
    for n in range(1, p.event_horizon_backwards + 1):
        if not knocked_out:
            current_start = is_chain_start(history, current - n)
            historic_start = is_chain_start(history, j - n)
            if current_start and historic_start:
                break
            if current_start or historic_start:
                knocked_out = True
            else:
                mine, theirs = history[current - n], history[j - n]
                d = situation_distance(p, matrix, mine.option, canonical_options(mine.options),
                                       theirs.option, canonical_options(theirs.options))
                if d > p.knockout:
                    knocked_out = True
                else:
                    total += weights[n] * d
                    weight_sum += weights[n]
        if knocked_out:
            total += weights[n] * p.penalty
            weight_sum += weights[n]
    return total, weight_sum


def time_of_day_differs(now: str | None, then: str | None) -> bool:
    """Parts of day differ only when both are known."""
    return now is not None and then is not None and now != then


# ---------------------------------------------------------------------------------------------

class ReferenceOracle(OracleParams):
    """PreferenceOracle, literal version: O(|options| * |history| * horizon * |options|^2) per rank.

    Parameters are the ten hyperparameters of ``Hyperparameters`` plus ``distances`` (a
    DistanceMatrix) and ``opening_tasks`` (task IRIs under soma:Opening).
    """

    def fit(self, history: Iterable[Step]) -> ReferenceOracle:
        self.params_ = self.hyperparameters()
        self.history_: list[Step] = []
        for step in history:
            self._append(step)
        return self

    def partial_fit(self, step: Step) -> ReferenceOracle:
        if not hasattr(self, "history_"):
            return self.fit([step])
        self._check_params()
        self._append(step)
        return self

    def _append(self, step: Step) -> None:
        if not isinstance(step, Step):
            raise TypeError(f"history entries must be Step records, got {type(step).__name__}")
        for option in (step.option, *step.options):
            for iri in (option.task, *option.objects()):
                class_row(self.distances, iri)
        self.history_.append(step)

    def _check_params(self) -> Hyperparameters:
        if not hasattr(self, "params_"):
            raise SettingsError(f"{type(self).__name__} is not fitted; call fit(history) first")
        if self.hyperparameters() != self.params_:
            raise SettingsError("hyperparameters changed since fit; call fit(history) again")
        return self.params_

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None) -> Ranking:
        """Rank the available options of ``current`` (a Step, or options plus ``time_of_day``).
        ``at`` (the decision's unix seconds) is accepted as every predictor's is, and not used:
        the thesis knows the part of the day only.

        The forward tree is built for the best ``tree_roots`` options (None: all).
        """
        p = self._check_params()
        offered, now = offered_options(current, time_of_day)
        for option in offered:
            for iri in (option.task, *option.objects()):
                class_row(self.distances, iri)
        matrix, history = self.distances, self.history_
        current_set = canonical_options(offered)
        weights = importance_weights(p.decreasing_importance_factor, p.event_horizon_backwards)

        results = []
        for position, candidate in enumerate(offered):
            similar: list[tuple[int, float]] = []  # H(s_o) with the distance of each member
            nearest = math.inf
            for j, historic in enumerate(history):
                nearest = min(nearest, overall_distance(p, matrix, candidate, historic.option))
                d0 = situation_distance(p, matrix, candidate, current_set,
                                        historic.option, canonical_options(historic.options))
                if d0 > p.knockout:  # eq. 4.6 (with <=, see docs: knockout 0 keeps identical tasks)
                    continue
                before, before_weight = predecessor_distance(p, matrix, history, j, weights)
                dist = (weights[0] * d0 + before) / (weights[0] + before_weight)
                if time_of_day_differs(now, historic.time_of_day):
                    dist = dist * p.time_of_day_penalty
                similar.append((j, dist))
            total = 0.0
            for _, dist in similar:
                total += dist
            roots = np.array([j for j, _ in similar], dtype=np.int64)
            dists = np.array([d for _, d in similar], dtype=np.float64)
            results.append(Candidate(position, candidate, len(similar), total, nearest, partial(_pair, roots, dists)))

        option_ids: dict[Option, int] = {}
        executed = np.array([option_ids.setdefault(step.option, len(option_ids)) for step in history],
                            dtype=np.int64)
        next_position = np.array([j + 1 if j + 1 < len(history) and not history[j + 1].idle else -1
                                  for j in range(len(history))], dtype=np.int64)
        request = RankRequest(p, self.opening_tasks, offered, tree_roots, present_objects)
        return assemble_ranking(request, results, Successions(next_position, executed, list(option_ids)))


def _pair(roots: np.ndarray, distances: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return roots, distances


def offered_options(current: Step | Iterable[Option], time_of_day: str | None) -> tuple[tuple[Option, ...], str | None]:
    """The offered options, duplicates dropped (first kept), and the time of day of now."""
    if isinstance(current, Step):
        options, now = current.options, current.time_of_day if time_of_day is None else time_of_day
    else:
        options, now = tuple(current), time_of_day
    seen: dict[Option, None] = {}
    for option in options:
        if not isinstance(option, Option):
            raise TypeError(f"available options must be Option records, got {option!r}")
        seen.setdefault(option, None)
    return tuple(seen), now


@dataclass(frozen=True)
class Candidate:
    """What the scoring found for one offered option: ``|H(s_o)|``, the sum of the member distances
    (added in history order), the nearest Algorithm 2 distance to any executed step, and a
    function returning the members' history positions and distances (only the tree needs them)."""

    position: int
    option: Option
    n_similar: int
    total: float
    nearest: float
    members: Callable[[], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class RankRequest:
    """One ``rank()`` call: the settings, the Opening tasks, the offered options (duplicates
    dropped), how many top candidates get a forward tree (None: all) and the objects present
    (None: those of the offered options)."""

    params: Hyperparameters
    opening_tasks: frozenset[str]
    offered: Sequence[Option]
    tree_roots: int | None
    present_objects: Iterable[str] | None


def assemble_ranking(request: RankRequest, results: Sequence[Candidate], history: Successions) -> Ranking:
    """Order candidates by eq. 4.12 (ties: offered order); those without similar history follow
    by nearest Algorithm 2 distance, then offered order. Shared by both oracles."""
    p, offered, tree_roots, present_objects = request.params, request.offered, request.tree_roots, request.present_objects
    scored = []
    for found in results:
        if found.n_similar:
            score = occurrence_value(found.total, found.n_similar, p.multiple_occurrences_factor)
            scored.append(((0, score, found.position), score, found))
        else:
            scored.append(((1, found.nearest, found.position), math.inf, found))
    scored.sort(key=lambda item: item[0])

    present = frozenset(present_objects) if present_objects is not None else frozenset(
        obj for option in offered for obj in option.objects())
    opening = frozenset(request.opening_tasks)
    shape = TreeShape(p.event_horizon_forward, p.multiple_occurrences_factor, present, opening)
    tasks = []
    for rank, (_, score, found) in enumerate(scored, start=1):
        successors: tuple[TreeNode, ...] = ()
        if found.n_similar and (tree_roots is None or rank <= tree_roots):
            roots, dists = found.members()
            successors = successor_tree(roots, dists, history, shape, found.option.task not in opening)
        tasks.append(RankedTask(rank, score, found.option, found.n_similar, found.nearest, successors))
    return Ranking(tuple(tasks))
