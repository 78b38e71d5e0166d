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
