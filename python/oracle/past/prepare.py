"""What is worth preparing now (thesis 6.4): the objects the user's routines of a coming part of
the day need, most needed first, each with its reason.

An object counts when the user moves it (it is picked in some action): a fridge or a table is not
prepared. A routine's weight is the share of the observed days it was seen on; an object's, the
sum over the routines of the part of the day that use it.

Each object's state is read from the actions so far (``object_state``): used (an action soiled it:
poured into, drunk from, a tool that stirred, cut or ate) and not washed since, in the dishwasher
but not washed, or washed (the dishwasher ran with it inside); the thesis's "clean the cup the
night before" is the first.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from oracle.chains import parse_call
from oracle.past.routines import Done, Routine, episodes_of
from oracle.timeline import PARTS_OF_DAY, clock, part_of_day_at

#: How many objects a preparation names.
LIMIT = 3
#: The kitchen world's tasks that leave an object used, by the positions of such objects among
#: the call's arguments: the recipient poured into, what is drunk from, the tool that stirs
#: (and what it stirs in), cuts or eats with.
SOILS = {"pour": (1,), "drink_from": (0,), "stir": (0, 1), "cut": (0,), "eat_with": (0,)}
#: Where the kitchen world washes dishes.
WASHER = "dish_washer"
USED, IN_WASHER, WASHED, UNKNOWN = "used", "in the dishwasher", "washed", "unknown"


@dataclass(frozen=True)
class ObjectState:
    """An object's state after the actions so far, since when and the action that left it so
    (``unknown``: no action soiled or washed it)."""

    state: str
    since: float | None = None
    call: str | None = None

    def to_json(self) -> dict[str, object]:
        return {"state": self.state, "since": self.since, "action": self.call}


def object_state(obj: str, done: Sequence[Done]) -> ObjectState:
    """``obj``'s state after ``done`` (in begin order): used by an action of SOILS, in the
    dishwasher once placed there, washed when the dishwasher is turned on with it inside (taken
    out again, it stays washed until used; taken out unwashed, it is as it was before)."""
    state, before, inside = ObjectState(UNKNOWN), ObjectState(UNKNOWN), False
    for d in sorted(done, key=lambda d: d.begin):
        call = parse_call(d.call)
        if call.task == "place" and call.args == (obj, WASHER):
            before, state, inside = state, ObjectState(IN_WASHER, d.begin, d.call), True
        elif call.task == "turn_on" and call.args == (WASHER,) and inside:
            state = ObjectState(WASHED, d.begin, d.call)
        elif call.task == "pick" and call.args == (obj,) and inside:
            state, inside = (before if state.state == IN_WASHER else state), False
        elif any(i < len(call.args) and call.args[i] == obj for i in SOILS.get(call.task, ())):
            state = ObjectState(USED, d.begin, d.call)
    return state


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
