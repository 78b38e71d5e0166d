"""Thesis Algorithm 2 (``reference.overall_distance``) between many options at once, for the routine predictor.

The thesis oracle keeps its own vectorised copy inside ``fast.py`` so that it stays bit-identical
to ``reference``; this one serves the new predictor and is held equal to ``reference`` by
tests/algorithm/test_routine.py. Options become rows of class indices (task, target, reference;
-1 for an empty slot) so that a whole table of distances is one numpy expression; ``OptionTable``
keeps the distances between the options a history interned.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from oracle.algorithm.reference import class_row
from oracle.algorithm.records import DistanceTable, Option


def class_rows(matrix: DistanceTable, options: Sequence[Option]) -> np.ndarray:
    """The (k, 3) class indices of ``options`` in the distance matrix; -1 for an empty role slot."""
    rows = np.empty((len(options), 3), dtype=np.int64)
    for i, option in enumerate(options):
        rows[i, 0] = class_row(matrix, option.task)
        rows[i, 1] = -1 if option.target is None else class_row(matrix, option.target)
        rows[i, 2] = -1 if option.reference is None else class_row(matrix, option.reference)
    return rows


def option_distances(values: np.ndarray, a: np.ndarray, b: np.ndarray, task_factor: float,
                     object_factor: float, penalty: float) -> np.ndarray:
    """Algorithm 2 between every row of ``a`` and every row of ``b``: an (len(a), len(b)) table.

    ``task_factor * dist(task) + object_factor * avg(slot distances)``, a slot filled on one side
    only costing ``penalty``, a slot empty on both sides left out of the average.
    """
    task = values[a[:, 0][:, None], b[:, 0][None, :]]
    total = np.zeros(task.shape)
    count = np.zeros(task.shape, dtype=np.int64)
    for slot in (1, 2):
        mine, theirs = a[:, slot][:, None], b[:, slot][None, :]
        both = (mine >= 0) & (theirs >= 0)
        one = (mine >= 0) ^ (theirs >= 0)
        total = total + np.where(both, values[np.maximum(mine, 0), np.maximum(theirs, 0)], 0.0)
        total = total + np.where(one, penalty, 0.0)
        count += both | one
    average = np.divide(total, count, out=np.zeros(task.shape), where=count > 0)
    result: np.ndarray = task_factor * task + object_factor * average
    return result


#: at most this many distinct offers ``OptionTable.offer`` keeps the ids of (each holds its options)
MAX_OFFERS = 4096
#: per offer met, by ``id``: the offer itself, its options' interned ids, those ids as a set
Offers = dict[int, tuple[tuple[Option, ...], list[int], frozenset[int]]]


@dataclass(eq=False)
class OptionTable:
    """Every option a history offered or did, interned in the order first seen, with its class
    row, its objects and its Algorithm 2 distance to each other interned option (a square table
    that doubles as it fills)."""

    matrix: DistanceTable
    task_factor: float
    object_factor: float
    penalty: float
    options: list[Option] = field(default_factory=list)
    ids: dict[Option, int] = field(default_factory=dict)
    objects: list[frozenset[str]] = field(default_factory=list)
    classes: np.ndarray = field(default_factory=lambda: np.empty((0, 3), dtype=np.int64))
    table: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))

    def __post_init__(self) -> None:
        self.values = np.asarray(self.matrix.values, dtype=np.float64)
        self._decayed: dict[float, tuple[np.ndarray, int]] = {}
        #: the arrays shared with the table this one was forked from: "table" (with ``classes``)
        #: and the temperatures of the kept exponentials; each is copied before it is changed
        self._borrowed: set[float | str] = set()

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state.pop("_decayed", None)  # rebuilt on demand: a pickled model stays the table's size
        state.pop("_borrowed", None)  # an unpickled table owns its arrays
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._decayed = {}
        self._borrowed = set()

    def fork(self) -> OptionTable:
        """A copy that shares this table's arrays until it would change one (copy on write):
        what it interns never reaches this table, and nothing is copied for a copy that
        interns nothing."""
        twin = OptionTable(self.matrix, self.task_factor, self.object_factor, self.penalty, list(self.options),
                           dict(self.ids), list(self.objects), self.classes, self.table)
        twin.values = self.values
        twin._decayed = dict(self._decayed)
        twin._borrowed = {"table", *twin._decayed}
        return twin

    def decayed(self, tau: float) -> np.ndarray:
        """``exp(-table / tau)`` over the interned options (each entry computed once, when its
        option is interned, by the same element-wise operations as on the whole table)."""
        count = len(self.options)
        kept, filled = self._decayed.get(tau, (np.empty((0, 0)), 0))
        if kept.shape[0] != self.table.shape[0]:
            grown = np.empty(self.table.shape)
            grown[:filled, :filled] = kept[:filled, :filled]
            kept = grown
            self._borrowed.discard(tau)
        elif filled < count and tau in self._borrowed:
            kept = kept.copy()
            self._borrowed.discard(tau)
        if filled < count:
            kept[filled:count, :count] = np.exp(-self.table[filled:count, :count] / tau)
            kept[:filled, filled:count] = np.exp(-self.table[:filled, filled:count] / tau)
        self._decayed[tau] = (kept, count)
        return kept[:count, :count]

    def distances(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Algorithm 2 between class rows (``option_distances`` with this table's factors)."""
        return option_distances(self.values, a, b, self.task_factor, self.object_factor, self.penalty)

    def intern(self, option: Option) -> int:
        """The option's id, interning it (and its distances to every interned option) if new."""
        known = self.ids.get(option)
        if known is not None:
            return known
        row = class_rows(self.matrix, [option])
        old = len(self.options)
        if old == self.table.shape[0]:
            size = max(32, 2 * old)
            table = np.zeros((size, size))
            table[:old, :old] = self.table[:old, :old]
            self.table = table
            classes = np.empty((size, 3), dtype=np.int64)
            classes[:old] = self.classes[:old]
            self.classes = classes
            self._borrowed.discard("table")
        elif "table" in self._borrowed:
            self.table, self.classes = self.table.copy(), self.classes.copy()
            self._borrowed.discard("table")
        self.classes[old] = row[0]
        distances = self.distances(row, self.classes[: old + 1])[0]
        self.table[old, : old + 1] = distances
        self.table[: old + 1, old] = distances
        self.ids[option] = old
        self.options.append(option)
        self.objects.append(frozenset(option.objects()))
        return old

    def offer(self, options: tuple[Option, ...], met: Offers | None = None) -> tuple[list[int], frozenset[int]]:
        """The interned ids of an offer's options (interning new ones), as a list and as a set;
        ``met`` keeps them per offer by identity for the next step that shares the offer (the
        steps of a history share a few hundred offers; an option keeps its id once interned)."""
        seen = met.get(id(options)) if met is not None else None
        if seen is not None and seen[0] is options:
            return seen[1], seen[2]
        known = self.ids
        ids = [self.intern(option) if (found := known.get(option)) is None else found for option in options]
        offer = frozenset(ids)
        if met is not None and len(met) < MAX_OFFERS:
            met[id(options)] = (options, ids, offer)
        return ids, offer
