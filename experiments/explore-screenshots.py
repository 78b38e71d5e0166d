"""docs/explore.md's screenshots, taken in headless chromium from ``oracle serve``.

A store of seven simulated users: the one explored (persona 0, 230 days, about 10,000 actions,
not shared) and six others (60 days each) who consented (``python -m oracle share``); the shared
prior is built from those six (``prior build --k 5``) and the service ranks with it, so the page
shows the prior's share of each ranking. A copy of the store with nothing kept shows the page
while the history is read through Prolog. Writes docs/explore-*.png; takes 3-6 minutes.

    python experiments/explore-screenshots.py [--out docs] [--work DIR]
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from oracle.benchmarks.explore import unkept_copy
from oracle.benchmarks.security import call, start, stop

ORACLE = [sys.executable, "-m", "oracle"]
WIDTH = 1280


def _import(store: Path, folder: Path, persona: int, days: int) -> str:
    """Persona ``persona``'s simulated days imported as a NEEM; its id."""
    from oracle.world.generate import simulate
    from oracle.world.personas import make_persona
    from oracle.world.worldfile import load_world

    rows, _ = simulate(make_persona(0, persona), load_world(), days, persona)
    chains = folder / f"user{persona}.jsonl"
    chains.write_text("".join(json.dumps(row.to_json()) + "\n" for row in rows))
    before = {n["id"] for n in _neems(store)} if store.exists() else set()
    subprocess.run([*ORACLE, "import", str(chains), "--store", str(store), "--commit-every", "1000"], check=True,
                   stdout=subprocess.DEVNULL)
    (made,) = [n["id"] for n in _neems(store) if n["id"] not in before]
    return str(made)


def _neems(store: Path) -> list[dict[str, Any]]:
    out = subprocess.run([*ORACLE, "neems", "--store", str(store), "--json"], check=True, capture_output=True, text=True)
    found: Any = json.loads(out.stdout)
    return list(found["neems"] if isinstance(found, dict) else found)


def _wait_decisions(url: str, neem: str) -> None:
    deadline = time.monotonic() + 900
    while call(url, f"/explore/api/neems/{neem}/decisions", timeout=120)[0] == 202:
        if time.monotonic() > deadline:
            raise SystemExit("the replay did not finish in 15 minutes")
        time.sleep(2)


def _shots(browser: Any, url: str, neem: str, out: Path) -> None:
    context = browser.new_context(viewport={"width": WIDTH, "height": 1000}, bypass_csp=True)
    page = context.new_page()
    page.goto(f"{url}/explore?neem={neem}")
    page.wait_for_function("window.neemExplorer && window.neemExplorer.state.decisions !== null", timeout=120_000)
    page.wait_for_function("document.querySelectorAll('#routines li').length > 0", timeout=60_000)
    x = "window.neemExplorer"
    # a decision a third into the NEEM, selected with the keyboard as a researcher would
    page.focus("#timeline")
    page.evaluate(f"{x}.select(Math.floor({x}.state.timeline.actionOfDecision.length / 3), true)")
    page.keyboard.press("ArrowRight")
    page.wait_for_timeout(300)
    page.screenshot(path=str(out / "explore-page-1280.png"), full_page=True)
    page.locator("#decision").screenshot(path=str(out / "explore-decision.png"))
    page.locator("#curve").evaluate("c => c.scrollIntoView()")
    page.locator("section:has(#curve)").screenshot(path=str(out / "explore-curve.png"))
    # a week of mornings: the hours 06:00-12:00 of seven days
    page.evaluate(f"""() => {{ const v = {x}.state.view, t = {x}.state.timeline;
      v.h0 = 6; v.h1 = 12; v.d0 = Math.floor(t.days / 3); v.d1 = v.d0 + 7; {x}.zoomHours(1); }}""")
    page.wait_for_timeout(300)
    page.locator("#timeline").screenshot(path=str(out / "explore-timeline-zoomed.png"))
    page.locator(".example").first.click()
    page.wait_for_function("document.querySelectorAll('#answers tbody tr').length > 0", timeout=60_000)
    page.locator("section:has(#console)").screenshot(path=str(out / "explore-console.png"))
    context.close()


def _reading(browser: Any, store: Path, neem: str, out: Path) -> None:
    """The page of a NEEM nothing was kept for, while its history is read through Prolog."""
    service = start(unkept_copy(store))
    try:
        context = browser.new_context(viewport={"width": WIDTH, "height": 800}, bypass_csp=True)
        page = context.new_page()
        page.goto(f"{service.url}/explore?neem={neem}")
        page.wait_for_function("performance.getEntriesByName('timeline-reading').length > 0", timeout=60_000)
        page.wait_for_timeout(1500)  # a second or two into the read: the status counts the seconds
        page.locator("section:has(#timeline)").screenshot(path=str(out / "explore-reading.png"))
        context.close()
    finally:
        stop(service)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("docs"))
    parser.add_argument("--work", type=Path, help="keep the store and the prior here (default: a temporary folder)")
    args = parser.parse_args()
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        raise SystemExit("needs chromium (make setup installs it)")
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as temporary:
        work = args.work or Path(temporary)
        work.mkdir(parents=True, exist_ok=True)
        store, prior = work / "s.sqlite", work / "prior.json"
        if not store.exists():
            explored = _import(store, work, 0, 230)
            for persona in range(1, 7):
                other = _import(store, work, persona, 60)
                subprocess.run([*ORACLE, "share", "--store", str(store), "--neem", other], check=True, stdout=subprocess.DEVNULL)
            subprocess.run([*ORACLE, "prior", "build", "--store", str(store), "--k", "5", "--out", str(prior)], check=True,
                           stdout=subprocess.DEVNULL)
            (work / "explored").write_text(explored)
        explored = (work / "explored").read_text()
        service = start(store, "--prior", str(prior))
        try:
            call(service.url, f"/explore/api/neems/{explored}/decisions", timeout=120)  # the replay starts
            _wait_decisions(service.url, explored)
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=chromium, headless=True,
                                                     args=["--no-sandbox", "--disable-gpu", "--no-first-run"])
                _shots(browser, service.url, explored, args.out)
                stop(service)
                _reading(browser, store, explored, args.out)
                browser.close()
        finally:
            stop(service)
    print(f"written: {', '.join(sorted(p.name for p in args.out.glob('explore-*.png')))}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
