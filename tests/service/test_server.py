"""The real server process on a free loopback port, and the tablet page in headless chromium."""

from __future__ import annotations

import json
import re
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


def start_server(store: Path, port: int, *extra: str) -> subprocess.Popen:
    """``oracle serve`` on a loopback port, once it answers."""
    process = subprocess.Popen([sys.executable, "-m", "oracle", "serve", "--store", str(store), "--port", str(port), *extra],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    base = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 120
    while True:
        try:
            urllib.request.urlopen(base + "/api/neems", timeout=2).read()
            return process
        except OSError:
            if process.poll() is not None or time.monotonic() > deadline:
                process.kill()
                pytest.fail(f"the server did not start: {process.stdout.read() if process.stdout else ''}")
            time.sleep(0.3)


def stop_server(process: subprocess.Popen) -> None:
    process.terminate()
    try:
        process.wait(timeout=20)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


@pytest.fixture(scope="module")
def server(tmp_path_factory) -> Iterator[str]:
    port = free_port()
    process = start_server(tmp_path_factory.mktemp("served") / "s.sqlite", port)
    yield f"http://127.0.0.1:{port}"
    stop_server(process)


def test_real_server_runs_the_loop_and_survives_bad_requests(server):
    assert call(server, "/api/neems", {"user": "bea", "neem": "bea"})[0] == 201
    for i, action in enumerate(ROUTINE[:3]):
        status, ranked = call(server, "/api/neems/bea/situation", {"available": AVAILABLE, "at": at(0, 10 * i)})
        assert status == 200 and len(ranked["ranking"]) == len(AVAILABLE)
        assert call(server, "/api/neems/bea/actions", {"call": action, "begin": at(0, 10 * i)})[0] == 200
    status, error = call(server, "/api/neems/bea/situation", {"available": "pick(red_mug)"})
    assert status == 422 and "\n" not in error["error"]
    assert call(server, "/api/prolog", {"query": "halt", "neem": "bea"})[0] == 403
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
    for day in range(2):
        for i, action in enumerate(ROUTINE):
            call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(day, 10 * i)})
            call(server, "/api/neems/cem/actions", {"call": action, "begin": at(day, 10 * i), "end": at(day, 10 * i + 5)})
    _, first = call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(2, 0)})
    # the test evaluates its own expressions in the page, which the page's CSP (no eval) would refuse
    page = browser.new_page(viewport={"width": 1024, "height": 1180}, bypass_csp=True)
    page.goto(server + "/?neem=cem")
    tasks = page.locator("#tasks .task .name")
    assert tasks.all_text_contents() == [r["task"] for r in first["ranking"]]
    page.wait_for_function("document.body.dataset.live === 'yes'")

    # live: the robot posts a smaller situation and the page follows without a reload
    _, second = call(server, "/api/neems/cem/situation", {"available": ["pick(banana)", "open(fridge)"], "at": at(2, 1)})
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
    call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(2, 2)})
    page.wait_for_function(f"document.querySelectorAll('#tasks .task').length === {len(AVAILABLE)}")
    _, latest = call(server, "/api/neems/cem/situation")
    assert latest["chain"][:2] == ROUTINE[:2]  # the morning after a night: yesterday's routine
    assert page.locator("#workflow .steps").text_content() == " \u2192 ".join(latest["chain"])
    page.locator("#workflow").click()
    page.wait_for_function("document.getElementById('status').textContent.startsWith('You chose the workflow')")
    assert call(server, "/api/neems/cem/choice")[1] == {"neem": "cem", "task": latest["chain"][0], "workflow": latest["chain"]}
    assert page.locator("#tasks li.flow").get_attribute("class") == "flow chosen"
    # each task says what backs it, as the API does
    assert page.locator("#tasks .task .why-score").all_text_contents() == [r["reason"] for r in latest["ranking"]]
    # what next? and something else? answer in the status box
    page.locator("#whatnext").click()
    page.wait_for_function("document.getElementById('status').textContent.startsWith('Next I expect')")
    page.locator("#other").click()
    page.wait_for_function("document.getElementById('status').textContent.startsWith('Instead of ')")
    assert latest["ranking"][0]["task"] in page.locator("#status").text_content()
    shot = os.environ.get("NEEM_ORACLE_SCREENSHOT")
    if shot:
        page.locator("#tasks .whynot").nth(2).click()
        page.wait_for_function("document.getElementById('status').textContent.includes('ranked')")
        page.screenshot(path=shot, full_page=True)


@pytest.mark.parametrize("width,height", [(768, 1024), (1280, 800), (800, 1280)])
def test_page_fits_a_tablet_and_every_control_is_a_named_large_target(server, browser, width, height):
    call(server, "/api/neems", {"user": "dana", "neem": "dana"})  # 400 once it exists: the same NEEM
    call(server, "/api/neems/dana/situation", {"available": AVAILABLE, "at": at(0, 0)})
    page = browser.new_page(viewport={"width": width, "height": height}, bypass_csp=True)
    page.goto(server + "/?neem=dana")
    page.wait_for_function("document.body.dataset.live === 'yes'")
    # nothing wider than the screen: no sideways scrolling on the tablet
    assert page.evaluate("document.documentElement.scrollWidth") <= width
    buttons = page.evaluate("""Array.from(document.querySelectorAll('button')).map(function (b) {
        var r = b.getBoundingClientRect(), name = b.getAttribute('aria-label') || b.textContent.trim();
        return {name: name, width: r.width, height: r.height, size: parseFloat(getComputedStyle(b).fontSize)}; })""")
    assert len(buttons) == 2 * len(AVAILABLE) + 2 + (1 if page.locator("#workflow").count() else 0)
    for button in buttons:  # touch targets far above WCAG's 44 px, type readable at arm's length
        assert button["name"] and button["height"] >= 88 and button["width"] >= 110 and button["size"] >= 19, button
    names = page.locator("#tasks .task .name").evaluate_all("(e) => e.map((n) => parseFloat(getComputedStyle(n).fontSize))")
    assert min(names) >= 28
    assert page.evaluate("document.documentElement.lang") == "en"
    assert page.locator("#status").get_attribute("aria-live") == "polite"
    # a switch scanner's arrows reach every control in order and wrap around
    page.locator("#tasks .task").first.focus()
    seen = []
    for _ in range(len(buttons)):
        seen.append(page.evaluate("document.activeElement.getAttribute('aria-label') || document.activeElement.id"))
        page.keyboard.press("ArrowDown")
    assert len(set(seen)) == len(buttons)
    assert page.evaluate("document.activeElement === document.querySelector('#tasks .task')")
    # the focus ring is visible: 6 px, the focus colour
    assert page.evaluate("getComputedStyle(document.activeElement).outlineWidth") == "6px"
    page.close()


def test_page_reconnects_after_the_service_restarts_and_catches_up(tmp_path, browser):
    store, port = tmp_path / "s.sqlite", free_port()
    base = f"http://127.0.0.1:{port}"
    process = start_server(store, port)
    try:
        eli = call(base, "/api/neems", {"user": "eli", "neem": "eli"})[1]["id"]
        call(base, "/api/neems/eli/situation", {"available": ["pick(red_mug)", "open(fridge)"], "at": at(0, 0)})
        page = browser.new_page(viewport={"width": 1024, "height": 768}, bypass_csp=True)
        fetched: list[str] = []  # the page names the NEEM by its id
        page.on("request", lambda r: fetched.append(r.url) if r.url.endswith(f"/api/neems/{eli}/situation") else None)
        page.goto(base + "/?neem=eli")
        page.wait_for_function("document.body.dataset.live === 'yes'")
        assert page.locator("#link").is_hidden()
        stop_server(process)
        page.wait_for_function("document.body.dataset.live === 'no'")
        assert page.locator("#link").is_visible() and "reconnecting" in page.locator("#link").text_content()
        process = start_server(store, port)
        call(base, "/api/neems/eli/situation", {"available": ["pick(banana)", "open(fridge)", "pick(thermos)"], "at": at(0, 1)})
        page.wait_for_function("document.querySelectorAll('#tasks .task').length === 3", timeout=60_000)
        page.wait_for_function("document.body.dataset.live === 'yes'")
        assert page.locator("#link").is_hidden()
        assert fetched, "the page did not fetch the latest ranking after it reconnected"
        page.close()
    finally:
        stop_server(process)


def test_simulate_command_drives_the_service_and_reports_latencies(server):
    """``oracle simulate`` as a user runs it: one robot, a persona's day, into its own NEEM."""
    from oracle.service.robot import persona_rows

    result = subprocess.run([sys.executable, "-m", "oracle", "simulate", "--serve", server, "--persona", "2",
                             "--days", "1", "--neem", "sim-cli"], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    made = re.fullmatch(rf"driving NEEM ([0-9a-f]{{24}}): the page is {re.escape(server)}/\?neem=\1", result.stdout.splitlines()[0])
    assert made, result.stdout
    assert [n["id"] for n in call(server, "/api/neems")[1] if n["name"] == "sim-cli"] == [made.group(1)]
    summary = re.search(r"^1 robot\(s\) drove (\d+) steps in [\d.]+ s; 0 errors$", result.stdout, re.M)
    assert summary, result.stdout
    _, rows = persona_rows(2, 3, 1)
    assert int(summary.group(1)) == len(rows)
    for kind in ("situation", "choice", "action"):
        assert re.search(rf"^  {kind}\s+n=\s*{len(rows)}\s+p50\s+[\d.]+ ms\s+p99\s+[\d.]+ ms$", result.stdout, re.M), kind
    assert call(server, "/api/neems/sim-cli/choice")[1]["task"] == str(rows[-1].action)
    _, latest = call(server, "/api/neems/sim-cli/situation")
    assert latest["history"] >= len(rows) - 1 and latest["ranking"]
    # a second run by the same name drives the same NEEM (no second one, no "already exists")
    from oracle.service.robot import drive

    later = [row for row in persona_rows(2, 3, 2)[1] if row.time > rows[-1].time][:2]
    announced: list[str] = []
    again = drive(server, "p2", later, "sim-cli", announce=announced.append)
    assert again.errors == [] and announced == [made.group(1)]
    assert [n["id"] for n in call(server, "/api/neems")[1] if n["name"] == "sim-cli"] == [made.group(1)]


@pytest.mark.parametrize("args,message", [
    (["--serve", "ftp://127.0.0.1:1"], "error: --serve 'ftp://127.0.0.1:1': expected http://HOST:PORT"),
    (["--serve", "http://127.0.0.1:1", "--robots", "0"], "error: --robots and --days must be at least 1"),
])
def test_simulate_refuses_bad_arguments_in_one_line(args, message):
    result = subprocess.run([sys.executable, "-m", "oracle", "simulate", *args], cwd=ROOT, capture_output=True,
                            text=True, timeout=120)
    assert (result.returncode, result.stderr.strip()) == (1, message)


def test_simulate_against_no_service_fails_with_the_reason():
    port = free_port()  # nothing listens there
    result = subprocess.run([sys.executable, "-m", "oracle", "simulate", "--serve", f"http://127.0.0.1:{port}",
                             "--days", "1"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 1
    assert "0 steps" in result.stdout and "1 errors" in result.stdout
    assert re.search(r"error: .*(refused|reach)", result.stdout, re.I), result.stdout
