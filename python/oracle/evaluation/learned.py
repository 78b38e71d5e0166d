"""Learned baselines: per-user rankers trained online on the routine predictor's evidence.

- ``logit``: an online conditional logit (maximum-entropy ranker), ``P(c) = softmax(w . x(c))``
  over the offer, one AdaGrad step on the log-likelihood of the option done after each decision
  (rate 0.1, L2 1e-4), starting from ``w = 0``.
- ``gbdt``: LightGBM's LambdaRank (``lightgbm.train``, 100 trees of 15 leaves, rate 0.1, one thread),
  refitted on all the user's past decisions when their number reaches 32, 64, 128, ... and then
  every 512; until its first fit it ranks by the routine predictor's first variant (the first column).

Both see exactly what the default sees: the same candidates, and as features the rows of
``oracle.algorithm.evidence.features`` (one home), computed from a routine predictor kept as
``rank`` serves it. Nothing is pre-trained; no other user's data is used. docs/evaluation.md,
"Learned baselines".
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from oracle.algorithm.evidence import features
from oracle.algorithm.records import Option, Step
from oracle.algorithm.routine import RoutineOracle
from oracle.evaluation.tokens import order_by_score

#: the gbdt baseline refits when the user's decisions reach these counts, then every GBDT_EVERY
GBDT_FIRST = 32
GBDT_EVERY = 512
GBDT_PARAMS = {"objective": "lambdarank", "num_leaves": 15, "learning_rate": 0.1, "min_data_in_leaf": 10,
               "num_threads": 1, "deterministic": True, "force_row_wise": True, "verbose": -1, "seed": 0}


class Evidence:
    """A routine predictor kept as ``rank`` serves it and the evidence rows of the offers it was
    asked about, shared by the learned baselines of one replay (each observed step is added once)."""

    def __init__(self, distances: Any, opening: frozenset[str]) -> None:
        self.distances = distances
        self.opening = opening
        self.model = RoutineOracle(distances, opening_tasks=opening).fit([])
        self.history: list[Step] = []
        self._asked: tuple[tuple[Option, ...], str | None, float | None, int] | None = None
        self._rows: np.ndarray | None = None

    def reset(self) -> None:
        if self.history:
            self.model = RoutineOracle(self.distances, opening_tasks=self.opening).fit([])
            self.history = []

    def rows(self, candidates: Sequence[Option], time_of_day: str | None, at: float | None) -> np.ndarray:
        key = (tuple(candidates), time_of_day, at, len(self.history))
        if key != self._asked or self._rows is None:
            self._asked, self._rows = key, features(self.model, candidates, time_of_day, at)
        return self._rows

    def observe(self, step: Step) -> None:
        if self.history and self.history[-1] is step:
            return
        self.history.append(step)
        self.model.extend(self.history)


class _Learned:
    name = "learned"

    def __init__(self, evidence: Evidence) -> None:
        self.evidence = evidence
        self.reset()

    def reset(self) -> None:
        self.evidence.reset()
        self._last: tuple[tuple[Option, ...], np.ndarray] | None = None

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        x = self.evidence.rows(candidates, time_of_day, at)
        self._last = (tuple(candidates), x)
        return order_by_score(candidates, self.scores(x).tolist())

    def observe(self, step: Step) -> None:
        if not step.idle and self._last is not None and step.option in self._last[0]:
            self.learn(self._last[1], self._last[0].index(step.option))
        self._last = None
        self.evidence.observe(step)

    def scores(self, x: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def learn(self, x: np.ndarray, truth: int) -> None:
        raise NotImplementedError


class OnlineLogit(_Learned):
    """``logit``: conditional logit, AdaGrad (module docstring)."""

    name = "logit"
    rate = 0.1
    l2 = 1e-4

    def reset(self) -> None:
        super().reset()
        self.w: np.ndarray | None = None
        self.g2: np.ndarray | None = None

    def scores(self, x: np.ndarray) -> np.ndarray:
        return x @ self.w if self.w is not None else np.zeros(len(x))

    def learn(self, x: np.ndarray, truth: int) -> None:
        if self.w is None or self.g2 is None:
            self.w, self.g2 = np.zeros(x.shape[1]), np.full(x.shape[1], 1e-8)
        u = x @ self.w
        p = np.exp(u - u.max())
        p /= p.sum()
        grad = p @ x - x[truth] + self.l2 * self.w
        self.g2 += grad * grad
        self.w -= self.rate * grad / np.sqrt(self.g2)


class Gbdt(_Learned):
    """``gbdt``: LightGBM LambdaRank refitted as the history grows (module docstring)."""

    name = "gbdt"

    def reset(self) -> None:
        super().reset()
        self.decisions: list[tuple[np.ndarray, int]] = []
        self.model: Any = None

    def scores(self, x: np.ndarray) -> np.ndarray:
        return self.model.predict(x) if self.model is not None else x[:, 0]

    def learn(self, x: np.ndarray, truth: int) -> None:
        self.decisions.append((x, truth))
        n = len(self.decisions)
        if n == GBDT_FIRST or (n > GBDT_FIRST and n & (n - 1) == 0 and n <= GBDT_EVERY) or (
                n > GBDT_EVERY and n % GBDT_EVERY == 0):
            self.model = fit_ranker(self.decisions)


def fit_ranker(decisions: Sequence[tuple[np.ndarray, int]]) -> Any:
    """A LightGBM LambdaRank model of the decisions (each: the offer's rows, the index done)."""
    import lightgbm

    x = np.concatenate([rows for rows, _ in decisions])
    y = np.concatenate([np.eye(len(rows))[truth] for rows, truth in decisions])
    data = lightgbm.Dataset(x, y, group=[len(rows) for rows, _ in decisions], params={"verbose": -1})
    return lightgbm.train(GBDT_PARAMS, data, num_boost_round=100)


def learned_baselines(distances: Any, opening: frozenset[str]) -> list[_Learned]:
    """``logit`` and ``gbdt``, sharing one routine predictor's evidence."""
    evidence = Evidence(distances, opening)
    return [OnlineLogit(evidence), Gbdt(evidence)]
