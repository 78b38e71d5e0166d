"""Similarity mass of past situations: the generalising part of the routine predictor (docs/algorithm.md).

Every past action ``a_j`` lends a candidate ``c`` the weight
``exp(-(d(c, a_j) + D_j) / tau) / rho^[time of day differs]``, where ``d`` is thesis Algorithm 2
and ``D_j`` compares the chain before ``a_j`` with the chain before now. The weights *add up*
over the history, so repetitions count (the thesis's eq. 4.12 averages them instead), and an
action never done still gets mass through the actions it resembles.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

START = -2   # before the first step: the chain has no predecessor there
_SPECIAL = 2  # the tokens below 0 a chain holds: START and IDLE (contexts.IDLE, -1)


class Rows:
    """A growing (n, width) int64 table with amortised O(1) append of one row."""

    def __init__(self, width: int) -> None:
        self._data = np.empty((64, max(width, 1)), dtype=np.int64)
        self.width = width
        self.size = 0

    def append(self, row: float | Sequence[float] | np.ndarray) -> None:
        if self.size == self._data.shape[0]:
            self._data = np.concatenate([self._data, np.empty_like(self._data)])
        if self.width == 1 and isinstance(row, int):  # one cell: a scalar store, not a slice's
            self._data[self.size, 0] = row
        else:
            self._data[self.size, : self.width] = row
        self.size += 1

    @property
    def view(self) -> np.ndarray:
        return self._data[: self.size, : self.width]

    def fork(self) -> Rows:
        """A copy of the rows (a block copy: rows are written in place, ``view``)."""
        twin = object.__new__(Rows)
        twin._data, twin.width, twin.size = self._data.copy(), self.width, self.size
        return twin


class PastSituations:
    """Each past action's predecessor tokens (``before``) and its *kind*: actions alike in their
    predecessors and part of day weigh alike in ``S``, so each kind's weight is worked out once
    and handed to its actions (``similarity_mass``'s ``kinds``)."""

    def __init__(self, depth: int) -> None:
        self.before = Rows(depth)       # per past action: predecessors 1..depth (START padded)
        self.kinds: dict[tuple[int, ...], int] = {}
        self.kind_before = Rows(depth)  # per kind: its predecessors
        self.kind_tod = Rows(1)         # per kind: its part-of-day code, -1 unknown
        self.kind_of = Rows(1)          # per past action: its kind

    def fork(self) -> PastSituations:
        """A copy (the kinds' keys are tuples, shared)."""
        twin = object.__new__(PastSituations)
        twin.before, twin.kinds, twin.kind_before = self.before.fork(), dict(self.kinds), self.kind_before.fork()
        twin.kind_tod, twin.kind_of = self.kind_tod.fork(), self.kind_of.fork()
        return twin

    def add(self, before: tuple[int, ...], tod: int) -> None:
        """The next past action: its predecessor tokens and part-of-day code."""
        self.before.append(before)
        key = (*before, tod)
        kind = self.kinds.get(key)
        if kind is None:
            kind = self.kinds[key] = len(self.kinds)
            self.kind_before.append(before)
            self.kind_tod.append(tod)
        self.kind_of.append(kind)

    def differs(self, now: int) -> np.ndarray:
        """Per kind: does its part of day differ from ``now``'s (unknown on either side: no)?"""
        then = self.kind_tod.view[:, 0]
        return (then >= 0) & (then != now) if now >= 0 else np.zeros(then.size, dtype=bool)


def context_distance(table: np.ndarray, now: tuple[int, ...], then: np.ndarray, penalty: float,
                     decay: float) -> np.ndarray:
    """``D_j = sum_n decay^(n-1) * delta(now_n, then_jn)`` over the ``len(now)`` predecessors.

    ``now[n-1]`` and ``then[:, n-1]`` are the n-th predecessor tokens (option id, idle or START);
    ``delta`` is Algorithm 2 between two options, 0 between equal special tokens and ``penalty``
    otherwise (a chain that started, or went idle, where the other did not).
    """
    total = np.zeros(then.shape[0])
    # one look-up per predecessor: the row of ``delta`` for every token, the two special tokens
    # (START, IDLE) first, then the options, indexed by the token + 2
    shifted = then + _SPECIAL
    lookup = np.empty(table.shape[1] + _SPECIAL)
    for n, token in enumerate(now):
        lookup[:_SPECIAL] = penalty
        if token >= 0:
            lookup[_SPECIAL:] = table[token]
        else:
            lookup[_SPECIAL:] = penalty
            lookup[token + _SPECIAL] = 0.0
        total += decay ** n * lookup[shifted[:, n]]
    return total


def similarity_mass(candidate_distances: np.ndarray, executed: np.ndarray, context: np.ndarray,
                    tod_differs: np.ndarray, tau: float, tod_penalty: float,
                    kinds: np.ndarray | None = None, decayed: np.ndarray | None = None) -> np.ndarray:
    """``S(c) = sum_j exp(-(d(c, a_j) + D_j) / tau) * rho^-[tod_j differs]`` for every candidate.

    ``candidate_distances`` is (candidates x options) Algorithm 2; ``executed`` the option id of
    every past action, ``context`` its ``D_j`` and ``tod_differs`` its part-of-day test; or, with
    ``kinds`` (each past action's kind), both given per kind: each kind's weight is worked out
    once and handed to its actions, the same number each would get alone, summed in the same
    order. ``decayed``, when given, is ``exp(-candidate_distances / tau)`` already worked out.
    Grouping the past actions by option first keeps it O(history + candidates x options).
    """
    n_options = candidate_distances.shape[1]
    if executed.size == 0 or n_options == 0:
        return np.zeros(candidate_distances.shape[0])
    log_weight = -context / tau - np.where(tod_differs, math.log(tod_penalty) if tod_penalty > 0 else 0.0, 0.0)
    shift = log_weight.max()  # the common factor exp(shift) cancels when S is normalised
    weights = np.exp(log_weight - shift)
    per_option = np.bincount(executed, weights=weights if kinds is None else weights[kinds], minlength=n_options)
    return (np.exp(-candidate_distances / tau) if decayed is None else decayed) @ per_option


def normalised(mass: np.ndarray) -> np.ndarray:
    """``Q(c) = S(c) / sum S``; uniform when nothing is known."""
    total = float(mass.sum())
    if not mass.size:
        return mass
    if total <= 0 or not math.isfinite(total):
        return np.full(mass.size, 1.0 / mass.size)
    return mass / total
