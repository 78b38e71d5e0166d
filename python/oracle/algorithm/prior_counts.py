"""Counting a shared prior from users' task sequences, with its privacy rules.

Each user's sequence gives cells ``(context, task)``: the task and the 0-3 tokens before it (idle
tokens included as context; a task never follows across the start of a sequence). Then:

1. clip: each user adds at most ``clip`` to any one cell (their own count, capped);
2. k users: a cell is kept only when at least ``k`` different users have it;
3. noise (``epsilon``): Laplace noise of scale ``clip / epsilon`` is added to each kept count and
   counts at or below 0 are dropped. One user changes any one count by at most ``clip`` (step 1):
   that is the sensitivity, so each released count is epsilon-differentially private
   (docs/algorithm.md, "Privacy", says what this does and does not protect).

``Population`` keeps the clipped sums and user counts of every cell, so the leave-one-user-out
evaluation builds each user's prior from the others by subtraction, never from a count that saw
the user.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from oracle.algorithm.prior import DEFAULT_CLIP, DEFAULT_K, IDLE, MAX_ORDER, Context, Prior
from oracle.errors import SettingsError

Cell = tuple[Context, str]


def cells_of(tokens: Sequence[str]) -> Counter[Cell]:
    """One sequence's cell counts: every non-idle token after each of its 0-3 previous tokens."""
    found: Counter[Cell] = Counter()
    for i, token in enumerate(tokens):
        if token == IDLE:
            continue
        for n in range(0, min(MAX_ORDER, i) + 1):
            found[(tuple(tokens[i - n:i]), token)] += 1
    return found


def check_privacy(k: int, epsilon: float | None, clip: int) -> None:
    if isinstance(k, bool) or not isinstance(k, int) or k < 1:
        raise SettingsError(f"k must be a whole number >= 1, got {k!r}")
    if epsilon is not None and not (isinstance(epsilon, (int, float)) and 0 < epsilon < float("inf")):
        raise SettingsError(f"epsilon must be a number > 0, got {epsilon!r}")
    if isinstance(clip, bool) or not isinstance(clip, int) or clip < 1:
        raise SettingsError(f"clip must be a whole number >= 1, got {clip!r}")


def released(sums: Mapping[Cell, float], users: Mapping[Cell, int], k: int, epsilon: float | None, clip: int,
             rng: np.random.Generator | None) -> dict[Context, dict[str, float]]:
    """The tables a prior may hold: cells of >= k users, with Laplace(clip / epsilon) noise."""
    kept = sorted(cell for cell, n in users.items() if n >= k)
    values = np.array([float(sums[cell]) for cell in kept])
    if epsilon is not None and len(kept):
        values = values + (rng or np.random.default_rng()).laplace(0.0, clip / epsilon, len(kept))
    tables: dict[Context, dict[str, float]] = {}
    for (context, task), value in zip(kept, values.tolist()):
        if value > 0:
            tables.setdefault(context, {})[task] = round(value, 3) if epsilon is not None else value
    return tables


class Population:
    """Every user's clipped cells and their sums (module docstring); users by any hashable name."""

    def __init__(self, clip: int = DEFAULT_CLIP) -> None:
        self.clip = clip
        self.by_user: dict[object, Counter[Cell]] = {}
        self.sums: Counter[Cell] = Counter()
        self.users: Counter[Cell] = Counter()

    def add(self, user: object, sequences: Iterable[Sequence[str]]) -> None:
        """A user's sequences (several NEEMs of one user are one user: clipped together)."""
        own: Counter[Cell] = self.by_user.pop(user, Counter())
        for cell in own:  # re-adding a user replaces their contribution
            self.sums[cell] -= own[cell]
            self.users[cell] -= 1
        raw: Counter[Cell] = Counter()
        for tokens in sequences:
            raw.update(cells_of(tokens))
        clipped = Counter({cell: min(n, self.clip) for cell, n in raw.items()})
        self.by_user[user] = clipped
        self.sums.update(clipped)
        self.users.update(clipped.keys())

    def prior(self, k: int = DEFAULT_K, epsilon: float | None = None, rng: np.random.Generator | None = None,
              fingerprint: str | None = None) -> Prior:
        check_privacy(k, epsilon, self.clip)
        return Prior(released(self.sums, self.users, k, epsilon, self.clip, rng), fingerprint, k, epsilon, self.clip,
                     len(self.by_user))

    def without(self, user: object, k: int = DEFAULT_K, epsilon: float | None = None,
                rng: np.random.Generator | None = None, fingerprint: str | None = None) -> Prior:
        """The prior of every user but ``user``: their cells subtracted before k and noise apply."""
        check_privacy(k, epsilon, self.clip)
        own = self.by_user.get(user, Counter())
        sums = {cell: self.sums[cell] - own.get(cell, 0) for cell in self.sums}
        users = {cell: self.users[cell] - (1 if cell in own else 0) for cell in self.users}
        return Prior(released(sums, users, k, epsilon, self.clip, rng), fingerprint, k, epsilon, self.clip,
                     len(self.by_user) - (1 if user in self.by_user else 0))


__all__ = ["Cell", "Population", "cells_of", "check_privacy", "released"]
