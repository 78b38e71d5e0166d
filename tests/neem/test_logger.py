"""NEEM logger: thesis 3.4-3.5 semantics, bad input, privacy, crash safety, and the CLI."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from dataclasses import replace
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pytest

from oracle.cli import main
from oracle.errors import LoggingError
from oracle.neem.importing import import_chains
from oracle.neem.lifecycle import persist
from oracle.neem.query import executed_actions, summarize_neem
from oracle.neem.writer import NeemLogger
from oracle.namespaces import DUL, OWL, SOMA
from oracle.store import RDF_TYPE, Scope, TriplePattern, Var
from oracle.store.ids import alias_of, is_object_id, resolve_neem
from oracle.store.model import HIERARCHY
from oracle.store.sqlite import SQLiteStore
from oracle.store.tbox import tbox_from_graph
from tests.store.conftest import backend, make_store, store  # noqa: F401 - the shared backend fixtures

T0 = datetime(2024, 5, 6, 8, 30)  # a Monday morning, wall clock


@pytest.fixture(scope="module")
def onto():
    from oracle.ontology import build_ontology

    return build_ontology()


@pytest.fixture(scope="module")
def tbox(onto):
    return tbox_from_graph(onto.graph)


@pytest.fixture(scope="module")
def small_tbox(tbox):
    """Only the named class and property hierarchy: mongomock scans every document on every
    lookup, so its NEEMs carry the part of the TBox that closures need, nothing more."""
    keep = tuple(t for t in tbox.triples if t.p in HIERARCHY and "#_:" not in t.s and "#_:" not in str(t.o))
    return replace(tbox, triples=keep, annotations=())




@pytest.fixture
def tbox_for(backend, tbox, small_tbox):
    return small_tbox if backend == "mongomock" else tbox


@pytest.fixture
def logger(store, onto, tbox_for):
    return NeemLogger.create(store, onto, user="alice", tbox=tbox_for)


def objects_of(store, neem, s, p):
    return sorted(str(d["o"]) for d in store.find(neem, s=s, p=p))


def test_action_is_stored_the_knowrob_way(logger, store, onto):
    a = logger.action("pour(thermos, green_mug)", T0, T0 + timedelta(seconds=12))
    neem = logger.neem_id
    assert objects_of(store, neem, a.iri, RDF_TYPE) == sorted([str(DUL.Action), str(OWL.NamedIndividual)])
    (task,) = objects_of(store, neem, a.iri, str(DUL.executesTask))
    assert onto.iri("pour") in objects_of(store, neem, task, RDF_TYPE)
    # pour's reference role is the thermos (poured object), its target the mug (recipient)
    rows = list(store.match(neem, [
        TriplePattern(task, str(DUL.isTaskOf), Var("R")),
        TriplePattern(Var("R"), str(DUL.classifies), Var("O")),
        TriplePattern(Var("R"), RDF_TYPE, Var("C")),
    ]))  # fmt: skip
    roles = {(r["C"], r["O"]) for r in rows if r["C"] != str(OWL.NamedIndividual)}
    assert roles == {(str(SOMA.PouredObject), logger.object_iri("thermos")),
                     (str(SOMA.RecipientRole), logger.object_iri("green_mug"))}  # fmt: skip
    participants = {d["o"] for d in store.find(neem, s=a.iri, p=str(DUL.hasParticipant), exact=True)}
    assert participants == {logger.object_iri("thermos"), logger.object_iri("green_mug")}
    assert objects_of(store, neem, logger.object_iri("thermos"), RDF_TYPE)[0] in (onto.iri("thermos"), str(OWL.NamedIndividual))
    (performer,) = objects_of(store, neem, a.iri, str(SOMA.isPerformedBy))
    assert performer.endswith("Agent_robot")
    (interval,) = objects_of(store, neem, a.iri, str(DUL.hasTimeInterval))
    assert onto.vocab.part_of_day("Morning") in objects_of(store, neem, interval, RDF_TYPE)
    (begin,) = store.match(neem, [TriplePattern(interval, str(SOMA.hasIntervalBegin), Var("B")),
                                  TriplePattern(interval, str(SOMA.hasIntervalEnd), Var("E"))])  # fmt: skip
    assert begin == {"B": T0.replace(tzinfo=timezone.utc).timestamp(), "E": T0.replace(tzinfo=timezone.utc).timestamp() + 12}


def test_type_closure_reaches_soma_and_dul(logger, store, onto):
    a = logger.action("pick(green_mug)", T0)
    actions = {d["s"] for d in store.find(logger.neem_id, p=RDF_TYPE, o=str(DUL.Event))}
    assert a.iri in actions
    (interval,) = objects_of(store, logger.neem_id, a.iri, str(DUL.hasTimeInterval))
    intervals = {d["s"] for d in store.find(logger.neem_id, p=RDF_TYPE, o=onto.vocab.time_of_day)}
    assert interval in intervals
    # isPerformedBy is a sub-property of hasParticipant: KnowRob's p* finds the robot too
    assert any(o.endswith("Agent_robot") for o in objects_of(store, logger.neem_id, a.iri, str(DUL.hasParticipant)))


def test_idle_gap_of_20_seconds_becomes_an_idle_task(logger, store, onto):
    logger.action("pick(green_mug)", T0, T0 + timedelta(seconds=5))
    short = logger.action("place(green_mug)", T0 + timedelta(seconds=24.9), T0 + timedelta(seconds=30))
    long = logger.action("pick(green_mug)", T0 + timedelta(seconds=50), T0 + timedelta(seconds=55))
    assert short.idle is None and long.idle is not None
    views = list(executed_actions(store, logger.neem_id))
    assert [v.task_class for v in views] == [onto.iri("pick"), onto.iri("place"), onto.vocab.idle_task, onto.iri("pick")]
    idle = views[2]
    assert (idle.end - idle.begin) == 20.0 and idle.participants == ()


def test_time_of_day_follows_the_wall_clock(logger, store, onto):
    for hour, part in ((3, "Night"), (9, "Morning"), (13, "Midday"), (19, "Evening"), (23, "Night")):
        moment = datetime(2024, 5, 7, hour, 0, tzinfo=timezone(timedelta(hours=2)))
        assert logger.action("pick(green_mug)", moment).part_of_day == part


def test_available_tasks_are_imagined_plans_of_the_executed_call(logger, store, onto):
    a = logger.action("pour(thermos, green_mug)", T0, available=["pick(green_mug)", "pour(thermos, green_mug)"])
    neem = logger.neem_id
    assert str(SOMA.MentalAction) in objects_of(store, neem, a.imagining, RDF_TYPE)
    rows = list(store.match(neem, [
        TriplePattern(a.imagining, str(DUL.executesTask), Var("I")),
        TriplePattern(Var("I"), RDF_TYPE, str(SOMA.Imagining)),
        TriplePattern(a.imagining, logger.vocab.imagines_situation, Var("P")),
        TriplePattern(Var("P"), RDF_TYPE, str(SOMA.ActionExecutionPlan)),
        TriplePattern(Var("P"), str(SOMA.isPlanFor), Var("T")),
    ]))  # fmt: skip
    assert len(rows) == 2
    # the executed task is the action's own individual, of the class of one of the options
    plan_classes = {c for r in rows for c in objects_of(store, neem, r["T"], RDF_TYPE)}
    assert a.task not in {r["T"] for r in rows} and onto.iri("pour") in plan_classes
    assert onto.iri("pour") in objects_of(store, neem, a.task, RDF_TYPE)


def test_each_action_executes_its_own_task_with_roles_scoped_to_the_action(logger, store, onto):
    first = logger.action("pour(thermos, green_mug)", T0, T0 + timedelta(seconds=12))
    second = logger.action("pour(thermos, green_mug)", T0 + timedelta(seconds=60), T0 + timedelta(seconds=70))
    later = logger.action("pick(green_mug)", T0 + timedelta(seconds=100))
    neem = logger.neem_id
    tasks = {a.iri: objects_of(store, neem, a.iri, str(DUL.executesTask)) for a in (first, second)}
    assert len({t for ts in tasks.values() for t in ts}) == 2  # one task individual per action
    idle_task = objects_of(store, neem, later.idle, str(DUL.executesTask))
    assert idle_task and not set(idle_task) & {t for ts in tasks.values() for t in ts}
    for action in (first, second):
        rows = list(store.match(neem, [
            TriplePattern(action.task, str(DUL.isTaskOf), Var("R")),
            TriplePattern(Var("R"), str(DUL.classifies), logger.object_iri("thermos")),
        ]))  # fmt: skip
        (role,) = {r["R"] for r in rows}
        (doc,) = store.find(neem, s=role, p=str(DUL.classifies), exact=True)
        scope = doc["scope"]["time"]
        assert (float(str(scope["since"])), float(str(scope["until"]))) == (action.begin, action.end)
        # the participation itself holds always, as neem-interface's has_participant
        (part,) = store.find(neem, s=action.iri, p=str(DUL.hasParticipant), o=logger.object_iri("thermos"), exact=True)
        assert float(str(part["scope"]["time"]["since"])) == 0.0
    # a role of the first pour does not classify the thermos during the second one
    during_second = {d["s"] for d in store.find(neem, p=str(DUL.classifies), o=logger.object_iri("thermos"),
                                                scope=Scope(second.begin + 1, second.begin + 1))}  # fmt: skip
    assert len(during_second) == 1


def test_preference_order_ranks_plans(logger, store):
    order = logger.preference([("pick(green_mug)", 0.7), ("place(green_mug)", 0.2)], T0)
    rows = list(store.match(logger.neem_id, [
        TriplePattern(Var("R"), logger.vocab.imagines_preference, order),
        TriplePattern(Var("R"), str(DUL.executesTask), Var("T")),
        TriplePattern(Var("T"), RDF_TYPE, str(SOMA.Reasoning)),
        TriplePattern(order, str(SOMA.orders), Var("E")),
        TriplePattern(Var("E"), str(SOMA.encapsulates), Var("P")),
        TriplePattern(Var("P"), str(SOMA.isPlanFor), Var("K")),
        TriplePattern(Var("E"), logger.vocab.has_rank, Var("N")),
        TriplePattern(Var("E"), logger.vocab.has_score, Var("S")),
    ]))  # fmt: skip
    ranked = sorted((r["N"], r["K"].rsplit("#", 1)[1], r["S"]) for r in rows)
    assert ranked == [(1, "Task_pick__green_mug", 0.7), (2, "Task_place__green_mug", 0.2)]
    assert str(SOMA.PreferenceOrder) in objects_of(store, logger.neem_id, order, RDF_TYPE)


def test_perceived_objects_are_typed_from_their_first_perception(logger, store, onto):
    iri = logger.perceive("thermos", T0)
    (doc,) = store.find(logger.neem_id, s=iri, p=RDF_TYPE, o=onto.iri("thermos"))
    assert doc["scope"]["time"]["since"].to_decimal() == doc["scope"]["time"]["since"].to_decimal()
    assert float(doc["scope"]["time"]["since"].to_decimal()) == T0.replace(tzinfo=timezone.utc).timestamp()
    assert logger.perceive("thermos", T0 + timedelta(seconds=1)) == iri
    assert len(list(store.find(logger.neem_id, s=iri, p=RDF_TYPE, exact=True))) == 2  # class + NamedIndividual


@pytest.mark.parametrize(
    "call, begin, end, message",
    [
        ("pour(thermos", T0 + timedelta(hours=1), None, "malformed action"),
        ("fly(green_mug)", T0 + timedelta(hours=1), None, "unknown task 'fly'"),
        ("pick(unicorn)", T0 + timedelta(hours=1), None, "unknown object 'unicorn'"),
        ("pick(green_mug)", T0 + timedelta(hours=1), T0, "ends .* before it starts"),
        ("pick(green_mug)", T0 - timedelta(hours=1), None, "time goes backwards"),
    ],
)
def test_bad_input_is_refused_and_nothing_logged_is_lost(logger, store, call, begin, end, message):
    logger.action("pick(green_mug)", T0, T0 + timedelta(seconds=3), action_id="first")
    before = store.count(logger.neem_id)
    with pytest.raises(LoggingError, match=message):
        logger.action(call, begin, end)
    assert store.count(logger.neem_id) == before
    assert [v.iri.rsplit("#", 1)[1] for v in executed_actions(store, logger.neem_id)] == ["Action_first"]


def test_duplicate_action_ids_are_refused(logger, store):
    logger.action("pick(green_mug)", T0, action_id="a1")
    with pytest.raises(LoggingError, match="duplicate action id 'a1'"):
        logger.action("place(green_mug)", T0 + timedelta(seconds=1), action_id="a1")
    resumed = NeemLogger(store, logger.onto, logger.neem_id)  # also after reopening
    with pytest.raises(LoggingError, match="duplicate action id"):
        resumed.action("place(green_mug)", T0 + timedelta(seconds=1), action_id="a1")


def test_resumed_logger_keeps_time_order_and_idle(logger, store, onto):
    logger.action("pick(green_mug)", T0, T0 + timedelta(seconds=5))
    resumed = NeemLogger(store, onto, logger.neem_id)
    with pytest.raises(LoggingError, match="time goes backwards"):
        resumed.action("place(green_mug)", T0 - timedelta(seconds=2))
    assert resumed.action("place(green_mug)", T0 + timedelta(seconds=60)).idle is not None


def test_writing_a_ranking_back_does_not_read_the_clock_but_the_next_action_does(logger, store, onto, monkeypatch):
    # rank writes its ranking into a NEEM of any length: reading every action's interval to
    # resume the clock (needed only to check the time of the next timed entry) is left to then.
    logger.action("pick(green_mug)", T0, T0 + timedelta(seconds=5))
    logger.flush()
    reads = []
    real = NeemLogger._resume_clock
    monkeypatch.setattr(NeemLogger, "_resume_clock", lambda self: reads.append(1) or real(self))
    resumed = NeemLogger(store, onto, logger.neem_id)
    resumed.preference([("place(green_mug)", 0.5)], T0 - timedelta(seconds=30))  # a decision before the last action
    resumed.flush()
    assert reads == []
    with pytest.raises(LoggingError, match="time goes backwards"):
        resumed.action("place(green_mug)", T0 - timedelta(seconds=2))
    assert reads == [1]


def test_overlapping_actions_are_logged_as_knowrob_events_may_overlap(logger, store, onto):
    """Two sensors firing at once: the second starts before the first ends. Starts stay ordered,
    and the idle gap runs from the latest end, also after reopening the NEEM."""
    logger.action("open(fridge)", T0, T0 + timedelta(seconds=40))
    overlapping = logger.action("pick(green_mug)", T0 + timedelta(seconds=5), T0 + timedelta(seconds=8))
    assert overlapping.idle is None
    resumed = NeemLogger(store, onto, logger.neem_id)
    with pytest.raises(LoggingError, match="time goes backwards"):
        resumed.action("place(green_mug)", T0 + timedelta(seconds=4))
    assert resumed.action("place(green_mug)", T0 + timedelta(seconds=50)).idle is None  # 10 s after the fridge closed
    assert resumed.action("close(fridge)", T0 + timedelta(seconds=90)).idle is not None
    assert [v.task_class.rsplit("#", 1)[1] for v in executed_actions(store, logger.neem_id)][:2] == ["open", "pick"]


def test_sessions_are_temporary_until_persisted(store, onto, tbox_for):
    tbox = tbox_for
    first = NeemLogger.start_session(store, onto, user="alice", tbox=tbox)
    first.action("pick(green_mug)", T0)
    second = NeemLogger.start_session(store, onto, user="alice", tbox=tbox)
    assert [i.id for i in store.neems()] == [second.neem_id]  # the first session was wiped
    second.action("pick(green_mug)", T0)
    persist(store, second.neem_id, "alice-monday")
    NeemLogger.start_session(store, onto, user="bob", tbox=tbox)
    kept = store.neem(resolve_neem(store, "alice-monday"))
    assert kept.id == second.neem_id  # persisting names the NEEM; its id stays
    assert not kept.temporary and summarize_neem(store, kept.id).actions == 1
    assert len(store.neems()) == 2


def test_group_commit_reports_what_is_durable(tmp_path, onto, tbox):
    store = SQLiteStore(tmp_path / "s.sqlite")
    logger = NeemLogger.create(store, onto, user="alice", tbox=tbox, commit_every=3)
    for i in range(4):
        logger.action("pick(green_mug)", T0 + timedelta(seconds=i))
    assert logger.committed == 3
    assert len(list(executed_actions(SQLiteStore(tmp_path / "s.sqlite"), logger.neem_id))) == 3
    logger.flush()
    assert logger.committed == 4


CHAINS = [
    {"user": "alice", "time": "2024-05-06T08:00:00", "action": "pour(thermos, green_mug)",
     "available": ["pick(green_mug)", "pour(thermos, green_mug)"], "duration": 10},
    {"user": "bob", "time": "2024-05-06T19:00:00", "action": "pick(green_mug)"},
    {"user": "alice", "time": "2024-05-06T08:01:00", "action": "pick(green_mug)", "end": "2024-05-06T08:01:05"},
]  # fmt: skip


def write_jsonl(path: Path, rows) -> Path:
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    return path


def test_import_logs_one_neem_per_user(tmp_path, store, onto, tbox_for):
    report = import_chains(store, onto, write_jsonl(tmp_path / "c.jsonl", CHAINS), tbox=tbox_for)
    assert report == {resolve_neem(store, "alice"): 2, resolve_neem(store, "bob"): 1}
    assert all(is_object_id(neem_id) for neem_id in report)
    alice = summarize_neem(store, resolve_neem(store, "alice"))
    assert alice.user == "alice" and alice.actions == 3  # pour, idle (50 s), pick
    assert alice.begin == datetime(2024, 5, 6, 8, tzinfo=timezone.utc).timestamp()


def test_import_error_names_the_line_and_writes_nothing(tmp_path, store, onto, tbox_for):
    # Every row is checked before the first is logged: a bad row anywhere leaves the store as it was.
    rows = CHAINS + [{"user": "alice", "time": "2024-05-06T07:00:00", "action": "pick(green_mug)"}]
    report: dict[str, int] = {}
    with pytest.raises(LoggingError, match=r"c\.jsonl:4: time goes backwards"):
        import_chains(store, onto, write_jsonl(tmp_path / "c.jsonl", rows), report=report, commit_every=50,
                      tbox=tbox_for)
    assert report == {}
    assert store.neems() == []


def test_cli_import_neems_export_load_persist(tmp_path, capsys):
    db = str(tmp_path / "cli.sqlite")
    chains = write_jsonl(tmp_path / "c.jsonl", CHAINS)
    assert main(["import", str(chains), "--store", db]) == 0
    printed = [line.split("\t") for line in capsys.readouterr().out.splitlines()]
    # the count `neems` shows: the two rows and the break between them, logged as an idle action
    assert [(name, count) for _, name, count in printed] == [
        ("alice", "3 actions (2 rows and 1 break, logged as idle actions)"), ("bob", "1 action")]
    alice, bob = (neem_id for neem_id, _, _ in printed)
    assert is_object_id(alice) and is_object_id(bob)
    assert main(["neems", "--store", db, "--json"]) == 0
    listing = json.loads(capsys.readouterr().out)
    assert [(n["id"], n["name"], n["user"], n["actions"]) for n in listing] == [(alice, "alice", "alice", 3),
                                                                               (bob, "bob", "bob", 1)]
    assert main(["export", "--store", db, "--out", str(tmp_path / "dump")]) == 0
    capsys.readouterr()
    other = f"sqlite://{tmp_path}/other.sqlite"
    assert main(["load", str(tmp_path / "dump" / bob), "--neem", "bob-copy", "--store", other]) == 0
    copy = capsys.readouterr().out.strip()
    assert is_object_id(copy) and copy != bob  # a new NEEM named bob-copy
    assert main(["load", str(tmp_path / "dump" / bob), "--store", other]) == 0
    assert capsys.readouterr().out.strip() == bob  # a dump keeps its id
    assert main(["persist", "--neem", "bob", "--as", "bob-kept", "--store", db]) == 0
    assert capsys.readouterr().out.strip() == bob
    assert main(["neems", "--store", db, "--json"]) == 0
    assert [(n["id"], n["name"]) for n in json.loads(capsys.readouterr().out)] == [(alice, "alice"), (bob, "bob-kept")]
    assert main(["export", "--store", db, "--neem", "bob-kept", "--out", str(tmp_path / "kept")]) == 0
    assert capsys.readouterr().out.startswith(f"{bob}: ")
    assert main(["persist", "--neem", "nobody", "--as", "x", "--store", db]) == 1
    assert "no NEEM 'nobody'" in capsys.readouterr().err
    assert main(["persist", "--neem", bob, "--as", "alice", "--store", db]) == 1
    assert f"taken by NEEM {alice!r}" in capsys.readouterr().err


CRASH_SCRIPT = textwrap.dedent(
    """
    import sys, time
    from datetime import datetime, timedelta
    from oracle.neem.writer import NeemLogger
    from oracle.ontology import build_ontology
    from oracle.store.sqlite import SQLiteStore
    onto = build_ontology()
    logger = NeemLogger.create(SQLiteStore(sys.argv[1]), onto, user="crash")
    t0 = datetime(2024, 5, 6, 8, 0)
    for i in range(100000):
        logger.action("pour(thermos, green_mug)", t0 + timedelta(seconds=2 * i), t0 + timedelta(seconds=2 * i + 1),
                      action_id=f"a{i}", available=["pick(green_mug)", "pour(thermos, green_mug)"])
        print(f"committed a{i}", flush=True)
    """
)


def test_a_killed_logger_loses_at_most_the_action_in_flight(tmp_path, onto):
    db = tmp_path / "crash.sqlite"
    script = tmp_path / "crash.py"
    script.write_text(CRASH_SCRIPT)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, str(script), str(db)], stdout=subprocess.PIPE, text=True, env=env)
    reported = []
    assert proc.stdout is not None
    for line in proc.stdout:
        reported.append(line.split()[1])
        if len(reported) >= 40:
            break
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    reported.extend(line.split()[1] for line in proc.stdout.read().splitlines() if line.startswith("committed"))
    store = SQLiteStore(db)
    views = {v.iri.rsplit("_", 1)[1]: v for v in executed_actions(store, resolve_neem(store, "crash"))}
    missing = [name for name in reported if name not in views]
    assert not missing
    assert len(views) <= len(reported) + 1
    for name in reported:  # intact: task class, interval and both participants
        view = views[name]
        assert view.task_class == onto.iri("pour") and view.end - view.begin == 1.0
        assert len(view.participants) == 2


def test_neem_ids_are_made_from_any_user_name(tmp_path, onto, small_tbox):
    store = SQLiteStore(tmp_path / "s.sqlite")
    first = NeemLogger.create(store, onto, user="Ann_B. Smith", tbox=small_tbox)
    second = NeemLogger.create(store, onto, user="Ann_B. Smith", tbox=small_tbox)
    assert is_object_id(first.neem_id) and is_object_id(second.neem_id) and first.neem_id != second.neem_id
    assert [alias_of(store.neem(n)) for n in (first.neem_id, second.neem_id)] == ["Ann-B-Smith", "Ann-B-Smith-2"]
    assert store.neem(second.neem_id).meta["name"] == "Ann-B-Smith-2"  # what openEASE lists
    assert store.neem(second.neem_id).user == "Ann_B. Smith"


def test_a_logged_neem_survives_export_and_load(tmp_path, onto, small_tbox):
    from oracle.store.dump import export_neem, load_dump

    store = SQLiteStore(tmp_path / "s.sqlite")
    logger = NeemLogger.create(store, onto, user="alice", tbox=small_tbox)
    logger.action("pour(thermos, green_mug)", T0, T0 + timedelta(seconds=4), available=["pick(green_mug)"])
    logger.action("pick(green_mug)", T0 + timedelta(minutes=2))
    export_neem(store, logger.neem_id, tmp_path / "dump")
    other = make_store("mongomock", tmp_path)
    (loaded,) = load_dump(other, tmp_path / "dump")
    assert list(executed_actions(other, loaded)) == list(executed_actions(store, logger.neem_id))
    assert summarize_neem(other, loaded).actions == 3
    # per-action task individuals and their roles' scopes survive the round trip
    def role_scopes(st, neem):
        return sorted(
            (d["s"], float(str(d["scope"]["time"]["since"])), float(str(d["scope"]["time"]["until"])))
            for d in st.find(neem, p=str(DUL.classifies), exact=True)
            if float(str(d["scope"]["time"]["since"])) > 0
        )
    scoped = role_scopes(store, logger.neem_id)
    # pour: 2 roles, pick: 1; the imagined plan pick(green_mug)'s role: the instant it was imagined
    assert len(scoped) == 4 and scoped == role_scopes(other, loaded)
    (plan_role,) = [row for row in scoped if "Role_pick__green_mug" in row[0]]
    pour_begin = min(since for _, since, _ in scoped)  # the imagining's time: pour's begin
    assert plan_role[1] == pour_begin and plan_role[1] < plan_role[2] < pour_begin + 1e-3
    for st, neem in ((store, logger.neem_id), (other, loaded)):
        executed = [d["o"] for a in executed_actions(st, neem) for d in st.find(neem, s=a.iri, p=str(DUL.executesTask))]
        assert len(executed) == len(set(executed)) == 3  # one task individual per action (idle included)


def test_a_repeated_available_set_writes_only_the_new_mental_action(tmp_path, onto, small_tbox):
    """Plans and their tasks and roles are shared: the second time the same options are
    available only the MentalAction, its own Imagining task, its interval and its
    imagines_situation links are new."""
    store = SQLiteStore(tmp_path / "s.sqlite")
    logger = NeemLogger.create(store, onto, user="alice", tbox=small_tbox)
    options = ["pick(green_mug)", "pour(thermos, green_mug)", "pick(thermos)"]
    logger.available(options, T0)
    before = store.count(logger.neem_id)
    second = logger.available(options, T0 + timedelta(seconds=5))
    assert store.count(logger.neem_id) - before == 4 + 2 + 4 + len(options)  # action, task, interval, links
    plans = objects_of(store, logger.neem_id, second, logger.vocab.imagines_situation)
    assert len(plans) == len(options) and all(p.startswith(logger.ns + "Plan_") for p in plans)
    store.close()


def test_event_iris_are_unique_and_grow_with_time(logger):
    iris = [logger.action("pick(green_mug)", T0 + timedelta(seconds=i)).iri for i in range(50)]
    ids = [iri.rsplit("_", 1)[1] for iri in iris]
    assert len(set(iris)) == 50 and all(len(i) == 24 and int(i, 16) >= 0 for i in ids)
    assert ids == sorted(ids)  # appended at the end of the indexes


def test_an_available_set_met_again_is_logged_as_a_new_equal_list_is(tmp_path, onto, small_tbox):
    """The logger remembers the plans of an available tuple it logged (an import's rows share
    one tuple per distinct set): the documents are the ones an equal new list gives, and a
    failed commit makes it forget them, so the plans are written again with the next action."""
    from oracle.chains import parse_call
    from oracle.errors import StoreError

    options = tuple(parse_call(c) for c in ("pick(green_mug)", "pour(thermos, green_mug)", "pick(thermos)"))

    def log(store, same):
        logger = NeemLogger.create(store, onto, user="alice", tbox=small_tbox)
        for i in range(3):
            logger.action("pick(green_mug)", T0 + timedelta(seconds=10 * i), available=options if same else list(options))
        return [(d["s"].rsplit("_", 1)[0], d["p"], str(d["o"]).rsplit("_", 1)[0]) for d in store.read_documents(logger.neem_id, "triples")]

    assert log(SQLiteStore(tmp_path / "a.sqlite"), True) == log(SQLiteStore(tmp_path / "b.sqlite"), False)

    store = SQLiteStore(tmp_path / "c.sqlite")
    logger = NeemLogger.create(store, onto, user="alice", tbox=small_tbox, commit_every=2)
    logger.action("pick(green_mug)", T0, available=options)  # buffered: its plans are new
    insert = store.insert
    store.insert = lambda *args: (_ for _ in ()).throw(StoreError("disk full"))  # type: ignore[method-assign]
    with pytest.raises(LoggingError, match="disk full"):
        logger.action("pick(green_mug)", T0 + timedelta(seconds=1), available=options)
    store.insert = insert  # type: ignore[method-assign]
    logger.action("pick(green_mug)", T0 + timedelta(seconds=2), available=options)
    logger.flush()
    plans = {d["o"] for d in store.find(logger.neem_id, p=logger.vocab.imagines_situation)}
    assert len(plans) == 3
    assert all(objects_of(store, logger.neem_id, plan, RDF_TYPE) for plan in plans)  # written again, typed


def test_a_replacement_is_known_by_the_replaced_neems_id_while_it_is_written(store, onto, tbox_for):
    old = NeemLogger.create(store, onto, user="alice", neem_id="alice", tbox=tbox_for)
    old.action("pick(green_mug)", T0)
    old.close()
    new = NeemLogger.create(store, onto, user="alice", neem_id="alice", replace=True, tbox=tbox_for)
    assert new.replacing and new.neem_id == old.neem_id  # not the hidden staging NEEM's id
    new.action("open(fridge)", T0)
    with pytest.raises(LoggingError, match=f"in NEEM '{old.neem_id}'"):
        new.action("close(fridge)", T0 - timedelta(seconds=1))
    assert [v.task_class.rsplit("#", 1)[1] for v in executed_actions(store, old.neem_id)] == ["pick"]  # untouched
    new.close()
    assert not new.replacing and new.neem_id == old.neem_id
    assert [v.task_class.rsplit("#", 1)[1] for v in executed_actions(store, new.neem_id)] == ["open"]
