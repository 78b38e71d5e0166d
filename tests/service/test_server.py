"""The real server process on a free loopback port, and the tablet page in headless chromium."""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.service.conftest import AVAILABLE, ROUTINE, at

pytestmark = pytest.mark.skipif(shutil.which("swipl") is None, reason="SWI-Prolog (swipl) is not installed; run make setup")
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
ROOT = Path(__file__).resolve().parents[2]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def call(base: str, path: str, body: dict | None = None) -> tuple[int, dict]:
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(base + path, data=data, headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(request, timeout=30) as response:
            return response.status, json.loads(response.read())
    except urllib.error.HTTPError as error:
        return error.code, json.loads(error.read())


@pytest.fixture(scope="module")
def server(tmp_path_factory) -> Iterator[str]:
    store = tmp_path_factory.mktemp("served") / "s.sqlite"
    port = free_port()
    process = subprocess.Popen([sys.executable, "-m", "oracle", "serve", "--store", str(store), "--port", str(port)],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    base = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 120
    while True:
        try:
            urllib.request.urlopen(base + "/api/neems", timeout=2).read()
            break
        except OSError:
            if process.poll() is not None or time.monotonic() > deadline:
                process.kill()
                pytest.fail(f"the server did not start: {process.stdout.read() if process.stdout else ''}")
            time.sleep(0.3)
    yield base
    process.terminate()
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        process.kill()


def test_real_server_runs_the_loop_and_survives_bad_requests(server):
    assert call(server, "/api/neems", {"user": "bea", "neem": "bea"})[0] == 201
    for i, action in enumerate(ROUTINE[:3]):
        status, ranked = call(server, "/api/neems/bea/situation", {"available": AVAILABLE, "at": at(0, 10 * i)})
        assert status == 200 and len(ranked["ranking"]) == len(AVAILABLE)
        assert call(server, "/api/neems/bea/actions", {"call": action, "begin": at(0, 10 * i)})[0] == 200
    status, error = call(server, "/api/neems/bea/situation", {"available": "pick(red_mug)"})
    assert status == 422 and "\n" not in error["error"]
    assert call(server, "/api/prolog", {"query": "halt", "neem": "bea"})[0] == 400
    status, answer = call(server, "/api/neems/bea/why-not?task=pick(banana)")
    assert status == 200 and "pick(banana)" in answer["sentence"]


def test_simulated_robot_drives_a_persona_without_errors(server):
    from oracle.service.robot import drive, persona_rows

    user, rows = persona_rows(1, 3, 1)
    result = drive(server, user, rows[:20], "robot-sim")
    assert result.errors == [] and result.steps == 20
    assert len(result.latencies["situation"]) == len(result.latencies["choice"]) == 20
    assert call(server, "/api/neems/robot-sim/choice")[1]["task"] == str(rows[19].action)
    history = call(server, "/api/neems/robot-sim/situation")[1]["history"]
    assert history >= 19  # every action but the last was in the history the last situation ranked


def test_binding_beyond_loopback_needs_a_token():
    result = subprocess.run([sys.executable, "-m", "oracle", "serve", "--host", "0.0.0.0", "--port", "1"],
                            cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert result.stderr.strip() == "error: --host 0.0.0.0: binding beyond loopback needs --token or --token-file"


@pytest.fixture()
def browser() -> Iterator:
    if CHROMIUM is None:
        pytest.skip("no chromium installed (make setup installs Debian's chromium)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (pip install -e '.[dev]')")
    with sync_api.sync_playwright() as playwright:
        launched = playwright.chromium.launch(
            executable_path=CHROMIUM, headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync"])
        yield launched
        launched.close()


def test_page_shows_ranking_updates_live_posts_the_tap_and_answers_why_not(server, browser):
    assert call(server, "/api/neems", {"user": "cem", "neem": "cem"})[0] == 201
    for i, action in enumerate(ROUTINE):
        call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(0, 10 * i)})
        call(server, "/api/neems/cem/actions", {"call": action, "begin": at(0, 10 * i), "end": at(0, 10 * i + 5)})
    _, first = call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(1, 0)})
    # the test evaluates its own expressions in the page, which the page's CSP (no eval) would refuse
    page = browser.new_page(viewport={"width": 1024, "height": 1180}, bypass_csp=True)
    page.goto(server + "/?neem=cem")
    tasks = page.locator("#tasks .task .name")
    assert tasks.all_text_contents() == [r["task"] for r in first["ranking"]]
    page.wait_for_function("document.body.dataset.live === 'yes'")

    # live: the robot posts a smaller situation and the page follows without a reload
    _, second = call(server, "/api/neems/cem/situation", {"available": ["pick(banana)", "open(fridge)"], "at": at(1, 1)})
    page.wait_for_function("document.querySelectorAll('#tasks .task').length === 2")
    assert tasks.all_text_contents() == [r["task"] for r in second["ranking"]]

    # keyboard: Tab reaches the top suggestion, Enter chooses it
    page.keyboard.press("Tab")
    assert page.evaluate("document.activeElement.dataset.task") == second["ranking"][0]["task"]
    page.keyboard.press("Enter")
    page.wait_for_function("document.getElementById('status').textContent.startsWith('You chose')")
    assert call(server, "/api/neems/cem/choice")[1]["task"] == second["ranking"][0]["task"]

    # a tap on the second task is posted as the decision; why-not shows the sentence
    page.locator("#tasks .task").nth(1).click()
    page.wait_for_function(f"document.getElementById('status').textContent.includes({json.dumps(second['ranking'][1]['task'])})")
    assert call(server, "/api/neems/cem/choice")[1]["task"] == second["ranking"][1]["task"]
    page.locator("#tasks .whynot").nth(1).click()
    page.wait_for_function("document.getElementById('status').textContent.includes('ranked')")
    assert second["ranking"][1]["task"] in page.locator("#status").text_content()
    # the predicted chain is one choice: the whole workflow is posted, its first step first
    call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(1, 2)})
    page.wait_for_function(f"document.querySelectorAll('#tasks .task').length === {len(AVAILABLE)}")
    _, latest = call(server, "/api/neems/cem/situation")
    if len(latest["chain"]) >= 2:
        page.locator("#workflow").click()
        page.wait_for_function("document.getElementById('status').textContent.startsWith('You chose the workflow')")
        assert call(server, "/api/neems/cem/choice")[1]["workflow"] == latest["chain"]
    shot = os.environ.get("NEEM_ORACLE_SCREENSHOT")
    if shot:
        page.locator("#tasks .whynot").nth(2).click()
        page.wait_for_function("document.getElementById('status').textContent.includes('ranked')")
        page.screenshot(path=shot, full_page=True)
