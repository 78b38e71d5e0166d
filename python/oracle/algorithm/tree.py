"""The forward preference tree (thesis 4.4 "Looking into the Future", Fig. 4.6, eq. 4.13, Fig. 4.7).

For one candidate ``s_o`` the similar historic situations ``H(s_o)`` and their distances are the
roots; the successors ``n(s_h)`` are grouped by executed option, each group valued by eq. 4.12 over
the distances of the roots it came from, down to ``event horizon forward`` levels. Branches using
objects not present now are pruned, except below tasks under soma:Opening. Both oracles share
this module, so their trees are identical whenever their ``H(s_o)`` and distances are.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from oracle.algorithm.situation import Option, TreeNode


def occurrence_value(total: float, count: int, factor: float) -> float:
    """Eq. 4.12: ``v = (avg + 0.0001) / len^x`` with ``avg = total / count``; lower is better."""
    return (total / count + 0.0001) / (count ** factor)


def successor_tree(
    roots: np.ndarray,
    distances: np.ndarray,
    next_position: np.ndarray,
    executed: np.ndarray,
    options: Sequence[Option],
    depth: int,
    factor: float,
    present: frozenset[str],
    opening_tasks: frozenset[str],
    checked: bool,
) -> tuple[TreeNode, ...]:
    """Children of a node whose chains currently stand at history positions ``roots``.

    ``roots`` (ascending) and ``distances`` pair each similar historic situation with its
    distance to the candidate; ``next_position[i]`` is the position of the successor of step i
    (-1 when the history ends or the successor is an odb:IdleTask, which ends the chain);
    ``executed[i]`` is the id of step i's executed option in ``options``. ``checked`` is False
    below an Opening task, where objects are not checked for presence (Fig. 4.7).
    """
    if depth <= 0 or roots.size == 0:
        return ()
    successors = next_position[roots]
    keep = successors >= 0
    successors, weights = successors[keep], distances[keep]
    if successors.size == 0:
        return ()
    ids = executed[successors]
    groups, first, inverse = np.unique(ids, return_index=True, return_inverse=True)
    # bincount adds in input order, i.e. in history order, so the sum is reproducible.
    totals = np.bincount(inverse, weights=weights, minlength=groups.size)
    counts = np.bincount(inverse, minlength=groups.size)
    nodes: list[tuple[float, int, TreeNode]] = []
    for g, option_id in enumerate(groups.tolist()):
        option = options[option_id]
        if checked and not set(option.objects()) <= present:
            continue  # Fig. 4.7: this successor needs an object that is not here now
        count = int(counts[g])
        score = occurrence_value(float(totals[g]), count, factor)
        mask = inverse == g
        children = successor_tree(
            successors[mask], weights[mask], next_position, executed, options, depth - 1, factor,
            present, opening_tasks, checked and option.task not in opening_tasks,
        )
        nodes.append((score, int(successors[first[g]]), TreeNode(option, score, count, children)))
    nodes.sort(key=lambda item: (item[0], item[1]))
    return tuple(node for _, _, node in nodes)
