"""The pooled predictor: the routine predictor's served probability and a per-user conditional
logit over its evidence, pooled log-linearly.

``u(c) = a log P(c) + (1 - a) log Q(c)``, ranked by ``u`` over the offer, where ``P`` is the routine
predictor's served probability (as in ``online``) and ``Q(c) = softmax(w . x(c))`` a conditional
logit over the raw evidence rows ``x`` of ``evidence.features`` (the same function every learned
ranker uses), learnt from nothing by one AdaGrad step on ``-log Q(done) + l2 / 2 |w|^2`` after each
decision (rate ``online_rate``, ``online_l2``; the squared-gradient sums start at
``online_damping``). With these defaults the logit is the ``logit`` baseline of the replay, so the
pool weighs two rankers that are each measured alone; ``a = pool_weight`` (1: the routine predictor;
0: the logit). The two are pooled, not chained: the logit learns its own likelihood, not a
correction of ``P`` (what ``online`` does, docs/algorithm.md, "Online predictor").

Everything else is ``online``'s: ``fit`` learns from the latest ``online_window`` decisions,
``extend`` and ``partial_fit`` from every later one, the rows of a decision are taken at the moment
its history shows (``evidence.DecisionClock``), and every ranked option keeps the routine
predictor's explanation, with the pool's rank, probability (``softmax(u)``) and score.
docs/algorithm.md, "Pooled predictor".
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any, cast

import numpy as np

from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.records import Step
from oracle.errors import SettingsError

#: The routine predictor's weight in the pool (chosen on the development sets, docs/algorithm.md).
POOL_WEIGHT = 0.3


class PooledOracle(OnlineOracle):
    """The routine predictor pooled with a per-user conditional logit (module docstring)."""

    _param_names = OnlineOracle._param_names + ("pool_weight",)

    def __init__(self, distances: Any = None, *, pool_weight: float = POOL_WEIGHT, online_damping: float = 1e-8,
                 online_gate: float | None = None, **online: Any) -> None:
        super().__init__(distances, online_damping=online_damping, online_gate=online_gate, **online)
        self.pool_weight = pool_weight

    def fit(self, history: Iterable[Step]) -> PooledOracle:
        weight = self.pool_weight
        if isinstance(weight, bool) or not isinstance(weight, (int, float)) or not 0.0 <= weight <= 1.0:
            raise SettingsError(f"{type(self).__name__}: pool_weight must be a number from 0 to 1, got {weight!r}")
        super().fit(history)
        return self

    def _learn(self, x: np.ndarray, offset: np.ndarray, truth: int) -> None:
        """One AdaGrad step of the logit on the decision (raw evidence ``x``, the index done); the
        routine predictor's ``offset`` takes no part in what the logit learns."""
        if self.coef_ is None or self.squared_ is None:
            self.coef_ = np.zeros(x.shape[1])
            self.squared_ = np.full(x.shape[1], max(float(self.online_damping), 1e-12))
        self._step(x, 0.0, truth)

    def serves(self) -> bool:
        """Whether ``rank`` pools: once the logit has learnt from a decision, and the routine
        predictor does not take the whole weight."""
        return self.weights() is not None and self.pool_weight < 1.0

    def _combined(self, log_p: np.ndarray, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``a log P + (1 - a) log Q``: the routine predictor's and the logit's log-probabilities."""
        logit = x @ w
        logit = logit - logit.max()
        logit = logit - math.log(float(np.exp(logit).sum()))
        a = float(self.pool_weight)
        return cast(np.ndarray, a * log_p + (1.0 - a) * logit)
