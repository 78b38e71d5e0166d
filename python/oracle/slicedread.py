"""A NEEM's whole history read in bounded slices, for where no view is kept (a MongoDB store, a
lost or damaged kept entry): ``Bridge.history_view()`` in one call holds every row of the NEEM
in Prolog's stacks at once (482 MiB at 50,000 actions) and, on the service, the one engine
thread for the whole read. Here the history is read ``SLICE_ACTIONS`` actions at a time
(odb_history:situation_history_json/3, each slice ending at an action's begin so that the
imaginings before an action are read with it) and joined: the rows equal the one-call read's.

``sliced_view`` reads every slice in one go; ``SlicedRead`` is the same read step by step, so
that the service runs each slice as its own job on the engine thread (oracle.service.
explore_routes) and a robot's situation waits at most one slice."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from oracle.bridge.records import HistoryRow, HistoryView

if TYPE_CHECKING:
    from oracle.bridge import Bridge

#: Actions read per slice: at 2,000 a slice's Prolog stacks stay a few tens of MiB, and the
#: slices' own cost (one bounds query, a few store queries each) is small beside the rows'.
SLICE_ACTIONS = 2_000


@dataclass
class SlicedRead:
    """A whole read in slices, one ``step`` at a time: ``bounds`` (from ``start``) ends each
    slice but the last, which reads to the end with the latest situation (``finish``)."""

    size: int = SLICE_ACTIONS
    bounds: list[float] | None = None
    rows: list[HistoryRow] = field(default_factory=list)
    #: The end of the slices read so far (None: none read yet) and how many they are.
    after: float | None = None
    done: int = 0
    #: Each distinct available set once, as the one-call read shares it among its rows.
    _sets: dict[tuple[str, ...], list[str]] = field(default_factory=dict)

    def start(self, bridge: Bridge) -> None:
        """Where the slices end (one store query of the actions' begins)."""
        self.bounds = bridge.history_bounds(self.size)

    @property
    def slices_left(self) -> int:
        """The slices still to ``step`` before ``finish`` (the last one)."""
        if self.bounds is None:
            raise ValueError("SlicedRead.start first")
        return len(self.bounds) - self.done

    def step(self, bridge: Bridge) -> None:
        """Read the next slice but the last."""
        if self.slices_left <= 0:
            raise ValueError("no slice left before the last")
        assert self.bounds is not None
        until = self.bounds[self.done]
        self._add(bridge.history_slice(self.after, until))
        self.after, self.done = until, self.done + 1

    def finish(self, bridge: Bridge) -> HistoryView:
        """Read the last slice with the latest situation: the whole view."""
        while self.slices_left > 0:
            self.step(bridge)
        last = bridge.history_view(self.after)
        self._add(last.rows)
        return HistoryView(self.rows, last.latest)

    def _add(self, rows: list[HistoryRow]) -> None:
        for row in rows:
            available = row["available"]
            if available is not None:
                row["available"] = self._sets.setdefault(tuple(available), available)
        self.rows.extend(rows)


def sliced_view(bridge: Bridge, size: int = SLICE_ACTIONS) -> HistoryView:
    """``bridge.history_view()`` read in slices of about ``size`` actions and joined."""
    read = SlicedRead(size)
    read.start(bridge)
    return read.finish(bridge)
