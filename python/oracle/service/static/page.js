// The tablet page (docs/service.md, "The tablet page"). The server renders the first view and
// every later one (GET .../tablet: plain words in the page's language); this script only keeps
// the targets steady, asks before it acts, and talks to the service.
(function () {
  'use strict';
  var cfg = JSON.parse(document.getElementById('config').textContent);
  var T = cfg.text;  // the page's words in its language
  var list = document.getElementById('tasks'), answer = document.getElementById('answer');
  var robot = document.getElementById('robot'), fresh = document.getElementById('fresh');
  var when = document.getElementById('when'), sheet = document.getElementById('sheet');
  var auth = cfg.token ? {'Authorization': 'Bearer ' + cfg.token} : {};
  var prefs = settings();
  var shown = cfg.view, pending = null, newest = cfg.view;
  var lastTouch = 0, choosing = null;

  function api(path) { return '/api/neems/' + encodeURIComponent(cfg.neem) + path; }
  function lang(path) { return path + (path.indexOf('?') < 0 ? '?' : '&') + 'lang=' + encodeURIComponent(cfg.lang); }
  function getJSON(path) {
    return fetch(api(lang(path)), {headers: auth}).then(function (r) {
      return r.json().then(function (j) { if (!r.ok) throw new Error(j.error || r.status); return j; });
    });
  }
  function el(tag, cls, text) {
    var e = document.createElement(tag); if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text; return e;
  }
  function fill(text, values) { return text.replace(/\{(\w+)\}/g, function (_, k) { return values[k]; }); }

  // -- who uses the page: confirm by a second tap or by dwelling, the undo window -------------
  // Set per person by the carer with ?confirm=tap|dwell&dwell=S&undo=S&hold=S, kept in this browser.
  function settings() {
    var key = 'oracle-prefs-' + cfg.neem, saved = {};
    try { saved = JSON.parse(localStorage.getItem(key) || '{}'); } catch (e) { saved = {}; }
    var q = new URLSearchParams(location.search), out = {
      confirm: q.get('confirm') || saved.confirm || cfg.confirm,
      dwell: parseFloat(q.get('dwell') || saved.dwell || cfg.dwell_s),
      undo: parseFloat(q.get('undo') || saved.undo || cfg.undo_s),
      hold: parseFloat(q.get('hold') || saved.hold || cfg.hold_ms / 1000)
    };
    if (out.confirm !== 'dwell') out.confirm = 'tap';
    try { localStorage.setItem(key, JSON.stringify(out)); } catch (e) { /* private mode */ }
    return out;
  }

  // -- steady targets -------------------------------------------------------------------------
  // While the user is on the page (a touch, pointer or key within the hold time, the keyboard's or
  // switch's focus on the list, the sheet open), a new ranking waits behind "New suggestions";
  // otherwise it is shown at once. A tapped button keeps the focus too, but not a visible one: a
  // touch user who has let go is idle.
  ['pointerdown', 'pointermove', 'touchstart', 'keydown', 'wheel'].forEach(function (kind) {
    document.addEventListener(kind, function () { lastTouch = Date.now(); }, {capture: true, passive: true});
  });
  function engaged() {
    var focused = document.activeElement;
    return Date.now() - lastTouch < prefs.hold * 1000 || sheet.open ||
      (list.contains(focused) && focused.matches(':focus-visible'));
  }
  function said(t) { return t.mode_said ? t.reason + ' ' + t.mode_said : t.reason; }  // why here, and who usually does it
  function calls(view) { return (view && view.tasks || []).map(function (t) { return t.task; }); }
  function same(a, b) { return JSON.stringify(a) === JSON.stringify(b); }
  function incoming(view) {
    newest = view;
    if (same(view.tasks, shown && shown.tasks) && same(view.workflow, shown && shown.workflow) &&
        same(view.routine, shown && shown.routine)) {
      shown = view; pending = null; showFresh(); when.textContent = view.clock || ''; return;
    }
    if (engaged()) { pending = view; showFresh(); } else { apply(view); }
  }
  function showFresh() { fresh.classList.toggle('waiting', !!pending); fresh.disabled = !pending; }
  setInterval(function () { if (pending && !engaged()) apply(pending); }, 500);
  function apply(view) {
    var focused = document.activeElement && document.activeElement.dataset.task;
    var onFlow = document.activeElement && (document.activeElement.id === 'workflow' || document.activeElement.id === 'routine')
      ? document.activeElement.id : null;
    render(view);
    pending = null; showFresh();
    var target = onFlow ? document.getElementById(onFlow) : focused && list.querySelector('button.task[data-task="' + CSS.escape(focused) + '"]');
    if (target) target.focus();
  }
  fresh.addEventListener('click', function () {
    if (!pending) return;
    apply(pending);
    var top = list.querySelector('button.task'); if (top) top.focus();
  });

  function render(view) {
    shown = view;
    list.textContent = '';
    when.textContent = view && view.clock ? view.clock : '';
    var tasks = view && view.tasks || [];
    if (!tasks.length) { list.appendChild(el('li', 'empty', T.waiting)); return; }
    tasks.forEach(function (t, i) {
      var li = el('li', i === 0 ? 'top' : '');
      var b = el('button', 'task'); b.type = 'button'; b.dataset.task = t.task;
      b.appendChild(el('span', 'rank', String(t.rank)));
      var words = el('span', 'words');
      words.appendChild(el('span', 'name', t.said));
      words.appendChild(el('span', 'reason', said(t)));
      b.appendChild(words);
      b.addEventListener('click', function () { open({task: t.task, said: t.said, reason: said(t), rank: t.rank}); });
      li.appendChild(b); list.appendChild(li);
      if (i === 0 && view.workflow && view.workflow.length >= 2) {
        var fl = el('li', 'flow'), fb = el('button'); fb.type = 'button'; fb.id = 'workflow';
        fb.appendChild(el('span', 'label', T.workflow));
        fb.appendChild(el('span', 'steps', view.workflow.map(function (s) { return s.said; }).join(' \u2192 ')));
        // the sheet's copy: who does each step is the person's to change, not the view's
        fb.addEventListener('click', function () {
          open({workflow: view.workflow.map(function (s) { return Object.assign({}, s); }), modes: true});
        });
        fl.appendChild(fb); list.appendChild(fl);
      }
      if (i === 0 && view.routine) {  // the routine in progress: its steps left, as one workflow
        var rl = el('li', 'routine'), rb = el('button', '', view.routine.label); rb.type = 'button'; rb.id = 'routine';
        rb.addEventListener('click', function () {
          open({workflow: view.routine.steps.map(function (s) { return Object.assign({}, s); }), modes: true,
                title: view.routine.label, note: T.routine_note + ' ' + T.who_hint, item: 'li.routine'});
        });
        rl.appendChild(rb); list.appendChild(rl);
      }
    });
  }

  // -- the sheet: what a choice is, why, confirm, undo -----------------------------------------
  var title = document.getElementById('sheet-title'), note = document.getElementById('sheet-note');
  var steps = document.getElementById('sheet-steps'), yes = document.getElementById('confirm');
  var why = document.getElementById('whyhere'), other = document.getElementById('instead');
  var back = document.getElementById('back'), undo = document.getElementById('undo');
  var timer = null, opener = null;

  function available(choice) {
    var now = calls(newest);
    var wanted = choice.workflow ? [choice.workflow[0].task] : [choice.task];
    return wanted.every(function (c) { return now.indexOf(c) >= 0; });
  }
  function open(choice) {
    opener = document.activeElement;
    choosing = choice;
    stopTimer();
    title.textContent = choice.title || (choice.workflow ? T.workflow_title : choice.said);
    steps.textContent = '';
    (choice.workflow || []).forEach(function (s, i) { steps.appendChild(step(s, i, choice.modes)); });
    steps.hidden = !choice.workflow;
    sheet.dataset.phase = 'ask';
    undo.hidden = true; back.hidden = false; yes.hidden = false; why.hidden = !!choice.workflow; other.hidden = !!choice.workflow;
    note.textContent = choice.note || (choice.workflow ? T.workflow_note + ' ' + T.who_hint : choice.reason);
    if (!available(choice)) {
      sheet.dataset.phase = 'gone'; yes.hidden = true; why.hidden = true; other.hidden = true;
      note.textContent = T.gone;
    }
    sheet.showModal();
    (yes.hidden ? back : yes).focus();
    if (!yes.hidden && prefs.confirm === 'dwell') countdown(prefs.dwell, T.dwell, confirm);
  }
  // -- who does each step of a workflow (thesis 6.3): the person, the robot, or the two together.
  // Each step's button keeps its place and the focus; a tap names the next one, nothing else moves.
  var MODES = ['robot', 'user', 'together'];  // chains.MODES: a tap names the next
  function step(s, i, toggles) {
    var li = el('li'), words = el('span', 'step', s.said);
    li.appendChild(words);
    if (!toggles) return li;
    var b = el('button', 'who'); b.type = 'button'; b.dataset.step = String(i);
    function show() {
      b.dataset.mode = s.mode; b.textContent = T['who_' + s.mode];
      b.setAttribute('aria-label', s.said + ': ' + fill(T.who_is, {who: T['who_' + s.mode]}));
    }
    b.addEventListener('click', function () {
      s.mode = MODES[(MODES.indexOf(s.mode) + 1) % MODES.length];
      show();
      if (timer && sheet.dataset.phase === 'ask') {  // a dwell starts again: the person is still choosing
        stopTimer(); countdown(prefs.dwell, T.dwell, confirm);
      }
    });
    show(); li.appendChild(b);
    return li;
  }
  function countdown(seconds, text, then) {
    var left = Math.max(1, Math.round(seconds));
    var line = document.getElementById('sheet-count');
    line.textContent = fill(text, {n: left});
    timer = setInterval(function () {
      left -= 1;
      if (left <= 0) { stopTimer(); then(); return; }
      line.textContent = fill(text, {n: left});
    }, 1000);
  }
  function stopTimer() {
    if (timer) clearInterval(timer);
    timer = null; document.getElementById('sheet-count').textContent = '';
  }
  function close() {
    stopTimer(); choosing = null;
    if (sheet.open) sheet.close();
    var back = opener && document.contains(opener) ? opener : list.querySelector('button.task');
    if (back) back.focus();
  }
  function confirm() {
    stopTimer();
    if (!choosing || !available(choosing)) { sheet.dataset.phase = 'gone'; note.textContent = T.gone; yes.hidden = true; back.focus(); return; }
    sheet.dataset.phase = 'undo';
    yes.hidden = true; why.hidden = true; other.hidden = true; back.hidden = true; undo.hidden = false;
    Array.prototype.forEach.call(steps.querySelectorAll('button.who'), function (b) { b.disabled = true; });
    note.textContent = fill(T.sending, {task: choosing.workflow ? choosing.workflow[0].said : choosing.said});
    undo.focus();
    countdown(prefs.undo, T.undo_in, send);
  }
  function send() {
    var choice = choosing;
    var body = choice.workflow ? {task: choice.workflow[0].task, workflow: choice.workflow.map(function (s) { return s.task; })}
                               : {task: choice.task};
    if (choice.modes) body.modes = choice.workflow.map(function (s) { return s.mode; });
    var headers = Object.assign({'Content-Type': 'application/json'}, auth);
    fetch(api('/choice'), {method: 'POST', headers: headers, body: JSON.stringify(body)})
      .then(function (r) { return r.json().then(function (j) { if (!r.ok) throw new Error(j.error || r.status); return j; }); })
      .then(function () {
        say(choice.workflow ? fill(T.chose_workflow, {steps: choice.workflow.map(function (s) {
              return choice.modes ? s.said + ' (' + T['who_' + s.mode] + ')' : s.said; }).join(' \u2192 ')})
                            : fill(T.chose, {task: choice.said}));
        markChosen(body.task, choice.workflow ? choice.item || 'li.flow' : null);
      })
      .catch(function (e) { say(fill(T.not_sent, {why: e.message})); });
    close();
  }
  function markChosen(task, flow) {
    Array.prototype.forEach.call(list.children, function (li) { li.classList.remove('chosen'); });
    var item = flow ? list.querySelector(flow) : (list.querySelector('button.task[data-task="' + CSS.escape(task) + '"]') || {}).parentNode;
    if (item && item.classList) item.classList.add('chosen');
  }
  yes.addEventListener('click', confirm);
  back.addEventListener('click', close);
  undo.addEventListener('click', function () { say(T.undone); close(); });
  sheet.addEventListener('cancel', function (e) { e.preventDefault(); if (sheet.dataset.phase === 'undo') say(T.undone); close(); });
  why.addEventListener('click', function () { stopTimer(); inSheet('/why-not?task=' + encodeURIComponent(choosing.task)); });
  other.addEventListener('click', function () { stopTimer(); inSheet('/something-else?task=' + encodeURIComponent(choosing.task)); });
  function inSheet(path) {
    note.textContent = T.asking;
    getJSON(path).then(function (j) { note.textContent = j.said; }).catch(function (e) { note.textContent = fill(T.no_answer, {why: e.message}); });
  }

  // -- answers the user asked for stay until the user asks again; the robot has its own line ---
  function say(text) { answer.textContent = text; }
  document.getElementById('whatnext').addEventListener('click', function () {
    say(T.asking);
    getJSON('/what-next').then(function (j) { say(j.said); }).catch(function (e) { say(fill(T.no_answer, {why: e.message})); });
  });

  // -- keyboard and switch scanning: arrows move through the buttons, as Tab does --------------
  document.addEventListener('keydown', function (e) {
    if (e.key !== 'ArrowDown' && e.key !== 'ArrowUp') return;
    var scope = sheet.open ? sheet : document;
    var items = Array.prototype.filter.call(scope.querySelectorAll('button'), function (b) {
      return !b.disabled && !b.hidden && b.offsetParent !== null;
    });
    var i = items.indexOf(document.activeElement);
    var next = items[(i + (e.key === 'ArrowDown' ? 1 : items.length - 1)) % items.length];
    if (next) { next.focus(); e.preventDefault(); }
  });

  // -- live: the robot's events. The browser reconnects a dropped stream by itself (the server
  // asks for 2 s); a refused one (the service restarting) is retried here, backing off to 15 s.
  // Events sent meanwhile are lost, so every reconnection fetches the latest view.
  var url = '/api/events?neem=' + encodeURIComponent(cfg.neem) + (cfg.token ? '&token=' + encodeURIComponent(cfg.token) : '');
  var link = document.getElementById('link'), lost = false, delay = 1000, asked = 0;
  function refresh() {
    var mine = ++asked;  // answers arriving out of order: only the latest request counts
    getJSON('/tablet').then(function (view) { if (mine === asked) incoming(view); }).catch(function () {});
  }
  function connect() {
    var source = new EventSource(url);
    source.addEventListener('situation', refresh);
    source.addEventListener('action', function (m) {
      var a = JSON.parse(m.data);
      getJSON('/words?call=' + encodeURIComponent(a.call)).then(function (w) { robot.textContent = fill(T.robot_did, {task: w.said}); })
        .catch(function () { robot.textContent = fill(T.robot_did, {task: a.call}); });
    });
    source.onopen = function () {
      document.body.dataset.live = 'yes'; link.hidden = true; delay = 1000;
      if (lost) { lost = false; refresh(); }
    };
    source.onerror = function () {
      document.body.dataset.live = 'no'; lost = true; link.hidden = false;
      if (source.readyState === EventSource.CLOSED) { setTimeout(connect, delay); delay = Math.min(2 * delay, 15000); }
    };
  }
  render(cfg.view);
  showFresh();
  document.body.dataset.ready = 'yes';
  connect();
})();
