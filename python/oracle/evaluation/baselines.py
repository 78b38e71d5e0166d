"""Baselines that rank the same candidate sets as the oracle, from the same history.

- ``chance``: the expected hit rate of a random order, computed exactly (no sampling).
- ``most_frequent``: candidates by how often the user executed that exact action before.
- ``bigram``: candidates by count after the previous action, ties broken by overall frequency.
- ``ngram``: PPM-C blending of contexts up to order 3 (without exclusion), backing off to the
  user's action frequencies and finally to uniform; documented in docs/evaluation.md.

Each method ranks by a score and breaks ties by the candidate order it was given; the replay
shuffles every candidate set with a seeded generator, so ties never leak the answer.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Sequence

from oracle.algorithm.records import Option, Step

IDLE_TOKEN = "<idle>"


def token(step: Step) -> object:
    return IDLE_TOKEN if step.idle else step.option


class CountingMethod:
    """Shared history bookkeeping for the count-based baselines."""

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

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None) -> list[Option]:
        scores = self.scores(candidates)
        order = sorted(range(len(candidates)), key=lambda i: -scores[i])
        return [candidates[i] for i in order]


class MostFrequent(CountingMethod):
    name = "most_frequent"

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        return [float(self.unigram[c]) for c in candidates]


class Bigram(CountingMethod):
    name = "bigram"

    def reset(self) -> None:
        super().reset()
        self.pairs: dict[object, Counter[object]] = defaultdict(Counter)

    def observe(self, step: Step) -> None:
        if self.tokens:
            self.pairs[self.tokens[-1]][token(step)] += 1
        super().observe(step)

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        following = self.pairs.get(self.tokens[-1], Counter()) if self.tokens else Counter()
        total = sum(self.unigram.values()) or 1
        # counts after the previous action dominate; overall frequency only breaks their ties
        return [following[c] + self.unigram[c] / (total + 1) for c in candidates]


class NGram(CountingMethod):
    """PPM-C without exclusion: P(c) = (n(ctx,c) + esc(ctx) * P_lower(c)) / (n(ctx) + d(ctx))."""

    name = "ngram"

    def __init__(self, order: int = 3) -> None:
        self.order = order
        super().__init__()

    def reset(self) -> None:
        super().reset()
        self.tables: list[dict[tuple, Counter[object]]] = [defaultdict(Counter) for _ in range(self.order + 1)]

    def observe(self, step: Step) -> None:
        tok = token(step)
        for n in range(1, self.order + 1):
            if len(self.tokens) >= n:
                self.tables[n][tuple(self.tokens[-n:])][tok] += 1
        super().observe(step)

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        if not candidates:
            return []
        total = sum(self.unigram.values())
        distinct = len(self.unigram)
        uniform = 1.0 / len(candidates)
        probs = [
            (self.unigram[c] + distinct * uniform) / (total + distinct) if total else uniform for c in candidates
        ]
        for n in range(1, self.order + 1):
            if len(self.tokens) < n:
                break
            counts = self.tables[n].get(tuple(self.tokens[-n:]))
            if not counts:
                continue
            seen = sum(counts.values())
            kinds = len(counts)
            probs = [(counts[c] + kinds * p) / (seen + kinds) for c, p in zip(candidates, probs)]
        return probs


def chance_hit(k: int, n_candidates: int, truth_offered: bool) -> float:
    """Probability that a uniformly random order puts the truth in the top k."""
    if not truth_offered or n_candidates == 0:
        return 0.0
    return min(k, n_candidates) / n_candidates


BASELINES = {"most_frequent": MostFrequent, "bigram": Bigram, "ngram": NGram}
