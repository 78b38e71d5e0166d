"""What is worth preparing now (thesis 6.4): the objects the user's routines of a coming part of
the day need, most needed first, each with its reason.

An object counts when the user moves it (it is picked in some action): a fridge or a table is not
prepared. A routine's weight is the share of the observed days it was seen on; an object's, the
sum over the routines of the part of the day that use it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from oracle.chains import parse_call
from oracle.past.routines import Done, Routine, episodes_of
from oracle.timeline import PARTS_OF_DAY, clock, part_of_day_at

#: How many objects a preparation names.
LIMIT = 3


@dataclass(frozen=True)
class Preparation:
    """One object to prepare: its weight, the routines that need it (key and name) and why."""

    obj: str
    weight: float
    routines: tuple[tuple[str, str], ...]
    reason: str

    def to_json(self) -> dict[str, object]:
        return {"object": self.obj, "weight": round(self.weight, 3), "routines": [list(r) for r in self.routines],
                "reason": self.reason}


def movable(done: Sequence[Done]) -> set[str]:
    """The objects the user picks (the ones worth preparing)."""
    return {c.args[0] for c in (parse_call(d.call) for d in done) if c.task.startswith("pick") and c.args}


def next_part(now: float) -> str:
    """The part of the day after the one ``now`` lies in (Night follows Evening)."""
    names = [name for _, name in PARTS_OF_DAY]
    current = part_of_day_at(now)
    order = [n for i, n in enumerate(names) if n not in names[:i]]  # Night, Morning, Midday, Evening
    return order[(order.index(current) + 1) % len(order)]


def to_prepare(routines: Sequence[Routine], done: Sequence[Done], part: str, limit: int = LIMIT) -> list[Preparation]:
    """The (at most ``limit``) objects the routines usually begun in ``part`` need."""
    days = len({e.day for e in episodes_of(done)}) or 1
    moved = movable(done)
    weights: dict[str, float] = {}
    needs: dict[str, list[Routine]] = {}
    for routine in routines:
        if routine.part != part:
            continue
        for obj in dict.fromkeys(a for step in routine.steps for a in parse_call(step).args):
            if obj in moved:
                weights[obj] = weights.get(obj, 0.0) + routine.days / days
                needs.setdefault(obj, []).append(routine)
    ranked = sorted(weights, key=lambda o: (-weights[o], o))[:limit]
    return [Preparation(obj, weights[obj], tuple((r.key, r.name) for r in needs[obj]),
                        "; ".join(f"{r.name} is usual at {r.usual_time} ({r.days} of {days} days) and needs the "
                                  f"{obj.replace('_', ' ')}" for r in needs[obj]))
            for obj in ranked]


def most_used(done: Sequence[Done], limit: int = LIMIT) -> list[str]:
    """The baseline: the moved objects used in the most actions."""
    moved = movable(done)
    counts: dict[str, int] = {}
    for d in done:
        for obj in dict.fromkeys(parse_call(d.call).args):
            if obj in moved:
                counts[obj] = counts.get(obj, 0) + 1
    return sorted(counts, key=lambda o: (-counts[o], o))[:limit]


def used_in(done: Sequence[Done], day: str, part: str) -> set[str]:
    """The objects of the actions begun on ``day`` (ISO date) in ``part``."""
    return {a for d in done if clock(d.begin).date().isoformat() == day and part_of_day_at(d.begin) == part
            for a in parse_call(d.call).args}
