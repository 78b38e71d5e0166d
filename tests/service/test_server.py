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
        except urllib.error.HTTPError:  # it answers (a token refused)
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


def routine_neem(server: str, name: str) -> dict:
    """Two mornings of the routine and the third morning's situation: its ranking."""
    assert call(server, "/api/neems", {"user": name.title(), "neem": name})[0] == 201
    for day in range(2):
        for i, action in enumerate(ROUTINE):
            call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(day, 10 * i)})
            call(server, f"/api/neems/{name}/actions", {"call": action, "begin": at(day, 10 * i), "end": at(day, 10 * i + 5)})
    return call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(2, 0)})[1]


def routine_in_progress_neem(server: str, name: str) -> dict:
    """Three mornings of the routine (a mined routine), two steps of the fourth and its situation."""
    assert call(server, "/api/neems", {"user": name.title(), "neem": name})[0] == 201
    for day in range(4):
        for i, action in enumerate(ROUTINE if day < 3 else ROUTINE[:2]):
            call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(day, 10 * i)})
            call(server, f"/api/neems/{name}/actions", {"call": action, "begin": at(day, 10 * i), "end": at(day, 10 * i + 5)})
    return call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(3, 25)})[1]


def open_page(browser, server: str, query: str, width: int = 1024, height: int = 1180, lang: str = "en-US"):
    # the test evaluates its own expressions in the page, which the page's CSP (no eval) would refuse
    page = browser.new_page(viewport={"width": width, "height": height}, bypass_csp=True, locale=lang)
    # these tests click as fast as a script can: the repeat-hit filter (test_page_switch.py's) is off
    page.goto(f"{server}/?{query}" + ("" if "filter=" in query else "&filter=0"))
    page.wait_for_function("document.body.dataset.live === 'yes'")
    return page


def test_page_holds_the_list_while_the_user_is_on_it_and_confirms_before_it_sends(server, browser):
    first = routine_neem(server, "cem")
    page = open_page(browser, server, "neem=cem&undo=1")
    tasks = page.locator("#tasks button.task")
    assert tasks.evaluate_all("(b) => b.map((x) => x.dataset.task)") == [r["task"] for r in first["ranking"]]
    assert page.locator("#tasks .name").first.text_content() == "Open the small drawer"

    # idle: a new ranking is shown at once
    call(server, "/api/neems/cem/situation", {"available": ["pick(banana)", "open(fridge)"], "at": at(2, 1)})
    page.wait_for_function("document.querySelectorAll('#tasks .task').length === 2")
    # on the list: focus on the second task; the robot posts; the list and the focus stay put
    page.keyboard.press("Tab")
    page.keyboard.press("Tab")
    held = page.evaluate("document.activeElement.dataset.task")
    box = tasks.nth(1).bounding_box()
    for second in range(2, 5):
        call(server, "/api/neems/cem/situation", {"available": AVAILABLE[:second + 2], "at": at(2, second)})
    page.wait_for_function("document.getElementById('fresh').classList.contains('waiting')")
    page.wait_for_timeout(800)
    assert page.evaluate("document.activeElement.dataset.task") == held and tasks.count() == 2
    assert tasks.nth(1).bounding_box() == box
    # "New suggestions" shows the latest ranking, focus on its top
    page.locator("#fresh").click()
    _, latest = call(server, "/api/neems/cem/situation")
    assert tasks.evaluate_all("(b) => b.map((x) => x.dataset.task)") == [r["task"] for r in latest["ranking"]]
    assert page.evaluate("document.activeElement.dataset.task") == latest["ranking"][0]["task"]

    # a choice: Enter opens the sheet, "Yes" confirms, and only after the undo window it is sent
    before = call(server, "/api/neems/cem/choice")[1]
    page.keyboard.press("Enter")
    page.wait_for_function("document.getElementById('sheet').open")
    assert page.evaluate("document.activeElement.id") == "confirm"
    page.keyboard.press("Enter")
    assert page.evaluate("document.activeElement.id") == "confirm"  # "Yes" is off now; Undo is where Back was
    assert call(server, "/api/neems/cem/choice")[1] == before  # not yet
    page.wait_for_function("document.getElementById('answer').textContent.startsWith('You chose: ')")  # the service took it
    assert call(server, "/api/neems/cem/choice")[1]["task"] == latest["ranking"][0]["task"]
    # undo: nothing is sent
    made = call(server, "/api/neems/cem/choice")[1]
    tasks.nth(1).click()
    page.locator("#confirm").click()
    page.locator("#undo").click()
    page.wait_for_timeout(1500)
    assert call(server, "/api/neems/cem/choice")[1] == made
    assert page.locator("#answer").text_content().startswith("Undone")

    # answers stay: what next? is not overwritten by the robot's next action
    page.locator("#whatnext").click()  # answered in the sheet, where the person is looking
    page.wait_for_function("document.getElementById('sheet-answer').textContent.startsWith('Next I expect')")
    said = page.locator("#sheet-answer").text_content()
    call(server, "/api/neems/cem/actions", {"call": "open(fridge)", "begin": at(2, 6)})
    page.wait_for_function("document.getElementById('robot').textContent === 'The robot did: Open the fridge.'")
    assert page.locator("#sheet-answer").text_content() == said
    page.locator("#back").click()

    # why here? on any task, in the sheet; a task no longer offered says so
    call(server, "/api/neems/cem/situation", {"available": AVAILABLE, "at": at(2, 7)})
    page.wait_for_timeout(600)
    if page.locator("#fresh.waiting").count():
        page.locator("#fresh").click()
    page.wait_for_function(f"document.querySelectorAll('#tasks .task').length === {len(AVAILABLE)}")
    tasks.nth(2).click()
    page.locator("#whyhere").click()
    page.wait_for_function("document.getElementById('sheet-answer').textContent.startsWith('I put this in place 3')")
    page.locator("#back").click()
    call(server, "/api/neems/cem/situation", {"available": ["pick(banana)"], "at": at(2, 8)})
    page.wait_for_timeout(300)
    tasks.nth(3).click()  # the user is on the list: the old list stays, the task is gone
    page.wait_for_function("document.getElementById('sheet').dataset.phase === 'gone'")
    assert "cannot do this any more" in page.locator("#sheet-note").text_content()
    assert page.locator("#confirm").is_hidden()
    page.close()


def test_page_shows_a_workflows_steps_before_it_starts_and_speaks_german(server, browser):
    first = routine_neem(server, "dora")
    assert first["chain"][:2] == ROUTINE[:2]  # the morning after a night: yesterday's routine
    page = open_page(browser, server, "neem=dora&undo=1", lang="de-DE")
    assert page.evaluate("document.documentElement.lang") == "de"
    assert page.locator("h1").text_content().startswith("Was möchten Sie jetzt?")
    assert page.locator("#tasks .name").first.text_content() == "Die kleine Schublade öffnen"
    page.locator("#workflow").click()
    steps = page.locator("#sheet-steps li .step").all_text_contents()
    assert len(steps) == len(first["chain"]) and steps[0] == "Die kleine Schublade öffnen"
    assert page.locator("#sheet-steps button.who").all_text_contents() == ["Der Roboter"] * len(steps)
    page.locator("#confirm").click()
    page.wait_for_function("document.getElementById('answer').textContent.startsWith('Sie haben gewählt')")
    assert call(server, "/api/neems/dora/choice")[1]["workflow"] == first["chain"]
    assert page.locator("#tasks li.flow").get_attribute("class") == "flow chosen"
    shot = os.environ.get("NEEM_ORACLE_SCREENSHOTS")
    if shot:
        for lang, (width, height) in [(lang, size) for lang in ("en", "de") for size in ((800, 1280), (390, 844))]:
            view = open_page(browser, server, f"neem=dora&lang={lang}", width, height)
            view.screenshot(path=f"{shot}/service-page-{lang}-{width}.png", full_page=True)
            if width == 800:  # the sheet of the workflow: its steps before anything starts
                view.locator("#workflow").click()
                view.screenshot(path=f"{shot}/service-sheet-{lang}-{width}.png")
            view.close()
    page.close()


@pytest.mark.parametrize("width,height", [(390, 844), (768, 1024), (1280, 800), (800, 1280)])
def test_page_fits_and_a_switch_reaches_every_control_in_n_plus_3_steps(server, browser, width, height):
    if call(server, "/api/neems/eda/situation")[0] == 404:  # the first size makes the NEEM
        routine_neem(server, "eda")
    page = open_page(browser, server, "neem=eda", width, height)
    # nothing wider than the screen: no sideways scrolling on the tablet or the phone
    assert page.evaluate("document.documentElement.scrollWidth") <= width
    n = page.locator("#tasks button.task").count()
    buttons = page.evaluate("""Array.from(document.querySelectorAll('main > :not(dialog) button')).filter(function (b) {
        return !b.disabled && b.offsetParent !== null && getComputedStyle(b).visibility === 'visible'; }).map(function (b) {
        var r = b.getBoundingClientRect();
        return {name: b.textContent.trim(), width: r.width, height: r.height, size: parseFloat(getComputedStyle(b).fontSize)}; })""")
    for button in buttons:  # touch targets far above WCAG's 24 px, type readable at arm's length
        assert button["name"] and button["height"] >= 88 and button["width"] >= 110 and button["size"] >= 19, button
    # one target per task: N tasks, the workflow, what next? (and new suggestions when waiting)
    assert len(buttons) <= n + 3
    seen, rings = [], set()
    for _ in range(n + 3):
        page.keyboard.press("Tab")
        seen.append(page.evaluate("document.activeElement.dataset.task || document.activeElement.id"))
        if seen[-1]:
            rings.add(page.evaluate("getComputedStyle(document.activeElement).outlineWidth"))
    assert {b for b in seen if b} >= {"workflow", "whatnext"} and len({b for b in seen if b}) == len(buttons)
    assert rings == {"6px"}  # the focus ring is visible on every control
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
        page.on("request", lambda r: fetched.append(r.url) if f"/api/neems/{eli}/tablet" in r.url else None)
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


@pytest.fixture(scope="module")
def axe_source(tmp_path_factory) -> str:
    """axe-core from npm, installed into a cache folder outside the tree (never committed)."""
    npm = shutil.which("npm")
    if npm is None:
        pytest.skip("npm is not installed: axe-core cannot be fetched")
    cache = Path(os.environ.get("NEEM_ORACLE_AXE_DIR", Path.home() / ".cache" / "neem-oracle" / "axe"))
    script = cache / "node_modules" / "axe-core" / "axe.min.js"
    if not script.exists():
        result = subprocess.run([npm, "install", "--no-save", "--no-audit", "--no-fund", "--prefix", str(cache), "axe-core@4"],
                                capture_output=True, text=True, timeout=300)
        if result.returncode != 0 or not script.exists():
            pytest.skip(f"npm could not install axe-core: {result.stderr.strip().splitlines()[-1:]}")
    return script.read_text(encoding="utf-8")


def serious(page, axe: str) -> list[str]:
    """axe-core's serious and critical WCAG 2.2 A/AA violations on the page as it is now."""
    if not page.evaluate("typeof axe !== 'undefined'"):
        page.add_script_tag(content=axe)
    found = page.evaluate("""axe.run(document, {runOnly: {type: 'tag', values: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa',
        'wcag22aa']}}).then(function (r) { return r.violations.filter(function (v) {
        return v.impact === 'serious' || v.impact === 'critical'; }).map(function (v) {
        return v.id + ': ' + v.nodes.map(function (n) { return n.target.join(' '); }).join(', '); }); })""")
    return list(found)


@pytest.mark.parametrize("width,lang", [(800, "en"), (390, "de")])
def test_axe_finds_no_serious_violation_in_any_state_of_the_page(server, browser, axe_source, width, lang):
    name = f"axe{width}"
    routine_neem(server, name)
    page = open_page(browser, server, f"neem={name}&lang={lang}&undo=30", width, 1280)
    states = {"list": serious(page, axe_source)}
    page.keyboard.press("Tab")  # on the list: the next ranking waits behind "New suggestions"
    call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE[:4], "at": at(2, 1)})
    page.wait_for_function("document.getElementById('fresh').classList.contains('waiting')")
    states["waiting"] = serious(page, axe_source)
    page.locator("#fresh").click()
    page.locator("#whatnext").click()
    page.wait_for_function("document.getElementById('sheet-answer').textContent.length > 20")
    states["answer"] = serious(page, axe_source)
    page.locator("#back").click()
    page.locator("#tasks button.task").first.click()
    states["sheet"] = serious(page, axe_source)
    page.locator("#whyhere").click()
    page.wait_for_function("document.getElementById('sheet-note').textContent.length > 20")
    states["why"] = serious(page, axe_source)
    page.locator("#confirm").click()
    states["undo"] = serious(page, axe_source)
    page.locator("#undo").click()
    assert states == {state: [] for state in states}
    page.close()


def test_docs_render_the_schema_in_the_browser(server, browser):
    page = browser.new_page(viewport={"width": 1280, "height": 900})
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    page.goto(server + "/docs")
    page.wait_for_selector('.opblock-summary-path[data-path="/api/neems/{neem}/situation"]', timeout=30_000)
    assert page.locator("text=Unable to render").count() == 0
    assert all(url.startswith(server) for url in requests), requests  # nothing from a CDN
    page.close()


def test_a_busy_port_is_one_line_and_no_banner(server):
    port = int(server.rsplit(":", 1)[1])
    result = subprocess.run([sys.executable, "-m", "oracle", "serve", "--port", str(port)], cwd=ROOT,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1 and result.stdout == ""
    assert len(result.stderr.strip().splitlines()) == 1 and f"--port {port}: cannot listen" in result.stderr


def test_ctrl_c_stops_within_a_second_with_one_line_while_the_page_listens(tmp_path, browser):
    import signal

    port = free_port()
    process = start_server(tmp_path / "s.sqlite", port, "--token", "a-long-enough-token")
    base = f"http://127.0.0.1:{port}"
    page = browser.new_page(bypass_csp=True)
    try:
        page.goto(base + "/")  # without the token: the page asks for it instead of answering JSON
        assert page.locator("input#token").count() == 1
        request = urllib.request.Request(base + "/api/neems", data=json.dumps({"user": "fay", "neem": "fay"}).encode(),
                                         headers={"Content-Type": "application/json", "Authorization": "Bearer a-long-enough-token"})
        urllib.request.urlopen(request, timeout=30).read()
        page.locator("input#token").fill("a-long-enough-token")
        page.locator("form button").click()
        page.wait_for_function("document.body.dataset.live === 'yes'")  # an open event stream
        started = time.monotonic()
        process.send_signal(signal.SIGINT)
        process.wait(timeout=20)
        took = time.monotonic() - started
    finally:
        page.close()
        if process.poll() is None:
            process.kill()
    out = process.stdout.read() if process.stdout else ""
    lines = [line for line in out.splitlines() if "oracle.service" not in line]  # the request log
    # the token is never printed to a pipe (stdout is often a log): the link with it is in a 0600 file
    assert lines[0].startswith("serving ") and f"http://127.0.0.1:{port}/ (with its token: the link in " in lines[0]
    assert "a-long-enough-token" not in out
    link = Path(lines[0].split("the link in ", 1)[1].split(",", 1)[0])
    assert link.read_text().strip() == f"http://127.0.0.1:{port}/?token=a-long-enough-token"
    assert link.stat().st_mode & 0o077 == 0
    assert lines[1:] == ["stopped"] and "Traceback" not in out
    # an open stream no longer holds the stop (it took ~8 s); the under-a-second figure of a quiet
    # machine is docs/service.md's, a loaded CI machine gets room
    assert took < 4.0, took


def test_a_robot_following_the_tablet_does_what_the_person_chose(server):
    import threading

    from oracle.service.robot import drive, persona_rows

    user, rows = persona_rows(1, 3, 1)
    step = next(i for i, row in enumerate(rows) if len(row.available or ()) >= 2)
    rows = rows[:step + 1]
    other = next(str(c) for c in rows[-1].available if c != rows[-1].action)
    done: list = []
    robot = threading.Thread(target=lambda: done.append(drive(server, user, rows, "follow", follow=30.0)))
    robot.start()
    deadline = time.monotonic() + 60
    while call(server, "/api/neems/follow/situation")[1].get("at") != rows[-1].time.timestamp() and time.monotonic() < deadline:
        time.sleep(0.2)
    time.sleep(0.5)  # the robot now waits for the person
    assert call(server, "/api/neems/follow/choice", {"task": other})[0] == 200
    robot.join(60)
    assert done and done[0].errors == [] and done[0].executed[-1] == other != str(rows[-1].action)


def test_dwell_confirms_by_itself_for_a_person_who_cannot_tap_twice(server, browser):
    assert call(server, "/api/neems", {"user": "Gus", "neem": "gus"})[0] == 201
    call(server, "/api/neems/gus/situation", {"available": ["open(fridge)", "pick(banana)"], "at": at(0, 0)})
    context = browser.new_context(viewport={"width": 1024, "height": 1180}, bypass_csp=True)
    page = context.new_page()
    page.goto(f"{server}/?neem=gus&confirm=dwell&dwell=1&undo=1&filter=0")
    page.wait_for_function("document.body.dataset.live === 'yes'")
    page.locator("#tasks button.task").nth(1).click()  # one tap; then the person only waits
    page.wait_for_function("document.getElementById('sheet').dataset.phase === 'undo'")
    page.wait_for_function("document.getElementById('answer').textContent.startsWith('You chose: ')")
    chosen = page.evaluate("document.querySelectorAll('#tasks button.task')[1].dataset.task")
    assert call(server, "/api/neems/gus/choice")[1]["task"] == chosen
    # the setting is the person's: kept in this browser for this NEEM
    again = context.new_page()
    again.goto(f"{server}/?neem=gus&filter=0")
    again.wait_for_function("document.body.dataset.live === 'yes'")
    again.locator("#tasks button.task").first.click()
    again.wait_for_function("document.getElementById('sheet-count').textContent.startsWith('Chosen in')")
    again.locator("#back").click()
    assert not again.evaluate("document.getElementById('sheet').open")
    context.close()


def test_the_listening_socket_says_tcp_so_answers_go_out_without_nagles_delay():
    import socket

    from oracle.commands.serve import _listen

    sock = _listen("127.0.0.1", 0)
    try:  # asyncio sets TCP_NODELAY only on sockets whose proto is TCP; accepted ones inherit it
        assert sock.proto == socket.IPPROTO_TCP
    finally:
        sock.close()


def test_a_touch_user_who_let_go_gets_the_new_ranking_at_once(server, browser):
    assert call(server, "/api/neems", {"user": "Hal", "neem": "hal"})[0] == 201
    call(server, "/api/neems/hal/situation", {"available": ["open(fridge)", "pick(banana)"], "at": at(0, 0)})
    page = open_page(browser, server, "neem=hal&hold=1")
    page.locator("#tasks button.task").first.click()  # a tap: the button keeps an invisible focus
    page.locator("#back").click()
    assert page.evaluate("document.activeElement.dataset.task") == "open(fridge)"
    call(server, "/api/neems/hal/situation", {"available": ["open(fridge)", "pick(banana)", "pick(red_mug)"], "at": at(0, 1)})
    page.wait_for_function("document.querySelectorAll('#tasks .task').length === 3")  # after the 1 s hold
    assert not page.locator("#fresh.waiting").count()
    page.close()


@pytest.mark.parametrize("width,lang", [(390, "de"), (800, "en")])
def test_page_offers_to_finish_the_routine_in_progress(server, browser, axe_source, width, lang):
    name = f"fin{width}"
    situation = routine_in_progress_neem(server, name)
    left = situation["routine"]["remaining"]
    assert left == ROUTINE[2:]
    page = open_page(browser, server, f"neem={name}&lang={lang}&undo=1", width, 1280)
    assert page.evaluate("document.documentElement.scrollWidth") <= width
    control = page.locator("#routine")
    words = {"en": f"Finish \u201c{situation['routine']['name']}\u201d (5 steps left)",
             "de": f"\u201e{situation['routine']['name']}\u201c zu Ende f\u00fchren (noch 5 Schritte)"}
    assert control.text_content() == words[lang]
    box = control.bounding_box()
    assert box["height"] >= 88 and box["width"] >= 110
    # one more target than the workflow's page: N tasks, the workflow, the routine, what next, new suggestions
    n = page.locator("#tasks button.task").count()
    shown = page.evaluate("""Array.from(document.querySelectorAll('main > :not(dialog) button')).filter(function (b) {
        return !b.disabled && b.offsetParent !== null && getComputedStyle(b).visibility === 'visible'; }).length""")
    assert shown <= n + 4
    ids = set()
    for _ in range(n + 4):
        page.keyboard.press("Tab")
        ids.add(page.evaluate("document.activeElement.dataset.task || document.activeElement.id"))
    assert {"routine", "whatnext"} <= ids
    assert serious(page, axe_source) == []
    control.click()
    said = page.locator("#sheet-steps li").all_text_contents()
    assert len(said) == len(left) and page.locator("#sheet-title").text_content() == words[lang]
    assert serious(page, axe_source) == []
    toggles = page.locator("#sheet-steps button.who")  # who does each step left, as in the workflow's sheet
    assert toggles.count() == len(left)
    toggles.nth(0).click()  # the robot -> the person: "I put the mug down myself"
    page.locator("#confirm").click()
    page.wait_for_function("document.querySelector('#tasks li.routine').classList.contains('chosen')")
    assert call(server, f"/api/neems/{name}/choice")[1]["workflow"] == left
    assert call(server, f"/api/neems/{name}/choice")[1]["modes"] == ["user"] + ["robot"] * (len(left) - 1)
    assert page.locator("button.task[data-task]").count() == n  # the task buttons are as they were
    page.close()


def test_the_workflow_sheet_lets_the_person_say_who_does_each_step(server, browser, axe_source):
    """"I bring the cup, you pour" (thesis 6.3): each step of the workflow sheet says who does it
    (who usually does it, from the person's past), a tap names the next of the person, the robot
    and the two together, in place, the focus staying on it; the choice sent carries them."""
    name = "ida"
    assert call(server, "/api/neems", {"user": "Ida", "neem": name})[0] == 201
    for day in range(3):  # three times the same way: the mode is kept (docs/beyond.md), not shrunk to the robot
        for i, action in enumerate(ROUTINE):
            call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(day, 10 * i)})
            call(server, f"/api/neems/{name}/actions", {"call": action, "begin": at(day, 10 * i), "end": at(day, 10 * i + 5),
                                                       "performed_by": "user" if action == "pick(red_mug)" else "robot"})
    first = call(server, f"/api/neems/{name}/situation", {"available": AVAILABLE, "at": at(3, 0)})[1]
    assert first["chain"][:2] == ROUTINE[:2] and first["chain_modes"][:2] == ["robot", "user"]
    page = open_page(browser, server, f"neem={name}&lang=en&undo=1", 800, 1280)
    mug = page.locator("#tasks button.task[data-task='pick(red_mug)'] .reason").text_content()
    assert mug.endswith("You usually do this yourself (3 of 3 times).")
    page.locator("#workflow").click()
    toggles = page.locator("#sheet-steps button.who")
    assert toggles.all_text_contents()[:2] == ["The robot", "You"]
    assert serious(page, axe_source) == []
    box = toggles.nth(0).bounding_box()
    assert box["height"] >= 88 and box["width"] >= 110  # a target as large as the page's others
    toggles.nth(0).focus()
    page.keyboard.press("Enter")  # the robot -> the person
    page.keyboard.press("Enter")  # the person -> together
    assert page.evaluate("document.activeElement.dataset.step") == "0"  # the focus stayed on the step
    assert toggles.nth(0).text_content() == "Together"
    assert toggles.nth(0).get_attribute("aria-label") == "Open the small drawer: Who does it: Together"
    toggles.nth(1).click()  # the person -> together
    toggles.nth(1).click()  # together -> the robot
    assert toggles.all_text_contents()[:2] == ["Together", "The robot"]
    page.keyboard.press("ArrowDown")  # the switch's scan passes through the steps' buttons
    assert page.evaluate("document.activeElement.dataset.step") == "2"
    page.locator("#confirm").click()
    page.wait_for_function("document.getElementById('answer').textContent.startsWith('You chose')")
    assert "Open the small drawer (Together)" in page.locator("#answer").text_content()
    chosen = call(server, f"/api/neems/{name}/choice")[1]
    assert chosen["workflow"] == first["chain"]
    assert chosen["modes"] == ["together", "robot", *first["chain_modes"][2:]]
    page.close()
