"""Exact-context counts over one token stream and their PPM-C blend (docs/algorithm.md, "Routine predictor").

A token is an option id (>= 0) or ``IDLE``. ``ContextCounts`` counts, for every context of
1..``max_order`` tokens, which token followed it, and how often each action was done at all
(order 0). ``blend`` turns them into a distribution over candidates by PPM-C without exclusion,
starting from a given base distribution instead of the uniform one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

IDLE = -1      # the odb:IdleTask token
UNKNOWN = -3   # a candidate the history never saw (never counted)


@dataclass(frozen=True)
class Blend:
    """The blended distribution and, per candidate, its longest exact context with a count."""

    probabilities: np.ndarray
    order: np.ndarray      # longest n >= 1 whose context was followed by the candidate; 0: only done before; -1: never
    count: np.ndarray      # how often, at that order


class ContextCounts:
    """Follower counts of every context of 1..max_order tokens, kept incrementally."""

    def __init__(self, max_order: int) -> None:
        self.max_order = max_order
        self.tokens: list[int] = []
        self.tables: list[dict[tuple[int, ...], dict[int, int]]] = [{} for _ in range(max_order + 1)]
        self.totals: list[dict[tuple[int, ...], int]] = [{} for _ in range(max_order + 1)]

    def add(self, token: int) -> None:
        history = self.tokens
        for n in range(0 if token != IDLE else 1, self.max_order + 1):  # idle is no action: no order-0 count
            if len(history) < n:
                break
            context = tuple(history[len(history) - n:]) if n else ()
            followers = self.tables[n].setdefault(context, {})
            followers[token] = followers.get(token, 0) + 1
            self.totals[n][context] = self.totals[n].get(context, 0) + 1
        history.append(token)

    def context(self, n: int) -> tuple[int, ...] | None:
        """The current context of order n, or None when the stream is shorter."""
        if n == 0:
            return ()
        return tuple(self.tokens[-n:]) if len(self.tokens) >= n else None

    def blend(self, candidates: Sequence[int], base: np.ndarray, max_order: int, min_order: int = 0) -> Blend:
        """``P_n(c) = (n(ctx_n, c) + u_n P_{n-1}(c)) / (N(ctx_n) + u_n)`` from ``P_{-1} = base`` up to
        ``max_order``; an unseen context leaves the distribution as it is (PPM-C, no exclusion)."""
        probs = base.astype(np.float64, copy=True)
        order = np.full(len(candidates), -1, dtype=np.int64)
        count = np.zeros(len(candidates), dtype=np.int64)
        for n in range(min_order, min(max_order, self.max_order) + 1):
            context = self.context(n)
            if context is None:
                break
            followers = self.tables[n].get(context)
            if not followers:
                continue
            seen = np.array([followers.get(c, 0) for c in candidates], dtype=np.float64)
            kinds = len(followers)
            probs = (seen + kinds * probs) / (self.totals[n][context] + kinds)
            hit = seen > 0
            order[hit] = n
            count[hit] = seen[hit].astype(np.int64)
        return Blend(probs, order, count)
