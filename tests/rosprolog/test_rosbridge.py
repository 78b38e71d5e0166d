"""The rosbridge route: roslibpy (PyPI, what neem_interface_python uses) calls rosprolog through
the live service with no ROS installed; the same answers as the ROS door, the Prolog strings
neem_interface_python sends, writes only where the service allows them, and the service's Host,
Origin and token rules on the websocket."""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Iterator

import pytest

from tests.rosprolog.conftest import needs_swipl
from tests.service.test_server import free_port, start_server, stop_server

roslibpy = pytest.importorskip("roslibpy", reason="roslibpy is not installed; run make setup")
websockets_sync = pytest.importorskip("websockets.sync.client", reason="websockets is not installed; run make setup")
pytestmark = needs_swipl
OK, NO_SOLUTION, WRONG_ID, QUERY_FAILED = 3, 0, 1, 2
TOKEN = "rosbridge-Test-token-8472"


class Prolog:
    """rosprolog over roslibpy, as neem_interface_python's client calls it (written here from
    the protocol; its ids, modes and statuses)."""

    def __init__(self, ros) -> None:
        self.query_srv = roslibpy.Service(ros, "/rosprolog/query", "json_prolog_msgs/srv/PrologQuery")
        self.next_srv = roslibpy.Service(ros, "/rosprolog/next_solution", "json_prolog_msgs/srv/PrologNextSolution")
        self.finish_srv = roslibpy.Service(ros, "/rosprolog/finish", "json_prolog_msgs/srv/PrologFinish")
        self.count = 0

    def call(self, service, **args) -> dict:
        return dict(service.call(roslibpy.ServiceRequest(args), timeout=60))

    def solutions(self, text: str, mode: int = 0, take: int | None = None) -> list[dict]:
        self.count += 1
        qid = f"PYTHON_QUERY_{os.getpid()}_{self.count}"
        assert self.call(self.query_srv, id=qid, query=text, mode=mode)["ok"]
        found: list[dict] = []
        try:
            while take is None or len(found) < take:
                answer = self.call(self.next_srv, id=qid)
                if answer["status"] == QUERY_FAILED:
                    raise RuntimeError(answer["solution"])
                if answer["status"] != OK:
                    assert answer["status"] == NO_SOLUTION
                    break
                found.append(json.loads(answer["solution"]))
        finally:
            self.call(self.finish_srv, id=qid)
        assert self.call(self.next_srv, id=qid)["status"] == WRONG_ID
        return found

    def once(self, text: str) -> dict | None:
        found = self.solutions(text, mode=1, take=1)
        return found[0] if found else None


def atom(text: str) -> str:
    """neem_interface_python's own quoting of an IRI or name (utils: prefixed names stay bare)."""
    return text if ":'" in text else f"'{text}'"


def connect(url: str, **headers: str):
    ros = roslibpy.Ros(url, transport="asyncio", headers=headers or None)
    ros.run(timeout=30)
    return ros


@pytest.fixture(scope="module")
def prolog(service) -> Iterator[Prolog]:
    ros = connect(f"{service}/rosbridge")
    yield Prolog(ros)
    ros.terminate()


def test_same_answers_as_the_ros_door(prolog):
    assert [s["X"] for s in prolog.solutions("member(X, [a, 1, 2.5, \"s\", [b]])")] == ["a", 1, 2.5, "\"s\"", ["b"]]
    first = prolog.once("kb_call(executes_task(A, T))")
    assert first is not None and first["A"].startswith("http")
    assert [s["X"] for s in prolog.solutions("between(1, 13, X)", mode=1, take=5)] == [1, 2, 3, 4, 5]
    assert len(prolog.solutions("between(1, 13, X)", mode=1)) == 13
    with pytest.raises(RuntimeError, match="no_such_predicate/1"):
        prolog.solutions("no_such_predicate(X)")
    assert prolog.solutions("X = foo(a, [1, 2.5], \"str\"), Y = _") == [
        {"X": {"term": ["foo", "a", [1, 2.5], "\"str\""]}, "Y": "_"}]
    assert prolog.once("member(X, [])") is None


def test_neem_interface_python_read_methods(prolog):
    """Its NEEM and NEEMInterface read methods' query strings, built as it builds them."""
    episode = prolog.once("kb_call(is_episode(Episode))")["Episode"]
    actions = {s["Action"] for s in prolog.solutions("is_action(Action)")}
    assert actions
    top = prolog.solutions(f"kb_call([is_action(Action), is_setting_for({atom(episode)}, Action)]).")
    assert top and {s["Action"] for s in top} <= actions
    action = sorted(s["Action"] for s in prolog.solutions("is_action(Action), event_interval(Action, _, _)"))[0]
    begin_end = prolog.once(f"event_interval({atom(action)}, Begin, End)")
    assert isinstance(begin_end["Begin"], float) and begin_end["End"] >= begin_end["Begin"]
    # (NEEM.get_trajectory's has_time_interval/3 is left out: stock KnowRob has only /2 and refuses it too)
    tasks = prolog.solutions(f"""kb_call([executes_task({atom(action)}, Task),
                                          instance_of(Task, TaskType),
                                          subclass_of(TaskType, dul:'Task')])""")
    assert tasks and all(s["Task"].startswith("http") for s in tasks)
    typed = prolog.solutions(f"is_action(Action), instance_of(Action, {atom('dul:' + chr(39) + 'Action' + chr(39))})")
    assert {s["Action"] for s in typed} == actions
    objects = prolog.solutions(f"kb_call(holds({atom(action)}, {atom('dul:' + chr(39) + 'executesTask' + chr(39))}, X))")
    assert {s["X"] for s in objects} >= {s["Task"] for s in tasks}
    participants = prolog.solutions(f"kb_call(has_participant({atom(action)}, Participant))")
    assert all(isinstance(s["Participant"], str) for s in participants)
    assert prolog.solutions("is_state(State)") is not None  # answers (none in this NEEM), no error


def test_writes_refused_read_only(prolog):
    with pytest.raises(RuntimeError, match="kb_project/1"):
        prolog.solutions("kb_project(has_participant('a', 'b'))")


@pytest.fixture(scope="module")
def writable(neem_store, tmp_path_factory) -> Iterator[str]:
    """The service over a copy of the store, with --allow-prolog-writes (which needs a token)."""
    folder = tmp_path_factory.mktemp("writable")
    store = folder / "w.sqlite"
    shutil.copy(neem_store, store)
    token_file = folder / "token"
    token_file.write_text(TOKEN)
    token_file.chmod(0o600)
    port = free_port()
    process = start_server(store, port, "--allow-prolog-writes", "--token-file", str(token_file))
    yield f"ws://127.0.0.1:{port}"
    stop_server(process)


def test_neem_interface_python_write_methods_where_writes_are_allowed(writable):
    ros = connect(f"{writable}/rosbridge", Authorization=f"Bearer {TOKEN}")
    try:
        prolog = Prolog(ros)
        action = sorted(s["Action"] for s in prolog.solutions("is_action(Action)"))[0]
        # assert_state's participants and assert_situation's objects, as it writes them
        cup = atom("http://example.org/cup_1")
        assert prolog.once(f"kb_project(has_participant({atom(action)}, {cup}))") == {}
        assert prolog.once(f"kb_project(holds({atom(action)}, dul:'includesObject', {cup}))") == {}
        participants = {s["P"] for s in prolog.solutions(f"kb_call(has_participant({atom(action)}, P))")}
        assert "http://example.org/cup_1" in participants
        assert prolog.once(f"kb_call(holds({atom(action)}, dul:'includesObject', O))") == {"O": "http://example.org/cup_1"}
    finally:
        ros.terminate()


def raw(url: str, messages: list[dict], answers: int, **headers: str) -> list[dict]:
    with websockets_sync.connect(url, additional_headers=headers or None, open_timeout=30) as socket:
        for message in messages:
            socket.send(json.dumps(message))
        return [json.loads(socket.recv(timeout=60)) for _ in range(answers)]


def test_topic_ops_taken_quietly_and_unknown_services_answered(service):
    replies = raw(f"{service}/", [
        {"op": "advertise", "topic": "/tf", "type": "tf2_msgs/TFMessage"},
        {"op": "subscribe", "topic": "/clock"},
        {"op": "publish", "topic": "/tf", "msg": {}},
        {"op": "call_service", "id": "c1", "service": "/rosapi/topics", "args": {}},
        {"op": "call_service", "id": "c2", "service": "rosprolog/query", "args": {"id": "raw", "query": "X = 1", "mode": 1}},
        {"op": "call_service", "id": "c3", "service": "/json_prolog/simple_query",
         "args": {"id": "old", "query": "X = 2", "mode": 0}},
        {"op": "no_such_op"},
    ], 4)
    by_id = {reply.get("id"): reply for reply in replies}
    assert by_id["c1"]["result"] is False and "does not exist" in by_id["c1"]["values"]
    assert by_id["c2"] == {"op": "service_response", "service": "rosprolog/query", "id": "c2", "result": True,
                           "values": {"ok": True, "message": ""}}
    assert by_id["c3"]["values"] == {"ok": True, "message": ""}  # json_prolog's older name, as CRAM calls it
    assert by_id[None]["op"] == "status" and "no_such_op" in by_id[None]["msg"]


def refused(url: str, **headers: str) -> int:
    with pytest.raises(websockets_sync.InvalidStatus) as caught:
        raw(url, [], 0, **headers)
    return caught.value.response.status_code


def test_host_origin_and_token_rules(service, writable):
    assert refused(f"{service}/rosbridge", Origin="http://evil.example") == 403
    assert refused(f"{writable}/rosbridge") == 403  # no token
    assert refused(f"{writable}/rosbridge", Authorization="Bearer wrong-token-123456") == 403
    assert raw(f"{writable}/rosbridge?token={TOKEN}", [{"op": "call_service", "id": 1, "service": "/rosprolog/finish",
                                                        "args": {"id": "*"}}], 1)[0]["result"] is True


def test_neem_chosen_on_the_address(service):
    def first(url: str) -> dict:
        with websockets_sync.connect(url, open_timeout=30) as socket:  # one call at a time, as roslibpy
            for name, args in (("query", {"id": url, "query": "kb_call(is_episode(E))", "mode": 1}),
                               ("next_solution", {"id": url})):
                socket.send(json.dumps({"op": "call_service", "service": f"/rosprolog/{name}", "args": args}))
                values = json.loads(socket.recv(timeout=60))["values"]
        return dict(values)

    assert first(f"{service}/rosbridge?neem=alice")["status"] == OK
    assert refused(f"{service}/rosbridge?neem=nobody") == 403  # not a NEEM of the store


def test_twenty_clients_at_once_without_errors(service):
    import threading

    counts: dict[int, int] = {}
    errors: list[str] = []

    def client(i: int) -> None:
        try:
            with websockets_sync.connect(f"{service}/rosbridge", open_timeout=60) as socket:
                def call(name: str, args: dict) -> dict:
                    socket.send(json.dumps({"op": "call_service", "service": f"/rosprolog/{name}", "args": args}))
                    return dict(json.loads(socket.recv(timeout=120))["values"])

                assert call("query", {"id": f"crowd{i}", "query": "between(1, 13, X)", "mode": i % 2})["ok"]
                counts[i] = 0
                while call("next_solution", {"id": f"crowd{i}"})["status"] == OK:
                    counts[i] += 1
                call("finish", {"id": f"crowd{i}"})
        except Exception as error:  # counted: the assertion below names them
            errors.append(repr(error))

    threads = [threading.Thread(target=client, args=(i,)) for i in range(20)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert errors == [] and counts == {i: 13 for i in range(20)}
