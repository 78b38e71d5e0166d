"""The service's routes of the questions about the past, over the hand-checked NEEM."""

from __future__ import annotations

import shutil

import pytest

from oracle.algorithm.params import Hyperparameters

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed")


@pytest.fixture()
def client(small_store, onto, tmp_path):
    from fastapi.testclient import TestClient

    from oracle.service import build_context
    from oracle.service.app import create_app

    copy = tmp_path / "s.sqlite"
    shutil.copy(small_store, copy)
    ctx = build_context(str(copy), onto, Hyperparameters())
    with TestClient(create_app(ctx), base_url="http://127.0.0.1") as test_client:
        yield test_client
    ctx.thread.close()


def test_ask_route_answers_in_the_questions_language(client):
    reply = client.get("/api/neems/small/ask", params={"q": "Wann habe ich zuletzt pick(green_mug) gemacht?"})
    assert reply.status_code == 200
    body = reply.json()
    assert body["language"] == "de" and body["text"] == "Zuletzt um 08:01 den grünen Becher genommen."
    assert body["english"] == "Picking up the green mug was last done at 08:01."


def test_ask_route_as_of_a_time(client):
    body = client.get("/api/neems/small/ask", params={"q": "what did you do today", "at": "2025-03-03T12:30"}).json()
    assert [a["task"] for a in body["evidence"]["actions"]][-1] == "eat(apple)"


def test_bad_question_and_missing_neem_are_one_line_errors(client):
    bad = client.get("/api/neems/small/ask", params={"q": "sing"})
    assert bad.status_code == 400 and "not a question I know" in bad.json()["error"]
    missing = client.get("/api/neems/nobody/ask", params={"q": "where is the green mug"})
    assert missing.status_code == 404
    assert client.get("/api/neems/small/ask", params={"q": "where is the mug", "at": "yesterday"}).status_code == 400


def test_summary_route(client):
    body = client.get("/api/neems/small/summary").json()
    assert body["latest"]["task"] == "place(green_mug, kitchen_table)" and body["today"] == 5


def test_routines_route(client):
    body = client.get("/api/neems/small/routines").json()
    assert body["routines"] == [] and body["in_progress"] is None  # two days: nothing recurs on three


def test_prepare_route(client):
    body = client.get("/api/neems/small/prepare", params={"for": "Morning"}).json()
    assert body["for"] == "Morning" and body["prepare"] == []  # no routine yet
    assert client.get("/api/neems/small/prepare", params={"for": "teatime"}).status_code == 422


def test_answers_after_an_action_is_logged_are_not_stale(client):
    """The engine keeps what the answers read of the NEEM (oracle.past.kept): an action logged
    through the service is in the next answer and the next summary."""
    from oracle.timeline import seconds_of
    from tests.past.conftest import t

    def after_fridge():
        return client.get("/api/neems/small/ask", params={"q": "what do I usually do after open(fridge)?"}).json()

    assert after_fridge()["evidence"]["occurrences"] == 3
    assert client.get("/api/neems/small/summary").json()["latest"]["task"] == "place(green_mug, kitchen_table)"
    begin = seconds_of(t(1, 8, 2))
    for offset, call in ((0, "open(fridge)"), (15, "pick(apple)")):
        logged = client.post("/api/neems/small/actions", json={"call": call, "begin": begin + offset, "end": begin + offset + 10})
        assert logged.status_code == 200
    evidence = after_fridge()["evidence"]
    assert evidence["occurrences"] == 4 and {"task": "pick(apple)", "count": 2} in evidence["next"]
    assert client.get("/api/neems/small/summary").json()["latest"]["task"] == "pick(apple)"
