"""The symbolic kitchen state: where every object is, what the single arm holds, what is open or on.

A State is immutable; ``World.apply`` (rules.py) returns a new one. Locations form a tree rooted in
fixtures (surfaces, containers, appliances); an object is reachable when nothing on its path to a
fixture is closed, switched on (the dish washer), or held.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

#: The location of the object the arm holds.
HAND = "<hand>"

OBJECT_KINDS = ("item", "surface", "container", "receptacle", "appliance")


@dataclass(frozen=True)
class ObjectSpec:
    """One object of the world file: its kind, start location, afforded tasks, tags and accepts."""

    name: str
    kind: str = "item"
    at: str | None = None
    affords: tuple[str, ...] = ()
    tags: frozenset[str] = frozenset()
    accepts: frozenset[str] = frozenset()

    @property
    def fixture(self) -> bool:
        """Fixtures never move: surfaces, containers, appliances without a start location."""
        return self.kind in ("surface", "container", "appliance")


@dataclass(frozen=True)
class State:
    """Locations of the movable objects, the held object, open containers, running appliances."""

    location: Mapping[str, str]
    held: str | None = None
    opened: frozenset[str] = frozenset()
    switched_on: frozenset[str] = frozenset()

    def __post_init__(self) -> None:
        if not isinstance(self.location, MappingProxyType):
            object.__setattr__(self, "location", MappingProxyType(dict(self.location)))

    # --- transitions (each returns a new State) ---------------------------------------------
    def grasp(self, obj: str) -> State:
        location = dict(self.location)
        location[obj] = HAND
        return replace(self, location=location, held=obj)

    def put(self, obj: str, destination: str) -> State:
        location = dict(self.location)
        location[obj] = destination
        return replace(self, location=location, held=None if self.held == obj else self.held)

    def open(self, obj: str) -> State:
        return replace(self, opened=self.opened | {obj})

    def close(self, obj: str) -> State:
        return replace(self, opened=self.opened - {obj})

    def switch_on(self, obj: str) -> State:
        return replace(self, switched_on=self.switched_on | {obj})

    def switch_off(self, obj: str) -> State:
        return replace(self, switched_on=self.switched_on - {obj})

    def describe(self) -> dict[str, object]:
        """A plain dict for messages and docs."""
        return {
            "held": self.held,
            "opened": sorted(self.opened),
            "switched_on": sorted(self.switched_on),
            "location": dict(sorted(self.location.items())),
        }


def path_to_fixture(state: State, obj: str) -> list[str]:
    """The chain of locations from ``obj`` outwards, e.g. ``['small_drawer']`` for a mug in it."""
    path: list[str] = []
    current = state.location.get(obj)
    seen = {obj}
    while current is not None and current not in seen:
        path.append(current)
        seen.add(current)
        if current == HAND:
            break
        current = state.location.get(current)
    return path


def blocker(state: State, specs: Mapping[str, ObjectSpec], obj: str) -> str | None:
    """The innermost thing that makes ``obj`` unreachable, or None when it is reachable.

    The result is the object itself when it is held, ``HAND``'s holder when an enclosing item is
    held, a closed container, or a running appliance (its contents are locked in).
    """
    if state.held == obj:
        return obj
    for place in path_to_fixture(state, obj):
        if place == HAND:
            return state.held
        spec = specs.get(place)
        if spec is None:
            continue
        if spec.kind == "container" and place not in state.opened:
            return place
        if spec.kind == "appliance" and place in state.switched_on:
            return place
    return None


def reachable(state: State, specs: Mapping[str, ObjectSpec], obj: str) -> bool:
    """Whether the arm could take ``obj`` now (it is not held and nothing encloses it)."""
    return blocker(state, specs, obj) is None
