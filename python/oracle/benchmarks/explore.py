"""Benchmark of the NEEM explorer (/explore, docs/explore.md) in headless chromium: a simulated
user's NEEM of about 10,000 actions (1,000 with --quick) served by ``oracle serve``.

- first paint of the timeline: the page's own ``timeline-painted`` mark (chromium's performance
  API, ms since navigation) while the NEEM's replay runs in the service (started just before by
  a request for the decisions, as a first open starts it): cold (the service's first page, in a
  fresh browser: nothing cached on either side) and warm (the same page opened again in that
  browser), then once the replay is done; each one's floor is the same page's first contentful
  paint (the shell, before any data);
- a NEEM nothing was kept for (the same store with its kept view removed, as a loaded dump or a
  server's store): when the page says what is being read (``timeline-reading``) and when the
  timeline paints after the one read through Prolog, beside the same floor;
- pan and zoom: a scripted pan/zoom on every animation frame for 2 s, frames the timeline was
  redrawn in per second and the 95th percentile of one redraw (``timeline-draw`` measures); the
  floor is the browser's own frame rate in the same page, an empty requestAnimationFrame loop.
Targets: first paint <= 1 s, >= 30 frames/s.
"""

from __future__ import annotations

import json
import shutil
import tempfile
import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.security import call, start, stop

#: The pan/zoom script: each frame pans a little and zooms in or out, as a dragging, wheeling hand.
MOTION_JS = """async (seconds) => {
  const x = window.neemExplorer, draws = () => performance.getEntriesByName('timeline-draw').length;
  performance.clearMeasures('timeline-draw');
  const t0 = performance.now(); let frames = 0;
  await new Promise((done) => {
    const step = () => {
      frames += 1;
      if (frames % 2) { x.pan(0.05, 0.4); } else { x.zoomHours(frames % 4 ? 0.97 : 1.03); }
      if (performance.now() - t0 < seconds * 1000) { requestAnimationFrame(step); } else { done(); }
    };
    requestAnimationFrame(step);
  });
  const took = (performance.now() - t0) / 1000;
  const each = performance.getEntriesByName('timeline-draw').map((e) => e.duration).sort((a, b) => a - b);
  return {fps: draws() / took, p95: each[Math.floor(each.length * 0.95)] || 0, draws: draws()};
}"""
FLOOR_JS = """async (seconds) => {
  const t0 = performance.now(); let frames = 0;
  await new Promise((done) => {
    const step = () => { frames += 1; if (performance.now() - t0 < seconds * 1000) { requestAnimationFrame(step); } else { done(); } };
    requestAnimationFrame(step);
  });
  return frames / ((performance.now() - t0) / 1000);
}"""


def _neem(folder: Path, days: int) -> tuple[Path, int]:
    """The NEEM as ``python -m oracle import`` makes it: with the history the oracle reads kept
    beside it (a NEEM whose history nobody has read yet, such as a loaded dump, costs its first
    open one read through Prolog: 6-10 s at 10,000 actions here)."""
    import subprocess
    import sys

    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    rows, _ = simulate(make_persona(0, 0), load_world(), days, 0)
    chains = folder / "chains.jsonl"
    chains.write_text("".join(json.dumps(row.to_json()) + "\n" for row in rows))
    subprocess.run([sys.executable, "-m", "oracle", "import", str(chains), "--store", str(folder / "s.sqlite"),
                    "--commit-every", "1000"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return folder / "s.sqlite", len(rows)


def _paint(context: Any, url: str, mark: str = "timeline-painted") -> tuple[float, float, Any]:
    page = context.new_page()
    page.goto(url)
    page.wait_for_function(f"performance.getEntriesByName('{mark}').length > 0", timeout=120_000)
    painted = page.evaluate(f"performance.getEntriesByName('{mark}')[0].startTime")
    shell = page.evaluate("(performance.getEntriesByName('first-contentful-paint')[0] || {startTime: NaN}).startTime")
    return float(painted), float(shell), page


def _pending(url: str, neem: str) -> bool:
    return call(url, f"/explore/api/neems/{neem}/decisions", timeout=120)[0] == 202


def _row(name: str, actions: int, painted: float, shell: float, **more: Any) -> dict[str, Any]:
    return {"area": "explore", "name": name, "actions": actions, "ms": round(painted, 1), "floor_ms": round(shell, 1), **more}


def _opens(browser: Any, url: str, neem: str, actions: int) -> tuple[list[dict[str, Any]], Any]:
    """The three opens of a kept NEEM; the last page, for the pan and zoom."""
    rows = []
    context = browser.new_context(viewport={"width": 1280, "height": 1000}, bypass_csp=True)
    _pending(url, neem)  # starts the replay, as a first open does once its timeline is painted
    page = None
    for when in ("cold", "warm"):
        if page is not None:
            page.close()
        painted, shell, page = _paint(context, url + "/explore")
        running = _pending(url, neem)
        print(f"  {actions} actions, {when} open, the replay running: timeline painted at {painted:7.1f} ms"
              f" (floor: the shell's first contentful paint {shell:6.1f} ms)"
              f"{'' if running else '; the replay ended meanwhile'}", flush=True)
        rows.append(_row(f"first paint, {when}, the replay running", actions, painted, shell, replay_running=running))
    deadline = time.monotonic() + 600
    while _pending(url, neem) and time.monotonic() < deadline:
        time.sleep(1)
    assert page is not None
    page.close()
    painted, shell, page = _paint(context, url + "/explore")
    print(f"  {actions} actions, warm open, the replay done: timeline painted at {painted:7.1f} ms"
          f" (floor: the shell's first contentful paint {shell:6.1f} ms)", flush=True)
    rows.append(_row("first paint, warm, the replay done", actions, painted, shell))
    return rows, page


def unkept_copy(path: Path) -> Path:
    """A copy of the store beside it with nothing kept (no view, no fit): what a MongoDB store or a
    lost entry gives."""
    import sqlite3

    copy = path.with_name("unkept.sqlite")
    shutil.copy(path, copy)
    with sqlite3.connect(copy) as conn:
        conn.execute("DELETE FROM kept")
    return copy


def _unkept(browser: Any, path: Path, actions: int) -> list[dict[str, Any]]:
    """A copy of the store with nothing kept: what the page says, and when the timeline comes."""
    service = start(unkept_copy(path))
    try:
        context = browser.new_context(viewport={"width": 1280, "height": 1000}, bypass_csp=True)
        painted, shell, page = _paint(context, service.url + "/explore")
        said = page.evaluate("(performance.getEntriesByName('timeline-reading')[0] || {startTime: NaN}).startTime")
        print(f"  {actions} actions, nothing kept: the page says what it reads at {said:7.1f} ms, timeline painted at"
              f" {painted:7.1f} ms (floor: the shell's first contentful paint {shell:6.1f} ms)", flush=True)
        context.close()
        return [_row("first paint, nothing kept", actions, painted, shell, reading_said_ms=round(float(said), 1))]
    finally:
        stop(service)


def run(quick: bool = False) -> list[dict[str, Any]]:
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        sync_playwright = None  # type: ignore[assignment]
    if chromium is None or sync_playwright is None:
        print("  skipped: needs chromium and playwright (make setup installs both)", flush=True)
        return []
    rows: list[dict[str, Any]] = []
    days = 23 if quick else 230
    with tempfile.TemporaryDirectory() as folder:
        path, actions = _neem(Path(folder), days)
        service = start(path)
        try:
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=chromium, headless=True,
                                                     args=["--no-sandbox", "--disable-gpu", "--no-first-run"])
                listed: Any = call(service.url, "/explore/api/neems")[1]  # a JSON list, where call's type says dict
                opened, page = _opens(browser, service.url, listed[0]["id"], actions)
                rows += opened
                motion = page.evaluate(MOTION_JS, 2)
                floor = page.evaluate(FLOOR_JS, 2)
                print(f"  pan and zoom: {motion['fps']:5.1f} redraws/s, one redraw p95 {motion['p95']:5.2f} ms"
                      f" (floor: the browser's frame rate {floor:5.1f}/s)", flush=True)
                rows.append({"area": "explore", "name": "pan and zoom", "actions": actions, "fps": round(motion["fps"], 1),
                             "p95_draw_ms": round(motion["p95"], 2), "floor_fps": round(floor, 1)})
                page.close()
                stop(service)
                rows += _unkept(browser, path, actions)
                browser.close()
        finally:
            stop(service)
    return rows
