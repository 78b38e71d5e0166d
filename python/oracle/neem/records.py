"""The records the NEEM writer (oracle.neem.writer) passes around: a moment checked into an instant,
the triples of one call before they are written, what an action wrote, where the writes go, and the
scope of a fact that holds during an action."""

from __future__ import annotations

import math
from dataclasses import dataclass

from oracle.chains import TaskCall
from oracle.errors import LoggingError
from oracle.store.model import INFINITY, USER_GRAPH, TripleRow, Value
from oracle.timeline import Instant, Moment, TimeValueError


def checked_instant(moment: Moment) -> Instant:
    """A moment as an instant; a bad one as a LoggingError (nothing written)."""
    try:
        return Instant.of(moment)
    except TimeValueError as error:
        raise LoggingError(str(error)) from None


@dataclass(frozen=True)
class LoggedAction:
    """What ``NeemLogger.action`` wrote: the action, and the idle action it inserted before it."""

    iri: str
    call: TaskCall
    begin: float
    end: float
    part_of_day: str | None
    task: str
    idle: str | None = None
    imagining: str | None = None


class TripleBuffer(list[TripleRow]):
    """Triples of one call, before they are written, and the individuals they create.

    They are plain ``(s, p, o, graph, since, until)`` tuples, as ``Store.insert`` takes them: a
    call writes ~50, and a tuple costs a third of a ``Triple`` to make."""

    def __init__(self) -> None:
        super().__init__()
        self.created: set[str] = set()

    def add(self, s: str, p: str, o: Value, since: float = 0.0, until: float = INFINITY) -> None:
        self.append((s, p, o, USER_GRAPH, since, until))


@dataclass
class Target:
    """The NEEM a logger writes, shared by the logger and its individuals (which look there for
    what exists, and name it in their errors)."""

    #: The NEEM the writes go to: a hidden staging NEEM until ``close()`` when it replaces one.
    writing: str
    #: The NEEM this one replaces when ``close()`` swaps it in (``create(replace=True)``).
    replaces: str | None = None
    may_replace: bool = False

    @property
    def neem_id(self) -> str:
        """The NEEM's id as everyone else knows it (``NeemLogger.neem_id``)."""
        return self.replaces or self.writing


def fact_extent(begin: float, end: float) -> tuple[float, float]:
    """The scope of a fact that holds during an action from ``begin`` to ``end``. KnowRob sees a
    fact only where its scope has an extent (since < until, ``kb_scope``), so an instantaneous
    action (logged with a start only) scopes its facts to the shortest interval a double holds,
    ``[begin, nextafter(begin)]``: ``has_role(O, R) during A`` then answers as it does for any
    action, and the extent ends before any later action starts (docs/store.md)."""
    return (begin, end) if end > begin else (begin, math.nextafter(begin, math.inf))
