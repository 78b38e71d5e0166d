"""The robot API in-process: the thesis loop online, answers, Prolog, and refusals that change nothing."""

from __future__ import annotations

import pytest

from oracle.algorithm.params import Hyperparameters
from oracle.service.app import create_app
from tests.service.conftest import AVAILABLE, ROUTINE, at, drive, drive_day

pytestmark = pytest.mark.usefixtures("onto")


@pytest.fixture()
def neem(client) -> str:
    response = client.post("/api/neems", json={"user": "ada", "neem": "ada"})
    assert response.status_code == 201, response.text
    made = response.json()
    assert made["name"] == "ada" and len(made["id"]) == 24 and made["id"] != "ada"  # an ObjectId, named ada
    return "ada"  # the tests address the NEEM by its name; test_the_id_and_the_name_reach_one_session by both


def test_situation_answers_ranking_and_chain_and_writes_the_preference(client, neem):
    drive(client, neem)
    answer = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()
    # the night between is an idle action; so is the pause before this decision (the replay's rule)
    assert answer["history"] == 2 * len(ROUTINE) + 2
    assert [r["rank"] for r in answer["ranking"]] == list(range(1, len(AVAILABLE) + 1))
    assert sorted(r["task"] for r in answer["ranking"]) == AVAILABLE
    top = answer["ranking"][0]["task"]
    assert top in ROUTINE and answer["chain"][0] == top
    assert set(answer["chain"]) <= set(ROUTINE)  # the chain follows the routine, never the banana
    assert all(r["support"] >= 0 for r in answer["ranking"])
    # the preference is in the NEEM: Prolog's what-next reads it back
    nxt = client.get(f"/api/neems/{neem}/what-next").json()
    assert nxt["answer"]["chain"][0]["task"] == top
    assert nxt["sentence"].startswith(f"Next I expect {top}")


def test_incremental_predictor_ranks_like_a_fresh_fit_of_the_neem(client, neem, ctx, onto):
    """partial_fit per action must give what ranking.rank_neem gives from the stored history."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.ranking import rank_neem
    from oracle.timeline import Instant

    drive(client, neem)
    live = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()

    def refit():
        bridge = ctx.engine.bridge(neem)
        return rank_neem(bridge, onto, Hyperparameters(), AVAILABLE, Instant.of(at(2, 0)), write=False)

    fresh = ctx.thread.call(refit)
    assert fresh.history == live["history"]
    assert [str(c) for c in fresh.calls] == [r["task"] for r in live["ranking"]]
    assert [round(min(t.score, 1e9), 9) for t in fresh.ranking] == [round(r["score"], 9) for r in live["ranking"]]
    # the support too: the same past situations, found by their place in the stored history
    from oracle.ranking import support_fields

    begins = [float(row["begin"]) for row in ctx.thread.call(lambda: ctx.engine.bridge(neem).history())]
    assert [[begins[p] for p in support_fields(t).get("situations", [])] for t in fresh.ranking] == \
        [r["situations"] for r in live["ranking"]]
    assert [t.n_similar for t in fresh.ranking] == [r["support"] for r in live["ranking"]]


def test_actions_logged_without_a_situation_are_offered_what_was_done_before_live_and_read_back(client, neem, ctx, onto):
    """An action with no imagined situation before it is offered the user's earlier actions, by
    the live predictor and by the history read alike (docs/algorithm.md, "Steps without an offer")."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.algorithm.records import Option
    from oracle.calls import option_of, steps_from_history
    from oracle.chains import parse_call
    from oracle.ranking import rank_neem
    from oracle.timeline import Instant

    for day in range(3):
        for i, call in enumerate(ROUTINE):
            begin = at(day, 10 * i)
            if day == 1 and i % 2:      # the second morning imagines every other step
                assert client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": begin}).status_code == 200
            response = client.post(f"/api/neems/{neem}/actions", json={"call": call, "begin": begin, "end": begin + 5})
            assert response.status_code == 200, response.text
    live = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(3, 0)}).json()
    history = ctx.thread.call(lambda: ctx.engine.bridge(neem).history())
    steps = [s for s in steps_from_history(onto, history) if not s.idle]
    routine = [option_of(onto, parse_call(c)) for c in ROUTINE]
    assert steps[0].options == () and steps[3].options == tuple(routine[:3])     # what came before, in order
    assert steps[7].options == tuple(routine)
    assert set(steps[8].options) == {option_of(onto, parse_call(c)) for c in AVAILABLE}  # the imagined one
    assert all(isinstance(o, Option) for s in steps for o in s.options)

    def refit():
        return rank_neem(ctx.engine.bridge(neem), onto, Hyperparameters(), AVAILABLE, Instant.of(at(3, 0)), write=False)

    fresh = ctx.thread.call(refit)
    assert fresh.history == live["history"]
    assert [str(c) for c in fresh.calls] == [r["task"] for r in live["ranking"]]
    assert [round(min(t.score, 1e9), 9) for t in fresh.ranking] == [round(r["score"], 9) for r in live["ranking"]]


def test_support_names_the_past_situations_behind_each_task(client, neem):
    """The routine predictor's support: how often the user did the task after the same context,
    and when (only times at which the user began that very task)."""
    drive(client, neem)
    ranking = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()["ranking"]
    began = {call: {at(day, 10 * i) for day in range(2) for i, c in enumerate(ROUTINE) if c == call} for call in AVAILABLE}
    for entry in ranking:
        assert set(entry["situations"]) <= began[entry["task"]], entry
        assert entry["situations"] == sorted(entry["situations"])  # latest last
        assert entry["reason"] and "\n" not in entry["reason"]
    top = ranking[0]
    assert top["context_order"] >= 1 and top["support"] >= 1 and top["situations"]
    # the morning after a night: the routine's first task, after the break, the morning before
    assert top["task"] == ROUTINE[0] and top["context"][-1] == "idle" and top["situations"] == [at(1, 0)]
    assert top["reason"].startswith("after ") and "a break: 1\u00d7" in top["reason"]
    banana = next(e for e in ranking if e["task"] == "pick(banana)")
    assert (banana["context_order"], banana["support"], banana["situations"]) == (-1, 0, [])
    assert banana["reason"].startswith("never done")


def test_a_situation_after_a_break_is_ranked_after_the_idle_step(client, neem):
    """The replay observes the idle step before it ranks the next decision; live, the NEEM's
    idle action is written only with the next action, so the session must add it itself."""
    drive(client, neem)
    morning = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()
    soon = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 1)}).json()
    assert morning["history"] == soon["history"]  # one break, however many situations
    assert morning["chain"][:2] == ROUTINE[:2]
    done = client.post(f"/api/neems/{neem}/actions", json={"call": ROUTINE[0], "begin": at(2, 2)}).json()
    assert done["idle"] is not None and done["history"] == morning["history"] + 1


def test_an_action_inside_the_gap_undoes_the_break(client, neem, ctx, onto):
    """A situation after the idle gap, then an action that began before it: the NEEM holds no
    idle action, and the live predictor must again equal a fresh fit of the NEEM."""
    from oracle.algorithm.params import Hyperparameters
    from oracle.ranking import rank_neem
    from oracle.timeline import Instant

    drive(client, neem, days=1)
    last = at(0, 10 * (len(ROUTINE) - 1)) + 5
    client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": last + 60})
    done = client.post(f"/api/neems/{neem}/actions", json={"call": "pick(apple)", "begin": last + 5, "end": last + 6}).json()
    assert done["idle"] is None and done["history"] == len(ROUTINE) + 1
    live = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": last + 8}).json()
    fresh = ctx.thread.call(lambda: rank_neem(ctx.engine.bridge(neem), onto, Hyperparameters(), AVAILABLE,
                                              Instant.of(last + 8), write=False))
    assert fresh.history == live["history"]
    assert [round(min(t.score, 1e9), 9) for t in fresh.ranking] == [round(r["score"], 9) for r in live["ranking"]]


def test_why_not_and_something_else_in_english_and_structured(client, neem):
    drive(client, neem)
    client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)})
    why = client.get(f"/api/neems/{neem}/why-not", params={"task": "pick(banana)"}).json()
    assert "pick(banana)" in why["sentence"]
    assert why["answer"]["reasons"][0]["reason"] == "ranked_lower"
    other = client.get(f"/api/neems/{neem}/something-else", params={"task": "open(small_drawer)"}).json()
    assert other["sentence"].startswith("Instead of open(small_drawer) I would do")


def test_action_begin_then_end_and_idle_detection(client, neem):
    opened = client.post(f"/api/neems/{neem}/actions", json={"call": "pick(red_mug)", "phase": "begin", "at": at(0, 0)}).json()
    assert opened["open"] is True
    done = client.post(f"/api/neems/{neem}/actions", json={"phase": "end", "id": opened["id"], "at": at(0, 4)}).json()
    assert (done["begin"], done["end"], done["idle"]) == (at(0, 0), at(0, 4), None)
    later = client.post(f"/api/neems/{neem}/actions", json={"call": "pick(thermos)", "begin": at(0, 60)}).json()
    assert later["idle"] is not None  # 56 s of nothing is an odb:IdleTask action
    assert later["history"] == 3


def test_perception_is_logged_and_unknown_objects_refused(client, neem):
    ok = client.post(f"/api/neems/{neem}/perception", json={"objects": [{"name": "banana", "pose": [0.1, 0.2, 0.9]}], "at": at(0, 0)})
    assert ok.status_code == 200 and ok.json()["logged"][0].endswith("Object_banana")
    bad = client.post(f"/api/neems/{neem}/perception", json={"objects": [{"name": "apple"}, {"name": "unicorn"}], "at": at(0, 1)})
    assert bad.status_code == 400 and "unicorn" in bad.json()["error"]


def test_a_perceived_pose_goes_into_the_neem_and_prolog_says_where_the_object_was(client, neem):
    pose = [0.5, -0.25, 0.9, 0.0, 0.0, 0.7071, 0.7071]
    ok = client.post(f"/api/neems/{neem}/perception", json={"objects": [{"name": "red_mug", "pose": pose}], "at": at(0, 0)})
    assert ok.status_code == 200, ok.text
    answer = client.post("/api/prolog", json={"query": "is_at(odb:'Object_red_mug', [Ref, Pos, Rot])", "neem": neem}).json()
    (where,) = answer["solutions"]
    assert where["Pos"] == pose[:3] and where["Rot"] == pose[3:]
    short = client.post(f"/api/neems/{neem}/perception", json={"objects": [{"name": "apple", "pose": [1, 2, 3, 4]}], "at": at(0, 1)})
    assert short.status_code == 400 and "x, y, z" in short.json()["error"]


@pytest.mark.parametrize("path,body,status,needle", [
    ("/api/neems/ada/situation", {"available": ["fly(red_mug)"]}, 400, "fly"),
    ("/api/neems/ada/situation", {"available": ["pick(red_mug"]}, 400, "malformed"),
    ("/api/neems/ada/situation", {"available": []}, 422, "available"),
    ("/api/neems/ada/situation", {"available": ["pick(red_mug)"], "at": "yesterday"}, 400, "ISO-8601"),
    ("/api/neems/ada/situation", {"available": ["pick(red_mug)"], "at": 1.0}, 409, "backwards"),
    ("/api/neems/nobody/situation", {"available": ["pick(red_mug)"]}, 404, "nobody"),
    ("/api/neems/ada/actions", {"phase": "end", "id": "a9"}, 400, "no open action"),
    ("/api/neems/ada/actions", {"call": "pick(red_mug)", "begin": at(0, 9), "end": at(0, 1)}, 400, "before it starts"),
    ("/api/neems/ada/choice", {"task": "fly(away)"}, 400, "fly"),
    ("/api/prolog", {"query": "halt", "neem": "ada"}, 403, "not allowed"),
    ("/api/prolog", {"query": "kb_call(halt)", "neem": "ada"}, 403, "not allowed"),
    ("/api/prolog", {"query": "member(X, [a", "neem": "ada"}, 400, "syntax"),
    ("/api/neems/ada/situation", {"available": ["pick(red_mug)"], "at": 1e300}, 400, "between 1970"),
    ("/api/neems/ada/situation", {"available": ["pick(red_mug)"], "at": "9999-12-31T23:59"}, 400, "between 1970"),
    ("/api/neems/ada/situation", {"available": "pick(red_mug)"}, 422, "available"),
    ("/api/neems/ada/perception", {"objects": [{"name": "red_mug", "pose": [1, 2]}]}, 422, "pose"),
    ("/api/neems/ada/perception", {"objects": [{"name": "red_mug"}], "at": "soon"}, 400, "ISO-8601"),
    ("/api/neems/ada/actions", {"phase": "begin"}, 400, "call is required"),
    ("/api/neems/ada/actions", {"phase": "end"}, 400, "needs the id"),
    ("/api/neems/ada/actions", {"call": "pick(red_mug)", "performed_by": "cat"}, 422, "performed_by"),
    ("/api/neems/ada/actions", {"call": "fly(red_mug)"}, 400, "fly"),
    ("/api/neems/ada/choice", {"task": "pick(red_mug)", "workflow": ["fly(x)"]}, 400, "workflow"),
    ("/api/neems", {"user": "ada", "neem": "ada"}, 409, "already exists"),
    ("/api/neems", {"user": ""}, 422, "user"),
    ("/api/prolog", {"query": "X = 1", "neem": "nobody"}, 404, "nobody"),
    ("/api/prolog", {"query": "X = 1", "neem": "ada", "bindings": {"X": True}}, 400, "binding X"),
    ("/api/prolog", {"query": "X = 1", "neem": "ada", "limit": 0}, 422, "limit"),
    ("/api/prolog", {"query": "open('/etc/passwd', read, S)", "neem": "ada"}, 403, "not allowed"),
    ("/api/prolog", {"query": "assertz(foo)", "neem": "ada"}, 403, "not allowed"),
])
def test_bad_input_is_a_one_line_4xx_and_changes_nothing(client, neem, ctx, path, body, status, needle):
    client.post(f"/api/neems/{neem}/actions", json={"call": "pick(apple)", "begin": at(0, 0), "end": at(0, 2)})
    count = ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem)))
    response = client.post(path, json=body)
    assert response.status_code == status, response.text
    error = response.json()["error"]
    assert needle in error and "\n" not in error
    assert ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem))) == count
    assert client.get("/api/neems").status_code == 200  # still serving


@pytest.mark.parametrize("method,path,status,needle", [
    ("GET", "/api/neems/ada/why-not", 422, "task"),
    ("GET", "/api/neems/ada/why-not?task=fly(x)", 400, "fly"),
    ("GET", "/api/neems/ada/why-not?task=pick(banana)&at=never", 400, "ISO-8601"),
    ("GET", "/api/neems/nobody/why-not?task=pick(banana)", 404, "nobody"),
    ("GET", "/api/neems/nobody/what-next", 404, "nobody"),
    ("GET", "/api/neems/nobody/situation", 404, "nobody"),
    ("GET", "/api/neems/ada/something-else?task=pick(", 400, "malformed"),
    ("GET", "/api/nothing-here", 404, "Not Found"),
    ("DELETE", "/api/neems", 405, "Method Not Allowed"),
    ("POST", "/api/neems/ada/situation", 422, "JSON"),  # a body that is not JSON
])
def test_every_other_refusal_is_one_line_too(client, neem, ctx, method, path, status, needle):
    count = ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem)))
    response = client.request(method, path, content=b"{not json", headers={"Content-Type": "application/json"})
    assert response.status_code == status, response.text
    error = response.json()["error"]
    assert needle in error and "\n" not in error
    assert ctx.thread.call(lambda: ctx.engine.store.count(ctx.engine.resolve(neem))) == count
    assert ctx.thread.call(lambda: (ctx.engine.session(neem).latest, ctx.engine.session(neem).choice)) == (None, None)


def test_the_id_and_the_name_reach_one_session(client, neem, ctx):
    neem_id = next(n["id"] for n in client.get("/api/neems").json() if n["name"] == neem)
    client.post(f"/api/neems/{neem}/actions", json={"call": "pick(apple)", "begin": at(0, 0), "end": at(0, 2)})
    answer = client.post(f"/api/neems/{neem_id}/actions", json={"call": "pick(red_mug)", "begin": at(0, 3), "end": at(0, 4)})
    assert answer.json()["neem"] == neem_id and answer.json()["history"] == 2  # one session, whichever name is used
    assert ctx.thread.call(lambda: ctx.engine.session(neem) is ctx.engine.session(neem_id))
    query = {"query": "kb_call(executes_task(A, T))", "limit": 100}
    by_name = client.post("/api/prolog", json={**query, "neem": neem}).json()["solutions"]
    by_id = client.post("/api/prolog", json={**query, "neem": neem_id}).json()["solutions"]
    # Prolog reads the one NEEM either names (two actions, and the top-level action of their episode)
    assert len(by_name) == 3 and by_name == by_id


def test_prolog_pages_solutions_and_binds_values_as_terms(client, neem):
    drive(client, neem, days=1)
    query = {"query": "kb_call(executes_task(A, T))", "neem": neem, "limit": 3}
    first = client.post("/api/prolog", json=query).json()
    assert len(first["solutions"]) == 3 and first["more"] is True
    rest = client.post("/api/prolog", json={**query, "offset": 3, "limit": 100}).json()
    assert rest["more"] is False and len(first["solutions"]) + len(rest["solutions"]) == 3 * len(ROUTINE) + 1
    # (each step: the action, and the imagining and the reasoning of its situation; and the
    # top-level action of the day's episode)
    # a value with quotes and a comma stays one atom: it is bound, never spliced into the text
    tricky = "x'), halt, ('"
    bound = client.post("/api/prolog", json={"query": "atom_length(X, N)", "bindings": {"X": tricky}, "neem": neem}).json()
    assert bound["solutions"] == [{"X": tricky, "N": len(tricky)}]


def test_choice_is_published_to_the_robot(client, neem):
    made = client.post(f"/api/neems/{neem}/choice", json={"task": "pick(red_mug)",
                                                           "workflow": ["pick(red_mug)", "place(red_mug, counter_top)"]})
    assert made.status_code == 200
    assert client.get(f"/api/neems/{neem}/choice").json()["workflow"] == ["pick(red_mug)", "place(red_mug, counter_top)"]


def test_token_is_checked_on_every_api_call_and_the_stream(ctx):
    from fastapi.testclient import TestClient

    ctx.token = "s3cret-token-123"
    with TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
        assert client.get("/api/neems").status_code == 401
        assert client.get("/api/events").status_code == 401
        assert client.get("/").status_code == 401
        assert client.get("/api/neems", headers={"Authorization": "Bearer wrong-token-000"}).status_code == 401
        assert client.get("/api/neems", headers={"Authorization": "Bearer s3cret-token-123"}).status_code == 200
        assert client.get("/api/neems", params={"token": "s3cret-token-123"}).status_code == 200
        assert client.get("/openapi.json").status_code == 200  # the schema holds no user data


def test_no_cors_and_cross_origin_refused(client, neem):
    response = client.get("/api/neems", headers={"Origin": "http://evil.example"})
    assert response.status_code == 403
    assert "access-control-allow-origin" not in {k.lower() for k in response.headers}


def test_openapi_and_offline_docs(client):
    schema = client.get("/openapi.json").json()
    assert "/api/neems/{neem}/situation" in schema["paths"]
    docs = client.get("/docs").text
    assert "/docs/static/swagger-ui-bundle.js" in docs and "cdn" not in docs
    assert client.get("/docs/static/swagger-ui-bundle.js").status_code == 200


def test_every_route_declares_its_answer_and_the_error_sent_is_the_one_documented(client, neem):
    schema = client.get("/openapi.json").json()
    for path, methods in schema["paths"].items():
        for method, operation in methods.items():
            ok = next(code for code in operation["responses"] if code.startswith("2"))
            content = operation["responses"][ok].get("content", {})
            if path == "/api/events":
                continue  # a stream, not a JSON answer
            assert content["application/json"]["schema"] != {}, (method, path)
            assert operation["responses"]["422"]["content"]["application/json"]["schema"]["$ref"].endswith("/ErrorAnswer")
    assert set(schema["components"]["schemas"]["ErrorAnswer"]["properties"]) == {"error"}
    sent = client.post(f"/api/neems/{neem}/situation", json={"available": "x"}).json()
    assert set(sent) == {"error"}


def test_page_renders_the_latest_ranking_without_external_resources(client, neem):
    drive(client, neem, days=1)
    client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(1, 0)})
    page = client.get("/", params={"neem": neem})
    assert page.status_code == 200
    html = page.text
    # the robot's call stays on the button (data-task); the person reads plain words
    assert "data-task='open(small_drawer)'" in html and "Open the small drawer" in html
    assert "http://" not in html.replace("http://www.w3", "") and "https://" not in html
    policy = page.headers["content-security-policy"]
    assert "default-src 'none'" in policy and "unsafe-inline" not in policy
    for name in ("page.js", "page.css"):
        assert client.get(f"/static/{name}").status_code == 200
    assert client.get("/favicon.ico").headers["content-type"] == "image/svg+xml"
    assert client.get("/static/../app.py").status_code == 404


def test_a_neem_logged_elsewhere_shows_its_latest_situation(ctx, onto):
    """The page after `make demo`: a NEEM whose last record is an imagined situation."""
    from fastapi.testclient import TestClient

    from oracle.neem.writer import NeemLogger

    def log() -> None:
        logger = NeemLogger.create(ctx.engine.store, onto, user="eve", neem_id="eve")
        logger.action("pick(red_mug)", at(0, 0), at(0, 2))
        logger.available(["pick(thermos)", "open(fridge)"], at(0, 5))
        logger.flush()

    ctx.thread.call(log)
    with TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
        shown = client.get("/api/neems/eve/situation").json()
        assert sorted(r["task"] for r in shown["ranking"]) == ["open(fridge)", "pick(thermos)"]
        assert "pick(thermos)" in client.get("/", params={"neem": "eve"}).text


def test_the_thesis_oracle_explains_with_its_similar_situations(tmp_path, onto):
    """``serve --method thesis``: support is |H(s_o)| and the reason says so; no context fields."""
    import re

    from fastapi.testclient import TestClient

    from oracle.algorithm.params import Hyperparameters
    from oracle.service import build_context

    context = build_context(str(tmp_path / "t.sqlite"), onto, Hyperparameters(), method="thesis")
    try:
        with TestClient(create_app(context), base_url="http://127.0.0.1") as client:
            client.post("/api/neems", json={"user": "ada", "neem": "ada"})
            drive(client, "ada", days=1)
            ranking = client.post("/api/neems/ada/situation", json={"available": AVAILABLE, "at": at(1, 0)}).json()["ranking"]
    finally:
        context.thread.close()
    assert all((e["probability"], e["context_order"], e["context"], e["situations"]) == (None, None, [], []) for e in ranking)
    for entry in ranking:
        n = entry["support"]
        assert entry["reason"] == ("new to me" if n == 0 else f"like {n} past situation{'s' if n != 1 else ''}")
        assert re.fullmatch(r"like \d+ past situations?|new to me", entry["reason"])
    assert any(e["support"] > 0 for e in ranking)


def test_the_request_log_holds_ids_never_the_users_data(ctx, caplog):
    """Method, route template, NEEM id, status and time; no task, object, query or token, also on
    refusals."""
    import logging

    from fastapi.testclient import TestClient

    ctx.token = "s3cret-token-123"
    auth = {"Authorization": "Bearer s3cret-token-123"}
    with caplog.at_level(logging.INFO, logger="oracle.service"), TestClient(create_app(ctx), base_url="http://127.0.0.1") as client:
        client.post("/api/neems", json={"user": "Ada Lovelace", "neem": "ada"}, headers=auth)
        client.post("/api/neems/ada/perception", json={"objects": [{"name": "banana"}], "at": at(0, 0)}, headers=auth)
        client.post("/api/neems/ada/situation", json={"available": ["pick(red_mug)", "open(fridge)"], "at": at(0, 1)}, headers=auth)
        client.post("/api/neems/ada/actions", json={"call": "pick(red_mug)", "begin": at(0, 2)}, headers=auth)
        client.get("/api/neems/ada/why-not", params={"task": "pick(thermos)"}, headers=auth)
        client.post("/api/neems/ada/situation", json={"available": ["fly(unicorn)"]}, headers=auth)
        client.post("/api/prolog", json={"query": "atom_length(secretquery, N)", "neem": "ada"}, headers=auth)
        client.get("/api/neems", params={"token": "wrong-token-guess"})
    text = "\n".join(record.getMessage() for record in caplog.records)
    assert "POST /api/neems/{neem}/situation neem=ada 200" in text
    for secret in ("Ada Lovelace", "banana", "red_mug", "fridge", "thermos", "unicorn", "secretquery", "s3cret", "wrong-token"):
        assert secret not in text, secret


def test_a_reason_names_the_objects_in_hand_where_no_context_backs_the_task():
    from oracle.answers import support_sentence

    never = {"support": 0, "context_order": -1, "context": [], "situations": [], "done": False}
    assert support_sentence({**never, "focus": ["red_mug"]}) == "never done: uses red_mug in hand"
    assert support_sentence({**never, "focus": []}) == "never done: like similar tasks"
    done = {**never, "support": 2, "context_order": 0, "done": True, "focus": ["fridge", "milk"]}
    assert support_sentence(done) == "done 2\u00d7, not at this point; uses fridge, milk in hand"
    after = {**done, "context_order": 1, "context": ["pick(milk)"]}
    assert support_sentence(after) == "after pick(milk): 2\u00d7"    # a counted context says enough


def test_a_reason_says_a_task_is_newly_possible_where_no_context_backs_it():
    from oracle.answers import support_sentence

    never = {"support": 0, "context_order": -1, "context": [], "situations": [], "done": False, "new": True}
    assert support_sentence({**never, "focus": []}) == "never done: newly possible"
    assert support_sentence({**never, "focus": ["red_mug"]}) == "never done: uses red_mug in hand; newly possible"
    done = {**never, "support": 3, "context_order": 0, "done": True, "focus": []}
    assert support_sentence(done) == "done 3\u00d7, not at this point; newly possible"
    assert support_sentence({**done, "context_order": 2, "context": ["a", "b"]}) == "after a \u2192 b: 3\u00d7"
    back = {**done, "new": False, "resumed": True, "focus": ["red_mug"]}
    assert support_sentence(back) == "done 3\u00d7, not at this point; uses red_mug in hand; goes on from before the break"


def test_tablet_view_speaks_the_persons_language_and_keeps_the_calls(client, neem):
    drive(client, neem, days=2)
    ranked = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()
    english = client.get(f"/api/neems/{neem}/tablet", params={"lang": "en"}).json()
    german = client.get(f"/api/neems/{neem}/tablet", headers={"Accept-Language": "de-DE,de;q=0.9,en;q=0.5"}).json()
    assert [t["task"] for t in english["tasks"]] == [r["task"] for r in ranked["ranking"]] == [t["task"] for t in german["tasks"]]
    said = {t["task"]: t["said"] for t in english["tasks"]}
    assert said["pour(thermos, red_mug)"] == "Pour the coffee into the red mug"
    assert {t["task"]: t["said"] for t in german["tasks"]}["open(small_drawer)"] == "Die kleine Schublade öffnen"
    assert english["user"] == "ada" and english["clock"] == "Morning, 08:00" and german["clock"] == "morgens, 08:00"
    assert english["person"] == "Ada"  # the header's name; a persona id would give none (test_words)
    for view in (english, german):
        for task in view["tasks"]:  # one short sentence, no call syntax, no scores
            assert task["reason"].endswith(".") and task["reason"].count(". ") == 0 and "(" not in task["reason"], task
    assert [s["task"] for s in english["workflow"]] == ranked["chain"]


def test_why_not_in_plain_words_fits_every_task_the_top_one_included(client, neem):
    drive(client, neem, days=2)
    ranked = client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()
    for entry in ranked["ranking"]:
        said = client.get(f"/api/neems/{neem}/why-not", params={"task": entry["task"], "lang": "en"}).json()["said"]
        assert 1 <= said.count(". ") + 1 <= 2 and len(said) < 200 and "score" not in said, said
        assert ("first suggestion" in said) == (entry["rank"] == 1), said
    gone = client.get(f"/api/neems/{neem}/why-not", params={"task": "pick(apple)", "lang": "de"}).json()["said"]
    assert gone.startswith("Das kann der Roboter jetzt nicht tun")


def test_a_choice_is_the_users_decision_in_the_neem_and_survives_a_restart(ctx, onto, neem, client):
    from fastapi.testclient import TestClient

    from oracle.service import build_context

    drive(client, neem, days=1)
    client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(1, 0)})
    made = client.post(f"/api/neems/{neem}/choice", json={"task": "open(small_drawer)", "at": at(1, 1),
                                                          "workflow": ["open(small_drawer)", "pick(red_mug)"]}).json()
    assert made["at"] == at(1, 1) and made["decision"]
    # the decision is the user's: performed by the person, not the robot
    performer = ctx.thread.call(lambda: [d["o"] for d in ctx.engine.store.find(
        ctx.engine.resolve(neem), s=made["decision"], p="http://www.ease-crc.org/ont/SOMA.owl#isPerformedBy", exact=True)])
    assert performer and "Agent_robot" not in performer[0]
    bad = client.post(f"/api/neems/{neem}/choice", json={"task": "pick(red_mug)", "workflow": ["open(small_drawer)"]})
    assert bad.status_code == 400
    store = ctx.thread.call(lambda: ctx.engine.store.location)
    ctx.thread.call(lambda: ctx.engine.store.close())
    again = build_context(store, onto, Hyperparameters())
    with TestClient(create_app(again), base_url="http://127.0.0.1") as restarted:
        back = restarted.get(f"/api/neems/{neem}/choice").json()
    assert (back["task"], back["workflow"], back["at"]) == ("open(small_drawer)", ["open(small_drawer)", "pick(red_mug)"], at(1, 1))


def test_a_wrong_method_is_a_405_whose_allow_names_every_method_of_the_path(client, neem):
    for path, allowed in [(f"/api/neems/{neem}/situation", "GET, POST"), (f"/api/neems/{neem}/choice", "GET, POST"),
                          ("/api/neems", "GET, POST"), ("/api/prolog", "POST")]:
        answer = client.delete(path)
        assert (answer.status_code, answer.headers["allow"]) == (405, allowed), path
        assert set(answer.json()) == {"error"}


def test_the_page_shows_times_on_the_zone_it_was_given_and_what_next_tells_choice_from_action(ctx, client, neem):
    from oracle.timeline import display_zone

    ctx.zone = display_zone("Europe/Berlin")
    drive(client, neem, days=1)
    client.post(f"/api/neems/{neem}/situation", json={"available": AVAILABLE, "at": at(1, 0)})
    assert client.get(f"/api/neems/{neem}/tablet").json()["clock"] == "Morning, 09:00"  # 08:00 UTC in March
    client.post(f"/api/neems/{neem}/choice", json={"task": "pick(banana)", "at": at(1, 1)})
    said = client.get(f"/api/neems/{neem}/what-next").json()["said"]
    assert "You chose \u201cPick up the banana\u201d; the robot has not done it yet." in said
    client.post(f"/api/neems/{neem}/actions", json={"call": "pick(banana)", "begin": at(1, 2)})
    said = client.get(f"/api/neems/{neem}/what-next").json()["said"]
    assert said.endswith("At 09:00 the robot did: Pick up the banana.")
    with pytest.raises(Exception, match="no such time zone"):
        display_zone("Mars/Olympus")


def test_neem_interface_reads_through_the_json_prolog_endpoint(client, neem):
    """neem_interface_python's reading methods against the service's JSON Prolog endpoint (in
    place of rosprolog); its logging methods are refused there (the endpoint is read-only)."""
    from oracle.service.neem_interface import NEEMError, NEEMInterface, OverHttp

    drive(client, neem, days=1)
    ni = NEEMInterface(OverHttp("http://in-process", neem, post=lambda path, body: client.post(path, json=body).json()))
    actions = ni.get_all_actions()
    assert len(actions) >= len(ROUTINE)  # the routine's actions, and the day's top-level action
    tasks = {a: ni.get_tasks_for_action(a) for a in actions}
    picks = [a for a, ts in tasks.items() if any("#pick_" in t for t in ts)]
    assert len(picks) == 2  # pick(red_mug), pick(thermos): tasks named <TaskClass>_<id>
    begins = sorted(ni.get_interval_for_event(a)[0] for a in picks)
    assert begins == [at(0, 10), at(0, 40)]
    assert ni.get_tf_trajectory("http://e.org/x#cup", 0.0, 1e10) == []
    with pytest.raises(NEEMError):
        ni.add_participant_with_role(picks[0], "http://e.org/x#cup", "soma:'Patient'")


def test_the_situation_answer_names_the_routine_in_progress_and_what_remains(client):
    client.post("/api/neems", json={"user": "Rae", "neem": "rae"})
    drive(client, "rae", days=2)
    two_days = client.post("/api/neems/rae/situation", json={"available": AVAILABLE, "at": at(2, 0)}).json()
    assert two_days["routine"] is None  # seen on two days: not yet a routine
    drive_day(client, "rae", 2)
    for i, call in enumerate(ROUTINE[:2]):  # the fourth morning: two steps done
        done = {"call": call, "begin": at(3, 10 * i), "end": at(3, 10 * i + 5)}
        assert client.post("/api/neems/rae/actions", json=done).status_code == 200
    body = client.post("/api/neems/rae/situation", json={"available": AVAILABLE, "at": at(3, 25)}).json()
    assert body["routine"]["remaining"] == ROUTINE[2:] and body["routine"]["steps_left"] == 5
    assert body["routine"]["done"] == 2 and body["routine"]["key"] == "r1" and body["routine"]["name"]
    assert client.get("/api/neems/rae/situation").json()["routine"] == body["routine"]
    view = client.get("/api/neems/rae/tablet", params={"lang": "en"}).json()["routine"]
    assert view["label"] == f"Finish \u201c{body['routine']['name']}\u201d (5 steps left)"
    assert [s["task"] for s in view["steps"]] == ROUTINE[2:]
    # who usually does each step that remains: the robot, which did all of them
    assert body["routine"]["remaining_modes"] == ["robot"] * 5 and {s["mode"] for s in view["steps"]} == {"robot"}
    later = client.post("/api/neems/rae/situation", json={"available": AVAILABLE, "at": at(3, 3600)}).json()
    assert later["routine"] is None  # an hour idle since: no routine in progress


def test_stopping_the_service_ends_each_neems_recording_session(tmp_path, onto):
    """KnowRob's mem_episode_stop as the service stops: every episode of a NEEM the service wrote
    has its actions as constituents of its top-level action and an interval with an end, the
    last (still open) one included; a service started again on the store opens a new one."""
    from fastapi.testclient import TestClient

    from oracle.namespaces import DUL_IRI, SOMA_IRI
    from oracle.service import build_context
    from oracle.store import RDF_TYPE

    path = str(tmp_path / "s.sqlite")

    def serve(days: range) -> None:
        context = build_context(path, onto, Hyperparameters())
        try:
            with TestClient(create_app(context), base_url="http://127.0.0.1") as test_client:
                if days.start == 0:
                    assert test_client.post("/api/neems", json={"user": "ada", "neem": "ada"}).status_code == 201
                for day in days:
                    drive_day(test_client, "ada", day)
                # while it runs, the open session has no constituents yet (they are written at its end)
                store = context.thread.call(lambda: context.engine.store)
                neem = context.thread.call(lambda: context.engine.resolve("ada"))
                assert len(_ended(store, neem)[1]) == days.stop - 1
        finally:
            context.thread.close()

    serve(range(0, 2))
    serve(range(2, 3))
    from oracle.store import open_store

    store = open_store(path)
    neem = next(info.id for info in store.neems())
    episodes, ended = _ended(store, neem)
    assert len(episodes) == 3 and sorted(ended) == sorted(episodes)
    constituents = [d["o"] for d in store.find(neem, p=DUL_IRI + "hasConstituent")]
    actions = {d["s"] for d in store.find(neem, p=RDF_TYPE, o=DUL_IRI + "Action", exact=True)}
    # every logged action (the idle ones too) is a constituent of exactly one top-level action
    assert sorted(constituents) == sorted(actions) and len(actions) == 3 * len(ROUTINE) + 2
    assert all(d["s"] in episodes for d in store.find(neem, p=RDF_TYPE, o=SOMA_IRI + "Episode", exact=True))


def _ended(store, neem: str) -> tuple[list[str], list[str]]:
    """The NEEM's episodes, and those whose top-level action has constituents and an ended interval."""
    from oracle.namespaces import DUL_IRI, SOMA_IRI
    from oracle.store import RDF_TYPE

    episodes = [d["s"] for d in store.find(neem, p=RDF_TYPE, o=SOMA_IRI + "Episode", exact=True)]
    ended = []
    for episode in episodes:
        top = next(store.find(neem, s=episode, p=DUL_IRI + "includesAction"))["o"]
        interval = next(store.find(neem, s=top, p=DUL_IRI + "hasTimeInterval"))["o"]
        if list(store.find(neem, s=top, p=DUL_IRI + "hasConstituent")) and list(
                store.find(neem, s=interval, p=SOMA_IRI + "hasIntervalEnd")):
            ended.append(episode)
    return episodes, ended
