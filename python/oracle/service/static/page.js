// The tablet page (docs/service.md, "The tablet page"). The server renders the first view and
// every later one (GET .../tablet: plain words in the page's language); this script keeps the
// targets steady, asks before it acts, scans for switches, and talks to the service.
(function () {
  'use strict';
  var cfg = JSON.parse(document.getElementById('config').textContent);
  var T = cfg.text;  // the page's words in its language
  var list = document.getElementById('tasks'), answer = document.getElementById('answer');
  var robot = document.getElementById('robot'), fresh = document.getElementById('fresh');
  var when = document.getElementById('when'), sheet = document.getElementById('sheet');
  var strip = document.getElementById('strip'), link = document.getElementById('link');
  var auth = cfg.token ? {'Authorization': 'Bearer ' + cfg.token} : {};
  var prefs = settings();
  var shown = cfg.view, pending = null, newest = cfg.view;
  var lastTouch = 0, choosing = null, online = true, kept = null;
  // After a choice the person waits for the robot: its next ranking is shown at once, focus on its top.
  var following = false;
  var SHOWN = 5;  // page.py's SHOWN: the top five, then "More suggestions"

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
  function each(selector, fn) { Array.prototype.forEach.call(document.querySelectorAll(selector), fn); }

  // -- the carer's settings for this person, kept in this browser for this NEEM ----------------
  // ?confirm=tap|dwell&dwell=S&undo=S&hold=S&scan=off|one|two&step=S&filter=S&gaze=S
  function settings() {
    var key = 'oracle-prefs-' + cfg.neem, saved = {};
    try { saved = JSON.parse(localStorage.getItem(key) || '{}'); } catch (e) { saved = {}; }
    var q = new URLSearchParams(location.search);
    function num(name, fallback) {
      var v = parseFloat(q.get(name) !== null ? q.get(name) : (saved[name] !== undefined ? saved[name] : fallback));
      return isFinite(v) && v >= 0 ? v : fallback;
    }
    var out = {
      confirm: q.get('confirm') || saved.confirm || cfg.confirm,
      dwell: num('dwell', cfg.dwell_s), undo: num('undo', cfg.undo_s), hold: num('hold', cfg.hold_ms / 1000),
      scan: q.get('scan') || saved.scan || cfg.scan, step: num('step', cfg.scan_s),
      filter: num('filter', cfg.filter_s), gaze: num('gaze', cfg.gaze_s)
    };
    if (out.confirm !== 'dwell') out.confirm = 'tap';
    if (['one', 'two'].indexOf(out.scan) < 0) out.scan = 'off';
    out.step = Math.max(0.3, out.step);
    try { localStorage.setItem(key, JSON.stringify(out)); } catch (e) { /* private mode */ }
    return out;
  }

  // -- one hit counts once: a second within the filter time changes nothing (Grid 3's and TD
  // Snap's repeat-hit filter), and a target that is off (aria-disabled) does nothing ----------
  var lastHit = -1e9, passing = false;
  function hit() {
    var now = performance.now();
    if (now - lastHit < prefs.filter * 1000) return false;
    lastHit = now; return true;
  }
  function off(b) { return b.getAttribute('aria-disabled') === 'true'; }
  function press(b) { passing = true; try { b.click(); } finally { passing = false; } }  // a hit already counted
  document.addEventListener('click', function (e) {
    var b = e.target.closest ? e.target.closest('button') : null;
    if (!b) return;
    if (off(b) || (!passing && !hit())) { e.preventDefault(); e.stopImmediatePropagation(); }
  }, true);
  document.addEventListener('mousedown', function (e) {  // a press on a target that is off leaves the focus where it is
    var b = e.target.closest ? e.target.closest('button') : null;
    if (b && off(b)) e.preventDefault();
  }, true);

  // -- steady targets -------------------------------------------------------------------------
  // While the person is on the list (a touch, pointer or key within the hold time, the keyboard's
  // or two-switch focus on the list, the sheet open), a new ranking waits behind "New suggestions";
  // otherwise, and always right after a choice, it is shown at once.
  // (a pointer or eye gaze moving over the page counts: the person is aiming at something)
  ['pointerdown', 'pointermove', 'touchstart', 'keydown', 'wheel'].forEach(function (kind) {
    document.addEventListener(kind, function (e) { if (e.isTrusted) lastTouch = Date.now(); }, {capture: true, passive: true});
  });
  function engaged() {
    if (following) return false;
    var focused = document.activeElement;
    return Date.now() - lastTouch < prefs.hold * 1000 || sheet.open ||
      (prefs.scan !== 'one' && list.contains(focused) && focused.matches(':focus-visible'));
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
    if (engaged()) { pending = view; showFresh(); } else { apply(view, following); }
  }
  function showFresh() { fresh.classList.toggle('waiting', !!pending); fresh.disabled = !pending; showStrip(); }
  setInterval(function () { if (pending && !engaged()) apply(pending, false); }, 500);
  var KEEP = ['workflow', 'routine', 'whatnext', 'otherthing', 'more'];  // controls that keep the focus by id
  function apply(view, toTop) {
    var active = document.activeElement;
    var focused = active && active.dataset && active.dataset.task;
    var byId = active && KEEP.indexOf(active.id) >= 0 ? active.id : null;
    var hadFocus = list.contains(active);
    render(view);
    pending = null; showFresh();
    if (toTop) { following = false; focusTop(); return; }
    var target = byId ? document.getElementById(byId) : focused && list.querySelector('button.task[data-task="' + CSS.escape(focused) + '"]');
    if (!target && hadFocus) target = list.querySelector('button.task');
    if (target) target.focus();
  }
  function focusTop() {
    var top = list.querySelector('button.task');
    if (top) { top.focus(); top.scrollIntoView({block: 'nearest'}); }
    restartScan();
  }
  fresh.addEventListener('click', function () { if (pending) { apply(pending, true); } });

  var expanded = false;
  function render(view) {
    shown = view;
    expanded = false;
    list.textContent = '';
    when.textContent = view && view.clock ? view.clock : '';
    var tasks = view && view.tasks || [];
    if (!tasks.length) { list.appendChild(el('li', 'empty', T.waiting)); return; }
    tasks.forEach(function (t, i) {
      if (i === SHOWN) list.appendChild(moreItem(tasks.length - SHOWN));
      var li = el('li', i === 0 ? 'top' : 'rest'); li.hidden = i >= SHOWN;
      var b = el('button', 'task'); b.type = 'button'; b.dataset.task = t.task;
      b.appendChild(el('span', 'rank', String(t.rank)));
      var words = el('span', 'words');
      words.appendChild(el('span', 'name', t.said));
      words.appendChild(el('span', 'reason', said(t)));
      b.appendChild(words);
      b.addEventListener('click', function () { open({task: t.task, said: t.said, reason: said(t), rank: t.rank}); });
      li.appendChild(b); list.appendChild(li);
      if (i > 0) return;
      if (view.workflow && view.workflow.length >= 2) {
        var fl = el('li', 'flow'), fb = el('button'); fb.type = 'button'; fb.id = 'workflow';
        fb.appendChild(el('span', 'label', T.workflow));
        fb.appendChild(el('span', 'steps', view.workflow.map(function (s) { return s.said; }).join(' \u2192 ')));
        // the sheet's copy: who does each step is the person's to change, not the view's
        fb.addEventListener('click', function () {
          open({workflow: view.workflow.map(function (s) { return Object.assign({}, s); }), modes: true});
        });
        fl.appendChild(fb); list.appendChild(fl);
      }
      if (view.routine) {  // the routine in progress: its steps left, as one workflow
        var rl = el('li', 'routine'), rb = el('button', '', view.routine.label); rb.type = 'button'; rb.id = 'routine';
        rb.addEventListener('click', function () {
          open({workflow: view.routine.steps.map(function (s) { return Object.assign({}, s); }), modes: true,
                title: view.routine.label, note: T.routine_note + ' ' + T.who_hint, item: 'li.routine'});
        });
        rl.appendChild(rb); list.appendChild(rl);
      }
      // the two questions right under the top suggestion: a few presses away for a switch
      var ask = el('li', 'ask');
      var wn = el('button', '', T.whatnext); wn.type = 'button'; wn.id = 'whatnext';
      wn.addEventListener('click', function () { question(T.whatnext, '/what-next'); });
      var se = el('button', '', T.instead); se.type = 'button'; se.id = 'otherthing';
      se.addEventListener('click', function () { question(T.instead, '/something-else?task=' + encodeURIComponent(t.task)); });
      ask.appendChild(wn); ask.appendChild(se); list.appendChild(ask);
    });
    if (!online) markOff(true);
  }
  function moreItem(n) {
    var li = el('li', 'more'), b = el('button', '', fill(T.more, {n: n})); b.type = 'button'; b.id = 'more';
    b.setAttribute('aria-expanded', 'false');
    b.addEventListener('click', function () {  // the rest unfold below it: nothing above moves
      expanded = !expanded;
      b.setAttribute('aria-expanded', String(expanded));
      b.textContent = expanded ? T.fewer : fill(T.more, {n: n});
      Array.prototype.forEach.call(list.querySelectorAll('li.rest'), function (item, i) { if (i >= SHOWN - 1) item.hidden = !expanded; });
    });
    li.appendChild(b); return li;
  }

  // -- the sheet: what a choice is, why, confirm, undo; and the answers to the two questions ----
  var title = document.getElementById('sheet-title'), note = document.getElementById('sheet-note');
  var steps = document.getElementById('sheet-steps'), yes = document.getElementById('confirm');
  var why = document.getElementById('whyhere'), other = document.getElementById('instead');
  var back = document.getElementById('back'), undo = document.getElementById('undo');
  var reply = document.getElementById('sheet-answer');
  var timer = null, opener = null;

  function available(choice) {
    var now = calls(newest);
    var wanted = choice.workflow ? [choice.workflow[0].task] : [choice.task];
    return wanted.every(function (c) { return now.indexOf(c) >= 0; });
  }
  function reset() {  // every button in its own cell (page.css): hiding one moves no other
    stopTimer();
    following = false;
    yes.textContent = T.confirm; yes.classList.remove('done');
    if (online) yes.removeAttribute('aria-disabled');
    steps.textContent = ''; steps.hidden = true; reply.textContent = '';
    undo.hidden = true; back.hidden = false; yes.hidden = false; why.hidden = false; other.hidden = false;
  }
  function show(first) {
    if (!sheet.open) sheet.showModal();
    first.focus();
    restartScan();
  }
  function open(choice) {
    opener = document.activeElement;
    reset();
    choosing = choice;
    title.textContent = choice.title || (choice.workflow ? T.workflow_title : choice.said);
    (choice.workflow || []).forEach(function (s, i) { steps.appendChild(step(s, i, choice.modes)); });
    steps.hidden = !choice.workflow;
    sheet.dataset.phase = 'ask';
    why.hidden = !!choice.workflow; other.hidden = !!choice.workflow;
    note.textContent = choice.note || (choice.workflow ? T.workflow_note + ' ' + T.who_hint : choice.reason);
    if (!available(choice)) {
      sheet.dataset.phase = 'gone'; yes.hidden = true; why.hidden = true; other.hidden = true;
      note.textContent = T.gone;
    }
    show(yes.hidden ? back : yes);
    if (!yes.hidden && prefs.confirm === 'dwell' && online) countdown(prefs.dwell, T.dwell, confirm);
  }
  function question(asked, path) {  // the answer opens where the person is looking: in the sheet
    opener = document.activeElement;
    reset();
    choosing = null;
    sheet.dataset.phase = 'answer';
    title.textContent = asked; note.textContent = '';
    yes.hidden = true; why.hidden = true; other.hidden = true;
    show(back);
    inSheet(path);
  }
  // -- who does each step of a workflow (thesis 6.3): the person, the robot, or the two together.
  // Each step's button keeps its place and the focus; a tap names the next one, nothing else moves.
  var MODES = ['robot', 'user', 'together'];  // chains.MODES: a tap names the next
  function step(s, i, toggles) {
    var li = el('li'), words = el('span', 'step', s.said);
    li.appendChild(words);
    if (!toggles) return li;
    var b = el('button', 'who'); b.type = 'button'; b.dataset.step = String(i);
    function label() {
      b.dataset.mode = s.mode; b.textContent = T['who_' + s.mode];
      b.setAttribute('aria-label', s.said + ': ' + fill(T.who_is, {who: T['who_' + s.mode]}));
    }
    b.addEventListener('click', function () {
      s.mode = MODES[(MODES.indexOf(s.mode) + 1) % MODES.length];
      label();
      if (timer && sheet.dataset.phase === 'ask') {  // a dwell starts again: the person is still choosing
        stopTimer(); countdown(prefs.dwell, T.dwell, confirm);
      }
    });
    label(); li.appendChild(b);
    return li;
  }
  function countdown(seconds, text, then) {
    if (seconds <= 0) { then(); return; }
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
    var to = opener && document.contains(opener) ? opener : list.querySelector('button.task');
    if (to) to.focus();
    restartScan();
  }
  function confirm() {
    stopTimer();
    if (!choosing || !available(choosing)) { sheet.dataset.phase = 'gone'; note.textContent = T.gone; yes.hidden = true; back.focus(); return; }
    // "Yes" stays where it was, off and saying "Chosen": a second tap there does nothing. "Undo"
    // takes the place of "Back", far from it; the focus stays on "Yes".
    sheet.dataset.phase = 'undo';
    yes.textContent = T.chosen; yes.classList.add('done'); yes.setAttribute('aria-disabled', 'true');
    why.hidden = true; other.hidden = true; back.hidden = true; undo.hidden = false;
    Array.prototype.forEach.call(steps.querySelectorAll('button.who'), function (b) { b.disabled = true; });
    // the note above the buttons stays as it is (a new text there would move them): the countdown
    // line below them says what is about to happen
    var sending = fill(T.sending, {task: choosing.workflow ? choosing.workflow[0].said : choosing.said});
    if (document.activeElement !== yes) yes.focus();
    restartScan();
    countdown(prefs.undo, sending + ' ' + T.undo_in, send);
  }
  function send() {
    var choice = choosing;
    var body = choice.workflow ? {task: choice.workflow[0].task, workflow: choice.workflow.map(function (s) { return s.task; })}
                               : {task: choice.task};
    if (choice.modes) body.modes = choice.workflow.map(function (s) { return s.mode; });
    opener = null;
    close();
    following = true;  // the robot's next ranking comes at once, the focus on its top
    if (pending) apply(pending, false);
    focusTop();
    if (!online) { keep(choice, body); return; }
    post(choice, body, null);
  }
  function chosenWords(choice) {
    return choice.workflow ? fill(T.chose_workflow, {steps: choice.workflow.map(function (s) {
      return choice.modes ? s.said + ' (' + T['who_' + s.mode] + ')' : s.said; }).join(' \u2192 ')})
                           : fill(T.chose, {task: choice.said});
  }
  function post(choice, body, saying) {
    var headers = Object.assign({'Content-Type': 'application/json'}, auth);
    return fetch(api('/choice'), {method: 'POST', headers: headers, body: JSON.stringify(body)})
      .then(function (r) { return r.json().then(function (j) { if (!r.ok) throw new Error(j.error || r.status); return j; }); },
            function () { keep(choice, body); return null; })  // no answer at all: kept, sent when the robot is back
      .then(function (j) {
        if (!j) return;
        kept = null;
        say(saying || chosenWords(choice));
        markChosen(body.task, choice.workflow ? choice.item || 'li.flow' : null);
      })
      .catch(function (e) { kept = null; say(fill(T.not_sent, {why: e.message})); });
  }
  function keep(choice, body) {
    kept = {choice: choice, body: body};
    say(fill(T.kept, {task: choice.workflow ? choice.workflow[0].said : choice.said}));
  }
  function flushKept() {  // back online: the choice kept goes out if the robot still offers it
    if (!kept) return;
    var k = kept, task = k.choice.workflow ? k.choice.workflow[0].said : k.choice.said;
    if (!available(k.choice)) { kept = null; say(fill(T.kept_gone, {task: task})); return; }
    post(k.choice, k.body, fill(T.kept_sent, {task: task}));
  }
  setInterval(function () { if (kept && online) refresh().then(flushKept); }, 3000);  // a lost POST with the stream up
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
  function inSheet(path) {  // below the buttons: a long answer moves none of them
    reply.textContent = T.asking;
    getJSON(path).then(function (j) { reply.textContent = j.said; }).catch(function (e) { reply.textContent = fill(T.no_answer, {why: e.message}); })
      .then(function () { reply.scrollIntoView({block: 'nearest'}); });
  }

  // -- the strip over the foot of the screen: what was chosen, what the robot did, offline -----
  function say(text) { answer.textContent = text; showStrip(); }
  function showStrip() {
    strip.hidden = !(answer.textContent || robot.textContent || !link.hidden || pending);
    // a focused button scrolls clear of the strip, never under it, and the last one can: room for
    // the strip below the page's end (nothing above it moves)
    var room = strip.hidden ? 0 : strip.offsetHeight + 12;
    document.documentElement.style.scrollPaddingBottom = room + 'px';
    document.querySelector('main').style.paddingBottom = room ? room + 40 + 'px' : '';
  }

  // -- switches: the page's own scanning. Two switches: Space moves, Enter selects. One switch:
  // the highlight moves by itself every `step` seconds, Space or Enter selects. Without
  // scanning the arrow keys move through the buttons, as Tab does. -------------------------
  var scanTimer = null;
  function scanItems() {
    var scope = sheet.open ? sheet : document;
    return Array.prototype.filter.call(scope.querySelectorAll('button'), function (b) {
      return !b.disabled && !b.hidden && b.offsetParent !== null && !off(b) && getComputedStyle(b).visibility === 'visible';
    });
  }
  function move(by) {
    var items = scanItems();
    if (!items.length) return;
    var i = items.indexOf(document.activeElement);
    var next = i < 0 ? items[0] : items[(i + by + items.length) % items.length];
    next.focus();
    next.scrollIntoView({block: 'nearest'});
  }
  function restartScan() {
    if (scanTimer) clearInterval(scanTimer);
    scanTimer = prefs.scan === 'one' ? setInterval(function () { move(1); }, prefs.step * 1000) : null;
  }
  function select() {
    var b = document.activeElement;
    if (b && scanItems().indexOf(b) >= 0) press(b); else move(0);
  }
  document.addEventListener('keydown', function (e) {
    var selects = prefs.scan === 'one' ? (e.key === ' ' || e.key === 'Enter') : prefs.scan === 'two' && e.key === 'Enter';
    var moves = prefs.scan === 'two' && e.key === ' ';
    if (selects || moves) {
      e.preventDefault(); e.stopPropagation();
      if (e.repeat || !hit()) return;
      if (moves) move(1); else select();
      restartScan();
      return;
    }
    if (e.key !== 'ArrowDown' && e.key !== 'ArrowUp') return;
    move(e.key === 'ArrowDown' ? 1 : -1);
    e.preventDefault();
  }, true);
  document.addEventListener('keyup', function (e) {  // a button's own Space would click on keyup
    if (prefs.scan !== 'off' && e.key === ' ') { e.preventDefault(); e.stopPropagation(); }
  }, true);

  // -- dwell to select: a pointer or eye gaze resting `gaze` seconds on a button selects it,
  // the button filling up meanwhile; it selects again only after the pointer has left it ------
  var gazeOn = null, gazeTimer = null;
  function stopGaze() {
    if (gazeTimer) clearTimeout(gazeTimer);
    if (gazeOn) gazeOn.classList.remove('gazing');
    gazeOn = null; gazeTimer = null;
  }
  if (prefs.gaze > 0) {
    document.documentElement.style.setProperty('--gaze', prefs.gaze + 's');
    document.addEventListener('pointerover', function (e) {
      if (e.pointerType === 'touch') return;
      var b = e.target.closest ? e.target.closest('button') : null;
      if (b === gazeOn) return;
      stopGaze();
      if (!b || b.disabled || off(b)) return;
      gazeOn = b; b.classList.add('gazing');
      gazeTimer = setTimeout(function () {
        gazeTimer = null; b.classList.remove('gazing');
        if (!off(b) && hit()) press(b);
      }, prefs.gaze * 1000);
    });
    document.addEventListener('pointerout', function (e) {
      if (gazeOn && e.target.closest && e.target.closest('button') === gazeOn && !gazeOn.contains(e.relatedTarget)) stopGaze();
    });
  }

  // -- live: the robot's events. The browser reconnects a dropped stream by itself (the server
  // asks for 2 s); a refused one (the service restarting) is retried here, backing off to 15 s.
  // Events sent meanwhile are lost, so every reconnection fetches the latest view. Offline,
  // every target that would reach the robot is off (aria-disabled, striped) until it is back.
  var url = '/api/events?neem=' + encodeURIComponent(cfg.neem) + (cfg.token ? '&token=' + encodeURIComponent(cfg.token) : '');
  var lost = false, delay = 1000, asked = 0;
  var REACH = '#tasks button:not(#more), #confirm, #whyhere, #instead';
  function markOff(isOff) {
    each(REACH, function (b) {
      if (isOff) b.setAttribute('aria-disabled', 'true');
      else if (!(b === yes && sheet.dataset.phase === 'undo')) b.removeAttribute('aria-disabled');
    });
    if (isOff && sheet.dataset.phase === 'ask') stopTimer();  // a dwell stops; an undo window runs on, its choice kept
  }
  function refresh() {
    var mine = ++asked;  // answers arriving out of order: only the latest request counts
    return getJSON('/tablet').then(function (view) { if (mine === asked) incoming(view); }).catch(function () {});
  }
  function connect() {
    var source = new EventSource(url);
    source.addEventListener('situation', refresh);
    source.addEventListener('action', function (m) {
      var a = JSON.parse(m.data);
      getJSON('/words?call=' + encodeURIComponent(a.call)).then(function (w) { robot.textContent = fill(T.robot_did, {task: w.said}); })
        .catch(function () { robot.textContent = fill(T.robot_did, {task: a.call}); }).then(showStrip);
    });
    source.onopen = function () {
      document.body.dataset.live = 'yes'; link.hidden = true; delay = 1000;
      if (!online) { online = true; markOff(false); }
      showStrip();
      if (lost) { lost = false; refresh().then(flushKept); }
    };
    source.onerror = function () {
      document.body.dataset.live = 'no'; lost = true; link.hidden = false;
      online = false; markOff(true); showStrip();
      if (source.readyState === EventSource.CLOSED) { setTimeout(connect, delay); delay = Math.min(2 * delay, 15000); }
    };
  }
  document.body.dataset.scan = prefs.scan;
  render(cfg.view);
  showFresh();
  if (prefs.scan !== 'off') focusTop();
  document.body.dataset.ready = 'yes';
  connect();
})();
