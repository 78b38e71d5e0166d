"""The routine predictor's clock: how long ago the user last did each offered option, weighed by
the user's own odds, and the gate that lets those odds rank only for a user whose own history
shows them ahead on Top-1 (docs/algorithm.md, "How long ago").

Each offered option falls into one bucket of the time since the user last did it (``edges`` in
seconds; one more bucket past the last edge and one for "never done"). Bucket ``b`` weighs
``(h_b + 1) / (s_b + 1)``: ``h_b`` counts the past decisions whose option done was in ``b``,
``s_b`` sums the share of each decision's offer in ``b``; only decisions whose offer spans two
buckets or more count. The gate compares, on every scored step, the first option of the ranking
with and without the weights, and opens once ``lead > z sqrt(spread)`` (the switch margin of the
self-tuning, on Top-1 hits).
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

#: The bucket edges of the default, in seconds: 1 min, 10 min, 1 h, 4 h, 12 h, 36 h.
EDGES = (60.0, 600.0, 3600.0, 4 * 3600.0, 12 * 3600.0, 36 * 3600.0)


@dataclass
class SinceDone:
    """When each option was last done, and the user's odds per bucket of the time since."""

    edges: tuple[float, ...]
    last: dict[int, float] = field(default_factory=dict)   # interned option id -> latest begin
    hits: list[float] = field(default_factory=list)
    share: list[float] = field(default_factory=list)

    def __post_init__(self) -> None:
        if not self.hits:
            self.hits = [0.0] * (len(self.edges) + 2)
            self.share = [0.0] * (len(self.edges) + 2)

    def buckets(self, ids: Sequence[int], now: float | None) -> list[int] | None:
        """The bucket of each offered option (interned ids) at ``now``; None without a clock or
        when the offer does not span two buckets (then nothing is weighed or counted)."""
        if now is None or not self.edges:
            return None
        never, last, edges = len(self.edges) + 1, self.last, self.edges
        out = [never if (t := last.get(i)) is None else bisect_right(edges, now - t) for i in ids]
        return out if len(set(out)) > 1 else None

    def ages(self, ids: Sequence[int], now: float | None, weighed: bool) -> list[float | None]:
        """Seconds since each offered option was last done, where the clock ``weighed`` the
        ranking (None for the others, and for an option never done)."""
        if not weighed or now is None:
            return [None] * len(ids)
        return [None if (t := self.last.get(i)) is None else now - t for i in ids]

    def weights(self, buckets: Sequence[int] | None) -> np.ndarray | None:
        """Each offered option's weight (None: nothing to weigh)."""
        if buckets is None:
            return None
        hits, share = self.hits, self.share
        return np.array([(hits[b] + 1.0) / (share[b] + 1.0) for b in buckets])

    def observe(self, buckets: Sequence[int] | None, truth: int) -> None:
        """Count a decision (the buckets of its offer, the index of the option done)."""
        if buckets is None:
            return
        self.hits[buckets[truth]] += 1.0
        each = 1.0 / len(buckets)
        for b in buckets:
            self.share[b] += each

    def done(self, option: int, when: float | None) -> None:
        """The user did ``option`` at ``when`` (unix seconds; None: no clock)."""
        if when is not None:
            self.last[option] = when

    def fork(self) -> SinceDone:
        """A copy."""
        return SinceDone(self.edges, dict(self.last), list(self.hits), list(self.share))


@dataclass
class ClockGate:
    """Top-1 with the clock's odds against without, on the scored steps; with ``kept`` the terms
    stay with their history positions so that ``keep_from`` re-cuts them as the variants' scores
    are (``selftune.VariantWeights``)."""

    lead: float = 0.0     # sum of (hit with - hit without)
    spread: float = 0.0   # sum of its squares
    kept: list[tuple[int, float]] | None = None

    def open(self, margin: float) -> bool:
        return bool(self.lead > margin * math.sqrt(self.spread))

    def update(self, plain: np.ndarray, lifted: np.ndarray, truth: int, position: int) -> None:
        """Score a step: the first option of each distribution (ties: the earlier offered)."""
        d = float(int(np.argmax(lifted)) == truth) - float(int(np.argmax(plain)) == truth)
        self.lead += d
        self.spread += d * d
        if self.kept is not None:
            self.kept.append((position, d))

    def fork(self) -> ClockGate:
        """A copy (the kept terms are tuples, shared)."""
        return ClockGate(self.lead, self.spread, None if self.kept is None else list(self.kept))

    def keep_from(self, position: int) -> None:
        """Forget the steps scored before history ``position`` (the sums of the later ones, added
        in the same order)."""
        if self.kept is None:
            return
        later = [(at, d) for at, d in self.kept if at >= position]
        if len(later) == len(self.kept):
            return
        self.lead = self.spread = 0.0
        for _, d in later:
            self.lead += d
            self.spread += d * d
        self.kept = later


def reweighted(p: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """``p`` reweighted and normalised (``p`` as it is when the weights leave nothing)."""
    out: np.ndarray = p * weights
    total = float(out.sum())
    return out / total if total > 0 else p
