"""The tablet page (thesis 2.1 and its first future-work item) as HTML: the shell around the
first view (``oracle.service.tablet``), the sheet where a choice is confirmed and can be undone,
and the page that asks for the access code. Style and script are static files
(``service/static/``), served by the service itself: the page loads nothing from elsewhere.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from html import escape
from pathlib import Path
from typing import Any


#: The page's own files (style, script, icon).
STATIC = Path(__file__).resolve().parent / "static"


@dataclass(frozen=True)
class Manner:
    """How the page behaves for its person (the carer's settings, docs/service.md): ``confirm``
    "tap" (a second tap on "Yes") or "dwell" (chosen after ``dwell_s`` unless they go back);
    ``undo_s``: how long a confirmed choice can be undone before it is sent; ``hold_ms``: how
    long after a touch, pointer or key the list stays as it is when the robot sends a new
    ranking; ``scan``: the page's own switch scanning, "off", "one" (it moves by itself every
    ``scan_s``, a press selects) or "two" (Space moves, Enter selects); ``filter_s``: a second
    hit within this time after one that counted changes nothing (a tremor's double tap);
    ``gaze_s``: a pointer or eye gaze resting this long on a button selects it (0: off)."""

    confirm: str = "tap"
    dwell_s: float = 3.0
    undo_s: float = 5.0
    hold_ms: int = 4000
    scan: str = "off"
    scan_s: float = 1.5
    filter_s: float = 0.5
    gaze_s: float = 0.0


def render_page(view: Mapping[str, Any] | None, text: Mapping[str, str], token: str | None,
                manner: Manner = Manner()) -> str:
    """The whole page for a NEEM's view (None: the store holds no NEEM yet)."""
    lang = str(view["lang"]) if view else "en"
    if view is None:
        return _shell(lang, text["no_neem"], "", f"<p class='empty'>{escape(text['no_neem'])}</p>")
    config = json.dumps({"neem": view["neem"], "lang": lang, "view": view, "text": text, "token": token,
                         "confirm": manner.confirm, "dwell_s": manner.dwell_s, "undo_s": manner.undo_s,
                         "hold_ms": manner.hold_ms, "scan": manner.scan, "scan_s": manner.scan_s,
                         "filter_s": manner.filter_s, "gaze_s": manner.gaze_s}).replace("</", "<\\/")
    user = text["for"].format(user=view["person"]) if view.get("person") else ""  # a name, never an id
    # Everything that comes and goes (the offline line, "You chose", what the robot did, "New
    # suggestions") lives in a strip laid over the foot of the screen, so nothing above it moves;
    # answers to questions open in the sheet, where the person is looking.
    body = f"""
<div id="top"><h1>{escape(text['title'])} <small id="when">{escape(view.get('clock') or '')}</small></h1></div>
<ol id="tasks" aria-label="{escape(text['list'])}">{_items(view, text)}</ol>
<div id="strip"><p id="link" role="alert" hidden>{escape(text['offline'])}</p>
<p id="answer" role="status" aria-live="polite"></p><p id="robot" role="status" aria-live="polite"></p>
<button type="button" id="fresh" disabled aria-describedby="fresh-hint">{escape(text['fresh'])}</button>
<span id="fresh-hint" hidden>{escape(text['fresh_hint'])}</span></div>
<dialog id="sheet" aria-labelledby="sheet-title" aria-describedby="sheet-note">
<h2 id="sheet-title"></h2><ol id="sheet-steps" hidden></ol>
<p id="sheet-note"></p>
<div class="actions"><button type="button" id="confirm">{escape(text['confirm'])}</button>
<button type="button" id="instead">{escape(text['instead'])}</button>
<button type="button" id="whyhere">{escape(text['whyhere'])}</button>
<button type="button" id="back">{escape(text['back'])}</button>
<button type="button" id="undo" hidden>{escape(text['undo'])}</button></div>
<p id="sheet-count" aria-live="polite"></p><p id="sheet-answer" aria-live="polite"></p>
</dialog>
<script type="application/json" id="config">{config}</script>
<script src="/static/page.js"></script>"""
    return _shell(lang, "EDAN", user, body)


#: Tasks shown before "More suggestions": the top five, as AAC pages keep a short first screen.
SHOWN = 5


def _items(view: Mapping[str, Any], text: Mapping[str, str]) -> str:
    """The first view's list as the script draws it (it redraws it on load): the top task, its
    workflow and routine, the two questions, the next four tasks, "More" and the rest, folded."""
    tasks = view.get("tasks") or []
    if not tasks:
        return f"<li class='empty'>{escape(text['waiting'])}</li>"
    out = []
    for index, task in enumerate(tasks):
        if index == SHOWN:
            out.append(f"<li class='more'><button type='button' id='more' aria-expanded='false'>"
                       f"{escape(text['more'].format(n=len(tasks) - SHOWN))}</button></li>")
        hidden = " hidden" if index >= SHOWN else ""
        out.append(
            f"<li class='{'top' if index == 0 else 'rest'}'{hidden}><button type='button' class='task' data-task='{escape(task['task'])}'>"
            f"<span class='rank'>{task['rank']}</span><span class='words'><span class='name'>{escape(task['said'])}</span>"
            f"<span class='reason'>{escape(_why(task))}</span></span></button></li>")
        if index > 0:
            continue
        flow = view.get("workflow") or []
        if len(flow) >= 2:
            steps = escape(" \u2192 ".join(s["said"] for s in flow))
            out.append(f"<li class='flow'><button id='workflow' type='button'><span class='label'>{escape(text['workflow'])}"
                       f"</span><span class='steps'>{steps}</span></button></li>")
        if view.get("routine"):
            out.append(f"<li class='routine'><button id='routine' type='button'>{escape(view['routine']['label'])}</button></li>")
        out.append(f"<li class='ask'><button type='button' id='whatnext'>{escape(text['whatnext'])}</button>"
                   f"<button type='button' id='otherthing'>{escape(text['instead'])}</button></li>")
    return "".join(out)


def _why(task: Mapping[str, Any]) -> str:
    """A task's line under its name: why it stands here, and who usually does it (as page.js says it)."""
    mode = task.get("mode_said") or ""
    return f"{task['reason']} {mode}" if mode else str(task["reason"])


def render_token_page(lang: str, text: Mapping[str, str], neem: str | None) -> str:
    """Asked for when the service has a token and the page was opened without it."""
    keep = f"<input type='hidden' name='neem' value='{escape(neem)}'>" if neem else ""
    body = f"""<h1>{escape(text['token_title'])}</h1>
<form method="get" action="/" id="token-form">{keep}
<label for="token">{escape(text['token_label'])}</label>
<input id="token" name="token" type="password" autocomplete="current-password" required minlength="12">
<button type="submit">{escape(text['token_go'])}</button></form>"""
    return _shell(lang, "EDAN", "", body)


def _shell(lang: str, title: str, who: str, body: str) -> str:
    return f"""<!doctype html>
<html lang="{escape(lang)}"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{escape(title)}</title>
<link rel="icon" href="/favicon.ico" type="image/svg+xml">
<link rel="stylesheet" href="/static/page.css"></head>
<body><header><b>EDAN</b><span>{escape(who)}</span></header>
<main>{body}</main></body></html>"""
