"""The online predictor: the routine predictor's ranking re-weighed by a per-user conditional logit
over its own evidence (``evidence.features``), learnt online, one AdaGrad step after each decision.

``u(c) = log P(c) + sum_f w_f x_f(c) / s_f``, ``P'(c | offered) = softmax(u)`` over the offer: ``P``
is the routine predictor's own served probability (its self-tuned variant, the clock's odds where
its gate is open), ``x`` the evidence and ``s_f`` the spread of column ``f`` over every row learnt
so far (with ``SPREAD_PRIOR`` rows of unit variance). ``w`` starts at 0 (the routine predictor
exactly) and after each decision takes one AdaGrad step on that decision's log-likelihood, ``-log
P'(done)`` plus ``online_l2 / 2 |w|^2`` (the pull back to the routine predictor): ``w -= online_rate
g / sqrt(online_damping + sum g^2)`` (a larger damping makes the first steps follow the gradient's
size, not only its sign). The gate: before each step, the combination as served and the routine
predictor alone rank the decision; the combination re-weighs ``rank`` only once its summed hit score
(``([r <= 1] + [r <= 3] + [r <= 5]) / 3``) leads by more than ``online_gate`` standard errors of the
paired differences (the self-tuning's switch rule; None: always). Every ranked option keeps the
routine predictor's explanation (its context, support, successors); only its rank, probability and
score are the combination's. docs/algorithm.md, "Online predictor".
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any, cast

import numpy as np

from oracle.algorithm.clock import reweighted
from oracle.algorithm.contexts import Blend
from oracle.algorithm.evidence import DecisionClock, features
from oracle.algorithm.records import Option, Ranking, RoutineTask, Step
from oracle.algorithm.reference import offered_options
from oracle.algorithm.routine import TUNING_WINDOW, RoutineOracle
from oracle.algorithm.selftune import FLOOR, mixed_distribution
from oracle.algorithm.stacked import hit_score
from oracle.errors import SettingsError

#: pseudo-rows of unit variance in each column's spread: the few rows of a user's first decisions
#: do not blow a column up (a column that barely varied yet would weigh as if it decided)
SPREAD_PRIOR = 20.0

def _reranked(task: RoutineTask, rank: int, probability: float) -> RoutineTask:
    """``dataclasses.replace(task, rank=rank, probability=probability, score=-log2 probability)``
    without replace's work per field (a ranking of 20 options is re-made per hypothetical step of
    the predicted chain): the same fields, the three given."""
    twin = object.__new__(type(task))
    twin.__dict__.update(task.__dict__, rank=rank, probability=probability,
                         score=-math.log2(probability) if probability > 0 else math.inf)
    return twin


class OnlineOracle(RoutineOracle):
    """The routine predictor with an online-learnt combination of its evidence (module docstring):
    rate ``online_rate``, penalty ``online_l2``, damping ``online_damping``, ``online_average``: serve
    the mean of every step's ``w``, gate margin ``online_gate``; ``fit`` learns from the latest
    ``online_window`` decisions of the history it is given, ``extend`` and ``partial_fit`` from
    every later one."""

    _param_names = RoutineOracle._param_names + ("online_rate", "online_l2", "online_damping",
                                                 "online_average", "online_gate", "online_window")

    def __init__(self, distances: Any = None, *, online_rate: float = 0.1, online_l2: float = 1e-4,
                 online_damping: float = 1.0, online_average: bool = False, online_gate: float | None = 1.0,
                 online_window: int = TUNING_WINDOW, **routine: Any) -> None:
        super().__init__(distances, **routine)
        self.online_rate = online_rate
        self.online_l2 = online_l2
        self.online_damping = online_damping
        self.online_average = online_average
        self.online_gate = online_gate
        self.online_window = online_window

    def fit(self, history: Iterable[Step]) -> OnlineOracle:
        for name in ("online_rate", "online_l2", "online_damping"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value < math.inf:
                raise SettingsError(f"{type(self).__name__}: {name} must be a number >= 0, got {value!r}")
        if not isinstance(self.online_average, bool):
            raise SettingsError(f"{type(self).__name__}: online_average must be True or False, got {self.online_average!r}")
        gate = self.online_gate
        if gate is not None and (isinstance(gate, bool) or not isinstance(gate, (int, float)) or not 0 <= gate < math.inf):
            raise SettingsError(f"{type(self).__name__}: online_gate must be a number >= 0 or None, got {gate!r}")
        window = self.online_window
        if isinstance(window, bool) or not isinstance(window, int) or window < 0:
            raise SettingsError(f"{type(self).__name__}: online_window must be a whole number >= 0, got {window!r}")
        self.coef_: np.ndarray | None = None     # w
        self.squared_: np.ndarray | None = None  # AdaGrad's sum of squared gradients
        self.moments_: np.ndarray | None = None  # per column: rows, sum, sum of squares
        self.learnt_ = 0                         # decisions learnt from
        self.summed_: np.ndarray | None = None   # the sum of w after each step (online_average)
        self.lead_ = 0.0                         # hit score of the combination minus routine's, summed
        self.spread_ = 0.0                       # the sum of its squares
        self._learn_from = 0
        self._clock = DecisionClock()
        self._rows_at: tuple[tuple[Any, ...], np.ndarray] | None = None  # _rows's latest answer
        super().fit(history)
        return self

    def _grow(self, steps: Sequence[Step]) -> None:
        # a decision's evidence costs about one scored step: fit learns from the latest ones only
        self._learn_from = len(steps) - self.online_window
        super()._grow(steps)

    def partial_fit(self, step: Step) -> OnlineOracle:
        if not hasattr(self, "variants_"):
            return self.fit([step])
        self._learn_from = self.n_steps_
        super().partial_fit(step)
        return self

    def _add(self, step: Step, score: bool, offers: Any = None) -> None:
        if not isinstance(step, Step):
            raise TypeError(f"history entries must be Step records, got {type(step).__name__}")
        if self.n_steps_ >= self._learn_from and not step.idle and len(step.options) > 1:
            offered, _ = offered_options(step, None)
            if len(offered) > 1 and step.option in offered:
                when, part = self._clock.decided(step)
                x = self._rows(offered, part, when)
                self._learn(x, self._served(x, self._evidence(offered, part).ids, when), offered.index(step.option))
        super()._add(step, score, offers)
        self._clock.passed(step)

    def _rows(self, offered: Sequence[Option], time_of_day: str | None, at: float | None) -> np.ndarray:
        """``_features`` of an offer (read-only), kept while the model is as it is: ranking a
        decision and then learning it (the predicted chain's hypothetical steps: each ranked, then
        taken as done) read the same rows. The number of steps counted is part of the key (only
        counting a step changes the evidence; ``fit`` and a new prior start afresh)."""
        key = (tuple(offered), time_of_day, at, self.n_steps_)
        kept = self.__dict__.get("_rows_at")
        if kept is not None and kept[0] == key:
            return cast(np.ndarray, kept[1])
        x = self._features(offered, time_of_day, at)
        x.flags.writeable = False
        self._rows_at = (key, x)
        return x

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state.pop("_rows_at", None)  # a cache of the present state only
        return state

    def _used_evidence(self, offered: Sequence[Option], ids: list[int], now: str | None, used: list[int],
                       inside: np.ndarray | None, new: np.ndarray | None, resumed: np.ndarray | None
                       ) -> tuple[list[np.ndarray], list[Blend], np.ndarray]:
        # a ranking this model re-weighs reads every variant's evidence of the offer next
        # (``_rows``): the used variants' are taken from it, not computed a second time
        if len(offered) < 2 or not self.serves():
            return super()._used_evidence(offered, ids, now, used, inside, new, resumed)
        seen = self._evidence(offered, now)
        return [seen.probabilities[v] for v in used], [seen.blends[v] for v in used], seen.distances

    def _features(self, offered: Sequence[Option], time_of_day: str | None, at: float | None) -> np.ndarray:
        """The evidence rows of an offer (``evidence.features``); a subclass may add columns."""
        return features(self, offered, time_of_day, at)

    def _served(self, x: np.ndarray, ids: list[int], when: float | None) -> np.ndarray:
        """log P: the routine predictor's probability of each option of an evidence block, as its
        ``rank`` serves it now (the self-tuned variants' columns mixed, the clock's odds if open)."""
        weights = self.weights_.weights(self.tuning, self.switch_margin)
        used = np.flatnonzero(weights > 0).tolist()
        mixed = mixed_distribution(weights[used], [np.exp(x[:, v]) for v in used])
        if self.gate_.open(self.recency_gate):
            clock = self.clock_.weights(self.clock_.buckets(ids, when))
            if clock is not None:
                mixed = reweighted(mixed, clock)
        return cast(np.ndarray, np.log(np.maximum(mixed, FLOOR)))

    def _spread(self) -> np.ndarray:
        """Each column's spread over the rows learnt so far, with ``SPREAD_PRIOR`` rows of unit variance."""
        assert self.moments_ is not None
        n, total, squares = self.moments_
        spread = np.sqrt((np.maximum(squares - total * total / n, 0.0) + SPREAD_PRIOR) / (n + SPREAD_PRIOR))
        return cast(np.ndarray, spread)

    def _learn(self, x: np.ndarray, offset: np.ndarray, truth: int) -> None:
        """One AdaGrad step on the decision (evidence ``x``, routine's ``log P``, the index done)."""
        moments = np.stack([np.full(x.shape[1], float(len(x))), x.sum(axis=0), (x * x).sum(axis=0)])
        if self.moments_ is None or self.coef_ is None or self.squared_ is None:
            self.moments_ = moments
            self.coef_, self.squared_ = np.zeros(x.shape[1]), np.full(x.shape[1],
                                                                           max(float(self.online_damping), 1e-8))
        else:
            self.moments_ = self.moments_ + moments
        z = x / self._spread()
        served = self.weights()
        if served is not None:  # the gate's evidence: the combination as served, before it learns this
            d = hit_score(offset + z @ served, truth) - hit_score(offset, truth)
            self.lead_ += d
            self.spread_ += d * d
        self._step(z, offset, truth)

    def _step(self, z: np.ndarray, offset: np.ndarray | float, truth: int) -> None:
        """One AdaGrad step on ``-log softmax(offset + z w)[truth] + online_l2 / 2 |w|^2``."""
        assert self.coef_ is not None and self.squared_ is not None
        u = offset + z @ self.coef_
        p = np.exp(u - u.max())
        p /= p.sum()
        grad = p @ z - z[truth] + self.online_l2 * self.coef_
        self.squared_ = self.squared_ + grad * grad
        self.coef_ = self.coef_ - self.online_rate * grad / np.sqrt(self.squared_)
        self.summed_ = self.coef_.copy() if self.summed_ is None else self.summed_ + self.coef_
        self.learnt_ += 1

    def weights(self) -> np.ndarray | None:
        """The combination's ``w`` as ``rank`` uses it (the average of every step's with
        ``online_average``), whatever the gate says; None before the first decision learnt."""
        if self.coef_ is None or self.summed_ is None:
            return None
        return self.summed_ / self.learnt_ if self.online_average else self.coef_

    def _combined(self, log_p: np.ndarray, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        """The served scores of options with the routine predictor's ``log P`` and evidence ``x``."""
        return cast(np.ndarray, log_p + (x / self._spread()) @ w)

    def serves(self) -> bool:
        """Whether ``rank`` re-weighs (w != 0 and, with ``online_gate`` z, the combination's hit
        score leads the routine predictor's on the decisions learnt by more than z standard errors)."""
        w = self.weights()
        if w is None or not np.any(w):
            return False
        return self.online_gate is None or self.lead_ > self.online_gate * math.sqrt(self.spread_)

    def rank(self, current: Step | Iterable[Option], time_of_day: str | None = None, *,
             tree_roots: int | None = 3, present_objects: Iterable[str] | None = None,
             at: float | None = None, explain: bool = True) -> Ranking:
        ranking = super().rank(current, time_of_day, tree_roots=tree_roots, present_objects=present_objects, at=at,
                               explain=explain)
        w = self.weights()
        if w is None or not self.serves() or len(ranking.tasks) < 2:
            return ranking  # w = 0 (or the gate shut): the routine predictor's own ranking
        offered, now = offered_options(current, time_of_day)
        when = at if at is not None else current.time if isinstance(current, Step) else None
        tasks = cast(tuple[RoutineTask, ...], ranking.tasks)
        # the evidence as the decision will be learnt: at the moment its history will show (the
        # previous action's start, not the end a replay ranks at), in the order offered (computed
        # once for both), then in the ranking's order
        row = {option: i for i, option in enumerate(offered)}
        moment = self._clock.moment() if when is not None else None
        x = self._rows(offered, now, moment)[[row[t.option] for t in tasks]]
        u = self._combined(np.log(np.maximum([t.probability for t in tasks], FLOOR)), x, w)
        p = np.exp(u - u.max())
        p /= p.sum()
        order = sorted(range(len(tasks)), key=lambda i: (-p[i], i))  # ties: the routine predictor's order
        return Ranking(tuple(_reranked(tasks[i], rank, float(p[i])) for rank, i in enumerate(order, start=1)))
