"""The routine predictor's lifts: binary features of the offered options, each weighed by the
user's own likelihood ratio (docs/algorithm.md, "Objects in hand", "Newly offered options" and
"After a break").

The features: an option uses an object of the user's latest actions (the objects in hand), an
option was not offered at the previous decision (newly offered: what the last action made
possible), and, right after an idle gap, an option once followed the last action before the gap
(it picks up where the user left off). For a feature, ``w_in = (h + 1) / (s + 1)`` and ``w_out = (n - h + 1) / (n - s + 1)``
over the ``n`` past steps whose offer held options with it and without it: ``h`` of them chose
one with it, ``s`` sums the share of such options in each offer. The routine predictor multiplies
its similarity level by them (``routine.RoutineOracle``, parameters ``focus``, ``focus_odds``,
``focus_level``, ``fresh``, ``resume``).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np


def held_objects(objects: Iterable[frozenset[str]]) -> frozenset[str]:
    """The objects of the given actions together."""
    return frozenset().union(*objects)


def in_focus(held: frozenset[str], objects: Iterable[Iterable[str]]) -> np.ndarray:
    """Per offered option (given by its objects): does it use one of the ``held`` objects?"""
    return np.array([not held.isdisjoint(used) for used in objects], dtype=bool)


def tells_apart(inside: np.ndarray | None) -> bool:
    """Whether a feature holds for some offered options and not for others (only then does its
    lift weigh the offer, and only then does the explanation name it)."""
    return inside is not None and bool(inside.any()) and not bool(inside.all())


def decision(ids: list[int], truth: int | None, distinct: frozenset[int] | None = None) -> tuple[list[int], int] | None:
    """A decision as the lifts count it: the interned ids offered (duplicates dropped, as
    ``offered_options`` drops them) and the index of the option done; None when it was not offered.
    ``distinct``, the set of ``ids`` when known, spares the copy of an offer without duplicates
    (the list returned is then ``ids`` itself, which the lifts only read)."""
    offered = ids if distinct is not None and len(distinct) == len(ids) else list(dict.fromkeys(ids))
    return (offered, offered.index(truth)) if truth is not None and truth in offered else None


@dataclass
class FeatureLift:
    """What the user's past steps say about choosing an option with a binary feature (in focus,
    newly offered, going on after a break)."""

    hits: float = 0.0    # steps whose option done had the feature
    share: float = 0.0   # sum over the steps of the share of the offer with it
    steps: int = 0

    def observe(self, inside: Sequence[bool], truth: int) -> None:
        """Count a step (``inside`` per offered option, ``truth`` the index of the option done),
        when its offer held options with the feature and without it."""
        n_in = sum(inside)
        if 0 < n_in < len(inside):
            self.hits += float(inside[truth])
            self.share += n_in / len(inside)
            self.steps += 1

    def lift(self, odds: bool) -> tuple[float, float]:
        """``(w_in, w_out)``, each with one pseudo-step; ``w_out`` is 1 without ``odds``."""
        inside = (self.hits + 1.0) / (self.share + 1.0)
        outside = (self.steps - self.hits + 1.0) / (self.steps - self.share + 1.0) if odds else 1.0
        return inside, outside

    def weights(self, inside: np.ndarray | None, odds: bool) -> np.ndarray | None:
        """The weight of each offered option, or None (no focus, or nothing to tell apart)."""
        if inside is None or not tells_apart(inside):
            return None
        w_in, w_out = self.lift(odds)
        return np.where(inside, w_in, w_out)

    def fork(self) -> FeatureLift:
        """A copy."""
        return FeatureLift(self.hits, self.share, self.steps)


@dataclass
class NewOffers:
    """The newly offered options: the latest decision's offer (interned ids) and the user's lift
    of the options that were not in it."""

    lift: FeatureLift = field(default_factory=FeatureLift)
    offer: frozenset[int] = frozenset()

    def which(self, ids: Iterable[int]) -> np.ndarray:
        """Per offered option (given by its interned id): was it not offered at the latest decision?"""
        return np.array([i not in self.offer for i in ids], dtype=bool)

    def observe(self, offered: list[int], truth: int) -> None:
        """Count a decision (the ids offered, duplicates dropped; the index of the option done)."""
        offer = self.offer
        self.lift.observe([i not in offer for i in offered], truth)

    def fork(self) -> NewOffers:
        """A copy (the offer is a frozenset, shared)."""
        return NewOffers(self.lift.fork(), self.offer)


def combined(a: np.ndarray | None, b: np.ndarray | None) -> np.ndarray | None:
    """The product of two lifts' weights over the same offer (None: no weights)."""
    if a is None or b is None:
        return b if a is None else a
    product: np.ndarray = a * b
    return product


def split_weights(hand: np.ndarray | None, new: np.ndarray | None,
                  new_on_top: bool) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The weights of ``Q`` and of each variant's blend (None: none): the objects in hand's on
    ``Q``, the newly offered options' on the blend (``new_on_top``) or on ``Q`` with them."""
    if new is None or new_on_top:
        return hand, new
    return combined(hand, new), None


@dataclass
class Resumption:
    """After a break: which actions ever came right after each action (idle gaps skipped), the
    latest action, and the user's lift of the options that once followed it, counted on the
    decisions right after an idle gap."""

    lift: FeatureLift = field(default_factory=FeatureLift)
    followers: dict[int, set[int]] = field(default_factory=dict)
    last: int = -1

    def which(self, ids: Iterable[int], paused: bool) -> np.ndarray | None:
        """Per offered option (interned id): did it ever follow the latest action? None unless
        the user paused right before now."""
        if not paused or self.last < 0:
            return None
        after = self.followers.get(self.last, set())
        return np.array([i in after for i in ids], dtype=bool)

    def observe(self, offered: list[int], truth: int) -> None:
        """Count a decision right after a gap (the ids offered, duplicates dropped; the index of
        the option done)."""
        if self.last >= 0:
            after = self.followers.get(self.last, set())
            self.lift.observe([i in after for i in offered], truth)

    def follow(self, action: int) -> None:
        """The next action done (after a gap or not)."""
        if self.last >= 0:
            after = self.followers.get(self.last)
            if after is None or action not in after:
                # a new set, never one changed in place: a fork shares the sets (``fork``)
                self.followers[self.last] = {action} if after is None else after | {action}
        self.last = action

    def fork(self) -> Resumption:
        """A copy (the followers' sets shared: neither side changes one in place, ``follow``)."""
        return Resumption(self.lift.fork(), dict(self.followers), self.last)
