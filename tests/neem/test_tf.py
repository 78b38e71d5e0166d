"""Object poses with perceptions: KnowRob's tf layout in the NEEM, is_at/2 in Prolog, dumps."""

from __future__ import annotations

from datetime import datetime, timedelta, timezone

import pytest

from oracle.bridge import Bridge
from oracle.errors import LoggingError
from oracle.neem.tf import Pose, pose_at
from oracle.neem.writer import NeemLogger
from oracle.store.dump import export_neem, load_dump
from oracle.store.sqlite import SQLiteStore
from tests.store.conftest import make_store

T0 = datetime(2024, 5, 6, 8, 30)


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


@pytest.fixture()
def logged(tmp_path, onto):
    store = SQLiteStore(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="alice")
    log.perceive("green_mug", T0, pose=Pose((1.0, 2.0, 0.8)))
    log.perceive("green_mug", T0 + timedelta(minutes=5), pose=Pose((3.0, 2.0, 0.8), (0.0, 0.0, 0.7071068, 0.7071068), "table"))
    log.perceive("thermos", T0)  # no pose: no transform
    log.flush()
    yield store, log
    store.close()


def test_transforms_in_knowrobs_layout(logged):
    store, log = logged
    docs = list(store.read_documents(log.neem_id, "tf"))
    assert len(docs) == 2
    first = min(docs, key=lambda d: d["header"]["seq"])
    assert first["child_frame_id"] == log.object_iri("green_mug").rsplit("#", 1)[1]
    assert first["header"]["frame_id"] == "map" and isinstance(first["header"]["stamp"], datetime)
    assert first["transform"] == {"translation": {"x": 1.0, "y": 2.0, "z": 0.8},
                                  "rotation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}
    assert first["__topic"] == "/tf"


def test_pose_at_a_time_is_the_latest_before_it(logged):
    store, log = logged
    frame = log.object_iri("green_mug").rsplit("#", 1)[1]
    t0 = T0.replace(tzinfo=timezone.utc).timestamp()  # a naive time is the wall clock, read as UTC
    found = pose_at(store, log.neem_id, frame, t0 + 60)
    assert found is not None and found[1].position == (1.0, 2.0, 0.8)
    assert pose_at(store, log.neem_id, frame, t0 - 1) is None
    latest = pose_at(store, log.neem_id, frame, None)
    assert latest is not None and latest[1].frame == "table"


def test_is_at_over_the_bridge_and_through_a_dump(logged, tmp_path):
    store, log = logged
    mug = log.object_iri("green_mug")
    t0 = T0.replace(tzinfo=timezone.utc).timestamp()
    bridge = Bridge(store, log.neem_id)
    try:
        (row,) = bridge.query(f"is_at('{mug}', [Ref, [X, _, _], _])")
        assert row["Ref"] == "table" and row["X"] == 3.0
        (row,) = bridge.query(f"kb_call(is_at('{mug}', [Ref, [X, _, _], _]) until {t0 + 60})")
        assert row["Ref"] == "map" and row["X"] == 1.0
        assert bridge.query(f"kb_call(is_at('{mug}', _) until {t0 - 1})") == []
    finally:
        bridge.close()
    export_neem(store, log.neem_id, tmp_path / "dump")
    other = make_store("mongomock", tmp_path)
    (loaded,) = load_dump(other, tmp_path / "dump")
    frame = mug.rsplit("#", 1)[1]
    assert pose_at(other, loaded, frame, None) == pose_at(store, log.neem_id, frame, None)


@pytest.mark.parametrize("pose", [
    lambda: Pose((1.0, 2.0)),  # two coordinates
    lambda: Pose((1.0, 2.0, float("nan"))),
    lambda: Pose((1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 2.0)),  # not a unit quaternion
    lambda: Pose((1.0, 2.0, 3.0), frame=""),
])  # fmt: skip
def test_bad_poses_are_one_line_errors(pose):
    with pytest.raises(LoggingError, match="pose:"):
        pose()


def test_a_bad_pose_argument_writes_nothing(tmp_path, onto):
    store = SQLiteStore(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="alice")
    before = store.count(log.neem_id)
    with pytest.raises(LoggingError, match="pose must be a Pose"):
        log.perceive("green_mug", T0, pose=(1.0, 2.0, 3.0))  # type: ignore[arg-type]
    log.flush()
    assert store.count(log.neem_id) == before and list(store.read_documents(log.neem_id, "tf")) == []
    store.close()


def test_is_at_walks_the_frame_chain_to_map(tmp_path, onto):
    """A small tf tree recorded by the logger (the thermos in map, turned 90 degrees about z;
    the mug on the thermos' frame; the apple on the mug's, turned 90 degrees): the poses in map
    equal the hand computation to 1e-9, in SQLite through Prolog, and so do KnowRob's
    tf_get_pose/4 and tf_mng_trajectory/4."""
    import math

    h = math.sqrt(0.5)
    store = SQLiteStore(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user="alice")
    log.perceive("thermos", T0, pose=Pose((1.0, 2.0, 0.0), (0.0, 0.0, h, h), "map"))
    log.perceive("green_mug", T0, pose=Pose((0.5, 0.0, 0.8), frame="Object_thermos"))
    log.perceive("apple", T0, pose=Pose((0.1, 0.0, 0.0), (0.0, 0.0, h, h), "Object_green_mug"))
    log.perceive("thermos", T0 + timedelta(minutes=1), pose=Pose((5.0, 5.0, 0.0), frame="map"))
    log.flush()
    t0 = T0.replace(tzinfo=timezone.utc).timestamp()
    bridge = Bridge(store, log.neem_id, onto)
    try:
        def pose(obj: str, frame: str, at: float) -> tuple[list[float], list[float]]:
            (row,) = bridge.query(f"kb_call(is_at(odb:'Object_{obj}', ['{frame}', P, R]) until {at})")
            return row["P"], row["R"]

        def close(a: list[float], b: list[float]) -> bool:
            return all(abs(x - y) <= 1e-9 for x, y in zip(a, b, strict=True))

        p, r = pose("green_mug", "map", t0 + 10)  # (1,2,0) + Rz90 (0.5,0,0.8)
        assert close(p, [1.0, 2.5, 0.8]) and close(r, [0.0, 0.0, h, h])
        p, r = pose("apple", "map", t0 + 10)  # the mug's (1,2.5,0.8) + Rz90 (0.1,0,0); Rz180
        assert close(p, [1.0, 2.6, 0.8]) and close(r, [0.0, 0.0, 1.0, 0.0])
        p, _ = pose("apple", "Object_thermos", t0 + 10)  # an ancestor that is not map
        assert close(p, [0.6, 0.0, 0.8])
        p, _ = pose("green_mug", "map", t0 + 120)  # the thermos moved, no longer turned
        assert close(p, [5.5, 5.0, 0.8])
        assert bridge.query(f"kb_call(is_at(odb:'Object_green_mug', [kitchen, _, _]) until {t0 + 10})") == []
        (got,) = bridge.query(f"time_scope(=({t0 + 10}), =({t0 + 10}), Q), tf_get_pose(odb:'Object_apple', [map, P, _], Q, F),"
                              " get_dict(time, F, T), get_dict(since, T, S)")  # fmt: skip
        assert close(got["P"], [1.0, 2.6, 0.8]) and got["S"] == t0
        (traj,) = bridge.query(f"tf_mng_trajectory(odb:'Object_thermos', {t0 - 1}, {t0 + 100}, L), length(L, N)")
        assert traj["N"] == 2
    finally:
        bridge.close()
        store.close()
