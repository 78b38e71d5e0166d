"""Records of the PreferenceOracle: options, executed steps (situations), rankings and the forward tree.

Every class and task is a full IRI; ``label`` is for display only. See docs/algorithm.md.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

from oracle.timeline import TIME_OF_DAY_NAMES



class DistanceTable(Protocol):
    """Algorithm 1 precomputed (``ontology.DistanceMatrix``): ``index`` maps a class IRI to its
    row and column of ``values``."""

    @property
    def index(self) -> Mapping[str, int]: ...

    @property
    def values(self) -> Any: ...


@dataclass(frozen=True)
class Option:
    """A task that can be executed, with the object class in each role slot (or None)."""

    task: str
    target: str | None = None
    reference: str | None = None

    def objects(self) -> tuple[str, ...]:
        """The object classes the option uses, target first."""
        return tuple(obj for obj in (self.target, self.reference) if obj is not None)

    def __str__(self) -> str:
        names = [local_name(obj) for obj in (self.reference, self.target) if obj is not None]
        return f"{local_name(self.task)}({', '.join(names)})" if names else local_name(self.task)


def option_key(option: Option) -> tuple[str, str, str]:
    """Total order on options (None sorts first); fixes the iteration order of an option set."""
    return (option.task, option.target or "", option.reference or "")


def canonical_options(options: Iterable[Option]) -> tuple[Option, ...]:
    """An available-option *set*: duplicates removed, in ``option_key`` order.

    Algorithm 3 averages over a set; fixing its order makes the floating-point sum reproducible,
    which is what lets ``fast`` return bit-identical scores.
    """
    return tuple(sorted(set(options), key=option_key))


def is_unix_seconds(value: object) -> bool:
    """Whether ``value`` is a time as the predictors take it: a finite number of unix seconds."""
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


@dataclass(frozen=True)
class Step:
    """One executed situation: the task and its objects, what else was available, when, and whether idle.

    ``idle`` marks an odb:IdleTask, which delimits task chains (thesis 4.4, "Looking Further Back").
    ``time`` is when it began, in unix seconds (None: the log has no clock).
    """

    task: str
    target: str | None = None
    reference: str | None = None
    options: tuple[Option, ...] = ()
    time_of_day: str | None = None
    idle: bool = False
    label: str = ""
    time: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.options, tuple):
            object.__setattr__(self, "options", tuple(self.options))
        for option in self.options:
            if not isinstance(option, Option):
                raise TypeError(f"step {self.label or self.task}: options must be Option records, got {option!r}")
        if self.time is not None and not is_unix_seconds(self.time):
            raise ValueError(f"step {self.label or self.task}: time must be finite unix seconds, got {self.time!r}")
        if self.time_of_day is not None and self.time_of_day not in TIME_OF_DAY_NAMES:
            raise ValueError(f"step {self.label or self.task}: time of day {self.time_of_day!r} "
                             f"is not one of {', '.join(TIME_OF_DAY_NAMES)}")

    @property
    def option(self) -> Option:
        """The executed task with its objects, as an option."""
        return Option(self.task, self.target, self.reference)

    def began(self, time: float) -> Step:
        """This step beginning at ``time`` (unix seconds): a copy whose options, checked when this
        one was made, are not checked again (a history of 50,000 steps shares a few hundred)."""
        if not is_unix_seconds(time):
            raise ValueError(f"step {self.label or self.task}: time must be finite unix seconds, got {time!r}")
        step = object.__new__(Step)
        step.__dict__.update(self.__dict__, time=float(time))
        return step


#: The thesis calls an executed step a situation.
Situation = Step


@dataclass(frozen=True)
class TreeNode:
    """A predicted successor in the forward preference tree (thesis Fig. 4.6, eq. 4.13).

    ``score`` is eq. 4.12 over the distances of the similar historic situations whose successor
    chains pass through this node (lower is better); ``support`` is how many there are.
    """

    option: Option
    score: float
    support: int
    children: tuple[TreeNode, ...] = ()


@dataclass(frozen=True)
class RankedTask:
    """One available option with its rank (1 = best) and eq. 4.12 value (lower is better).

    ``n_similar`` is ``|H(s_o)|``; when it is 0 the score is ``inf`` and the option is ranked after
    all options with similar history, by ``nearest`` (the smallest Algorithm 2 distance to any
    executed step; ``inf`` with an empty history), then in the order offered.
    """

    rank: int
    score: float
    option: Option
    n_similar: int
    nearest: float
    successors: tuple[TreeNode, ...] = field(default=(), compare=True)


@dataclass(frozen=True)
class RoutineTask(RankedTask):
    """A ranked option with what supports it.

    ``score`` is ``-log2 P`` (bits of surprise; lower is better, like the thesis's distance);
    ``context`` the longest exact context (oldest first, ``idle`` for a gap) that was followed by
    this option ``n_similar`` times, ``order`` its length (0: the option was done, in no matching
    context; -1: never done); ``situations`` the history positions of those past situations
    (latest last), or of the most similar past actions when there are none; ``focus`` the
    option's objects that the user's latest actions used (the objects in hand, which lift it);
    ``new`` whether it was not offered at the previous decision (newly possible) while others
    were, so that the user's lift of such options weighs it; ``resumed`` whether, right after a
    break, it once followed the last action before the break (it picks up where the user left
    off) while others did not; ``since`` how many seconds ago the user last did it, when the
    clock's odds weighed this ranking (None otherwise, and for an option never done).
    """

    probability: float = 0.0
    order: int = -1
    context: tuple[str, ...] = ()
    situations: tuple[int, ...] = ()
    focus: tuple[str, ...] = ()
    new: bool = False
    resumed: bool = False
    since: float | None = None


@dataclass(frozen=True)
class Ranking:
    """The ranked options, best first, each with its forward tree (possibly empty); ``ahead``:
    the predicted chain when it was worked out beside the ranking (oracle.algorithm.chaining),
    None: the forward tree's."""

    tasks: tuple[RankedTask, ...]
    ahead: tuple[Option, ...] | None = None

    def __iter__(self) -> Iterator[RankedTask]:
        return iter(self.tasks)

    def __len__(self) -> int:
        return len(self.tasks)

    def __getitem__(self, index: int) -> RankedTask:
        return self.tasks[index]

    def options(self) -> tuple[Option, ...]:
        return tuple(task.option for task in self.tasks)

    def chain(self) -> tuple[Option, ...]:
        """The predicted chain: ``ahead`` if set, else the best option, then the best successor
        at each depth of its forward tree (thesis Fig. 4.6)."""
        if self.ahead is not None:
            return self.ahead
        if not self.tasks:
            return ()
        chain = [self.tasks[0].option]
        nodes = self.tasks[0].successors
        while nodes:
            chain.append(nodes[0].option)
            nodes = nodes[0].children
        return tuple(chain)


def local_name(iri: str) -> str:
    for sep in ("#", "/"):
        if sep in iri:
            iri = iri.rsplit(sep, 1)[1]
    return iri
