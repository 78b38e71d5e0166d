"""Object poses in KnowRob's ``tf`` layout: the transform the logger writes with a perception,
and where a frame was at a time (the latest transform stamped at or before it, as KnowRob's tf
fluent reads ``header.stamp``)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Any

from oracle.errors import LoggingError
from oracle.store import Store
from oracle.store.model import unix_seconds

#: The ROS topic KnowRob's tf logger records transforms from.
TF_TOPIC = "/tf"


@dataclass(frozen=True)
class Pose:
    """Where an object was seen: ``position`` (x, y, z in metres) in ``frame``, ``rotation`` a
    unit quaternion (x, y, z, w)."""

    position: tuple[float, float, float]
    rotation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    frame: str = "map"

    def __post_init__(self) -> None:
        if not isinstance(self.frame, str) or not self.frame.strip():
            raise LoggingError(f"pose: the reference frame must be a non-empty name, got {self.frame!r}")
        _numbers("position", self.position, 3)
        _numbers("rotation", self.rotation, 4)
        norm = math.sqrt(sum(float(q) ** 2 for q in self.rotation))
        if abs(norm - 1.0) > 1e-3:
            raise LoggingError(f"pose: the rotation {tuple(self.rotation)} is not a unit quaternion (norm {norm:.4g})")


def _numbers(what: str, values: Sequence[Any], n: int) -> None:
    if not isinstance(values, (tuple, list)) or len(values) != n:
        raise LoggingError(f"pose: {what} must be {n} numbers, got {values!r}")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise LoggingError(f"pose: {what} must be {n} finite numbers, got {values!r}")


def frame_name(iri: str) -> str:
    """The tf frame of an object: its IRI's local name (KnowRob's object_frame_name default)."""
    for sep in ("#", "/"):
        if sep in iri:
            iri = iri.rsplit(sep, 1)[1]
    return iri


def tf_document(child: str, pose: Pose, stamp: float, seq: int) -> dict[str, Any]:
    """One transform as KnowRob's tf logger stores it (ROS TransformStamped, stamps as Dates)."""
    when = datetime.fromtimestamp(stamp, tz=timezone.utc)
    x, y, z = (float(v) for v in pose.position)
    qx, qy, qz, qw = (float(v) for v in pose.rotation)
    return {
        "header": {"seq": seq, "stamp": when, "frame_id": pose.frame},
        "child_frame_id": child,
        "transform": {"translation": {"x": x, "y": y, "z": z}, "rotation": {"x": qx, "y": qy, "z": qz, "w": qw}},
        "__recorded": when,
        "__topic": TF_TOPIC,
    }


def _pose_of(doc: dict[str, Any]) -> Pose:
    t, r = doc["transform"]["translation"], doc["transform"]["rotation"]
    return Pose((t["x"], t["y"], t["z"]), (r["x"], r["y"], r["z"], r["w"]), doc["header"]["frame_id"])


def poses_between(store: Store, neem_id: str, child: str, begin: float, end: float) -> list[tuple[float, Pose]]:
    """Every transform of ``child`` stamped in [begin, end], in time order (KnowRob's
    ``tf_mng_trajectory/4``)."""
    found = []
    for doc in store.read_documents(neem_id, "tf"):
        if doc.get("child_frame_id") != child:
            continue
        stamp = unix_seconds((doc.get("header") or {}).get("stamp"))
        if stamp is not None and begin <= stamp <= end:
            found.append((stamp, _pose_of(doc)))
    found.sort(key=lambda item: item[0])
    return found


def pose_at(store: Store, neem_id: str, child: str, at: float | None) -> tuple[float, Pose] | None:
    """The latest transform of ``child`` stamped at or before ``at`` (any time when None), with
    its stamp; None when there is none. Reads the NEEM's tf collection in one pass."""
    best: tuple[float, dict[str, Any]] | None = None
    for doc in store.read_documents(neem_id, "tf"):
        if doc.get("child_frame_id") != child:
            continue
        stamp = unix_seconds((doc.get("header") or {}).get("stamp"))
        if stamp is None or (at is not None and stamp > at):
            continue
        if best is None or stamp >= best[0]:
            best = (stamp, doc)
    if best is None:
        return None
    stamp, doc = best
    return stamp, _pose_of(doc)
