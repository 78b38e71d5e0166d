"""Baselines that rank the same candidate sets as the oracle, from the same history.

- ``chance``: the expected hit rate of a random order, computed exactly (no sampling).
- ``most_frequent``: candidates by how often the user executed that exact action before.
- ``bigram``: candidates by count after the previous action, ties broken by overall frequency.
- ``ngram``: PPM-C blending of contexts up to order 3 (without exclusion), backing off to the
  user's action frequencies and finally to uniform; ``ppmc1`` ... ``ppmc5`` the same at other orders.
- ``ppmx3``, ``ppmx5``: PPM-C with full exclusion (Cleary & Witten 1984, Moffat 1990).
- ``kn3``, ``kn5``: interpolated modified Kneser-Ney (discounts estimated from count-of-counts);
  ``wb3``, ``wb5``: interpolated Witten-Bell n-grams (smoothing.py).
- ``lz78``, ``alz``: the LZ78 predictor and Active LeZi (lempel_ziv.py).

Formulas and references: docs/evaluation.md. Each method ranks by a score and breaks ties by the
candidate order it was given; the replay shuffles every candidate set with a seeded generator, so
ties never leak the answer.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Callable, Sequence
from functools import partial

from oracle.algorithm.records import Option, Step
from oracle.evaluation.lempel_ziv import LZ78, ActiveLeZi
from oracle.evaluation.smoothing import MODIFIED, KneserNey, WittenBell
from oracle.evaluation.tokens import IDLE_TOKEN, CountingMethod, token


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


class ContextTables(CountingMethod):
    """Counts of what followed each context of length 1..order (idle tokens included)."""

    def __init__(self, order: int = 3, name: str | None = None) -> None:
        self.order = order
        if name is not None:
            self.name = name
        super().__init__()

    def reset(self) -> None:
        super().reset()
        self.tables: list[dict[tuple[object, ...], Counter[object]]] = [defaultdict(Counter) for _ in range(self.order + 1)]

    def observe(self, step: Step) -> None:
        tok = token(step)
        for n in range(1, self.order + 1):
            if len(self.tokens) >= n:
                self.tables[n][tuple(self.tokens[-n:])][tok] += 1
        super().observe(step)

    def contexts(self) -> list[Counter[object]]:
        """Follower counts of the current contexts that were seen before, shortest first."""
        found = []
        for n in range(1, min(self.order, len(self.tokens)) + 1):
            counts = self.tables[n].get(tuple(self.tokens[-n:]))
            if counts:
                found.append(counts)
        return found


class NGram(ContextTables):
    """PPM-C without exclusion: P(c) = (n(ctx,c) + d(ctx) * P_lower(c)) / (n(ctx) + d(ctx))."""

    name = "ngram"

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        if not candidates:
            return []
        total = sum(self.unigram.values())
        distinct = len(self.unigram)
        uniform = 1.0 / len(candidates)
        probs = [
            (self.unigram[c] + distinct * uniform) / (total + distinct) if total else uniform for c in candidates
        ]
        for counts in self.contexts():
            seen = sum(counts.values())
            kinds = len(counts)
            probs = [(counts[c] + kinds * p) / (seen + kinds) for c, p in zip(candidates, probs)]
        return probs


class PPMExclusion(ContextTables):
    """PPM-C with full exclusion: from the longest seen context down, a symbol is coded at the first
    order that saw it, and the symbols seen at higher orders are left out of every lower order's counts."""

    name = "ppmx"

    def scores(self, candidates: Sequence[Option]) -> list[float]:
        probs = {c: 0.0 for c in candidates}
        unassigned = set(probs)
        excluded: set[object] = set()
        escape = 1.0
        for counts in [*reversed(self.contexts()), self.unigram]:
            kept = {s: n for s, n in counts.items() if s not in excluded}
            seen = sum(kept.values())
            if not seen:
                continue
            kinds = len(kept)
            for symbol, n in kept.items():
                if symbol in unassigned:
                    probs[symbol] = escape * n / (seen + kinds)
                    unassigned.discard(symbol)
            escape *= kinds / (seen + kinds)
            excluded.update(kept)
        # order -1: what is left of the mass, spread evenly over the candidates no order has seen
        for symbol in unassigned:
            probs[symbol] = escape / len(unassigned)
        return [probs[c] for c in candidates]


def chance_hit(k: int, n_candidates: int, truth_offered: bool) -> float:
    """Probability that a uniformly random order puts the truth in the top k."""
    if not truth_offered or n_candidates == 0:
        return 0.0
    return min(k, n_candidates) / n_candidates


#: Every baseline by name; each value builds a fresh method. ``ngram`` keeps its historic name (PPM-C order 3).
BASELINES: dict[str, Callable[[], CountingMethod | LZ78 | ActiveLeZi | KneserNey | WittenBell]] = {
    "most_frequent": MostFrequent,
    "bigram": Bigram,
    "ngram": NGram,
    **{f"ppmc{n}": partial(NGram, n, f"ppmc{n}") for n in (1, 2, 4, 5)},
    **{f"ppmx{n}": partial(PPMExclusion, n, f"ppmx{n}") for n in (3, 5)},
    **{f"kn{n}": partial(KneserNey, n, MODIFIED, name=f"kn{n}") for n in (3, 5)},
    **{f"wb{n}": partial(WittenBell, n, name=f"wb{n}") for n in (3, 5)},
    "lz78": LZ78,
    "alz": ActiveLeZi,
}

__all__ = ["BASELINES", "IDLE_TOKEN", "Bigram", "MostFrequent", "NGram", "PPMExclusion", "chance_hit", "token"]
