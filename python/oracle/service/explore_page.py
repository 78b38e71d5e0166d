"""The explorer's page (``/explore``) as HTML: the shell its script fills (``static/explore.js``).

The console's examples are the queries of docs/prolog.md ("Using it"), which a test runs through
the page; the page loads nothing from elsewhere.
"""

from __future__ import annotations

import json
from html import escape
from pathlib import Path

from oracle.service.page import STATIC

#: Where the explorer's files are served: under /static/, which the guard serves without the token.
EXPLORE_STATIC = "/static/explore/"
EXPLORE_FILES: dict[str, tuple[Path, str]] = {
    "explore.js": (STATIC / "explore.js", "text/javascript"),
    "explore.css": (STATIC / "explore.css", "text/css"),
}
#: docs/prolog.md's example queries, and two that show a count and a compound answer.
EXAMPLES = (
    "kb_call(( is_action(A), executes_task(A, T), instance_of(T, odb:pick), has_participant(A, O), event_interval(A, B, E) ))",
    "occurs(E) during [1714550400, 1714554000]",
    "event_time_of_day(A, Part)",
    "aggregate_all(count, is_action(_), N)",
    "kb_call(( is_action(A), event_interval(A, B, E) )), Span = interval(B, E)",
)


def render_explore(neem: str | None, token: str | None) -> str:
    config = json.dumps({"neem": neem, "token": token, "examples": EXAMPLES}).replace("</", "<\\/")
    examples = "".join(f"<li><button type='button' class='example'>{escape(q)}</button></li>" for q in EXAMPLES)
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>NEEM explorer</title>
<link rel="icon" href="/favicon.ico" type="image/svg+xml">
<link rel="stylesheet" href="{EXPLORE_STATIC}explore.css"></head>
<body><header><b>EDAN</b> <span>NEEM explorer (read-only)</span></header>
<main>
<h1>NEEM explorer</h1>
<section aria-labelledby="neems-title">
<h2 id="neems-title">NEEMs of the store</h2>
<div class="scroll" tabindex="0" role="region" aria-labelledby="neems-title">
<table id="neems"><thead><tr><th scope="col">NEEM</th><th scope="col">User</th><th scope="col">Span</th>
<th scope="col">Actions</th><th scope="col">Ontology</th><th scope="col">Consent</th></tr></thead><tbody></tbody></table></div>
</section>
<section aria-labelledby="timeline-title">
<h2 id="timeline-title">Timeline <span id="neem-shown"></span></h2>
<div class="tools" role="toolbar" aria-label="Timeline">
<button type="button" id="zoom-in">Zoom in</button><button type="button" id="zoom-out">Zoom out</button>
<button type="button" id="zoom-reset">Whole NEEM</button>
<button type="button" id="timeline-png">Export PNG</button><button type="button" id="timeline-svg">Export SVG</button></div>
<canvas id="timeline" width="1000" height="420" tabindex="0" role="img" aria-roledescription="timeline"
 aria-label="The episode's actions as bars: time of day across, one row per day" aria-describedby="timeline-keys"></canvas>
<p id="timeline-keys" class="hint">Arrow keys: previous or next decision; Page Up/Down: a day up or down; + and -: zoom the
hours; [ and ]: zoom the days; Shift with the arrows: pan. Mouse: wheel zooms the hours (with Shift the days), drag pans,
a click selects a decision.</p>
<ul id="legend" class="legend" aria-label="Legend"></ul>
<p id="timeline-status" role="status" aria-live="polite"></p>
</section>
<section aria-labelledby="decision-title">
<h2 id="decision-title">Decision</h2>
<div id="decision" aria-live="polite"><p>Select a decision on the timeline.</p></div>
</section>
<section aria-labelledby="curve-title">
<h2 id="curve-title">Top-1/3/5 over the NEEM</h2>
<div class="tools" role="toolbar" aria-label="Curve">
<label for="window">Rolling window</label> <input id="window" type="number" min="5" max="5000" value="100">
<button type="button" id="curve-png">Export PNG</button><button type="button" id="curve-svg">Export SVG</button></div>
<canvas id="curve" width="1000" height="260" role="img"
 aria-label="Rolling Top-1, Top-3 and Top-5 (with a shared prior also its share) against the decision's position"></canvas>
<p id="figures" role="status"></p>
</section>
<section aria-labelledby="routines-title">
<h2 id="routines-title">Routines found</h2>
<ul id="routines"></ul>
</section>
<section aria-labelledby="console-title">
<h2 id="console-title">Query console</h2>
<form id="console">
<label for="query">Prolog query (KnowRob syntax, read-only)</label>
<textarea id="query" rows="3" spellcheck="false"></textarea>
<button type="submit">Run</button> <button type="button" id="answers-csv" disabled>Export CSV</button>
</form>
<p id="query-error" role="alert"></p>
<h3>Examples</h3><ul id="examples">{examples}</ul>
<h3>Last queries</h3><ul id="recent"></ul>
<div class="scroll" tabindex="0" role="region" aria-label="Answers"><table id="answers"></table></div>
</section>
</main>
<script type="application/json" id="config">{config}</script>
<script src="{EXPLORE_STATIC}explore.js"></script>
</body></html>"""
