"""The routines of one NEEM: mined from its history through Prolog, with the names the user
gave the stored workflows they continue, and the one in progress."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from oracle.past.kept import KeptPast
from oracle.past.routines import Done, InProgress, MiningSettings, Routine, begun_by, in_progress, mine_routines
from oracle.past.workflows import keep_user_names

if TYPE_CHECKING:
    from oracle.bridge import Bridge


@dataclass(frozen=True)
class NeemRoutines:
    """A NEEM's routines (``named``: the keys whose names the user gave), the one in progress at
    ``now`` (None when none) and whether they are stored in the NEEM as mined."""

    routines: tuple[Routine, ...]
    named: tuple[str, ...]
    current: InProgress | None
    now: float | None

    def to_json(self) -> dict[str, Any]:
        return {"now": self.now, "routines": [{**r.to_json(), "named_by_user": r.key in self.named} for r in self.routines],
                "in_progress": self.current.to_json() if self.current else None}


def neem_routines(bridge: Bridge, at: float | None = None, settings: MiningSettings | None = None,
                  done: list[Done] | None = None, kept: KeptPast | None = None) -> NeemRoutines:
    """Mine the NEEM's history (the actions begun by ``at``, default all) into routines; the
    history comes from the user's kept copy when the NEEM only grew since (oracle.historycache),
    or is ``done`` when the caller has it. ``kept``: what an earlier answer read of the NEEM
    (oracle.past.kept; default: nothing)."""
    kept = KeptPast() if kept is None else kept
    if done is None:
        done, mined = kept.mined(bridge, at, settings)
    else:
        done = begun_by(done, at)
        mined = mine_routines(done, settings)
    routines, named = keep_user_names(mined, kept.stored(bridge))
    now = at if at is not None else (max(d.end for d in done) if done else None)
    current = in_progress(routines, done, now) if now is not None else None
    return NeemRoutines(tuple(routines), tuple(named), current, now)


def neem_preparation(bridge: Bridge, part: str | None = None, at: float | None = None,
                     kept: KeptPast | None = None) -> dict[str, Any]:
    """What to prepare now for ``part`` of the day (default: the part after now's): the objects
    the routines of that part need (oracle.past.prepare), each with its reason, where the NEEM
    last had it (odb_past:object_place/3) and its state (used, in the dishwasher, washed)."""
    from oracle.past.evidence import request
    from oracle.past.prepare import next_part, object_state, to_prepare

    kept = KeptPast() if kept is None else kept
    now = at if at is not None else kept.now(bridge)
    if now is None:
        return {"now": None, "for": part, "prepare": []}
    target = part or next_part(now)
    found = neem_routines(bridge, at, kept=kept)
    items = []
    done = begun_by(kept.done(bridge), at)
    for prep in to_prepare(found.routines, done, target):
        place = request(bridge, ["where", prep.obj, now])
        items.append({**prep.to_json(), "pose": place["pose"], "last_used": place["used"],
                      "state": object_state(prep.obj, done).to_json()})
    return {"now": now, "for": target, "prepare": items}
