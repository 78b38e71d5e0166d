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

The gate (``online_gate``, ``POOL_GATE`` by default; None: always pool): before each decision is learnt, each
candidate weight (``pool_weight``: one weight, a list of them, or ``"auto"``: each of ``AUTO_WEIGHTS``) and the
routine predictor alone rank it; a candidate is served only once its summed hit score leads the
routine predictor's by more than ``online_gate`` standard errors of the paired differences, and of
those the one with the largest lead (the self-tuning's switch rule, the routine predictor the
incumbent). ``pool_evidence="likelihood"`` sums the log-probability of the option done instead of
the hit score (a development trial: it opens sooner and lost Top-3 on the persona sets). The
default predictor (``predictors.DEFAULT``). docs/algorithm.md, "Pooled predictor".
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import Any, cast

import numpy as np

from oracle.algorithm.online import OnlineOracle
from oracle.algorithm.records import Step
from oracle.algorithm.selftune import switch_to
from oracle.algorithm.stacked import hit_score
from oracle.errors import SettingsError

#: The routine predictor's weight in the pool: each user's own, chosen from ``AUTO_WEIGHTS`` behind
#: a gate of ``POOL_GATE`` standard errors (the one setting that passed every development set,
#: docs/algorithm.md, "Pooled predictor").
POOL_WEIGHT = "auto"
POOL_GATE = 2.0

#: the weights ``pool_weight="auto"`` chooses from, each user by their own decisions (the gate's rule)
AUTO_WEIGHTS = (0.8, 0.6, 0.4, 0.2)


class PooledOracle(OnlineOracle):
    """The routine predictor pooled with a per-user conditional logit (module docstring)."""

    _param_names = OnlineOracle._param_names + ("pool_weight", "pool_evidence")

    def __init__(self, distances: Any = None, *, pool_weight: float | str | Sequence[float] = POOL_WEIGHT, online_damping: float = 1e-8,
                 online_gate: float | None = POOL_GATE, pool_evidence: str = "hits", **online: Any) -> None:
        super().__init__(distances, online_damping=online_damping, online_gate=online_gate, **online)
        self.pool_weight = pool_weight
        self.pool_evidence = pool_evidence

    def fit(self, history: Iterable[Step]) -> PooledOracle:
        weight = self.pool_weight
        given = AUTO_WEIGHTS if weight == "auto" else tuple(weight) if isinstance(weight, (list, tuple)) else (weight,)
        if not given or any(isinstance(w, bool) or not isinstance(w, (int, float)) or not 0.0 <= w <= 1.0 for w in given):
            raise SettingsError(f"{type(self).__name__}: pool_weight must be a number from 0 to 1, a list of them "
                                f"or 'auto', got {weight!r}")
        if self.pool_evidence not in POOL_EVIDENCE:
            raise SettingsError(f"{type(self).__name__}: pool_evidence must be one of {', '.join(POOL_EVIDENCE)}, "
                                f"got {self.pool_evidence!r}")
        self.candidates_ = np.array(given, dtype=float)
        self.leads_ = np.zeros(len(given))    # each candidate's hit score minus routine's, summed
        self.spreads_ = np.zeros(len(given))  # the sums of their squares
        super().fit(history)
        return self

    def _learn(self, x: np.ndarray, offset: np.ndarray, truth: int) -> None:
        """One AdaGrad step of the logit on the decision (raw evidence ``x``, the index done); the
        routine predictor's ``offset`` takes no part in what the logit learns."""
        if self.coef_ is None or self.squared_ is None:
            self.coef_ = np.zeros(x.shape[1])
            self.squared_ = np.full(x.shape[1], max(float(self.online_damping), 1e-12))
        elif self.online_gate is not None or len(self.candidates_) > 1:
            # the gate's evidence: each candidate weight's pool before it learns this decision
            log_q = _log_softmax(x @ self.coef_)
            score = POOL_EVIDENCE[self.pool_evidence]
            alone = score(offset, truth)
            for i, a in enumerate(self.candidates_):
                d = score(a * offset + (1.0 - a) * log_q, truth) - alone
                self.leads_[i] += d
                self.spreads_[i] += d * d
        self._step(x, 0.0, truth)

    def served_weight(self) -> float | None:
        """The routine predictor's weight in the pool ``rank`` serves: the fixed ``pool_weight``, or
        with a gate the candidate leading by more than ``online_gate`` standard errors (the largest
        lead); None when the routine predictor ranks alone."""
        if self.weights() is None:
            return None
        gate = self.online_gate
        if gate is None and len(self.candidates_) == 1:
            chosen: float | None = float(self.candidates_[0])
        else:
            at = switch_to(self.leads_, self.spreads_, gate or 0.0)
            chosen = None if at is None else float(self.candidates_[at])
        return chosen if chosen is not None and chosen < 1.0 else None

    def serves(self) -> bool:
        """Whether ``rank`` pools (``served_weight``)."""
        return self.served_weight() is not None

    def _combined(self, log_p: np.ndarray, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``a log P + (1 - a) log Q``: the routine predictor's and the logit's log-probabilities."""
        a = self.served_weight()
        assert a is not None
        return cast(np.ndarray, a * log_p + (1.0 - a) * _log_softmax(x @ w))


def _log_likelihood(u: np.ndarray, truth: int) -> float:
    """``log softmax(u)[truth]``: the log-probability scores ``u`` give the option done."""
    return float(_log_softmax(u)[truth])


#: what the gate sums per decision, a candidate's minus the routine predictor's: the hit score
#: (``([r <= 1] + [r <= 3] + [r <= 5]) / 3``) or the log-likelihood of the option done
POOL_EVIDENCE: dict[str, Callable[[np.ndarray, int], float]] = {"hits": hit_score, "likelihood": _log_likelihood}


def _log_softmax(u: np.ndarray) -> np.ndarray:
    u = u - u.max()
    return cast(np.ndarray, u - math.log(float(np.exp(u).sum())))
