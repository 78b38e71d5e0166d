"""What the history-only baselines see of a step, and the ranking rule they share.

A baseline reads a user's history as a sequence of tokens: the executed option, or ``<idle>`` for
an idle delimiter. Every baseline sees exactly this sequence and the candidate set, nothing else.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

from oracle.algorithm.records import Option, Step

IDLE_TOKEN = "<idle>"


def token(step: Step) -> object:
    return IDLE_TOKEN if step.idle else step.option


def order_by_score(candidates: Sequence[Option], scores: Sequence[float]) -> list[Option]:
    """Candidates by descending score; ties keep the (shuffled) order the replay gave."""
    order = sorted(range(len(candidates)), key=lambda i: -scores[i])
    return [candidates[i] for i in order]


class CountingMethod:
    """Shared history bookkeeping: the token sequence and the counts of executed (non-idle) options."""

    name = "counting"

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        self.tokens: list[object] = []
        self.unigram: Counter[object] = Counter()

    def observe(self, step: Step) -> None:
        tok = token(step)
        self.tokens.append(tok)
        if not step.idle:
            self.unigram[tok] += 1

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        raise NotImplementedError

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return order_by_score(candidates, self.scores(candidates))


__all__ = ["IDLE_TOKEN", "CountingMethod", "order_by_score", "token"]
