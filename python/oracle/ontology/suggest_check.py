"""Leave-one-out check of ``ontology suggest`` against a hand mapping: each object's own line is
removed in turn, and the hand-chosen class (or one of its direct parents) is looked for among the
suggestions made for it without that line."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from oracle.ontology.mapping import Mapping
from oracle.ontology.odb import OdbObject
from oracle.ontology.suggest import Suggester, UpperClass
from oracle.ontology.suggest_embed import Nearness


@dataclass(frozen=True)
class HeldOut:
    """One held-out line: the hand class, the suggestions made without it, where it ranked."""

    entry: str
    hand: str
    suggested: tuple[str, ...]
    rank: int | None  # 1-based rank of the first accepted class; None if not among the suggestions


@dataclass(frozen=True)
class LeaveOneOut:
    objects: tuple[HeldOut, ...]
    tasks: tuple[HeldOut, ...]

    @staticmethod
    def rate(rows: tuple[HeldOut, ...], k: int) -> float:
        return sum(1 for r in rows if r.rank is not None and r.rank <= k) / len(rows) if rows else 0.0


def _accepted(hand: str, classes: dict[str, UpperClass]) -> set[str]:
    return {hand, *(classes[hand].parents if hand in classes else ())}


def leave_one_out(objects: dict[str, OdbObject], maps: Mapping, classes: dict[str, UpperClass], top: int = 5,
                  nearness: Nearness | None = None) -> LeaveOneOut:
    """Every object line and every task with its own ``task`` field, held out one at a time."""
    held_objects: list[HeldOut] = []
    for name, hand in sorted(maps.object_map.items()):
        if name not in objects:
            continue
        rest = dict(maps.object_map)
        del rest[name]
        suggester = Suggester(objects, dataclasses.replace(maps, object_map=rest), classes, nearness)
        held_objects.append(_row(name, hand, [s.iri for s in suggester.suggest_object(name, top)], classes))
    held_tasks: list[HeldOut] = []
    for name, action in sorted(maps.actions.items()):
        if not action.explicit_task or action.parent is not None:
            continue  # a child's class is its parent's: nothing to guess
        rest_actions = {n: a for n, a in maps.actions.items() if n != name}
        suggester = Suggester(objects, dataclasses.replace(maps, actions=rest_actions), classes, nearness)
        held_tasks.append(_row(name, action.task, [s.iri for s in suggester.suggest_task(name, top)], classes))
    return LeaveOneOut(tuple(held_objects), tuple(held_tasks))


def _row(name: str, hand: str, suggested: list[str], classes: dict[str, UpperClass]) -> HeldOut:
    accepted = _accepted(hand, classes)
    rank = next((i + 1 for i, iri in enumerate(suggested) if iri in accepted), None)
    return HeldOut(name, hand, tuple(suggested), rank)
