"""Robot code written for KnowRob 2.x logs into our NEEMs: a usage of neem-interface's
predicates of our own (downloads nothing), the REAL neem-interface.pl consulted unchanged (from
env NEEM_INTERFACE_PL or the project's mirror of code-iai/neem-interface; skipped when absent),
neem_interface_python's method names (``oracle.service.neem_interface``), and ``prolog --create``."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from oracle.bridge import Bridge
from oracle.neem.writer import NeemLogger
from oracle.service.neem_interface import InProcess, NEEMInterface, TfPoint
from oracle.store import open_store

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")

MIRROR = Path("/work/.mirror/code-iai+neem-interface/repo")
ENV = "http://example.org/env#"
URDF_ARM = """<?xml version="1.0"?>
<robot name="arm"><link name="base_link"/><link name="forearm"/><link name="gripper"/>
<joint name="elbow" type="revolute"><parent link="base_link"/><child link="forearm"/></joint>
<joint name="wrist" type="fixed"><parent link="forearm"/><child link="gripper"/></joint></robot>"""
URDF_ROOM = """<?xml version="1.0"?>
<robot name="kitchen"><link name="room"/><link name="table"/>
<joint name="table_joint" type="fixed"><parent link="room"/><child link="table"/></joint></robot>"""
OWL = """<?xml version="1.0"?>
<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#">
  <owl:Ontology rdf:about="http://example.org/NAME"/>
  <owl:NamedIndividual rdf:about="http://example.org/NAME#THING"/>
</rdf:RDF>"""


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


def files(tmp_path: Path) -> dict[str, str]:
    (tmp_path / "env.owl").write_text(OWL.replace("NAME", "env").replace("THING", "Kitchen"))
    (tmp_path / "agent.owl").write_text(OWL.replace("NAME", "agent").replace("THING", "Robot"))
    (tmp_path / "arm.urdf").write_text(URDF_ARM)
    (tmp_path / "room.urdf").write_text(URDF_ROOM)
    return {k: str(tmp_path / v) for k, v in
            (("env_owl", "env.owl"), ("agent_owl", "agent.owl"), ("agent_urdf", "arm.urdf"), ("env_urdf", "room.urdf"))}


def real_neem_interface(tmp_path: Path) -> Path | None:
    """The real file: env NEEM_INTERFACE_PL, else the mirror's HEAD (a bare repository)."""
    given = os.environ.get("NEEM_INTERFACE_PL")
    if given:
        return Path(given) if Path(given).is_file() else None
    if shutil.which("git") is None or not MIRROR.exists():
        return None
    shown = subprocess.run(["git", "-C", str(MIRROR), "show", "HEAD:neem-interface.pl"], capture_output=True)
    if shown.returncode != 0:
        return None
    path = tmp_path / "neem-interface.pl"
    path.write_bytes(shown.stdout)
    return path


def new_neem(tmp_path: Path, onto, name: str = "ep") -> tuple[object, Bridge]:
    store = open_store(tmp_path / "s.sqlite")
    log = NeemLogger.create(store, onto, user=name, neem_id=name)
    log.close()
    return store, Bridge(store, log.neem_id, onto)


def check_loaded_back(bridge: Bridge) -> None:
    """What a reader of the episode asks, on the NEEM loaded back from the dump."""
    q = bridge.query
    (row,) = q("kb_call((is_episode(E), is_setting_for(E, A), has_subevent(A, S)), any)")
    assert q(f"kb_call(action_succeeded('{row['S']}'), any)")
    assert q(f"kb_call(event_interval('{row['A']}', 100.0, 110.0), any)")
    (part,) = q(f"kb_call(has_participant('{row['S']}', '{ENV}Cup'), any)")
    roles = q(f"kb_call(has_role('{ENV}Cup', R) during '{row['S']}'), kb_call(has_type(R, soma:'Patient'), any)")
    assert len(roles) == 1
    (pose,) = q(f"kb_call(is_at('{ENV}Cup', [map, P, _]) until 103.0)")
    assert pose["P"] == [1.0, 2.0, 0.8]
    links = {r["L"] for r in q("kb_call(is_urdf_link(L), any)")}
    assert {"http://example.org/agent#base_link", "http://example.org/env#table"} <= links
    assert q("kb_call((is_urdf_joint(J), has_child_link(J, 'http://example.org/agent#forearm')), any)")


def test_our_own_usage_of_the_predicates(tmp_path, onto) -> None:
    """The predicates neem-interface uses, used as it uses them, in a file of our own."""
    f = files(tmp_path)
    (tmp_path / "usage.pl").write_text(f"""
:- use_module(library('db/mongo/client')).
run(Dir) :-
    mng_drop(roslog, tf), drop_graph(user), tf_logger_enable,
    load_owl('{f["env_owl"]}'),
    urdf_load('http://example.org/agent#Robot', '{f["agent_urdf"]}', [load_rdf]),
    urdf_load('http://example.org/env#Kitchen', '{f["env_urdf"]}', [load_rdf, prefix('k_')]),
    kb_project([ new_iri(E, soma:'Episode'), is_episode(E), new_iri(A, dul:'Action'), is_action(A),
                 new_iri(TI, dul:'TimeInterval'), holds(A, dul:'hasTimeInterval', TI),
                 holds(TI, soma:'hasIntervalBegin', 100.0),
                 new_iri(T, dul:'Task'), has_type(T, soma:'PhysicalTask'), executes_task(A, T),
                 is_setting_for(E, A), is_performed_by(A, 'http://example.org/agent#Robot') ]),
    kb_project([ new_iri(S, dul:'Action'), has_type(S, soma:'Action'), new_iri(T2, soma:'PickingUp'),
                 has_type(T2, soma:'PickingUp'), executes_task(S, T2), holds(A, dul:hasConstituent, S) ]),
    kb_project(event_interval(S, 101.0, 105.0)),
    kb_project([ has_participant(S, '{ENV}Cup'), has_type(R, soma:'Patient'),
                 has_role('{ENV}Cup', R) during S, task_role(T2, R) ]),
    kb_project(action_succeeded(S)),
    time_scope(=(102.0), =<('Infinity'), FS), tf_set_pose('{ENV}Cup', [map, [1.0, 2.0, 0.8], [0.0, 0.0, 0.0, 1.0]], FS),
    ignore(kb_unproject(triple(TI, soma:'hasIntervalEnd', double('Infinity')))),
    kb_project(holds(TI, soma:'hasIntervalEnd', 110.0)),
    memorize(Dir), drop_graph(user), tf_logger_disable.
""")
    store, bridge = new_neem(tmp_path, onto)
    try:
        assert bridge.query(f"consult('{tmp_path / 'usage.pl'}'), run('{tmp_path / 'dump'}')")
        assert bridge.query("kb_call(is_episode(_), any)") == []  # drop_graph(user) cleared the memory
        assert bridge.query(f"remember('{tmp_path / 'dump'}')")
        check_loaded_back(bridge)
    finally:
        bridge.close()
        store.close()


def test_the_real_neem_interface_logs_an_episode_that_loads_back(tmp_path, onto) -> None:
    real = real_neem_interface(tmp_path)
    if real is None:
        pytest.skip(f"neem-interface.pl not found (set NEEM_INTERFACE_PL, or mirror code-iai/neem-interface at {MIRROR})")
    f = files(tmp_path)
    store, bridge = new_neem(tmp_path, onto)
    try:
        ni = NEEMInterface(InProcess(bridge), real)
        top = ni.start_episode("soma:'PhysicalTask'", f["env_owl"], "http://example.org/env#Kitchen", f["env_urdf"], "k_",
                               f["agent_owl"], "http://example.org/agent#Robot", f["agent_urdf"], start_time=100.0)
        sub = ni.add_subaction_with_task(top, task_type="soma:'PickingUp'", start_time=101.0, end_time=105.0)
        ni.add_participant_with_role(sub, f"{ENV}Cup", "soma:'Patient'")
        ni.set_succeeded(sub)
        ni.assert_tf_trajectory([TfPoint(f"{ENV}Cup", "map", (1.0, 2.0, 0.8), (0.0, 0.0, 0.0, 1.0), 102.0),
                                 TfPoint(f"{ENV}Cup", "map", (1.5, 2.0, 0.8), (0.0, 0.0, 0.0, 1.0), 104.0)])
        assert ni.get_interval_for_event(sub) == (101.0, 105.0)
        trajectory = ni.get_tf_trajectory(f"{ENV}Cup", 100.0, 110.0)
        assert [stamp for stamp, _ in trajectory] == [102.0, 104.0] and trajectory[1][1][1] == [1.5, 2.0, 0.8]
        assert top in ni.get_all_actions() and sub in ni.get_all_actions()
        assert any("PickingUp" in t for t in ni.get_tasks_for_action(sub))
        ni.stop_episode(str(tmp_path / "neems"), end_time=110.0)
        (dump,) = (tmp_path / "neems").iterdir()  # mem_episode_stop memorizes to NeemPath/<time>
    finally:
        bridge.close()
        store.close()
    # the dump loads back with `oracle load` into another store, and is queryable there
    other = tmp_path / "other.sqlite"
    done = subprocess.run([sys.executable, "-m", "oracle", "load", str(dump), "--store", str(other), "--neem", "back"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    store2 = open_store(other)
    bridge2 = Bridge(store2, "back", onto)
    try:
        check_loaded_back(bridge2)
    finally:
        bridge2.close()
        store2.close()


def test_the_real_neem_interfaces_other_predicates_write_what_they_say(tmp_path, onto) -> None:
    """The predicates of the real neem-interface.pl that no episode above calls: parameters and
    regions, a grasping orientation, a comment, a perceived object's mesh shape, an event begun
    and ended now (with the agent's role during it), a diagnosis, the current pose."""
    real = real_neem_interface(tmp_path)
    if real is None:
        pytest.skip(f"neem-interface.pl not found (set NEEM_INTERFACE_PL, or mirror code-iai/neem-interface at {MIRROR})")
    f = files(tmp_path)
    store, bridge = new_neem(tmp_path, onto)
    soma = "http://www.ease-crc.org/ont/SOMA.owl#"
    try:
        ni = NEEMInterface(InProcess(bridge), real)
        top = ni.start_episode("soma:'PhysicalTask'", f["env_owl"], "http://example.org/env#Kitchen", f["env_urdf"], "k_",
                               f["agent_owl"], "http://example.org/agent#Robot", f["agent_urdf"], start_time=100.0)
        sub = ni.add_subaction_with_task(top, task_type="soma:'Grasping'", start_time=101.0, end_time=105.0)
        q = bridge.query
        (task,) = [r["T"] for r in q(f"kb_call(executes_task('{sub}', T), any)")]
        assert q(f"add_parameter('{task}', soma:'GraspingOrientation', soma:'Region')")
        params = q(f"kb_call((has_parameter('{task}', P), has_type(P, soma:'GraspingOrientation')), any)")
        assert len(params) == 1
        # the assignment neem-interface scopes to [0.0, 0.1]: there and only there
        p = params[0]["P"]
        assert q(f"kb_call(has_assignment('{p}', R) during [0.0, 0.1]), kb_call(has_type(R, soma:'Region'), any)")
        assert not q(f"kb_call(has_assignment('{p}', _) during [5.0, 6.0])")
        assert q(f"add_grasping_parameter('{sub}', soma:'FrontGrasp')")
        (region,) = q(f"kb_call((has_region('{sub}', G), has_type(G, soma:'FrontGrasp')), any)")
        assert q(f"kb_call((has_parameter('{task}', C), has_type(C, soma:'GraspingOrientation'),"
                 f" holds(C, dul:classifies, '{region['G']}')), any)")
        assert q(f"add_comment('{sub}', 'the cup was wet')")
        (comment,) = q(f"kb_call(triple('{sub}', rdfs:comment, C), any)")
        assert comment["C"] == "the cup was wet"
        assert q(f"belief_perceived_at(soma:'Cup', 'package://kitchen/cup.dae', [0.0, 0.0, 0.0, 1.0], '{ENV}Cup2')")
        (shape,) = q(f"kb_call((triple('{ENV}Cup2', soma:hasShape, S), triple(S, dul:hasRegion, M),"
                     f" has_type(M, soma:'MeshShape'), triple(M, soma:hasFilePath, F)), any)")
        assert shape["F"] == "package://kitchen/cup.dae"
        assert q(f"kb_call(has_type('{ENV}Cup2', soma:'Cup'), any)")
        assert q(f"belief_perceived_at(soma:'Bowl', '{ENV}Bowl1')") and q(f"kb_call(has_type('{ENV}Bowl1', soma:'Bowl'), any)")
        # an event begun now and ended now: its interval in the clock's present, the agent's role during it
        (event,) = [r["E"] for r in q(f"kb_call((has_subevent('{top}', E), executes_task(E, T), has_type(T, soma:'Grasping')), any)")]
        before = float(q("get_time(T)")[0]["T"])
        assert q(f"mem_event_begin('{event}')")
        assert q(f"mem_event_end('{event}')")
        after = float(q("get_time(T)")[0]["T"])
        ends = [float(r["E"]) for r in q(f"kb_call((triple('{event}', dul:hasTimeInterval, I), triple(I, soma:hasIntervalEnd, E)), any)")]
        assert any(before <= end <= after for end in ends)
        assert q(f"kb_call(has_role('http://example.org/agent#Robot', R) during '{event}'), kb_call(has_type(R, soma:'AgentRole'), any)")
        assert q(f"mem_event_add_diagnosis('{event}', '{soma}Diagnosis_1')")
        assert q(f"kb_call(satisfies('{event}', '{soma}Diagnosis_1'), any)")
        # the pose now (mem_tf_get/4 reads at the current scope); a pose set at 102 holds now
        assert q(f"mem_tf_set('{ENV}Cup', map, [1.0, 2.0, 0.8], [0.0, 0.0, 0.0, 1.0], 102.0)")
        (now,) = q(f"mem_tf_get('{ENV}Cup', map, P, R)")
        assert now["P"] == [1.0, 2.0, 0.8] and now["R"] == [0.0, 0.0, 0.0, 1.0]
        assert q(f"mem_tf_get('{ENV}Cup', map, [1.0, 2.0, 0.8], _, 102.0)")
        assert not q(f"mem_tf_get('{ENV}Cup', map, _, _, 101.0)")  # not yet there
    finally:
        bridge.close()
        store.close()


def test_prolog_create_starts_a_new_neem(tmp_path) -> None:
    store = tmp_path / "s.sqlite"
    run = lambda *a: subprocess.run([sys.executable, "-m", "oracle", "prolog", "--store", str(store), *a],  # noqa: E731
                                    capture_output=True, text=True)
    done = run("--neem", "fresh", "--create", "-q", "-g", "kb_project(has_type(x, soma:'Episode')), kb_call(is_episode(x), any)")
    assert done.returncode == 0, done.stderr
    again = run("--neem", "fresh", "--create", "-q", "-g", "true")
    assert again.returncode == 1 and "already exists" in again.stderr and len(again.stderr.strip().splitlines()) == 1
