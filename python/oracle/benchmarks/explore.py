"""Benchmark of the NEEM explorer (/explore, docs/explore.md) in headless chromium: a simulated
user's NEEM of about 10,000 actions (1,000 with --quick) served by ``oracle serve``.

- first paint of the timeline: the page's own ``timeline-painted`` mark (chromium's performance
  API, ms since navigation), on the page's first open after the service started, on a later open
  while the replay that first open started runs, and on one after it is done; its floor is the
  same page's first contentful paint (the shell, before any data);
- pan and zoom: a scripted pan/zoom on every animation frame for 2 s, frames the timeline was
  redrawn in per second and the 95th percentile of one redraw (``timeline-draw`` measures); the
  floor is the browser's own frame rate in the same page, an empty requestAnimationFrame loop.
Targets: first paint <= 1 s, >= 30 frames/s. The replay behind the decisions runs in
the service meanwhile (started by the page's first open), as it would for a researcher.
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


def _paint(browser: Any, url: str) -> tuple[float, float, Any]:
    page = browser.new_page(viewport={"width": 1280, "height": 1000}, bypass_csp=True)
    page.goto(url)
    page.wait_for_function("performance.getEntriesByName('timeline-painted').length > 0", timeout=120_000)
    painted = page.evaluate("performance.getEntriesByName('timeline-painted')[0].startTime")
    shell = page.evaluate("(performance.getEntriesByName('first-contentful-paint')[0] || {startTime: NaN}).startTime")
    return float(painted), float(shell), page


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
                url = service.url + "/explore"
                listed: Any = call(service.url, "/explore/api/neems")[1]  # a JSON list, where call's type says dict
                neem = listed[0]["id"]
                for when in ("first open", "a later open, the replay running", "a later open, the replay done"):
                    if when.endswith("done"):
                        deadline = time.monotonic() + 600
                        while call(service.url, f"/explore/api/neems/{neem}/decisions", timeout=120)[0] == 202:
                            if time.monotonic() > deadline:
                                break
                            time.sleep(1)
                    painted, shell, page = _paint(browser, url)
                    print(f"  {actions} actions, {when}: timeline painted at {painted:7.1f} ms"
                          f" (floor: the shell's first contentful paint {shell:6.1f} ms)", flush=True)
                    rows.append({"area": "explore", "name": f"first paint, {when}", "actions": actions,
                                 "ms": round(painted, 1), "floor_ms": round(shell, 1)})
                    if not when.endswith("done"):
                        page.close()
                motion = page.evaluate(MOTION_JS, 2)
                floor = page.evaluate(FLOOR_JS, 2)
                print(f"  pan and zoom: {motion['fps']:5.1f} redraws/s, one redraw p95 {motion['p95']:5.2f} ms"
                      f" (floor: the browser's frame rate {floor:5.1f}/s)", flush=True)
                rows.append({"area": "explore", "name": "pan and zoom", "actions": actions, "fps": round(motion["fps"], 1),
                             "p95_draw_ms": round(motion["p95"], 2), "floor_fps": round(floor, 1)})
                page.close()
                browser.close()
        finally:
            stop(service)
    return rows
