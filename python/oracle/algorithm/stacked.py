"""The stacked predictor: the routine predictor's ranking, re-weighed by a per-user conditional
logit over its own evidence (``evidence.features``), fitted on the user's latest decisions.

``u(c) = log P_0(c) + sum_f w_f x_f(c) / s_f``, ``P(c | offered) = softmax(u)`` over the offer:
``P_0`` is the routine predictor's first variant (its column in the evidence), ``x`` the evidence,
``s`` each column's spread over the window, ``w`` the maximum of the penalised conditional
log-likelihood of the latest ``combine_window`` decisions before the latest multiple of
``combine_every`` steps (``w = 0`` is the first variant itself; the penalty ``combine_shrink / 2
|w|^2`` pulls it there). Until the first such fit the routine predictor's own ranking is served.
Every ranked option keeps the routine predictor's explanation (its context, support, successors);
only its rank, probability and score are the combination's. docs/algorithm.md, "Stacked predictor".
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Sequence
from typing import Any, cast

import numpy as np

from oracle.algorithm.evidence import DecisionClock, features
from oracle.algorithm.records import Option, Ranking, RoutineTask, Step
from oracle.algorithm.reference import offered_options
from oracle.algorithm.routine import RoutineOracle
from oracle.errors import SettingsError


def fit_logit(rows: Sequence[tuple[np.ndarray, int]], shrink: float, offset: int | None = 0,
              iterations: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """The weights ``w`` and column spreads ``s`` of the conditional logit ``u = x[offset] + (x / s) w``
    (no offset column when ``offset`` is None) that maximise ``sum_d log softmax(u_d)[truth_d] -
    shrink / 2 |w|^2`` over the decisions ``rows`` (each: the offer's evidence, the index done)."""
    width = rows[0][0].shape[1]
    longest = max(x.shape[0] for x, _ in rows)
    stacked = np.zeros((len(rows), longest, width))
    mask = np.zeros((len(rows), longest), dtype=bool)
    truth = np.array([t for _, t in rows])
    for d, (x, _) in enumerate(rows):
        stacked[d, :x.shape[0]] = x
        mask[d, :x.shape[0]] = True
    flat = np.concatenate([x for x, _ in rows])
    spread = flat.std(axis=0)
    spread[spread < 1e-9] = 1.0
    scaled = stacked / spread
    base = stacked[:, :, offset] if offset is not None else np.zeros(mask.shape)
    picked = np.arange(len(rows))

    def loss(w: np.ndarray) -> tuple[float, np.ndarray]:
        u = np.where(mask, base + scaled @ w, -np.inf)
        top = u.max(axis=1, keepdims=True)
        e = np.exp(u - top)
        z = e.sum(axis=1, keepdims=True)
        p = e / z
        value = float(np.sum(np.log(z[:, 0]) + top[:, 0] - u[picked, truth])) + 0.5 * shrink * float(w @ w)
        grad = np.einsum("dc,dcf->f", p, scaled) - scaled[picked, truth].sum(axis=0) + shrink * w
        return value, grad

    from scipy.optimize import minimize  # 0.2-0.5 s to import: only where stacked is fitted

    found = minimize(loss, np.zeros(width), jac=True, method="L-BFGS-B", options={"maxiter": iterations})
    return np.asarray(found.x), spread


#: fewer window decisions than this: the routine predictor's ranking is served
MIN_DECISIONS = 30


def hit_score(u: np.ndarray, truth: int) -> float:
    """``([r <= 1] + [r <= 3] + [r <= 5]) / 3`` for the rank ``r`` utilities ``u`` give the truth
    (the self-tuning's hit score; ties count against the truth)."""
    better = int(np.count_nonzero(u >= u[truth])) - 1
    return ((better < 1) + (better < 3) + (better < 5)) / 3.0


def chosen_shrink(rows: Sequence[tuple[np.ndarray, int]], shrinks: Sequence[float], margin: float) -> float | None:
    """The penalty whose combination, fitted on the older two thirds of the window's decisions,
    leads the first variant alone (``w = 0``) on the latest third by more than ``margin`` standard
    errors of the paired hit-score differences, the largest such lead; None when none does (or
    the window holds fewer than ``MIN_DECISIONS``)."""
    if len(rows) < MIN_DECISIONS:
        return None
    split = len(rows) - len(rows) // 3
    plain = np.array([hit_score(x[:, 0], t) for x, t in rows[split:]])
    best, best_lead = None, 0.0
    for shrink in shrinks:
        w, spread = fit_logit(rows[:split], float(shrink))
        diff = np.array([hit_score(x[:, 0] + (x / spread) @ w, t) for x, t in rows[split:]]) - plain
        lead = float(diff.sum())
        if lead > margin * math.sqrt(float(diff @ diff)) and lead > best_lead:
            best, best_lead = float(shrink), lead
    return best


class StackedOracle(RoutineOracle):
    """The routine predictor with a learned combination of its evidence (module docstring);
    ``combine_window`` decisions, refitted every ``combine_every`` steps, penalty ``combine_shrink``."""

    _param_names = RoutineOracle._param_names + ("combine_window", "combine_every", "combine_shrink",
                                                 "combine_margin")

    def __init__(self, distances: Any = None, *, combine_window: int = 300, combine_every: int = 25,
                 combine_shrink: tuple[float, ...] = (1.0, 10.0, 100.0), combine_margin: float = 2.0,
                 **routine: Any) -> None:
        super().__init__(distances, **routine)
        self.combine_window = combine_window
        self.combine_every = combine_every
        self.combine_shrink = combine_shrink
        self.combine_margin = combine_margin

    def fit(self, history: Iterable[Step]) -> StackedOracle:
        for name in ("combine_window", "combine_every"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise SettingsError(f"{type(self).__name__}: {name} must be a whole number >= 1, got {value!r}")
        if (isinstance(self.combine_margin, bool) or not isinstance(self.combine_margin, (int, float))
                or not 0 <= self.combine_margin < math.inf):
            raise SettingsError(f"{type(self).__name__}: combine_margin must be a number >= 0, "
                                f"got {self.combine_margin!r}")
        if not self.combine_shrink or any(isinstance(v, bool) or not isinstance(v, (int, float))
                                          or not 0 < v < math.inf for v in self.combine_shrink):
            raise SettingsError(f"{type(self).__name__}: combine_shrink must be positive numbers, "
                                f"got {self.combine_shrink!r}")
        self.evidence_: dict[int, tuple[np.ndarray, int]] = {}
        self.coef_: np.ndarray | None = None
        self.spread_: np.ndarray | None = None
        self.refit_at_ = 0
        self._evidence_from = 0
        self._previous: tuple[float | None, bool] = (None, False)  # the last action's start; an idle step since
        super().fit(history)
        return self

    def _grow(self, steps: Sequence[Step]) -> None:
        # only the decisions a later refit can use get their evidence computed
        self._evidence_from = len(steps) - self.combine_window - self.combine_every
        super()._grow(steps)
        self._refit()

    def partial_fit(self, step: Step) -> StackedOracle:
        if not hasattr(self, "variants_"):
            return self.fit([step])
        self._evidence_from = self.n_steps_ - self.combine_window - self.combine_every
        super().partial_fit(step)
        self._refit()
        return self

    def _add(self, step: Step, score: bool, offers: Any = None) -> None:
        position = self.n_steps_
        if not isinstance(step, Step):
            raise TypeError(f"history entries must be Step records, got {type(step).__name__}")
        if position >= self._evidence_from and not step.idle and step.options:
            offered, _ = offered_options(step, None)
            if step.option in offered:
                when, part = self._decided(step)
                self.evidence_[position] = (features(self, offered, part, when), offered.index(step.option))
        super()._add(step, score, offers)
        last, paused = self._previous
        self._previous = (last, True) if step.idle else (step.time, False)

    def _decided(self, step: Step) -> tuple[float | None, str | None]:
        """When a past decision was taken, as its history shows it (the replay's rule, never the
        action's own start): the previous action's start, 20 s later after an idle gap; its part of day.
        Without a clock: the step's own part of day, as recorded."""
        clock = DecisionClock()  # the rule's one home
        clock.last, clock.paused = self._previous
        return clock.decided(step)

    def _refit(self) -> None:
        due = (self.n_steps_ // self.combine_every) * self.combine_every
        for position in [p for p in self.evidence_ if p < self.n_steps_ - self.combine_window - self.combine_every]:
            del self.evidence_[position]
        if due == self.refit_at_:
            return
        self.refit_at_ = due
        rows = [self.evidence_[p] for p in sorted(self.evidence_) if due - self.combine_window <= p < due]
        shrink = chosen_shrink(rows, self.combine_shrink, float(self.combine_margin))
        self.coef_, self.spread_ = fit_logit(rows, shrink) if shrink is not None else (None, None)

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None, explain: bool = True) -> Ranking:
        ranking = super().rank(current, time_of_day, tree_roots=tree_roots, present_objects=present_objects, at=at,
                               explain=explain)
        if self.coef_ is None or self.spread_ is None or not ranking.tasks:
            return ranking
        _, now = offered_options(current, time_of_day)
        when = at if at is not None else current.time if isinstance(current, Step) else None
        tasks = ranking.tasks
        x = features(self, [t.option for t in tasks], now, when)
        u = x[:, 0] + (x / self.spread_) @ self.coef_
        p = np.exp(u - u.max())
        p /= p.sum()
        order = sorted(range(len(tasks)), key=lambda i: (-p[i], i))  # ties: the routine predictor's order
        return Ranking(tuple(dataclasses.replace(
            cast(RoutineTask, tasks[i]), rank=rank, probability=float(p[i]),
            score=-math.log2(float(p[i])) if p[i] > 0 else math.inf) for rank, i in enumerate(order, start=1)))
