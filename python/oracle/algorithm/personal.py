"""The personal predictor (the default): a per-user online conditional logit over the routine
predictor's evidence and, when a shared prior is given, what other people usually do.

``P(c | offered) = softmax(w . [x(c), log P_others(c | last 1-3 tasks), log P_others(c)])``: ``x``
the rows of ``evidence.features`` (the ``logit`` baseline's features), ``P_others`` the prior's
PPM-C backed-off probability of the task after the user's own last three tokens (idle ones
included) and its order-0 share (``prior.Prior.probabilities``). ``w`` is learnt per user online,
one AdaGrad step on ``-log P(done) + l2 / 2 |w|^2`` after each decision (rate 0.1, L2 1e-4, the
``logit`` baseline's), and starts where it means something without tuning: 1 on the backed-off
prior (the ranking is then the others' habits, ``pop_ppm``) and 0 elsewhere; before the first
decision without a prior, the routine predictor ranks. Without a prior the two prior columns are
0 and the predictor is the ``logit`` baseline from its first learnt decision on, ranking as the
pooled predictor's logit alone (``pool_weight=0``, no gate) does.

Every ranked option keeps the routine predictor's explanation; ``PersonalOracle.usually`` says
what other people usually do after the same context, when the prior carried it. The prior is not
a parameter and is not kept with the fit: ``use_prior`` gives it (read-only, shared by every copy,
the hypothetical copies of the chain included). docs/algorithm.md, "Personal predictor".
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from oracle.algorithm.evidence import feature_names, features
from oracle.algorithm.pooled import PooledOracle
from oracle.algorithm.prior import IDLE, Prior, option_key
from oracle.algorithm.records import Option, Step
from oracle.algorithm.selftune import FLOOR

#: the prior's columns, after the evidence's
PRIOR_COLUMNS = ("log-p-others", "log-p-others-0")


class PersonalOracle(PooledOracle):
    """A per-user online logit over the evidence and the shared prior (module docstring)."""

    _param_names = PooledOracle._param_names + ("prior_start", "routine_start")

    def __init__(self, distances: Any = None, *, pool_weight: float | str | Sequence[float] = 0.0,
                 online_gate: float | None = None, prior_start: float = 1.0, routine_start: float = 0.0,
                 **pooled: Any) -> None:
        super().__init__(distances, pool_weight=pool_weight, online_gate=online_gate, **pooled)
        self.prior_start = prior_start
        self.routine_start = routine_start
        self._prior: Prior | None = None

    def use_prior(self, prior: Prior | None) -> PersonalOracle:
        """Rank with ``prior`` (None: without one) from now on; the weights learnt are kept."""
        self._prior = prior
        self._rows_at = None  # rows with the other prior's columns
        return self

    @property
    def prior(self) -> Prior | None:
        return getattr(self, "_prior", None)

    def fit(self, history: Iterable[Step]) -> PersonalOracle:
        self._tokens: list[str] = []  # the user's own history as the prior names it
        self._keys: dict[Option, str] = {}
        super().fit(history)
        return self

    def _add(self, step: Step, score: bool, offers: Any = None) -> None:
        super()._add(step, score, offers)  # the decision learnt from the tokens before it
        self._tokens.append(IDLE if step.idle else self._key(step.option))

    def _key(self, option: Option) -> str:
        key = self._keys.get(option)
        if key is None:
            key = self._keys[option] = option_key(option)
        return key

    def _features(self, offered: Sequence[Option], time_of_day: str | None, at: float | None) -> np.ndarray:
        x = features(self, offered, time_of_day, at)
        extra = np.zeros((len(offered), len(PRIOR_COLUMNS)))
        prior = self.prior
        if prior is not None and len(offered):
            backed, unigram = prior.probabilities(self._tokens[-3:], [self._key(o) for o in offered])
            extra[:, 0] = np.log(np.maximum(backed, FLOOR))
            extra[:, 1] = np.log(np.maximum(unigram, FLOOR))
        return np.hstack([x, extra])

    def _start(self) -> np.ndarray:
        """Where ``w`` starts: 1 on the backed-off prior, 0 elsewhere."""
        w = np.zeros(len(feature_names(self)) + len(PRIOR_COLUMNS))
        if self.prior is not None:
            w[-len(PRIOR_COLUMNS)] = self.prior_start
        w[0] = self.routine_start  # the routine predictor's first variant's log-probability
        return w

    def _learn(self, x: np.ndarray, offset: np.ndarray, truth: int) -> None:
        if self.coef_ is None or self.squared_ is None:
            self.coef_ = self._start()
            self.squared_ = np.full(x.shape[1], max(float(self.online_damping), 1e-12))
        super()._learn(x, offset, truth)

    def weights(self) -> np.ndarray | None:
        if self.coef_ is None and (self.prior is not None or self.routine_start) and hasattr(self, "variants_"):
            return self._start()  # nothing learnt yet: the others' habits rank
        return super().weights()

    def served_weight(self) -> float | None:
        return 0.0 if self.weights() is not None else None

    def _fork_part(self, name: str, value: Any) -> Any:
        # the prior is shared read-only and the names' cache shared, never copied, and the copy
        # needs only the last three tokens of the history
        if name in ("_prior", "_keys"):
            return value
        if name == "_tokens":
            return value[-3:]
        return super()._fork_part(name, value)

    def __getstate__(self) -> dict[str, Any]:
        # the prior is the process's, loaded from its file: never kept with a fit
        state = super().__getstate__()
        state["_prior"] = None
        if "_keys" in state:
            state["_keys"] = {}  # a cache, made again as it is needed
        return state

    def usually(self, option: Option, top: int = 3) -> tuple[int, float] | None:
        """What the prior says of ``option`` now: the order of the longest context of the user's
        own last tasks after which other people did it, and their share of what followed there
        (None: the prior did not carry it, or there is no prior)."""
        prior = self.prior
        if prior is None:
            return None
        key, tokens = self._key(option), getattr(self, "_tokens", [])
        for n in range(min(3, len(tokens)), -1, -1):
            followers = prior.tables.get(tuple(tokens[len(tokens) - n:]))
            if followers and followers.get(key, 0.0) > 0:
                ranked = sorted(followers.values(), reverse=True)
                if followers[key] >= ranked[min(top, len(ranked)) - 1]:
                    return n, followers[key] / sum(ranked)
        return None


def prior_share(log_p: np.ndarray, x: np.ndarray, w: np.ndarray, pooled: float) -> float | None:
    """How much of a ranking came from the shared prior, from what ``_combined`` scored it with:
    the routine predictor's ``log_p``, the rows ``x`` (the prior's columns last), the weights ``w``
    and the routine predictor's weight ``pooled`` in the pool (0 for this predictor). The scores
    split into the prior's part ``(1 - a) x_prior . w_prior`` and the user's own (their evidence's
    part and the routine predictor's); a softmax sees only differences between options, so each
    part counts by its spread over the offer (the sum of its distances from its mean), and the
    share is the prior's spread over both. None when neither part tells the options apart."""
    k = len(PRIOR_COLUMNS)
    prior = (1.0 - pooled) * (x[:, -k:] @ w[-k:])
    own = pooled * log_p + (1.0 - pooled) * (x[:, :-k] @ w[:-k])
    spread_prior = float(np.abs(prior - prior.mean()).sum())
    spread_own = float(np.abs(own - own.mean()).sum())
    total = spread_prior + spread_own
    return spread_prior / total if total > 0 else None


__all__ = ["PRIOR_COLUMNS", "PersonalOracle", "prior_share"]
