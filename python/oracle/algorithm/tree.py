"""The forward preference tree (thesis 4.4 "Looking into the Future", Fig. 4.6, eq. 4.13, Fig. 4.7).

For one candidate ``s_o`` the similar historic situations ``H(s_o)`` and their distances are the
roots; the successors ``n(s_h)`` are grouped by executed option, each group valued by eq. 4.12 over
the distances of the roots it came from, down to ``event horizon forward`` levels. Branches using
objects not present now are pruned, except below tasks under soma:Opening. Both oracles share
this module, so their trees are identical whenever their ``H(s_o)`` and distances are.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from oracle.algorithm.records import Option, TreeNode


def occurrence_value(total: float, count: int, factor: float) -> float:
    """Eq. 4.12: ``v = (avg + 0.0001) / len^x`` with ``avg = total / count``; lower is better."""
    return float((total / count + 0.0001) / (count ** factor))


@dataclass(frozen=True)
class Successions:
    """How the history goes on: ``next_position[i]`` is the position of the successor of step i
    (-1 when the history ends or the successor is an odb:IdleTask, which ends the chain);
    ``executed[i]`` is the id of step i's executed option in ``options``."""

    next_position: np.ndarray
    executed: np.ndarray
    options: Sequence[Option]


@dataclass(frozen=True)
class TreeShape:
    """What bounds a tree: ``depth`` levels (event horizon forward), eq. 4.12's ``factor``
    (multiple occurrences factor), the objects ``present`` now and the tasks under soma:Opening."""

    depth: int
    factor: float
    present: frozenset[str]
    opening_tasks: frozenset[str]


def successor_tree(
    roots: np.ndarray,
    distances: np.ndarray,
    history: Successions,
    shape: TreeShape,
    checked: bool,
) -> tuple[TreeNode, ...]:
    """The successor nodes of one candidate whose similar historic situations are at ``roots``.

    ``roots`` (ascending history positions) and ``distances`` pair each member of ``H(s_o)`` with
    its distance to the candidate. ``checked`` is False when the candidate is an Opening task,
    below which objects are not checked for presence (Fig. 4.7).

    A node at depth k is a distinct sequence of k successor options; it gathers the roots whose
    chains follow that sequence and is valued by eq. 4.12 over their distances, which are summed
    in history order. Siblings are sorted by value, then by the earliest history position.
    """
    next_position, executed, options = history.next_position, history.executed, history.options
    depth, factor, present, opening_tasks = shape.depth, shape.factor, shape.present, shape.opening_tasks
    if depth <= 0 or roots.size == 0:
        return ()
    n_options = max(len(options), 1)
    position = roots.astype(np.int64)
    parent = np.zeros(roots.size, dtype=np.int64)        # node index of each root at the previous level
    levels = []                                          # per depth: (option ids, parents, scores, counts, first positions)
    for _ in range(depth):
        alive = position >= 0
        position = np.where(alive, next_position[np.maximum(position, 0)], -1)
        alive = position >= 0
        if not alive.any():
            break
        codes = np.where(alive, parent * n_options + executed[np.maximum(position, 0)], -1)
        chosen = np.flatnonzero(alive)
        unique, first, inverse = np.unique(codes[chosen], return_index=True, return_inverse=True)
        totals = np.bincount(inverse, weights=distances[chosen], minlength=unique.size)
        counts = np.bincount(inverse, minlength=unique.size)
        levels.append((unique % n_options, unique // n_options, totals, counts, position[chosen[first]]))
        parent = np.full(roots.size, -1, dtype=np.int64)
        parent[chosen] = inverse
        position = np.where(parent >= 0, position, -1)

    # top-down: which nodes survive the presence check, and which are below an Opening task
    keep_above = np.array([True])
    checked_above = np.array([checked])
    kept_levels = []
    for option_ids, parents, _, _, _ in levels:
        distinct, where = np.unique(option_ids, return_inverse=True)
        here_now = np.empty(distinct.size, dtype=bool)
        opens = np.empty(distinct.size, dtype=bool)
        for k, option_id in enumerate(distinct.tolist()):
            option = options[option_id]
            here_now[k] = ((option.target is None or option.target in present)
                           and (option.reference is None or option.reference in present))
            opens[k] = option.task in opening_tasks
        checked_here = checked_above[parents]
        keep = keep_above[parents] & (~checked_here | here_now[where])
        kept_levels.append(keep)
        keep_above, checked_above = keep, checked_here & ~opens[where]

    # bottom-up: build the kept nodes with their sorted children
    below: dict[int, list[tuple[float, int, TreeNode]]] = {}
    for (option_ids, parents, totals, counts, firsts), keep in zip(reversed(levels), reversed(kept_levels)):
        here: dict[int, list[tuple[float, int, TreeNode]]] = {}
        kept = np.flatnonzero(keep)
        for index, option_id, up, total, count, first in zip(
                kept.tolist(), option_ids[kept].tolist(), parents[kept].tolist(), totals[kept].tolist(),
                counts[kept].tolist(), firsts[kept].tolist()):
            score = occurrence_value(total, count, factor)
            children = sorted(below.get(index, ()), key=lambda item: (item[0], item[1]))
            node = TreeNode(options[option_id], score, count, tuple(node for _, _, node in children))
            here.setdefault(up, []).append((score, first, node))
        below = here
    top = sorted(below.get(0, ()), key=lambda item: (item[0], item[1]))
    return tuple(node for _, _, node in top)
