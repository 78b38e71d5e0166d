"""/explore: the NEEM explorer's data routes in process, its curve held equal to ``evaluate``'s
figures on the same NEEM replayed, and the page in headless chromium (console, exports, keys, axe)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from oracle.algorithm.params import preset
from tests.service.test_server import ROOT, axe_source, browser, free_port, serious, start_server, stop_server  # noqa: F401

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")


def _persona_chains(path: Path, days: int) -> Path:
    """A simulated user's chains with their available sets (the persona benchmark's generator)."""
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    rows, _ = simulate(make_persona(0, 0), load_world(), days, 0)
    path.write_text("".join(json.dumps(row.to_json()) + "\n" for row in rows))
    return path


@pytest.fixture(scope="module")
def chains(tmp_path_factory) -> Path:
    return _persona_chains(tmp_path_factory.mktemp("explore") / "chains.jsonl", 3)


@pytest.fixture(scope="module")
def store(chains, tmp_path_factory) -> Path:
    from oracle.neem.importing import import_chains
    from oracle.ontology import build_ontology
    from oracle.store import open_store

    path = tmp_path_factory.mktemp("explore-store") / "s.sqlite"
    opened = open_store(path)
    import_chains(opened, build_ontology(), chains, commit_every=1000)
    opened.close()
    return path


@pytest.fixture()
def client(store, tmp_path) -> Iterator:
    from fastapi.testclient import TestClient

    from oracle.evaluation.neem_replay import replay_neem
    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    ctx = build_context(str(copy), build_ontology(), preset("recommended"))
    app = create_app(ctx)
    app.state.explore_replay = replay_neem  # as serve hands it in
    with TestClient(app, base_url="http://127.0.0.1") as test_client:
        yield test_client
    ctx.thread.close()


def _decisions(client, neem: str, window: int = 100) -> dict:
    deadline = time.monotonic() + 300
    while True:
        response = client.get(f"/explore/api/neems/{neem}/decisions?window={window}")
        if response.status_code != 202:
            assert response.status_code == 200, response.text
            return response.json()
        assert time.monotonic() < deadline, "the replay did not finish"
        time.sleep(0.2)


def _timeline(client, neem: str) -> dict:
    """The timeline, once the NEEM's first read is done (nothing is kept for a NEEM imported in
    process: the route answers 202 while the service reads it)."""
    deadline = time.monotonic() + 120
    while (response := client.get(f"/explore/api/neems/{neem}/timeline")).status_code == 202:
        assert response.json()["reading"] and time.monotonic() < deadline, "the first read did not finish"
        time.sleep(0.1)
    assert response.status_code == 200, response.text
    return response.json()


def test_the_list_and_the_timeline_show_the_store(client, chains):
    neems = client.get("/explore/api/neems").json()
    assert len(neems) == 1
    rows = chains.read_text().splitlines()
    neem = neems[0]
    assert neem["user"] == json.loads(rows[0])["user"] and neem["actions"] >= len(rows) and neem["begin"] < neem["end"]
    assert neem["consent"] == "not shared"  # nothing is shared by default (python -m oracle share)
    timeline = _timeline(client, neem["id"])
    calls = [timeline["calls"][timeline["rows"][i + 2]] for i in range(0, len(timeline["rows"]), 6)]
    assert [c for c in calls if c != "idle"] == [json.loads(r)["action"].replace(" ", "") for r in rows]
    assert "idle" in calls  # the nights are idle actions, drawn as gaps


def test_the_curve_equals_evaluate_on_the_same_neem_replayed(client, tmp_path, capsys):
    """The explorer's figures are the replay's, not a second implementation: the NEEM's own chains
    (neem_chains) replayed by ``python -m oracle evaluate`` give the same Top-1/3/5."""
    from oracle.cli import main
    from oracle.evaluation.neem_replay import neem_chains

    neem = client.get("/explore/api/neems").json()[0]
    found = _decisions(client, neem["id"], window=5000)
    n = len(found["rank"])
    for k in (1, 3, 5):  # a window over the whole NEEM ends on the whole NEEM's rate
        assert found["rolling"][f"top{k}"][-1] == pytest.approx(found["summary"][f"top{k}"], abs=1e-12)
    history = _timeline(client, neem["id"])
    from oracle.bridge.records import history_rows

    rows = history_rows(history)
    exported = tmp_path / "neem.jsonl"
    exported.write_text("".join(json.dumps(r.to_json()) + "\n" for r in neem_chains(rows, neem["user"])))
    out = tmp_path / "evaluate.json"
    assert main(["evaluate", str(exported), "--json", str(out)]) == 0
    capsys.readouterr()
    figures = json.loads(out.read_text())
    assert figures["n_predictions"] == n
    assert {k: figures["methods"][found["method"]][k] for k in ("top1", "top3", "top5")} == found["summary"]
    ranks = found["rank"]
    assert found["summary"]["top1"] == sum(1 for r in ranks if r == 1) / n
    assert all(len(r) <= 10 for r in found["ranked"])
    assert all(found["calls"][found["truth"][i]] == found["calls"][found["ranked"][i][r - 1]]
               for i, r in enumerate(ranks) if 1 <= r <= len(found["ranked"][i]))


def test_without_the_replay_the_decisions_say_so(store, tmp_path):
    from fastapi.testclient import TestClient

    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    ctx = build_context(str(copy), build_ontology(), preset("recommended"))
    try:
        with TestClient(create_app(ctx), base_url="http://127.0.0.1") as test_client:
            neem = test_client.get("/explore/api/neems").json()[0]["id"]
            answer = test_client.get(f"/explore/api/neems/{neem}/decisions")
            assert answer.status_code == 501 and "replay" in answer.json()["error"]
    finally:
        ctx.thread.close()


def test_the_page_and_its_files_are_served_with_the_tablets_rules(client):
    page = client.get("/explore")
    assert page.status_code == 200 and "script-src 'self'" in page.headers["content-security-policy"]
    assert client.get("/static/explore/explore.js").status_code == 200
    assert client.get("/static/explore/other.js").status_code == 404
    assert client.get("/explore", headers={"Host": "evil.example"}).status_code == 421
    assert client.post("/api/prolog", json={"query": "assertz(foo(1))"}).status_code == 403  # the console's route


def test_with_a_token_the_data_needs_it(store, tmp_path):
    from fastapi.testclient import TestClient

    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    token = "a-long-enough-token"
    ctx = build_context(str(copy), build_ontology(), preset("recommended"), token=token)
    try:
        with TestClient(create_app(ctx), base_url="http://127.0.0.1") as test_client:
            assert test_client.get("/explore").status_code == 401
            assert test_client.get("/explore/api/neems").status_code == 401
            assert test_client.get(f"/explore?token={token}").status_code == 200
            assert test_client.get("/explore/api/neems", headers={"Authorization": f"Bearer {token}"}).status_code == 200
            assert test_client.get("/static/explore/explore.js").status_code == 200  # files carry no data
    finally:
        ctx.thread.close()


# -- the page in chromium ------------------------------------------------------------------------
@pytest.fixture(scope="module")
def served(store, tmp_path_factory) -> Iterator[str]:
    copy = tmp_path_factory.mktemp("explore-served") / "s.sqlite"
    shutil.copy(store, copy)
    port = free_port()
    process = start_server(copy, port)
    yield f"http://127.0.0.1:{port}"
    stop_server(process)


def _open(browser, served: str, query: str = ""):  # noqa: F811 - the fixture imported above
    page = browser.new_page(viewport={"width": 1280, "height": 1000}, bypass_csp=True, accept_downloads=True)
    page.goto(served + "/explore" + query)
    page.wait_for_function("performance.getEntriesByName('timeline-painted').length > 0", timeout=60_000)
    page.wait_for_function("window.neemExplorer.state.decisions !== null", timeout=300_000)
    return page


def test_every_example_answers_as_a_table_and_a_write_is_refused(served, browser):  # noqa: F811
    from oracle.service.explore_page import EXAMPLES

    page = _open(browser, served)
    for index, query in enumerate(EXAMPLES):
        page.locator("#examples button").nth(index).click()
        page.wait_for_function("document.querySelector('#answers caption') !== null || "
                               "document.getElementById('query-error').textContent !== ''")
        assert page.locator("#query-error").text_content() == "", query
        assert page.locator("#answers thead th").count() >= 1, query
        page.evaluate("document.getElementById('answers').textContent = ''")
    assert page.locator("#answers").count() == 1
    page.locator("#query").fill("assertz(foo(1))")
    page.locator("#console button[type=submit]").click()
    page.wait_for_function("document.getElementById('query-error').textContent !== ''")
    error = page.locator("#query-error").text_content()
    assert error.startswith("error: assertz/1 is not allowed") and "\n" not in error
    recent = page.locator("#recent button").all_text_contents()
    assert recent[0] == "assertz(foo(1))" and len(recent) == len(EXAMPLES) + 1
    page.close()


def test_exports_keys_and_axe(served, browser, axe_source, tmp_path):  # noqa: F811
    page = _open(browser, served)
    page.locator("#examples button").nth(2).click()  # event_time_of_day(A, Part)
    page.wait_for_selector("#answers tbody tr")
    with page.expect_download() as download:
        page.locator("#answers-csv").click()
    text = Path(download.value.path()).read_text()
    assert text.splitlines()[0] == "A,Part" and text.count("\n") == page.locator("#answers tbody tr").count() + 1
    for button, name, head in (("#timeline-svg", "timeline.svg", "<svg"), ("#curve-svg", "curve.svg", "<svg"),
                               ("#timeline-png", "timeline.png", "\x89PNG"), ("#curve-png", "curve.png", "\x89PNG")):
        with page.expect_download() as download:
            page.locator(button).click()
        assert download.value.suggested_filename == name
        assert Path(download.value.path()).read_bytes().startswith(head.encode("latin-1"))
    page.locator("#timeline").focus()
    page.keyboard.press("Home")
    page.keyboard.press("ArrowRight")
    assert page.locator("#decision").text_content().startswith("Decision 2 of ")
    assert page.locator("#decision ol li").count() >= 1
    before = page.evaluate("JSON.stringify(window.neemExplorer.state.view)")
    page.keyboard.press("+")
    page.keyboard.press("Shift+ArrowRight")
    page.wait_for_timeout(100)
    assert page.evaluate("JSON.stringify(window.neemExplorer.state.view)") != before
    assert serious(page, axe_source) == []
    page.close()


def test_the_served_command_hands_in_the_replay(served):
    """``oracle serve`` itself (not only the tests) gives /explore its replay."""
    import urllib.request

    neem = json.loads(urllib.request.urlopen(served + "/explore/api/neems", timeout=30).read())[0]["id"]
    with urllib.request.urlopen(f"{served}/explore/api/neems/{neem}/decisions", timeout=60) as answer:
        assert answer.status in (200, 202)


def test_the_cli_starts_without_importing_the_evaluation():
    """Serving costs no evaluation import until /explore's decisions are asked for."""
    code = ("import sys; import oracle.commands.serve, oracle.service.app; "
            "print(any(m.startswith('oracle.evaluation') for m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.stdout.strip() == "False", result.stderr


def _broken(*args, **kwargs):
    raise ValueError("no replay today")


def test_a_failed_replay_is_one_line_and_tried_again(store, tmp_path):
    from fastapi.testclient import TestClient

    from oracle.ontology import build_ontology
    from oracle.service import build_context
    from oracle.service.app import create_app

    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    ctx = build_context(str(copy), build_ontology(), preset("recommended"))
    try:
        app = create_app(ctx)
        app.state.explore_replay = _broken
        with TestClient(app, base_url="http://127.0.0.1") as test_client:
            neem = test_client.get("/explore/api/neems").json()[0]["id"]
            deadline = time.monotonic() + 120
            while (answer := test_client.get(f"/explore/api/neems/{neem}/decisions")).status_code == 202:
                assert time.monotonic() < deadline
                time.sleep(0.2)
            assert answer.status_code == 500 and answer.json() == {"error": "the replay failed: ValueError: no replay today"}
            assert test_client.get(f"/explore/api/neems/{neem}/decisions").status_code == 202  # a new try
    finally:
        ctx.thread.close()


def test_the_page_works_with_a_token(store, browser, tmp_path):  # noqa: F811
    """Opened as serve prints it (?token=T), the page's own requests carry the token."""
    copy = tmp_path / "s.sqlite"
    shutil.copy(store, copy)
    token = "a-long-enough-token"
    port = free_port()
    process = start_server(copy, port, "--token", token)
    try:
        page = _open(browser, f"http://127.0.0.1:{port}", f"?token={token}")
        assert page.locator("#neems tbody tr").count() == 1
        page.locator("#examples button").nth(3).click()  # aggregate_all(count, is_action(_), N)
        page.wait_for_selector("#answers tbody tr")
        assert int(page.locator("#answers tbody td").first.text_content()) > 0
        page.close()
    finally:
        stop_server(process)


def test_a_neem_without_actions_shows_an_empty_timeline(client):
    assert client.post("/api/neems", json={"user": "new", "neem": "empty"}).status_code == 201
    assert _timeline(client, "empty")["rows"] == []
    assert client.get("/explore/api/neems/empty/decisions").json()["n_predictions"] == 0
    assert client.get("/explore/api/neems/nobody/timeline").status_code == 404
