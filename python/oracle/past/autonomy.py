"""Who usually performs an action (thesis 6.3, autonomy mode): the user by hand, the robot, or the
two together.

The mode of an action is predicted from the user's own past: the modes counted for the same call
(task and objects) in the same part of the day, for the call at any time, for the task in that
part of the day and for the task, the more specific counting more. Ties go to the mode that leaves
the user the most to do (the user, then together, then the robot: the robot leaves what the user
still can do to the user). The counts are also what the learned predictor
(``oracle.past.modelogit``, the one the ranking uses) is fitted to, and what its answers cite.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from oracle.chains import MODES, parse_call

if TYPE_CHECKING:
    from oracle.bridge import HistoryRow

USER, ROBOT, TOGETHER = "user", "robot", "together"
#: Who wins a tie: the mode that leaves the user more to do comes first.
TIE_ORDER = (USER, TOGETHER, ROBOT)
#: How much a count weighs in the contexts call and part, call, task and part, task.
WEIGHTS = (1.0, 0.5, 0.25, 0.1)
#: The part of the day of an action in a NEEM without a clock (its begins are positions).
NO_PART = "none"


@dataclass(frozen=True)
class Performed:
    """One action with its part of the day and who performed it."""

    call: str
    part: str
    mode: str


@dataclass(frozen=True)
class UsualMode:
    """The usual mode of a call (None: no action of its task is known), the most specific context
    with counts (``call and part``, ``call``, ``task and part``, ``task`` or ``none``) and the
    modes counted there: what the prediction rests on."""

    mode: str | None
    context: str
    counts: dict[str, int]

    def to_json(self) -> dict[str, Any]:
        return {"mode": self.mode, "context": self.context, "counts": dict(self.counts)}


@dataclass
class ModeCounts:
    """Counts of the modes in each context of the actions seen (``add``)."""

    counts: dict[tuple[str, ...], Counter[str]] = field(default_factory=dict)
    #: Each call's task, parsed once (a history repeats a few hundred calls).
    tasks: dict[str, str] = field(default_factory=dict, repr=False, compare=False)

    def task_of(self, call: str) -> str:
        task = self.tasks.get(call)
        if task is None:
            task = self.tasks[call] = parse_call(call).task
        return task

    def contexts(self, call: str, part: str) -> tuple[tuple[str, tuple[str, ...]], ...]:
        """The four contexts of a call, the most specific first, with their names."""
        task = self.task_of(call)
        return (("call and part", ("cp", call, part)), ("call", ("c", call)), ("task and part", ("tp", task, part)),
                ("task", ("t", task)))

    def add(self, action: Performed, times: int = 1) -> None:
        for _, key in self.contexts(action.call, action.part):
            self.counts.setdefault(key, Counter())[action.mode] += times

    def predict(self, call: str, part: str) -> tuple[str, str]:
        """The usual mode of ``call`` in ``part``, and the most specific context it was read
        from (``call and part``, ``call``, ``task and part``, ``task`` or ``none``): the modes'
        counts in the four contexts summed, each weighted by WEIGHTS (the more specific, the more)."""
        votes = {mode: 0.0 for mode in TIE_ORDER}
        source = "none"
        for (name, key), weight in zip(self.contexts(call, part), WEIGHTS):
            counts = self.counts.get(key)
            if counts:
                for mode, n in counts.items():
                    votes[mode] = votes.get(mode, 0.0) + weight * n
                if source == "none":
                    source = name
        return _most(votes), source

    def usual(self, call: str, part: str) -> UsualMode:
        """``predict`` with what it rests on: the counts of its most specific context."""
        mode, source = self.predict(call, part)
        if source == "none":
            return UsualMode(None, source, {m: 0 for m in MODES})
        key = dict(self.contexts(call, part))[source]
        counts = self.counts[key]
        return UsualMode(mode, source, {m: counts.get(m, 0) for m in MODES})


def _most(votes: dict[str, float]) -> str:
    """The mode with the most votes; a tie to the first of TIE_ORDER."""
    return max(TIE_ORDER, key=lambda mode: (votes.get(mode, 0.0), -TIE_ORDER.index(mode)))


def majority(counts: Counter[str]) -> str:
    """The mode with more votes; on a tie the one of TIE_ORDER first (the user)."""
    return _most({mode: float(counts[mode]) for mode in TIE_ORDER})


def fit(actions: Iterable[Performed]) -> ModeCounts:
    counts = ModeCounts()
    for action in actions:
        counts.add(action)
    return counts


def modes_from_rows(rows: Iterable[HistoryRow]) -> ModeCounts:
    """The modes of the history rows' actions (``HistoryRow.mode``, read with the history and
    kept with it, oracle.historycache) counted in their contexts, each in the part of the day it
    was logged with (``none`` without a clock). Idle steps and actions whose performer is
    neither the user nor another agent are not counted."""
    seen = Counter((row["call"], row["part"], row["mode"]) for row in rows)  # a history repeats a few hundred
    counts = ModeCounts()
    for (call, part, mode), times in seen.items():
        if call != "idle" and mode in MODES:
            counts.add(Performed(str(parse_call(call)), part or NO_PART, mode), times)
    return counts
