"""What a KnowRob client reads from a NEEM the service wrote: openEASE's timeline rule
(ease-crc/knowrob_openease ``src/backends/timeline.pl``, downloaded at run time and consulted
unchanged; env OPENEASE_TIMELINE_PL names a copy; skipped when GitHub is unreachable) gives one
row per event, every task individual splits as that rule splits it (no network), each action
logged as done succeeded and the robot's failed and cancelled ones say so, the chains file's
state too, plan roles classify no object during an action, and ``/api/prolog`` finds the store's
NEEM when it names none."""

from __future__ import annotations

import json
import os
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.service.conftest import at

TIMELINE_URL = "https://raw.githubusercontent.com/ease-crc/knowrob_openease/master/src/backends/timeline.pl"
#: The robot's morning: 13 actions, three of them tasks whose class names hold a `_`.
CALLS = ["open(small_drawer)", "pick(red_mug)", "place(red_mug, counter_top)", "close(small_drawer)",
         "turn_on(coffee_machine)", "pick(thermos)", "pour(thermos, red_mug)", "place(thermos, counter_top)",
         "turn_off(coffee_machine)", "pick(red_mug)", "drink_from(red_mug)", "place(red_mug, counter_top)",
         "open(fridge)"]
FAILED, CANCELLED = 6, 12  # the pour failed; opening the fridge was begun, then cancelled
#: openEASE's timeline.pl imports library(query_handler) (knowrob_openease's, for its answer
#: hooks); the rows it gives (timeline_data/4) need nothing from it.
QUERY_HANDLER = ":- module(query_handler, []).\n"


def timeline_rule(folder: Path) -> Path:
    given = os.environ.get("OPENEASE_TIMELINE_PL")
    if given:
        return Path(given)
    try:
        with urllib.request.urlopen(TIMELINE_URL, timeout=10) as response:
            text = response.read()
    except OSError as error:
        pytest.skip(f"GitHub unreachable ({error}): openEASE's timeline.pl is fetched at run time")
    path = folder / "timeline.pl"
    path.write_bytes(text)
    return path


@pytest.fixture()
def written(tmp_path, onto) -> Iterator[tuple[object, str]]:
    """A NEEM the service wrote (situation, then the action, for each step) and then stopped
    (which ends the recording session: the episode's top-level action gets its end)."""
    from fastapi.testclient import TestClient

    from oracle.algorithm.params import Hyperparameters
    from oracle.service import build_context
    from oracle.service.app import create_app
    from oracle.store import open_store

    ctx = build_context(str(tmp_path / "s.sqlite"), onto, Hyperparameters())
    try:
        with TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
            neem = client.post("/api/neems", json={"user": "ada"}).json()["id"]
            for i, call in enumerate(CALLS):
                begin = at(0, 10 * i)
                assert client.post(f"/api/neems/{neem}/situation", json={"available": sorted(set(CALLS)), "at": begin}).status_code == 200
                if i == CANCELLED:
                    opened = client.post(f"/api/neems/{neem}/actions", json={"call": call, "phase": "begin", "at": begin}).json()
                    body = {"phase": "end", "id": opened["id"], "at": begin + 5, "state": "cancelled"}
                else:
                    body = {"call": call, "begin": begin, "end": begin + (0 if i == 3 else 5)}  # one instantaneous
                    if i == FAILED:
                        body["state"] = "failed"
                answer = client.post(f"/api/neems/{neem}/actions", json=body)
                assert answer.status_code == 200, answer.text
            # rosprolog and openEASE's console name no NEEM: the store's only one is meant
            found = client.post("/api/prolog", json={"query": "kb_call(action_failed(A))"})
            assert found.status_code == 200, found.text
            assert len(found.json()["solutions"]) == 1
    finally:
        ctx.thread.close()
    store = open_store(tmp_path / "s.sqlite")
    yield store, neem
    store.close()


def bridge_over(written, onto):
    from oracle.bridge import Bridge

    store, neem = written
    return Bridge(store, neem, onto)


def test_openease_timeline_rule_gives_a_row_for_every_event(tmp_path, onto, written) -> None:
    rule = timeline_rule(tmp_path)
    library = tmp_path / "library"
    library.mkdir()
    (library / "query_handler.pl").write_text(QUERY_HANDLER)
    bridge = bridge_over(written, onto)
    try:
        bridge.query(f"asserta(user:file_search_path(library, '{library}')), consult('{rule}')")
        rows = bridge.query("findall(E-Task, timeline_handler:timeline_data(E, Task, _, _), Rows)")[0]["Rows"]
        # every event with a task and a closed interval, asked our own way
        events = bridge.query("findall(E, kb_call(( executes_task(E, _), event_interval(E, _, End), number(End) ), any), Es),"
                              " sort(Es, Sorted)")[0]["Sorted"]  # fmt: skip
        physical = bridge.query("findall(E, ( kb_call(triple(E, rdf:type, dul:'Action'), any),"
                                " \\+ kb_call(triple(E, rdf:type, soma:'MentalAction'), any) ), Es), sort(Es, S)")[0]["S"]
    finally:
        bridge.close()
    rule_events = sorted({str(e) for e in _events(rows)})
    assert len(physical) == 14  # the 13 actions and the session's top-level action
    assert set(physical) <= set(rule_events), sorted(set(physical) - set(rule_events))
    assert rule_events == sorted(events)  # the imaginings and rankings too


def _events(rows: list[object]) -> list[str]:
    """The event of each ``E-Task`` row (pyswip hands a pair back as its text ``-(E, Task)``)."""
    out = []
    for row in rows:
        text = str(row)
        out.append(text[2:text.index(", ")] if text.startswith("-(") else text.split("-")[0])
    return out


def test_every_task_individual_splits_as_the_timeline_rule_splits_it(onto, written) -> None:
    bridge = bridge_over(written, onto)
    try:
        tasks = bridge.query("findall(T, kb_call(executes_task(_, T), any), Ts), sort(Ts, S)")[0]["S"]
        unsplit = bridge.query("findall(T, ( kb_call(executes_task(_, T), any),"
                               " \\+ atomic_list_concat([_Task, _], '_', T) ), L)")[0]["L"]
    finally:
        bridge.close()
    assert len(tasks) > 13 * 2  # each action's, each imagining's and ranking's, the session's
    assert unsplit == []
    assert any("#TurnOn_" in t for t in tasks) and any("#DrinkFrom_" in t for t in tasks)


def test_actions_logged_as_done_succeeded_and_the_robots_states_are_kept(onto, written) -> None:
    bridge = bridge_over(written, onto)
    try:
        q = bridge.query
        states = {k: q(f"findall(A, kb_call({k}(A), any), L), sort(L, S)")[0]["S"]
                  for k in ("action_succeeded", "action_failed", "action_cancelled")}
        logged = q("findall(A, ( kb_call(executes_task(A, T), any), odb_calls:task_class(T, _) ), L), sort(L, S)")[0]["S"]
        poured = q("kb_call(( action_failed(A), executes_task(A, T) ), any), odb_calls:task_call(T, C), term_string(C, S)")
        fridge = q("kb_call(( action_cancelled(A), executes_task(A, T) ), any), odb_calls:task_call(T, C), term_string(C, S)")
    finally:
        bridge.close()
    assert len(logged) == 13
    assert len(states["action_succeeded"]) == 11 and set(states["action_succeeded"]) <= set(logged)
    assert [r["S"] for r in poured] == ["pour(thermos,red_mug)"]
    assert [r["S"] for r in fridge] == ["open(fridge)"]


def test_plan_roles_classify_no_object_during_an_action(onto, written) -> None:
    bridge = bridge_over(written, onto)
    try:
        rows = bridge.query("findall(A-Rs, ( kb_call(has_participant(A, odb:'Object_small_drawer'), any),"
                            " findall(R, kb_call(has_role(odb:'Object_small_drawer', R) during A), Rs) ), L)")[0]["L"]
        plan_roles = bridge.query("findall(R, ( kb_call(( plan_defines_task(_, T), task_role(T, R) ), any),"
                                  " kb_call(has_role(odb:'Object_small_drawer', R), any) ), L)")[0]["L"]  # fmt: skip
    finally:
        bridge.close()
    assert len(rows) == 2  # opened, closed (an instantaneous action)
    for row in rows:  # each action: its own role, no plan's
        assert str(row).count("Role_") == 1 and "__" not in str(row), row
    assert plan_roles  # the plans' roles are there, for a question about any time


def test_a_chains_files_states_are_written(tmp_path, onto) -> None:
    from oracle.bridge import Bridge
    from oracle.neem.importing import import_chains
    from oracle.store import open_store

    rows = [{"user": "bo", "time": "2024-05-01T08:00:00", "end": "2024-05-01T08:00:05", "action": "pick(apple)"},
            {"user": "bo", "time": "2024-05-01T08:00:10", "end": "2024-05-01T08:00:15", "action": "turn_on(stove)",
             "state": "failed"},
            {"user": "bo", "time": "2024-05-01T08:00:20", "action": "drink_from(red_mug)", "state": "cancelled"}]
    path = tmp_path / "c.jsonl"
    path.write_text("".join(json.dumps(r) + "\n" for r in rows))
    store = open_store(tmp_path / "s.sqlite")
    (neem,) = import_chains(store, onto, path)
    bridge = Bridge(store, neem, onto)
    try:
        counts = {k: bridge.query(f"findall(A, kb_call({k}(A), any), L), length(L, N)")[0]["N"]
                  for k in ("action_succeeded", "action_failed", "action_cancelled")}
    finally:
        bridge.close()
        store.close()
    assert counts == {"action_succeeded": 1, "action_failed": 1, "action_cancelled": 1}


def test_prolog_with_several_neems_says_how_to_choose(client) -> None:
    for user in ("ann", "ben"):
        assert client.post("/api/neems", json={"user": user}).status_code == 201
    answer = client.post("/api/prolog", json={"query": "true"})
    assert answer.status_code >= 400
    message = answer.json()["error"]
    assert "2 NEEMs (ann, ben)" in message and "serve --neem" in message and "\n" not in message
