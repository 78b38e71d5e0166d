"""The tablet page (thesis 2.1 and its first future-work item): the ranked available tasks
as large touch targets, top suggestion first, the predicted chain as one workflow choice,
"why not?" on any task, live updates from the event stream, and a tap posted back as the
user's decision.

Server-rendered HTML with one inline style and one inline script: no external resource (the
robot has no network), no build step. Native buttons give touch, keyboard and switch access
(Tab order, Enter/Space); the arrow keys also move between tasks for one-switch scanning.
"""

from __future__ import annotations

import json
from html import escape
from typing import Any

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
.task { flex:1; min-height:96px; text-align:left; padding:16px 24px; border:3px solid var(--line);
        background:#fff; color:var(--ink); display:flex; align-items:center; gap:20px; }
.task .rank { font-weight:700; font-size:40px; min-width:1.6em; text-align:center; }
.task .name { font-size:34px; font-weight:600; }
.task .why-score { margin-left:auto; font-size:22px; color:#555; text-align:right; }
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
  function whyNot(task) {
    fetch(api('/why-not?task=' + encodeURIComponent(task)), {headers: auth})
      .then(function (r) { return r.json(); })
      .then(function (j) { say(j.sentence || j.error); })
      .catch(function (e) { say('No answer: ' + e.message); });
  }
  function supportText(n) { return n ? (n === 1 ? 'like 1 past situation' : 'like ' + n + ' past situations') : 'new to me'; }
  function render(state) {
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
      b.appendChild(el('span', 'name', t.task));
      b.appendChild(el('span', 'why-score', supportText(t.support)));
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
  render(cfg.state);
  var url = '/api/events?neem=' + encodeURIComponent(cfg.neem) + (cfg.token ? '&token=' + encodeURIComponent(cfg.token) : '');
  var source = new EventSource(url);
  source.addEventListener('situation', function (m) { render(JSON.parse(m.data)); say(''); });
  source.addEventListener('action', function (m) { var a = JSON.parse(m.data); say('The robot did ' + a.call + '.'); });
  source.onopen = function () { document.body.dataset.live = 'yes'; };
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
<p id="status" role="status" aria-live="polite"></p>
<h1>What would you like now? <small id="when"></small></h1>
<ol id="tasks" aria-label="Tasks the robot can do now, best first">{items}</ol>
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
        n = task["support"]
        support = f"like {n} past situation{'s' if n != 1 else ''}" if n else "new to me"
        label = ("Suggested: " if index == 0 else f"Option {task['rank']}: ") + name
        out.append(
            f"<li class='{'top' if index == 0 else ''}'><button type='button' class='task' data-task='{name}'"
            f" aria-label='{label}'><span class='rank'>{task['rank']}</span><span class='name'>{name}</span>"
            f"<span class='why-score'>{support}</span></button>"
            f"<button type='button' class='whynot' aria-label='Why not {name}?'>Why not?</button></li>")
        if index == 0 and len(chain) >= 2:
            out.append("<li class='flow'><button id='workflow' type='button'><span class='label'>Or the whole"
                       f" workflow, one step after the other</span><span class='steps'>{escape(' → '.join(chain))}"
                       "</span></button></li>")
    return "".join(out)


def _shell(title: str, body: str, neem: str) -> str:
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Robot tasks · {escape(title)}</title>
<style>{_STYLE}</style></head>
<body><header><b>EDAN</b><span>{escape(neem)}</span></header>
<main>{body}</main></body></html>"""
