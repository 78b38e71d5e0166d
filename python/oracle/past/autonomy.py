"""Who usually performs an action (thesis 6.3, autonomy mode): the user by hand or the robot.

The mode of an action is predicted from the user's own past: the modes counted for the same call
(task and objects) in the same part of the day, for the call at any time, for the task in that
part of the day and for the task, the more specific counting more. Ties go to the user (the robot
leaves what the user still can do to the user).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field

from oracle.chains import parse_call

USER, ROBOT = "user", "robot"
#: How much a count weighs in the contexts call and part, call, task and part, task.
WEIGHTS = (1.0, 0.5, 0.25, 0.1)


@dataclass(frozen=True)
class Performed:
    """One action with its part of the day and who performed it."""

    call: str
    part: str
    mode: str


@dataclass
class ModeCounts:
    """Counts of the modes in each context of the actions seen (``add``)."""

    counts: dict[tuple[str, ...], Counter[str]] = field(default_factory=dict)

    @staticmethod
    def contexts(call: str, part: str) -> tuple[tuple[str, tuple[str, ...]], ...]:
        """The four contexts of a call, the most specific first, with their names."""
        task = parse_call(call).task
        return (("call and part", ("cp", call, part)), ("call", ("c", call)), ("task and part", ("tp", task, part)),
                ("task", ("t", task)))

    def add(self, action: Performed) -> None:
        for _, key in self.contexts(action.call, action.part):
            self.counts.setdefault(key, Counter())[action.mode] += 1

    def predict(self, call: str, part: str) -> tuple[str, str]:
        """The usual mode of ``call`` in ``part``, and the most specific context it was read
        from (``call and part``, ``call``, ``task and part``, ``task`` or ``none``): the modes'
        counts in the four contexts summed, each weighted by WEIGHTS (the more specific, the more)."""
        votes = {USER: 0.0, ROBOT: 0.0}
        source = "none"
        for (name, key), weight in zip(self.contexts(call, part), WEIGHTS):
            counts = self.counts.get(key)
            if counts:
                for mode, n in counts.items():
                    votes[mode] = votes.get(mode, 0.0) + weight * n
                if source == "none":
                    source = name
        return (ROBOT if votes[ROBOT] > votes[USER] else USER), source


def majority(counts: Counter[str]) -> str:
    """The mode with more votes; the user on a tie."""
    return ROBOT if counts[ROBOT] > counts[USER] else USER


def fit(actions: Iterable[Performed]) -> ModeCounts:
    counts = ModeCounts()
    for action in actions:
        counts.add(action)
    return counts
