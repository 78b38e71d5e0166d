"""Interpolated Kneser-Ney and Witten-Bell n-gram baselines, updated online.

They compute what ``nltk.lm.KneserNeyInterpolated`` and ``nltk.lm.WittenBellInterpolated``
(nltk 3.9+) return for a model fitted on all n-grams of the history so far (checked in
tests/evaluation/test_smoothing.py; Kneser-Ney differs from nltk only where nltk's weights do not
sum to one, see ``KneserNey.probabilities``). nltk itself refits nothing incrementally and recounts the
continuation counts of a context on every query by scanning every higher-order n-gram, which is far
too slow for a replay of tens of thousands of steps (``experiments/nltk-speed.py``); these classes keep
the same counts in tables updated once per observed step. Formulas: docs/evaluation.md.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Sequence

from oracle.algorithm.records import Option, Step
from oracle.evaluation.tokens import order_by_score, token

#: Kneser & Ney (1995) and Chen & Goodman (1999) use one absolute discount near 0.75; nltk's default 0.1
#: is a toy value (it keeps almost all mass on the observed counts).
KN_DISCOUNT = 0.75
#: ``KneserNey(discount=MODIFIED)``: three discounts per order estimated from its count-of-counts
#: (Chen & Goodman 1999, modified Kneser-Ney), as the ``kn3`` and ``kn5`` baselines use.
MODIFIED = "modified"


def modified_discounts(n1: int, n2: int, n3: int, n4: int) -> tuple[float, float, float]:
    """Chen & Goodman's discounts D1, D2, D3+ of an order whose counts hold ``n1`` .. ``n4``
    n-grams seen exactly 1 .. 4 times: ``Y = n1 / (n1 + 2 n2)``, ``D_k = k - (k + 1) Y n_(k+1) / n_k``,
    each kept in [0, k]; ``KN_DISCOUNT`` for each while its counts are missing (short histories)."""
    if not n1 or not n2:
        return (KN_DISCOUNT, KN_DISCOUNT, KN_DISCOUNT)
    y = n1 / (n1 + 2 * n2)
    d1 = min(max(1 - 2 * y * n2 / n1, 0.0), 1.0)
    d2 = min(max(2 - 3 * y * n3 / n2, 0.0), 2.0) if n3 else KN_DISCOUNT
    d3 = min(max(3 - 4 * y * n4 / n3, 0.0), 3.0) if n3 and n4 else d2
    return (d1, d2, d3)


class _NgramCounts:
    """Follower counts of every context of length 0..order-1 over the token sequence (idle included)."""

    name = "ngram_counts"

    def __init__(self, order: int = 3, name: str | None = None) -> None:
        if order < 1:
            raise ValueError(f"n-gram order must be at least 1, got {order}")
        self.order = order
        if name is not None:
            self.name = name
        self.reset()

    def reset(self) -> None:
        self.tokens: list[object] = []
        # follow[n][ctx] counts what came after the length-n context ctx; totals[n][ctx] is their sum
        self.follow: list[dict[tuple[object, ...], Counter[object]]] = [defaultdict(Counter) for _ in range(self.order)]
        self.totals: list[Counter[tuple[object, ...]]] = [Counter() for _ in range(self.order)]

    def observe(self, step: Step) -> None:
        word = token(step)
        for n in range(min(self.order - 1, len(self.tokens)) + 1):
            context = tuple(self.tokens[-n:]) if n else ()
            followers = self.follow[n][context]
            if followers[word] == 0:
                self._new_type(n, context, word)
            followers[word] += 1
            self.totals[n][context] += 1
        self.tokens.append(word)

    def _new_type(self, n: int, context: tuple[object, ...], word: object) -> None:
        """Hook: the n-gram ``context + (word,)`` was seen for the first time."""

    def levels(self) -> list[tuple[int, tuple[object, ...], Counter[object]]]:
        """(length, context, followers) for the current contexts of length 1..order-1, shortest first."""
        found = []
        for n in range(1, min(self.order - 1, len(self.tokens)) + 1):
            context = tuple(self.tokens[-n:])
            found.append((n, context, self.follow[n].get(context) or Counter()))
        return found

    def probability(self, word: object) -> float:
        return self.probabilities([word])[0]

    def probabilities(self, words: Sequence[object]) -> list[float]:
        raise NotImplementedError

    def rank(self, candidates: Sequence[Option], time_of_day: str | None = None, at: float | None = None) -> list[Option]:
        return order_by_score(candidates, self.probabilities(candidates))


class KneserNey(_NgramCounts):
    """Interpolated Kneser-Ney: the highest order discounts raw counts, lower orders continuation counts.

    P(w | c) = max(N(c w) - D, 0) / N(c .) + D * T(c) / N(c .) * P(w | c'),  c' = c without its oldest token,
    where N are raw counts at the highest order and continuation counts N1+(. c w) below it, T(c) the
    number of distinct w with N(c w) > 0, and the base case is P(w) = N1+(. w) / N1+(. .).
    With ``discount=MODIFIED`` D depends on the count (D1, D2, D3+, ``modified_discounts`` of the
    order's count-of-counts, kept as the counts grow) and ``D T(c)`` becomes
    ``D1 N1(c .) + D2 N2(c .) + D3+ N3+(c .)`` (Chen & Goodman 1999).
    """

    name = "kn"

    def __init__(self, order: int = 3, discount: float | str = KN_DISCOUNT, name: str | None = None) -> None:
        if discount != MODIFIED and (isinstance(discount, str) or not 0 <= discount <= 1):
            raise ValueError(f"Kneser-Ney discount must be in [0, 1] or {MODIFIED!r}, got {discount}")
        self.discount = discount
        super().__init__(order, name)

    def reset(self) -> None:
        super().reset()
        # continuation[n][ctx][w]: how many distinct tokens x preceded ctx + w; cont_totals: their sum over w
        self.continuation: list[dict[tuple[object, ...], Counter[object]]] = [defaultdict(Counter) for _ in range(self.order)]
        self.cont_totals: list[Counter[tuple[object, ...]]] = [Counter() for _ in range(self.order)]
        # per order: how many of the counts the order discounts hold each value 1..4 (modified discounts)
        self.count_of_counts: list[Counter[int]] = [Counter() for _ in range(self.order)]

    def observe(self, step: Step) -> None:
        top = self.order - 1
        if len(self.tokens) >= top:  # the highest order discounts raw counts: track their count-of-counts
            context = tuple(self.tokens[-top:]) if top else ()
            self._recount(top, self.follow[top].get(context, Counter())[token(step)])
        super().observe(step)

    def _recount(self, n: int, old: int) -> None:
        if old:
            self.count_of_counts[n][old] -= 1
        self.count_of_counts[n][old + 1] += 1

    def _new_type(self, n: int, context: tuple[object, ...], word: object) -> None:
        if n >= 1:
            if n - 1 < self.order - 1:
                self._recount(n - 1, self.continuation[n - 1][context[1:]][word])
            self.continuation[n - 1][context[1:]][word] += 1
            self.cont_totals[n - 1][context[1:]] += 1

    def discounts(self, n: int) -> tuple[float, float, float]:
        """The discounts of counts 1, 2 and 3+ at order ``n`` (context length)."""
        if self.discount == MODIFIED:
            c = self.count_of_counts[n]
            return modified_discounts(c[1], c[2], c[3], c[4])
        d = float(self.discount)
        return (d, d, d)

    def probabilities(self, words: Sequence[object]) -> list[float]:
        base = self.continuation[0].get(()) or Counter()
        base_total = self.cont_totals[0][()]
        # nltk divides by zero here (no bigram yet); this level then contributes nothing
        probs = [base[w] / base_total if base_total else 0.0 for w in words]
        for n, context, followers in self.levels():
            if not followers:
                continue  # unseen context: alpha 0, gamma 1
            if n + 1 == self.order:
                counts, total = followers, self.totals[n][context]
            else:
                counts, total = self.continuation[n].get(context) or Counter(), self.cont_totals[n][context]
            if not total:
                continue  # the context was only ever seen at the very start: nltk divides by zero
            # the interpolation weight counts the distinct words the level's own counts saw after the
            # context; nltk counts raw followers here, which breaks normalisation when the context's
            # only left-less occurrence (the history's first tokens) had a follower seen nowhere else
            ds = self.discounts(n)
            if ds[0] == ds[1] == ds[2]:
                d = ds[0]
                gamma = d * len(counts) / total
                probs = [max(counts[w] - d, 0.0) / total + gamma * p for w, p in zip(words, probs)]
                continue
            gamma = sum(ds[min(c, 3) - 1] for c in counts.values() if c > 0) / total
            probs = [(counts[w] - ds[min(counts[w], 3) - 1] if counts[w] > 0 else 0.0) / total + gamma * p
                     for w, p in zip(words, probs)]
        return probs


class WittenBell(_NgramCounts):
    """Interpolated Witten-Bell: P(w | c) = (1 - g(c)) * N(c w) / N(c) + g(c) * P(w | c'),
    g(c) = N1+(c .) / (N1+(c .) + N(c)), with the maximum-likelihood unigram at the bottom."""

    name = "wb"

    def probabilities(self, words: Sequence[object]) -> list[float]:
        unigrams = self.follow[0].get(()) or Counter()
        total = self.totals[0][()]
        probs = [unigrams[w] / total if total else 0.0 for w in words]
        for n, context, followers in self.levels():
            if not followers:
                continue
            seen = self.totals[n][context]
            gamma = len(followers) / (len(followers) + seen)
            probs = [(1 - gamma) * followers[w] / seen + gamma * p for w, p in zip(words, probs)]
        return probs


__all__ = ["KN_DISCOUNT", "MODIFIED", "KneserNey", "WittenBell", "modified_discounts"]
