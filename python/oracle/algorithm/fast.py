"""The PreferenceOracle for production: the reference algorithm with tables, numpy and incremental state.

What is precomputed (docs/algorithm.md, "Fast implementation"):

* every distinct executed or available option (task, target, reference) gets an id, and the
  Algorithm 2 distance between every pair of ids is kept in one growing table;
* every distinct available-option set gets an id; Algorithm 3's set distances between sets are
  memoised per pair as they are first needed;
* the Algorithm 3 distances of each of the last ``event horizon backwards`` executed steps to all
  earlier steps are computed once, when the step is added, as the thesis caches predecessor
  distances; a rank then only looks them up, shifted along the history.

It performs the same floating-point operations in the same order as ``reference``, so both
return identical scores; the property tests hold them to 1e-9.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from functools import partial

import numpy as np
import numpy.typing as npt

from oracle.algorithm.params import NAMES, Hyperparameters, OracleParams
from oracle.algorithm.reference import (
    Candidate, RankRequest, assemble_ranking, class_row, importance_weights, offered_options,
)
from oracle.algorithm.records import Option, Ranking, Step, option_key
from oracle.algorithm.tree import Successions
from oracle.errors import SettingsError
from oracle.timeline import TIME_OF_DAY_NAMES

_TOD: dict[str | None, int] = {name: code for code, name in enumerate(TIME_OF_DAY_NAMES)}


class _Column:
    """A growing 1-d numpy array with amortised O(1) append."""

    def __init__(self, dtype: npt.DTypeLike) -> None:
        self._data = np.empty(64, dtype=dtype)
        self.size = 0

    def append(self, value: float) -> None:
        if self.size == self._data.size:
            self._data = np.concatenate([self._data, np.empty_like(self._data)])
        self._data[self.size] = value
        self.size += 1

    @property
    def view(self) -> np.ndarray:
        return self._data[: self.size]


class PreferenceOracle(OracleParams):
    """PreferenceOracle, fast version; same parameters and results as ``ReferenceOracle``.

    ``fit(history)`` learns from a list of Steps, ``partial_fit(step)`` adds one more,
    ``rank(current)`` scores the available options without changing the model.
    """

    # -- learning -------------------------------------------------------------------------

    def fit(self, history: Iterable[Step]) -> PreferenceOracle:
        p = self.hyperparameters()
        self.params_ = p
        self._raw_params = tuple(getattr(self, name) for name in NAMES)
        self._weights = importance_weights(p.decreasing_importance_factor, p.event_horizon_backwards)
        self._matrix_values = np.asarray(self.distances.values, dtype=np.float64)
        self.options_: list[Option] = []            # id -> option
        self._option_ids: dict[Option, int] = {}
        self._option_classes = np.empty((0, 3), dtype=np.int64)  # task, target, reference rows (-1: none)
        self._option_table = np.empty((0, 0), dtype=np.float64)  # Algorithm 2 between option ids
        self._option_count = 0
        self._set_ids: dict[tuple[int, ...], int] = {}
        self._set_members: list[np.ndarray] = []     # option ids in canonical order
        self._set_flat = _Column(np.int64)              # all sets' members, concatenated
        self._set_start = _Column(np.int64)
        self._set_size = _Column(np.int64)
        self._set_distances: dict[int, np.ndarray] = {}  # set a -> Algorithm 3 set distance to set b (nan: unknown)
        self._executed = _Column(np.int64)
        self._set_of_step = _Column(np.int64)
        self._idle = _Column(np.bool_)
        self._time_of_day = _Column(np.int64)          # -1: unknown
        self._next_position = _Column(np.int64)        # successor position for the tree, -1: none
        self._rows: dict[int, np.ndarray] = {}         # position a -> Algorithm 3 to every earlier step
        self.n_steps_ = 0
        steps = list(history)
        for step in steps:
            self._add_step(step)
        for position in range(max(0, len(steps) - p.event_horizon_backwards), len(steps)):
            self._rows[position] = self._situation_row(position)
        self._update_predecessors()
        return self

    def _update_predecessors(self) -> None:
        """The weighted predecessor distances of every historic step against the current chain.

        They depend on the history only, not on the candidate, so they are computed once per
        added step rather than once per rank."""
        self._before, self._before_weight = self._predecessors(np.arange(self.n_steps_), self._weights)

    def partial_fit(self, step: Step) -> PreferenceOracle:
        if not hasattr(self, "params_"):
            return self.fit([step])
        p = self._check_params()
        self._add_step(step)
        position = self.n_steps_ - 1
        if p.event_horizon_backwards > 0:
            self._rows[position] = self._situation_row(position)
            self._rows.pop(position - p.event_horizon_backwards, None)
        self._update_predecessors()
        return self

    def _check_params(self) -> Hyperparameters:
        if not hasattr(self, "params_"):
            raise SettingsError(f"{type(self).__name__} is not fitted; call fit(history) first")
        if tuple(getattr(self, name) for name in NAMES) != self._raw_params:
            raise SettingsError("hyperparameters changed since fit; call fit(history) again")
        return self.params_

    def _add_step(self, step: Step) -> None:
        if not isinstance(step, Step):
            raise TypeError(f"history entries must be Step records, got {type(step).__name__}")
        executed = self._intern_options([step.option])[0]
        available = self._intern_options(step.options)
        key = tuple(sorted(set(available), key=lambda i: option_key(self.options_[i])))
        set_id = self._set_ids.get(key)
        if set_id is None:
            set_id = self._set_ids[key] = len(self._set_members)
            self._set_members.append(np.array(key, dtype=np.int64))
            self._set_start.append(self._set_flat.size)
            self._set_size.append(len(key))
            for member in key:
                self._set_flat.append(member)
        position = self.n_steps_
        if position > 0 and not step.idle:
            self._next_position.view[position - 1] = position
        self._executed.append(executed)
        self._set_of_step.append(set_id)
        self._idle.append(step.idle)
        self._time_of_day.append(_TOD.get(step.time_of_day, -1))
        self._next_position.append(-1)
        self.n_steps_ = position + 1

    def _classes_of(self, options: Sequence[Option]) -> np.ndarray:
        rows = np.empty((len(options), 3), dtype=np.int64)
        for i, option in enumerate(options):
            rows[i, 0] = class_row(self.distances, option.task)
            rows[i, 1] = -1 if option.target is None else class_row(self.distances, option.target)
            rows[i, 2] = -1 if option.reference is None else class_row(self.distances, option.reference)
        return rows

    def _intern_options(self, options: Iterable[Option]) -> list[int]:
        new = [o for o in dict.fromkeys(options) if o not in self._option_ids]
        if new:
            classes = self._classes_of(new)
            old, count = self._option_count, self._option_count + len(new)
            if count > self._option_table.shape[0]:
                size = max(64, 2 * count)
                table = np.empty((size, size), dtype=np.float64)
                table[:old, :old] = self._option_table[:old, :old]
                self._option_table = table
                grown = np.empty((size, 3), dtype=np.int64)
                grown[:old] = self._option_classes[:old]
                self._option_classes = grown
            self._option_classes[old:count] = classes
            all_classes = self._option_classes[:count]
            # both directions, so an asymmetric rounding in the class matrix is reproduced exactly
            self._option_table[old:count, :count] = self._option_distances(classes, all_classes)
            self._option_table[:count, old:count] = self._option_distances(all_classes, classes)
            for option in new:
                self._option_ids[option] = len(self.options_)
                self.options_.append(option)
            self._option_count = count
        return [self._option_ids[o] for o in options]

    def _option_distances(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Algorithm 2 between every option of ``a`` and every option of ``b`` (rows of class ids)."""
        p, values = self.params_, self._matrix_values
        task = values[a[:, 0][:, None], b[:, 0][None, :]]
        total = np.zeros(task.shape)
        count = np.zeros(task.shape, dtype=np.int64)
        for slot in (1, 2):  # target, then reference: the order of the reference's sum
            mine, theirs = a[:, slot][:, None], b[:, slot][None, :]
            both = (mine >= 0) & (theirs >= 0)
            one = (mine >= 0) ^ (theirs >= 0)
            term = np.where(both, values[np.maximum(mine, 0), np.maximum(theirs, 0)], 0.0)
            term = np.where(one, p.penalty, term)
            total = total + term
            count += both | one
        average = np.divide(total, count, out=np.zeros(task.shape), where=count > 0)
        distance: np.ndarray = p.task_factor * task + p.object_factor * average
        return distance

    def _set_distance_vector(self, rows: np.ndarray, set_ids: np.ndarray) -> np.ndarray:
        """Algorithm 3's option set distance from the options behind ``rows`` (canonical order;
        each row holds their Algorithm 2 distances to all option ids) to each set in ``set_ids``."""
        k = rows.shape[0]
        if k == 0:
            return np.zeros(set_ids.size)
        best = np.zeros((k, set_ids.size))  # an empty (unrecorded) set compares as 0
        n_sets = len(self._set_members)
        if 4 * set_ids.size >= n_sets:  # most sets are needed: reduce over all of them at once
            filled = np.flatnonzero(self._set_size.view > 0)
            if filled.size:
                mins = np.zeros((k, n_sets))
                mins[:, filled] = np.minimum.reduceat(rows[:, self._set_flat.view], self._set_start.view[filled], axis=1)
                best = mins[:, set_ids]
            return self._average_rows(best)
        members = [self._set_members[s] for s in set_ids.tolist()]
        sizes = np.array([m.size for m in members], dtype=np.int64)
        filled = np.flatnonzero(sizes > 0)
        if filled.size:
            flat = np.concatenate([members[i] for i in filled.tolist()])
            starts = np.concatenate([[0], np.cumsum(sizes[filled])[:-1]])
            best[:, filled] = np.minimum.reduceat(rows[:, flat], starts, axis=1)
        return self._average_rows(best)

    @staticmethod
    def _average_rows(best: np.ndarray) -> np.ndarray:
        k = best.shape[0]
        total = np.zeros(best.shape[1])
        for i in range(k):  # left to right, as the reference adds
            total += best[i]
        mean: np.ndarray = total / k
        return mean

    def _historic_set_distances(self, set_a: int, needed: np.ndarray) -> np.ndarray:
        """Memoised set distances from historic set ``set_a`` to every set id (nan where not needed)."""
        known = self._set_distances.get(set_a)
        n_sets = len(self._set_members)
        if known is None or known.size < n_sets:
            grown = np.full(n_sets, np.nan)
            if known is not None:
                grown[: known.size] = known
            known = self._set_distances[set_a] = grown
        missing = needed[np.isnan(known[needed])]
        if missing.size:
            members = self._set_members[set_a]
            rows = self._option_table[members, : self._option_count]
            known[missing] = self._set_distance_vector(rows, missing)
        return known

    def _situation_row(self, a: int) -> np.ndarray:
        """Algorithm 3 distance of step ``a`` (as the current side) to every earlier step."""
        p = self.params_
        executed = self._executed.view
        base: np.ndarray = self._option_table[executed[a], executed[:a]]
        if p.compare_situations <= 0 or a == 0:
            return base
        need = base < p.knockout
        if not need.any():
            return base
        sets = self._set_of_step.view[:a]
        table = self._historic_set_distances(int(self._set_of_step.view[a]), np.unique(sets[need]))
        row: np.ndarray = base.copy()
        row[need] = base[need] + table[sets[need]] * p.compare_situations
        return row

    # -- ranking --------------------------------------------------------------------------

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None) -> Ranking:
        """What ``ReferenceOracle.rank`` answers for the same arguments, from the kept tables."""
        p = self._check_params()
        offered, now = offered_options(current, time_of_day)
        count, length = self._option_count, self.n_steps_
        known = [self._option_ids.get(option, -1) for option in offered]
        if -1 in known:
            classes = self._classes_of(offered)
            cand_rows = self._option_distances(classes, self._option_classes[:count])  # C x options
        else:
            cand_rows = self._option_table[known, :count]
        executed = self._executed.view
        base = cand_rows[:, executed]                                               # C x L
        knockout = p.knockout
        # the (candidate, step) pairs of H(s_o), row-major: by candidate, then history order
        if p.compare_situations > 0 and length and offered:
            rows, cols = np.nonzero(base < knockout)       # Algorithm 3 compares these situations
            sets = self._set_of_step.view[cols]
            needed = np.unique(sets)
            lookup = np.zeros(len(self._set_members))
            if needed.size:
                order = sorted(range(len(offered)), key=lambda i: option_key(offered[i]))
                lookup[needed] = self._set_distance_vector(cand_rows[order], needed)
            d0 = base[rows, cols] + lookup[sets] * p.compare_situations
            keep = d0 <= knockout
            rows, cols, d0 = rows[keep], cols[keep], d0[keep]
            edge_rows, edge_cols = np.nonzero(base == knockout)  # skipped by Algorithm 3, still similar
            if edge_rows.size:
                rows = np.concatenate([rows, edge_rows])
                cols = np.concatenate([cols, edge_cols])
                d0 = np.concatenate([d0, base[edge_rows, edge_cols]])
                order_pairs = np.lexsort((cols, rows))
                rows, cols, d0 = rows[order_pairs], cols[order_pairs], d0[order_pairs]
        else:
            rows, cols = np.nonzero(base <= knockout)
            d0 = base[rows, cols]

        weights = self._weights
        dist = (weights[0] * d0 + self._before[cols]) / (weights[0] + self._before_weight[cols])
        now_code = _TOD.get(now, -1) if now is not None else -1
        if now_code >= 0:
            then = self._time_of_day.view[cols]
            dist = np.where((then >= 0) & (then != now_code), dist * p.time_of_day_penalty, dist)
        # bincount adds each candidate's members one by one in history order, as the reference does
        totals = np.bincount(rows, weights=dist, minlength=len(offered)).tolist()
        counts = np.bincount(rows, minlength=len(offered)).tolist()
        bounds = np.searchsorted(rows, np.arange(len(offered) + 1)).tolist()
        nearest = base.min(axis=1).tolist() if length else [math.inf] * len(offered)

        def members(c: int) -> tuple[np.ndarray, np.ndarray]:
            return cols[bounds[c]:bounds[c + 1]], dist[bounds[c]:bounds[c + 1]]

        results = [Candidate(c, option, counts[c], totals[c], nearest[c], partial(members, c))
                   for c, option in enumerate(offered)]
        request = RankRequest(p, self.opening_tasks, offered, tree_roots, present_objects)
        return assemble_ranking(request, results, Successions(self._next_position.view, executed, self.options_))

    def _predecessors(self, columns: np.ndarray, weights: list[float]) -> tuple[np.ndarray, np.ndarray]:
        """Weighted predecessor distances for the historic steps at ``columns`` (see reference)."""
        p = self.params_
        length = self.n_steps_
        idle = self._idle.view
        total = np.zeros(columns.size)
        weight_sum = np.zeros(columns.size)
        running = np.ones(columns.size, dtype=bool)    # not stopped at a common chain start
        knocked = np.zeros(columns.size, dtype=bool)
        for n in range(1, p.event_horizon_backwards + 1):
            if not running.any():
                break
            a = length - n
            b = columns - n
            historic_start = (b < 0) | idle[np.maximum(b, 0)]
            active = running & ~knocked
            if a < 0 or idle[a]:
                running &= ~(active & historic_start)
                knocked |= active & ~historic_start
            else:
                knocked |= active & historic_start  # only the historic chain starts here
                compared = np.flatnonzero(active & ~historic_start)
                d = self._rows[a][b[compared]]
                over = d > p.knockout
                knocked[compared[over]] = True
                fine = compared[~over]
                total[fine] += weights[n] * d[~over]
                weight_sum[fine] += weights[n]
            total[knocked] += weights[n] * p.penalty
            weight_sum[knocked] += weights[n]
        return total, weight_sum
