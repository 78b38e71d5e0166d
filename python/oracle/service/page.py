"""The tablet page (thesis 2.1 and its first future-work item): the ranked available tasks
as large touch targets, top suggestion first, the predicted chain as one workflow choice,
"why not?" on any task, "what next?" and "something else?", live updates from the event
stream (reconnecting after a drop), and a tap posted back as the user's decision.

Server-rendered HTML with one inline style and one inline script: no external resource (the
robot has no network), no build step. Native buttons give touch, keyboard and switch access
(Tab order, Enter/Space); the arrow keys also move between tasks for one-switch scanning.
"""

from __future__ import annotations

import json
from html import escape
from typing import Any

from oracle.answers import support_sentence

_STYLE = """
:root { --ink:#111; --paper:#fbfaf7; --top:#0b5394; --line:#c9c4b8; --focus:#ff9e00; }
* { box-sizing:border-box; }
body { margin:0; font:28px/1.35 system-ui, "DejaVu Sans", sans-serif; color:var(--ink); background:var(--paper); }
header { display:flex; justify-content:space-between; align-items:baseline; padding:16px 28px;
         background:#1d1d1d; color:#fff; font-size:24px; }
header b { font-size:30px; }
main { padding:20px 28px 40px; max-width:1100px; margin:auto; }
h1 { font-size:34px; margin:8px 0 16px; }
#status { min-height:1.4em; margin:0 0 18px; padding:14px 18px; border-radius:12px; background:#eee8da; }
#status:empty { display:none; }
ol { list-style:none; padding:0; margin:0; }
li { display:flex; gap:14px; margin:0 0 14px; }
button { font:inherit; border-radius:16px; cursor:pointer; }
button:focus-visible { outline:6px solid var(--focus); outline-offset:3px; }
.task { flex:1; min-width:0; min-height:96px; text-align:left; padding:16px 24px; border:3px solid var(--line);
        background:#fff; color:var(--ink); display:flex; align-items:center; gap:20px; }
.task .rank { font-weight:700; font-size:40px; min-width:1.6em; text-align:center; }
.task .name { font-size:34px; font-weight:600; overflow-wrap:anywhere; }
.task .why-score { margin-left:auto; font-size:22px; color:#555; text-align:right; max-width:40%; }
li.top .task { background:var(--top); border-color:var(--top); color:#fff; min-height:132px; }
li.top .task .name { font-size:42px; }
li.top .task .why-score { color:#dfe9f5; }
.whynot { min-width:180px; min-height:96px; border:3px solid var(--line); background:#f1efe9; color:var(--ink); font-size:24px; }
.chosen .task, .chosen #workflow { outline:6px solid #2e7d32; outline-offset:3px; }
li.flow { display:block; }
#workflow { width:100%; min-height:110px; margin:0 0 12px; padding:16px 24px; text-align:left;
            border:3px dashed var(--top); background:#e9f1fa; color:var(--ink); }
#workflow .label { display:block; font-size:22px; color:#444; }
#workflow .steps { font-size:32px; font-weight:600; }
.empty { font-size:30px; color:#555; padding:30px 0; }
#ask { display:flex; gap:14px; margin:10px 0 0; }
#ask button { flex:1; min-height:96px; border:3px solid var(--line); background:#f1efe9; color:var(--ink); font-size:28px; }
#link { margin:0 0 18px; padding:14px 18px; border-radius:12px; background:#7a1f1f; color:#fff; }
@media (max-width: 820px) {
  body { font-size:24px; } main { padding:14px 14px 30px; }
  .whynot { min-width:120px; font-size:22px; } .task { padding:14px 16px; gap:12px; }
  .task .why-score { font-size:19px; max-width:45%; }
}
"""

_SCRIPT = """
(function () {
  var cfg = JSON.parse(document.getElementById('config').textContent);
  var list = document.getElementById('tasks'), status = document.getElementById('status');
  var when = document.getElementById('when');
  var auth = cfg.token ? {'Authorization': 'Bearer ' + cfg.token} : {};
  function api(path) { return '/api/neems/' + encodeURIComponent(cfg.neem) + path; }
  function say(text) { status.textContent = text; if (text) status.scrollIntoView({block: 'nearest'}); }
  function send(path, body) {
    var headers = Object.assign({'Content-Type': 'application/json'}, auth);
    return fetch(api(path), {method: 'POST', headers: headers, body: JSON.stringify(body)})
      .then(function (r) { return r.json().then(function (j) { if (!r.ok) throw new Error(j.error || r.status); return j; }); });
  }
  function el(tag, cls, text) {
    var e = document.createElement(tag); if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text; return e;
  }
  function choose(task, workflow, item) {
    var body = {task: task}; if (workflow) body.workflow = workflow;
    send('/choice', body).then(function () {
      Array.prototype.forEach.call(list.children, function (li) { li.classList.remove('chosen'); });
      if (item) item.classList.add('chosen');
      say(workflow ? 'You chose the workflow ' + workflow.join(' \\u2192 ') + '. The robot starts with ' + task + '.'
                   : 'You chose ' + task + '. The robot will do it.');
    }).catch(function (e) { say('Could not send your choice: ' + e.message); });
  }
  function whyNot(task) { ask('/why-not?task=' + encodeURIComponent(task)); }
  function breakable(span, text) {  // a long call wraps after ( _ or , and never mid-word
    text.split(/(?<=[(_,])/).forEach(function (part, i) {
      if (i) span.appendChild(document.createElement('wbr'));
      span.appendChild(document.createTextNode(part));
    });
    return span;
  }
  function supportText(t) {
    if (t.reason) return t.reason;
    var n = t.support; return n ? (n === 1 ? 'like 1 past situation' : 'like ' + n + ' past situations') : 'new to me';
  }
  function ask(path) {
    fetch(api(path), {headers: auth})
      .then(function (r) { return r.json(); })
      .then(function (j) { say(j.sentence || j.error); })
      .catch(function (e) { say('No answer: ' + e.message); });
  }
  var shown = cfg.state;
  function render(state) {
    shown = state;
    list.textContent = '';
    if (!state || !state.ranking || !state.ranking.length) {
      list.appendChild(el('li', 'empty', 'Waiting for the robot to say what it can do.'));
      return;
    }
    var chain = state.chain || [];
    when.textContent = state.time_of_day + ', ' + new Date(state.at * 1000).toISOString().slice(11, 16) + ' UTC';
    state.ranking.forEach(function (t, i) {
      var li = el('li', i === 0 ? 'top' : '');
      var b = el('button', 'task'); b.type = 'button'; b.dataset.task = t.task;
      b.appendChild(el('span', 'rank', String(t.rank)));
      b.appendChild(breakable(el('span', 'name'), t.task));
      b.appendChild(el('span', 'why-score', supportText(t)));
      b.setAttribute('aria-label', (i === 0 ? 'Suggested: ' : 'Option ' + t.rank + ': ') + t.task);
      b.addEventListener('click', function () { choose(t.task, null, li); });
      var w = el('button', 'whynot', 'Why not?'); w.type = 'button';
      w.setAttribute('aria-label', 'Why not ' + t.task + '?');
      w.addEventListener('click', function () { whyNot(t.task); });
      li.appendChild(b); li.appendChild(w); list.appendChild(li);
      if (i === 0 && chain.length >= 2) {
        var fl = el('li', 'flow'), fb = el('button', '', undefined); fb.type = 'button'; fb.id = 'workflow';
        fb.appendChild(el('span', 'label', 'Or the whole workflow, one step after the other'));
        fb.appendChild(el('span', 'steps', chain.join(' \\u2192 ')));
        fb.setAttribute('aria-label', 'Workflow: ' + chain.join(', then '));
        fb.addEventListener('click', function () { choose(chain[0], chain, fl); });
        fl.appendChild(fb); list.appendChild(fl);
      }
    });
  }
  document.addEventListener('keydown', function (e) {
    if (e.key !== 'ArrowDown' && e.key !== 'ArrowUp') return;
    var items = Array.prototype.slice.call(document.querySelectorAll('button:not([hidden])'));
    var i = items.indexOf(document.activeElement);
    var next = items[(i + (e.key === 'ArrowDown' ? 1 : items.length - 1)) % items.length];
    if (next) { next.focus(); e.preventDefault(); }
  });
  document.getElementById('whatnext').addEventListener('click', function () { ask('/what-next'); });
  document.getElementById('other').addEventListener('click', function () {
    var top = shown && shown.ranking && shown.ranking[0];
    ask('/something-else' + (top ? '?task=' + encodeURIComponent(top.task) : ''));
  });
  render(cfg.state);
  // Live updates. The browser reconnects a dropped stream by itself (the server asks for 2 s);
  // a refused one (the service restarting) is retried here, backing off to 15 s. Events sent
  // while the page was away are lost, so every reconnection fetches the latest ranking.
  var url = '/api/events?neem=' + encodeURIComponent(cfg.neem) + (cfg.token ? '&token=' + encodeURIComponent(cfg.token) : '');
  var link = document.getElementById('link'), lost = false, delay = 1000;
  function catchUp() {
    fetch(api('/situation'), {headers: auth})
      .then(function (r) { return r.ok ? r.json() : null; })
      .then(function (j) { if (j && j.ranking && j.ranking.length) render(j); })
      .catch(function () {});
  }
  function connect() {
    var source = new EventSource(url);
    source.addEventListener('situation', function (m) { render(JSON.parse(m.data)); say(''); });
    source.addEventListener('action', function (m) { var a = JSON.parse(m.data); say('The robot did ' + a.call + '.'); });
    source.onopen = function () {
      document.body.dataset.live = 'yes'; link.hidden = true; delay = 1000;
      if (lost) { lost = false; catchUp(); }
    };
    source.onerror = function () {
      document.body.dataset.live = 'no'; lost = true; link.hidden = false;
      if (source.readyState === EventSource.CLOSED) { setTimeout(connect, delay); delay = Math.min(2 * delay, 15000); }
    };
  }
  connect();
})();
"""


def render_page(neem: str | None, state: dict[str, Any] | None, token: str | None) -> str:
    """The whole page for ``neem`` with its latest ranking (``state``, the situation JSON)."""
    if neem is None:
        return _shell("No NEEM", "<p class='empty'>The store holds no NEEM yet: start the robot, or"
                      " create one with POST /api/neems.</p>", "")
    config = json.dumps({"neem": neem, "state": state, "token": token}).replace("</", "<\\/")
    items = _items(state)
    body = f"""
<p id="link" role="alert" hidden>Lost the connection to the robot; reconnecting…</p>
<p id="status" role="status" aria-live="polite"></p>
<h1>What would you like now? <small id="when"></small></h1>
<ol id="tasks" aria-label="Tasks the robot can do now, best first">{items}</ol>
<div id="ask"><button type="button" id="whatnext">What next?</button>
<button type="button" id="other">Something else?</button></div>
<script type="application/json" id="config">{config}</script>
<script>{_SCRIPT}</script>"""
    return _shell(neem, body, neem)


def _items(state: dict[str, Any] | None) -> str:
    ranking = (state or {}).get("ranking") or []
    chain = (state or {}).get("chain") or []
    if not ranking:
        return "<li class='empty'>Waiting for the robot to say what it can do.</li>"
    out = []
    for index, task in enumerate(ranking):
        name = escape(task["task"])
        support = escape(task.get("reason") or support_sentence(task))
        label = ("Suggested: " if index == 0 else f"Option {task['rank']}: ") + name
        out.append(
            f"<li class='{'top' if index == 0 else ''}'><button type='button' class='task' data-task='{name}'"
            f" aria-label='{label}'><span class='rank'>{task['rank']}</span><span class='name'>{_breakable(name)}</span>"
            f"<span class='why-score'>{support}</span></button>"
            f"<button type='button' class='whynot' aria-label='Why not {name}?'>Why not?</button></li>")
        if index == 0 and len(chain) >= 2:
            out.append("<li class='flow'><button id='workflow' type='button'><span class='label'>Or the whole"
                       f" workflow, one step after the other</span><span class='steps'>{escape(' → '.join(chain))}"
                       "</span></button></li>")
    return "".join(out)


def _breakable(text: str) -> str:
    """Line-break opportunities after ( _ and , (the script's ``breakable``)."""
    return text.replace("(", "(<wbr>").replace("_", "_<wbr>").replace(",", ",<wbr>")


def _shell(title: str, body: str, neem: str) -> str:
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Robot tasks · {escape(title)}</title>
<style>{_STYLE}</style></head>
<body><header><b>EDAN</b><span>{escape(neem)}</span></header>
<main>{body}</main></body></html>"""
