"""Where an option followed a context in the user's history: the past situations the routine
predictor's explanation names (``RoutineTask.situations``; docs/algorithm.md, "Explanation")."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from oracle.algorithm.contexts import UNKNOWN


def followed_at(executed: np.ndarray, positions: np.ndarray, before: np.ndarray, tokens: Sequence[int],
                index: np.ndarray, option_id: int, context: tuple[int, ...], n: int) -> list[int]:
    """History positions where ``option_id`` followed ``context`` (its last ``n`` tokens; all its
    uses when n is 0). Per past action: ``executed`` its option id, ``positions`` its history
    position, ``before`` its kept predecessor tokens (nearest first), ``index`` its place in the
    stream's ``tokens``, which answer for a context longer than the kept predecessors."""
    if option_id == UNKNOWN or n < 0:
        return []
    hit = executed == option_id
    for k in range(min(n, before.shape[1])):
        hit &= before[:, k] == context[-1 - k]
    if n > before.shape[1]:  # longer than the kept predecessors: check the stream itself
        stream = np.asarray(tokens, dtype=np.int64)
        for k in range(before.shape[1], n):
            at = index - 1 - k
            hit &= (at >= 0) & (stream[np.maximum(at, 0)] == context[-1 - k])
    found: list[int] = positions[hit].tolist()
    return found
