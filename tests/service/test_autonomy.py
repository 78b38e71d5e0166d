"""The autonomy mode in the service (thesis 6.3): who usually does each ranked task and each step
of the chain, in the answer and on the page; a workflow chosen in mixed mode, kept in the NEEM."""

from __future__ import annotations

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.chains import MODES
from oracle.service.app import create_app
from tests.service.conftest import AVAILABLE, ROUTINE, at

pytestmark = pytest.mark.usefixtures("onto")

#: Who does each step of the routine: the user picks and places the mug, pours together with the
#: robot, and leaves the drawer and the thermos to the robot.
WHO = {"pick(red_mug)": "user", "place(red_mug, counter_top)": "user", "pour(thermos, red_mug)": "together"}


@pytest.fixture()
def neem(client) -> str:
    assert client.post("/api/neems", json={"user": "ada", "neem": "ada"}).status_code == 201
    return "ada"


def drive_modes(client, neem: str, days: int = 2) -> None:
    for day in range(days):
        for i, call in enumerate(ROUTINE):
            begin = at(day, 10 * i)
            assert client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": begin}).status_code == 200
            done = client.post(f"/api/neems/{neem}/actions", json={"call": call, "begin": begin, "end": begin + 5,
                                                                  "performed_by": WHO.get(call, "robot")})
            assert done.status_code == 200, done.text


def test_the_mode_routes_name_the_same_modes_as_the_chains():
    from typing import get_args

    from oracle.service.routes import Mode

    assert get_args(Mode) == MODES


def test_each_ranked_task_and_chain_step_carries_who_usually_does_it(client, neem):
    drive_modes(client, neem, days=3)  # each call three times, always the same way: it keeps its mode
    answer = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(3, 0)}).json()
    modes = {r["task"]: r["mode"] for r in answer["ranking"]}
    assert {task: modes[task] for task in ROUTINE} == {task: WHO.get(task, "robot") for task in ROUTINE}
    pour = next(r for r in answer["ranking"] if r["task"] == "pour(thermos, red_mug)")
    assert pour["mode_support"] == {"context": "call and part", "counts": {"robot": 0, "user": 0, "together": 3}}
    # never done, and its task is a tie: what the user's actions share decides (the robot does most of them)
    banana = next(r for r in answer["ranking"] if r["task"] == "pick(banana)")
    assert (banana["mode"], banana["mode_support"]) == ("robot", {"context": "task and part",
                                                                  "counts": {"robot": 3, "user": 3, "together": 0}})
    assert answer["chain_modes"] == [WHO.get(step, "robot") for step in answer["chain"]]
    assert client.get(f"/api/neems/{neem}/situation").json()["chain_modes"] == answer["chain_modes"]
    english = client.get(f"/api/neems/{neem}/tablet", params={"lang": "en"}).json()
    german = client.get(f"/api/neems/{neem}/tablet", params={"lang": "de"}).json()
    said = {t["task"]: t["mode_said"] for t in english["tasks"]}
    assert said["pour(thermos, red_mug)"] == "You usually do this together with the robot (3 of 3 times)."
    assert said["pick(red_mug)"] == "You usually do this yourself (3 of 3 times)."
    assert said["open(small_drawer)"] == "The robot usually does this for you (3 of 3 times)."
    assert {t["task"]: t["mode_said"] for t in german["tasks"]}["pick(red_mug)"] == "Das machen Sie meist selbst (3 von 3 Malen)."
    assert [(s["task"], s["mode"]) for s in english["workflow"]] == list(zip(answer["chain"], answer["chain_modes"]))
    assert {s["who"] for s in german["workflow"]} <= {"Sie", "Der Roboter", "Gemeinsam"}


def test_a_new_mode_logged_counts_at_the_next_ranking(client, neem):
    drive_modes(client, neem, days=1)
    for n in (1, 2, 3):
        begin = at(1, 20 * n)
        client.post(f"/api/neems/{neem}/actions", json={"call": "pick(banana)", "begin": begin, "end": begin + 1,
                                                       "performed_by": "together"})
        answer = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": begin + 10}).json()
        banana = next(r for r in answer["ranking"] if r["task"] == "pick(banana)")
        assert banana["mode_support"] == {"context": "call and part", "counts": {"robot": 0, "user": 0, "together": n}}
    assert banana["mode"] == "together"  # three times together, never otherwise: its own mode


def test_a_workflow_in_mixed_mode_is_the_users_decision_with_its_modes(ctx, onto, client, neem):
    from fastapi.testclient import TestClient

    from oracle.service import build_context

    drive_modes(client, neem, days=1)
    flow = ["pick(red_mug)", "place(red_mug, counter_top)", "pour(thermos, red_mug)"]
    # "I bring the cup, you pour"
    made = client.post(f"/api/neems/{neem}/choice", json={"task": flow[0], "workflow": flow, "at": at(1, 1),
                                                          "modes": ["user", "user", "robot"]})
    assert made.status_code == 200, made.text
    assert made.json()["modes"] == ["user", "user", "robot"]
    # without modes: who usually does each step
    usual = client.post(f"/api/neems/{neem}/choice", json={"task": flow[0], "workflow": flow, "at": at(1, 2)}).json()
    assert usual["modes"] == ["user", "user", "together"]
    single = client.post(f"/api/neems/{neem}/choice", json={"task": "eat(apple)", "at": at(1, 3)}).json()
    assert single["modes"] == ["robot"]  # no eating ever: the robot, which was asked
    count = ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem)))
    bad = client.post(f"/api/neems/{neem}/choice", json={"task": flow[0], "workflow": flow, "modes": ["user", "cat", "robot"]})
    assert bad.status_code == 422 and "'robot', 'user' or 'together'" in bad.json()["error"]
    short = client.post(f"/api/neems/{neem}/choice", json={"task": flow[0], "workflow": flow, "modes": ["user"]})
    assert short.status_code == 400 and short.json()["error"].startswith("modes: 1 given for 3 steps")
    assert "\n" not in bad.json()["error"] + short.json()["error"]
    assert ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem))) == count
    assert client.get(f"/api/neems/{neem}/choice").json()["modes"] == ["robot"]
    client.post(f"/api/neems/{neem}/choice", json={"task": flow[0], "workflow": flow, "at": at(1, 4),
                                                   "modes": ["user", "robot", "together"]})
    store = ctx.thread.call(lambda: ctx.engine.store.location)
    ctx.thread.call(lambda: ctx.engine.store.close())
    again = build_context(store, onto, Hyperparameters())
    with TestClient(create_app(again), base_url="http://127.0.0.1") as restarted:
        back = restarted.get(f"/api/neems/{neem}/choice").json()
    assert (back["workflow"], back["modes"]) == (flow, ["user", "robot", "together"])
