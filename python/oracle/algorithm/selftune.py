"""Self-tuning on the user's own history (thesis 4.5) without a tuning split: prequential weights.

Before a step joins the history, every variant has already predicted it; its log-probability of
what the user did is added to that variant's score. "mixture" weighs the variants by
``softmax(score)`` (the Bayesian posterior of the variants under a uniform prior). "leader" keeps a
second score, the variant's hits as the user's tablet would show them (truth at rank 1, in the top
3, in the top 5, each counting 1/3), and puts all weight on the best so far (follow the leader;
ties go to the earlier variant) among the variants that lead the first one by a margin of
standard errors. "fixed" always uses the first variant.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

#: Floor of a probability before its log: a variant that gave the truth 0 is penalised, not killed.
FLOOR = 1e-12


class VariantWeights:
    """Cumulative log-likelihood of each variant on the steps seen so far.

    With ``keep`` the terms each scored step added are kept with its history position, so that
    ``keep_from`` can drop the oldest ones and give exactly the sums a count of only the later
    steps would have (the fitted-model cache extends a fit this way, oracle.fitcache).
    """

    def __init__(self, n_variants: int, keep: bool = False) -> None:
        self.scores = np.zeros(n_variants)
        self.hits = np.zeros(n_variants)
        self.spread = np.zeros(n_variants)   # sum over steps of (hit_v - hit_0)^2
        self.steps = 0
        self.kept: list[tuple[int, np.ndarray]] | None = [] if keep else None  # (position, 3 x n terms)

    def update(self, probabilities: Sequence[np.ndarray], truth: int, position: int = -1) -> None:
        """Score every variant's distribution over the offered options on the option done
        (``position``: the step's place in the history, for ``keep_from``)."""
        terms = np.zeros((3, self.scores.size))
        stacked = np.asarray(probabilities)
        chosen = stacked[:, truth]
        n = len(chosen)
        terms[0, :n] = [math.log(max(p, FLOOR)) for p in chosen.tolist()]
        # rank as ``rank`` orders: by probability, ties by the order offered
        better = np.count_nonzero(stacked > chosen[:, None], axis=1) + np.count_nonzero(
            stacked[:, :truth] == chosen[:, None], axis=1)
        terms[1, :n] = ((better < 1).astype(float) + (better < 3) + (better < 5)) / 3.0
        terms[2, :n] = (terms[1, :n] - terms[1, 0]) ** 2
        self._add(terms)
        if self.kept is not None:
            self.kept.append((position, terms))

    def fork(self) -> VariantWeights:
        """A copy (the kept terms are never changed once kept: shared)."""
        twin = object.__new__(VariantWeights)
        twin.scores, twin.hits, twin.spread = self.scores.copy(), self.hits.copy(), self.spread.copy()
        twin.steps, twin.kept = self.steps, None if self.kept is None else list(self.kept)
        return twin

    def _add(self, terms: np.ndarray) -> None:
        self.scores += terms[0]
        self.hits += terms[1]
        self.spread += terms[2]
        self.steps += 1

    def keep_from(self, position: int) -> None:
        """Forget the steps scored before history ``position``: the sums become those of the
        later steps alone, added in the same order (bit for bit what scoring only them gives)."""
        if self.kept is None:
            raise ValueError("the scored steps were not kept")
        later = [(at, terms) for at, terms in self.kept if at >= position]
        if len(later) == len(self.kept):
            return
        self.scores[:] = 0.0
        self.hits[:] = 0.0
        self.spread[:] = 0.0
        self.steps = 0
        for _, terms in later:
            self._add(terms)
        self.kept = later

    def weights(self, tuning: str, margin: float = 0.0) -> np.ndarray:
        """All weight on one variant ("leader", "fixed") or the posterior ("mixture"). With
        ``margin`` z > 0 the leader is chosen among the variants whose lead over the first one is
        z standard errors or more, ``hits_v - hits_0 > z sqrt(sum_t (hit_vt - hit_0t)^2)`` (the
        first is always eligible): a variant must beat the default clearly to replace it."""
        n = self.scores.size
        out = np.zeros(n)
        if tuning == "fixed" or self.steps == 0:
            out[0] = 1.0
        elif tuning == "leader":
            chosen = switch_to(self.hits[1:] - self.hits[0], self.spread[1:], margin)
            out[0 if chosen is None else chosen + 1] = 1.0
        else:
            shifted = self.scores - self.scores.max()
            out = np.exp(shifted)
            out /= out.sum()
        return out

    def describe(self) -> list[float]:
        """Mean log2-likelihood per step of each variant (for reports)."""
        return [s / math.log(2) / max(1, self.steps) for s in self.scores.tolist()]


def switch_to(leads: np.ndarray, spreads: np.ndarray, margin: float) -> int | None:
    """The switch rule: of the challengers whose summed lead over the incumbent (``leads``, with
    ``spreads`` the sums of the squared per-step differences) is more than ``margin`` >= 0
    standard errors, the index of the largest lead (ties: the earlier); None: keep the incumbent."""
    passed = leads > margin * np.sqrt(spreads)
    return int(np.argmax(np.where(passed, leads, -np.inf))) if passed.any() else None


def mixed_distribution(weights: np.ndarray, probabilities: Sequence[np.ndarray]) -> np.ndarray:
    """The variants' distributions over the offer weighed by ``weights`` (those of weight 0 left
    out) and normalised: uniform when nothing is left."""
    mixed = np.zeros(len(probabilities[0]))
    for weight, p in zip(weights, probabilities):
        if weight > 0:
            mixed += weight * p
    total = float(mixed.sum())
    return mixed / total if total > 0 else np.full(len(mixed), 1.0 / len(mixed))
