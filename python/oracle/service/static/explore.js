/* The NEEM explorer (/explore): a timeline drawn on a canvas, the decision at hand, the rolling
   Top-k curve, the routines and a Prolog console. Everything it shows comes from the service's
   read-only routes; every drawing goes through a painter, so the same code draws on the canvas
   and writes the SVG export. */
(function () {
  "use strict";
  var config = JSON.parse(document.getElementById("config").textContent);
  var DAY = 86400;
  var PREFIXES = [["soma:", "http://www.ease-crc.org/ont/SOMA.owl#"], ["dul:", "http://www.ontologydesignpatterns.org/ont/dul/DUL.owl#"],
    ["odb:", "https://ontology.dlr.de/soma/odb#"], ["knowrob:", "http://knowrob.org/kb/knowrob.owl#"],
    ["owl:", "http://www.w3.org/2002/07/owl#"], ["rdf:", "http://www.w3.org/1999/02/22-rdf-syntax-ns#"],
    ["rdfs:", "http://www.w3.org/2000/01/rdf-schema#"], ["xsd:", "http://www.w3.org/2001/XMLSchema#"]];
  // Okabe-Ito colours (told apart by most colour-blind readers), then darker variants for more tasks.
  var PALETTE = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442", "#000000",
    "#004c7a", "#9c6b00", "#006b4f", "#8f4f78", "#2f7fa6", "#8f3f00", "#a89f2c", "#5a5a5a"];
  var RANK_COLOURS = { 1: "#1b6e2d", 3: "#2f6db5", 5: "#b26b00", miss: "#b3261e", none: "#8a8a8a" };
  var ROUTINE_COLOURS = ["#6a3d9a", "#b15928", "#1f78b4", "#33a02c", "#e31a1c", "#ff7f00"];

  var state = { neem: config.neem, timeline: null, decisions: null, routines: [], view: null, selected: -1, answers: null };

  function headers(extra) {
    var h = extra || {};
    if (config.token) { h.Authorization = "Bearer " + config.token; }
    return h;
  }
  function getJSON(path) {
    return fetch(path, { headers: headers() }).then(function (r) {
      return r.json().then(function (body) { return { status: r.status, body: body }; });
    });
  }
  function el(tag, attrs, text) {
    var node = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) { node.setAttribute(k, attrs[k]); });
    if (text !== undefined) { node.textContent = text; }
    return node;
  }
  function pad(n) { return (n < 10 ? "0" : "") + n; }
  function dateOf(seconds) {  // the project's one clock rule: UTC wall clock (oracle.timeline.clock)
    var d = new Date(seconds * 1000);
    return d.getUTCFullYear() + "-" + pad(d.getUTCMonth() + 1) + "-" + pad(d.getUTCDate());
  }
  function clockOf(seconds) {
    var d = new Date(seconds * 1000);
    return dateOf(seconds) + " " + pad(d.getUTCHours()) + ":" + pad(d.getUTCMinutes()) + ":" + pad(d.getUTCSeconds());
  }
  function hourText(h) { var m = Math.round(h * 60); return pad(Math.floor(m / 60) % 24) + ":" + pad(m % 60); }
  function shortIri(text) {
    var out = String(text);
    PREFIXES.forEach(function (p) { out = out.split(p[1]).join(p[0]); });
    return out;
  }
  function download(name, blob) {
    var a = el("a", { href: URL.createObjectURL(blob), download: name }, name);
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(function () { URL.revokeObjectURL(a.href); }, 1000);
  }

  // -- painters: one drawing code for the canvas and the SVG export ---------------------------
  function canvasPainter(ctx) {
    return {
      rect: function (x, y, w, h, fill) { ctx.fillStyle = fill; ctx.fillRect(x, y, w, h); },
      rects: function (fill, r) {  // x, y, w, h, ... in one path: one fill per colour, not per bar
        ctx.beginPath();
        for (var i = 0; i < r.length; i += 4) { ctx.rect(r[i], r[i + 1], r[i + 2], r[i + 3]); }
        ctx.fillStyle = fill; ctx.fill();
      },
      frame: function (x, y, w, h, stroke, width) { ctx.strokeStyle = stroke; ctx.lineWidth = width; ctx.strokeRect(x, y, w, h); },
      line: function (points, stroke, width, dash) {
        ctx.beginPath(); ctx.setLineDash(dash || []); ctx.strokeStyle = stroke; ctx.lineWidth = width;
        for (var i = 0; i < points.length; i += 2) { if (i === 0) { ctx.moveTo(points[0], points[1]); } else { ctx.lineTo(points[i], points[i + 1]); } }
        ctx.stroke(); ctx.setLineDash([]);
      },
      text: function (x, y, str, fill, align) {
        ctx.fillStyle = fill; ctx.font = "12px system-ui, sans-serif"; ctx.textAlign = align || "left"; ctx.fillText(str, x, y);
      },
      triangles: function (fill, points, size) {  // pointing down at each (x, y), one fill
        ctx.beginPath();
        for (var i = 0; i < points.length; i += 2) {
          var x = points[i], y = points[i + 1];
          ctx.moveTo(x, y); ctx.lineTo(x - size, y - size * 1.4); ctx.lineTo(x + size, y - size * 1.4); ctx.closePath();
        }
        ctx.fillStyle = fill; ctx.fill();
      }
    };
  }
  function svgPainter(width, height) {
    var parts = [];
    function esc(s) { return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;"); }
    function n(v) { return Math.round(v * 10) / 10; }
    return {
      rect: function (x, y, w, h, fill) { parts.push('<rect x="' + n(x) + '" y="' + n(y) + '" width="' + n(w) + '" height="' + n(h) + '" fill="' + fill + '"/>'); },
      rects: function (fill, r) {
        var d = [];
        for (var i = 0; i < r.length; i += 4) { d.push("M" + n(r[i]) + " " + n(r[i + 1]) + "h" + n(r[i + 2]) + "v" + n(r[i + 3]) + "h" + n(-r[i + 2]) + "z"); }
        if (d.length) { parts.push('<path fill="' + fill + '" d="' + d.join("") + '"/>'); }
      },
      frame: function (x, y, w, h, stroke, width2) {
        parts.push('<rect x="' + n(x) + '" y="' + n(y) + '" width="' + n(w) + '" height="' + n(h) + '" fill="none" stroke="' + stroke + '" stroke-width="' + width2 + '"/>');
      },
      line: function (points, stroke, width2, dash) {
        var d = [];
        for (var i = 0; i < points.length; i += 2) { d.push(n(points[i]) + "," + n(points[i + 1])); }
        parts.push('<polyline fill="none" stroke="' + stroke + '" stroke-width="' + width2 + '"' +
          (dash && dash.length ? ' stroke-dasharray="' + dash.join(" ") + '"' : "") + ' points="' + d.join(" ") + '"/>');
      },
      text: function (x, y, str, fill, align) {
        var anchor = align === "right" ? "end" : align === "center" ? "middle" : "start";
        parts.push('<text x="' + n(x) + '" y="' + n(y) + '" fill="' + fill + '" font-size="12" font-family="sans-serif" text-anchor="' + anchor + '">' + esc(str) + "</text>");
      },
      triangles: function (fill, points, size) {
        var d = [];
        for (var i = 0; i < points.length; i += 2) {
          var x = points[i], y = points[i + 1];
          d.push("M" + n(x) + " " + n(y) + "L" + n(x - size) + " " + n(y - size * 1.4) + "L" + n(x + size) + " " + n(y - size * 1.4) + "z");
        }
        if (d.length) { parts.push('<path fill="' + fill + '" d="' + d.join("") + '"/>'); }
      },
      done: function () {
        return '<svg xmlns="http://www.w3.org/2000/svg" width="' + width + '" height="' + height + '" viewBox="0 0 ' + width + " " + height + '">' +
          '<rect width="100%" height="100%" fill="#fff"/>' + parts.join("") + "</svg>";
      }
    };
  }

  // -- NEEMs ----------------------------------------------------------------------------------
  function loadNeems() {
    return getJSON("/explore/api/neems").then(function (r) {
      var body = document.querySelector("#neems tbody");
      body.textContent = "";
      if (r.status !== 200) { body.appendChild(el("tr")).appendChild(el("td", { colspan: "6" }, r.body.error || "error")); return; }
      r.body.forEach(function (n) {
        var tr = el("tr");
        var open = el("button", { type: "button", "data-neem": n.id }, n.name || n.id);
        open.setAttribute("aria-label", "Explore " + (n.name || n.id));
        open.addEventListener("click", function () { choose(n.id); });
        tr.appendChild(el("td")).appendChild(open);
        tr.appendChild(el("td", {}, n.user || "-"));
        tr.appendChild(el("td", {}, n.begin ? clockOf(n.begin) + " to " + clockOf(n.end) : "-"));
        tr.appendChild(el("td", {}, String(n.actions)));
        tr.appendChild(el("td", {}, n.ontology));
        tr.appendChild(el("td", {}, n.consent));
        if (n.id === state.neem || n.name === state.neem) { tr.className = "chosen"; }
        body.appendChild(tr);
      });
      if (!state.neem && r.body.length) { state.neem = r.body[0].id; body.firstChild.className = "chosen"; }
      return state.neem;
    });
  }

  function choose(neem) {
    state.neem = neem;
    document.querySelectorAll("#neems tr").forEach(function (tr) {
      var b = tr.querySelector("button"); tr.className = b && b.dataset.neem === neem ? "chosen" : "";
    });
    var url = new URL(location.href); url.searchParams.set("neem", neem);  // the token stays: a reload needs it
    history.replaceState(null, "", url.pathname + url.search);
    loadNeem();
  }

  // -- the timeline's model -------------------------------------------------------------------
  function buildTimeline(data) {
    var rows = data.rows, n = rows.length / 6;
    var t = { calls: data.calls, sets: data.sets, n: n, begin: new Float64Array(n), end: new Float64Array(n),
      call: new Int32Array(n), set: new Int32Array(n), idle: new Uint8Array(n), decisionOf: new Int32Array(n),
      actionOfDecision: [], tasks: [], taskOf: new Int32Array(data.calls.length) };
    var idleCall = data.calls.indexOf("idle"), taskIndex = {};
    data.calls.forEach(function (c, i) {
      var task = c.split("(")[0];
      if (!(task in taskIndex)) { taskIndex[task] = t.tasks.length; t.tasks.push(task); }
      t.taskOf[i] = taskIndex[task];
    });
    for (var i = 0; i < n; i++) {
      t.begin[i] = rows[6 * i]; t.end[i] = rows[6 * i + 1]; t.call[i] = rows[6 * i + 2]; t.set[i] = rows[6 * i + 4];
      t.idle[i] = t.call[i] === idleCall ? 1 : 0;
      t.decisionOf[i] = -1;
      if (!t.idle[i]) { t.decisionOf[i] = t.actionOfDecision.length; t.actionOfDecision.push(i); }
    }
    t.day0 = n ? Math.floor(t.begin[0] / DAY) : 0;
    t.days = n ? Math.floor(Math.max(t.end[n - 1], t.begin[n - 1]) / DAY) - t.day0 + 1 : 1;
    t.firstOfDay = new Int32Array(t.days + 1);  // actions sorted by begin: each day's are contiguous
    var day = 0;
    for (i = 0; i < n; i++) {
      var d = Math.floor(t.begin[i] / DAY) - t.day0;
      while (day <= d) { t.firstOfDay[day++] = i; }
    }
    while (day <= t.days) { t.firstOfDay[day++] = n; }
    return t;
  }

  function wholeView(t) { return { h0: 0, h1: 24, d0: 0, d1: Math.max(t.days, 1) }; }

  var AXIS_LEFT = 92, AXIS_TOP = 22;

  function drawTimeline(p, width, height, t, view) {
    var plotW = width - AXIS_LEFT - 8, plotH = height - AXIS_TOP - 6;
    var xOf = function (h) { return AXIS_LEFT + (h - view.h0) / (view.h1 - view.h0) * plotW; };
    var rowH = plotH / (view.d1 - view.d0);
    var yOf = function (d) { return AXIS_TOP + (d - view.d0) * rowH; };
    p.rect(0, 0, width, height, "#ffffff");
    // hour grid
    var step = [1, 2, 3, 6].filter(function (s) { return (view.h1 - view.h0) / s <= 14; })[0] || 6;
    if (view.h1 - view.h0 < 3) { step = 0.25; }
    for (var h = Math.ceil(view.h0 / step) * step; h <= view.h1; h += step) {
      p.line([xOf(h), AXIS_TOP, xOf(h), height - 6], "#e3e0d8", 1);
      p.text(xOf(h), AXIS_TOP - 6, hourText(h), "#333", "center");
    }
    var dayStep = Math.max(1, Math.ceil(14 / Math.max(rowH, 0.01)));
    var firstDay = Math.max(0, Math.floor(view.d0)), lastDay = Math.min(t.days - 1, Math.ceil(view.d1));
    for (var d = firstDay; d <= lastDay; d++) {
      if (d % dayStep === 0) { p.text(AXIS_LEFT - 6, yOf(d) + Math.min(rowH, 14) * 0.8 + 1, dateOf((t.day0 + d) * DAY), "#333", "right"); }
    }
    var barH = Math.max(1, rowH * 0.62), markH = Math.max(1, Math.min(rowH * 0.22, 6));
    var decided = state.decisions, buckets = {}, last = {};
    // whole pixels (no anti-aliased edges to blend), and a bar that would only repaint the pixel
    // column its colour just painted in this row is left out: at 10,000 actions most would
    function add(fill, x, y, w, h) {
      var x0 = Math.round(x), x1 = Math.max(Math.round(x + w), x0 + 1), y0 = Math.round(y), key = fill + y0;
      if (last[key] !== undefined && last[key] >= x1) { return; }
      last[key] = x1;
      (buckets[fill] || (buckets[fill] = [])).push(x0, y0, x1 - x0, Math.max(Math.round(y + h) - y0, 1));
    }
    for (d = firstDay; d <= lastDay; d++) {
      var y = yOf(d);
      for (var i = t.firstOfDay[d]; i < t.firstOfDay[d + 1]; i++) {
        var b = (t.begin[i] / DAY - t.day0 - d) * 24, e = (t.end[i] / DAY - t.day0 - d) * 24;
        if (e < view.h0 || b > view.h1) { continue; }
        var x0 = xOf(Math.max(b, view.h0)), x1 = xOf(Math.min(e, view.h1, 24));
        if (t.idle[i]) {  // an idle gap: a thin band across the rest of the row
          add("#cfcac0", x0, y + rowH * 0.45, Math.max(x1 - x0, 1), Math.max(1, rowH * 0.1));
          continue;
        }
        add(PALETTE[t.taskOf[t.call[i]] % PALETTE.length], x0, y + 1, Math.max(x1 - x0, 1.5), barH);
        var k = t.decisionOf[i];
        if (decided && k >= 0 && k < decided.rank.length) {
          add(rankColour(decided.rank[k]), x0, y + 1 + barH, Math.max(x1 - x0, 1.5), markH);
        }
      }
    }
    Object.keys(buckets).forEach(function (fill) { p.rects(fill, buckets[fill]); });
    // routines' occurrences: a triangle at each episode's begin
    var size = Math.max(2, Math.min(rowH * 0.3, 5));
    state.routines.forEach(function (r, ri) {
      if (!r.shown) { return; }
      var points = [];
      r.begins.forEach(function (begin) {
        var dd = Math.floor(begin / DAY) - t.day0, hh = (begin / DAY - t.day0 - dd) * 24;
        if (dd < view.d0 - 1 || dd > view.d1 || hh < view.h0 || hh > view.h1) { return; }
        points.push(xOf(hh), yOf(dd) + 1 + Math.min(rowH * 0.4, 7));
      });
      p.triangles(ROUTINE_COLOURS[ri % ROUTINE_COLOURS.length], points, size);
    });
    if (state.selected >= 0) {
      var a = t.actionOfDecision[state.selected];
      var sd = Math.floor(t.begin[a] / DAY) - t.day0;
      var sb = (t.begin[a] / DAY - t.day0 - sd) * 24, se = (t.end[a] / DAY - t.day0 - sd) * 24;
      p.frame(xOf(sb) - 2, yOf(sd) - 1, Math.max(xOf(se) - xOf(sb), 2) + 4, Math.max(rowH, 4) + 2, "#c25400", 2);
    }
    p.frame(AXIS_LEFT, AXIS_TOP, plotW, plotH, "#8a8478", 1);
  }

  function rankColour(rank) {
    if (rank === 0) { return RANK_COLOURS.none; }
    return rank === 1 ? RANK_COLOURS[1] : rank <= 3 ? RANK_COLOURS[3] : rank <= 5 ? RANK_COLOURS[5] : RANK_COLOURS.miss;
  }

  var painted = false, pending = false;
  function redraw() {
    if (pending) { return; }
    pending = true;
    requestAnimationFrame(function () {
      pending = false;
      var canvas = document.getElementById("timeline");
      if (!state.timeline) { return; }
      var size = fitCanvas(canvas);
      performance.mark("timeline-draw-start");
      drawTimeline(canvasPainter(canvas.getContext("2d")), size.w, size.h, state.timeline, state.view);
      performance.measure("timeline-draw", "timeline-draw-start");
      if (!painted) { painted = true; performance.mark("timeline-painted"); }
    });
  }

  function fitCanvas(canvas) {
    var ratio = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
      canvas.width = Math.round(w * ratio); canvas.height = Math.round(h * ratio);
    }
    canvas.getContext("2d").setTransform(ratio, 0, 0, ratio, 0, 0);
    return { w: w, h: h };
  }

  // -- zoom, pan, selection -------------------------------------------------------------------
  function clampView(v, t) {
    var span = Math.min(Math.max(v.h1 - v.h0, 0.05), 24);
    v.h0 = Math.min(Math.max(v.h0, 0), 24 - span); v.h1 = v.h0 + span;
    var days = Math.min(Math.max(v.d1 - v.d0, 1), Math.max(t.days, 1));
    v.d0 = Math.min(Math.max(v.d0, 0), Math.max(t.days - days, 0)); v.d1 = v.d0 + days;
    return v;
  }
  function zoomHours(factor, atHour) {
    if (!state.timeline) { return; }  // nothing to zoom or pan before the first timeline
    var v = state.view, at = atHour === undefined ? (v.h0 + v.h1) / 2 : atHour;
    v.h0 = at - (at - v.h0) * factor; v.h1 = at + (v.h1 - at) * factor;
    clampView(v, state.timeline); redraw();
  }
  function zoomDays(factor, atDay) {
    if (!state.timeline) { return; }  // nothing to zoom or pan before the first timeline
    var v = state.view, at = atDay === undefined ? (v.d0 + v.d1) / 2 : atDay;
    v.d0 = at - (at - v.d0) * factor; v.d1 = at + (v.d1 - at) * factor;
    clampView(v, state.timeline); redraw();
  }
  function pan(dh, dd) {
    if (!state.timeline) { return; }  // nothing to zoom or pan before the first timeline
    var v = state.view;
    v.h0 += dh; v.h1 += dh; v.d0 += dd; v.d1 += dd;
    clampView(v, state.timeline); redraw();
  }
  function plotPoint(canvas, event) {
    var r = canvas.getBoundingClientRect(), v = state.view;
    var plotW = r.width - AXIS_LEFT - 8, plotH = r.height - AXIS_TOP - 6;
    return { hour: v.h0 + (event.clientX - r.left - AXIS_LEFT) / plotW * (v.h1 - v.h0),
      day: v.d0 + (event.clientY - r.top - AXIS_TOP) / plotH * (v.d1 - v.d0), perHour: plotW / (v.h1 - v.h0),
      perDay: plotH / (v.d1 - v.d0) };
  }
  function bindTimeline() {
    var canvas = document.getElementById("timeline"), drag = null;
    canvas.addEventListener("wheel", function (event) {
      if (!state.timeline) { return; }
      event.preventDefault();
      var at = plotPoint(canvas, event), factor = event.deltaY > 0 ? 1.25 : 0.8;
      if (event.shiftKey) { zoomDays(factor, at.day); } else { zoomHours(factor, at.hour); }
    }, { passive: false });
    canvas.addEventListener("pointerdown", function (event) {
      if (!state.timeline) { return; }
      drag = { x: event.clientX, y: event.clientY, moved: false, at: plotPoint(canvas, event) };
      canvas.setPointerCapture(event.pointerId);
    });
    canvas.addEventListener("pointermove", function (event) {
      if (!drag) { return; }
      var dx = event.clientX - drag.x, dy = event.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) { drag.moved = true; }
      pan(-dx / drag.at.perHour, -dy / drag.at.perDay);
      drag.x = event.clientX; drag.y = event.clientY;
    });
    canvas.addEventListener("pointerup", function (event) {
      if (drag && !drag.moved) { selectAt(plotPoint(canvas, event)); }
      drag = null;
    });
    canvas.addEventListener("keydown", function (event) {
      if (!state.timeline) { return; }
      var v = state.view, handled = true;
      if (event.shiftKey && event.key === "ArrowLeft") { pan(-(v.h1 - v.h0) / 10, 0); }
      else if (event.shiftKey && event.key === "ArrowRight") { pan((v.h1 - v.h0) / 10, 0); }
      else if (event.shiftKey && event.key === "ArrowUp") { pan(0, -(v.d1 - v.d0) / 10); }
      else if (event.shiftKey && event.key === "ArrowDown") { pan(0, (v.d1 - v.d0) / 10); }
      else if (event.key === "ArrowLeft" || event.key === "ArrowUp") { select(Math.max(0, state.selected - 1), true); }
      else if (event.key === "ArrowRight" || event.key === "ArrowDown") { select(Math.min(state.timeline.actionOfDecision.length - 1, state.selected + 1), true); }
      else if (event.key === "PageUp" || event.key === "PageDown") { selectDay(event.key === "PageUp" ? -1 : 1); }
      else if (event.key === "Home") { select(0, true); }
      else if (event.key === "End") { select(state.timeline.actionOfDecision.length - 1, true); }
      else if (event.key === "+" || event.key === "=") { zoomHours(0.8); }
      else if (event.key === "-") { zoomHours(1.25); }
      else if (event.key === "[") { zoomDays(0.8); }
      else if (event.key === "]") { zoomDays(1.25); }
      else { handled = false; }
      if (handled) { event.preventDefault(); }
    });
    document.getElementById("zoom-in").addEventListener("click", function () { zoomHours(0.5); zoomDays(0.5); });
    document.getElementById("zoom-out").addEventListener("click", function () { zoomHours(2); zoomDays(2); });
    document.getElementById("zoom-reset").addEventListener("click", function () {
      if (state.timeline) { state.view = wholeView(state.timeline); redraw(); }
    });
    document.getElementById("timeline-png").addEventListener("click", function () {
      canvas.toBlob(function (blob) { download("timeline.png", blob); }, "image/png");
    });
    document.getElementById("timeline-svg").addEventListener("click", function () {
      var w = canvas.clientWidth, h = canvas.clientHeight, p = svgPainter(w, h);
      drawTimeline(p, w, h, state.timeline, state.view);
      download("timeline.svg", new Blob([p.done()], { type: "image/svg+xml" }));
    });
    window.addEventListener("resize", redraw);
  }
  function selectAt(point) {
    var t = state.timeline, d = Math.floor(point.day), best = -1, gap = Infinity;
    if (d < 0 || d >= t.days) { return; }
    for (var i = t.firstOfDay[d]; i < t.firstOfDay[d + 1]; i++) {
      if (t.idle[i]) { continue; }
      var b = (t.begin[i] / DAY - t.day0 - d) * 24, e = (t.end[i] / DAY - t.day0 - d) * 24;
      var off = point.hour < b ? b - point.hour : point.hour > e ? point.hour - e : 0;
      if (off < gap) { gap = off; best = i; }
    }
    if (best >= 0 && gap * point.perHour < 12) { select(t.decisionOf[best], false); }
  }
  function selectDay(delta) {
    var t = state.timeline, a = t.actionOfDecision[Math.max(state.selected, 0)];
    var d = Math.floor(t.begin[a] / DAY) - t.day0 + delta;
    while (d >= 0 && d < t.days) {
      for (var i = t.firstOfDay[d]; i < t.firstOfDay[d + 1]; i++) { if (!t.idle[i]) { select(t.decisionOf[i], true); return; } }
      d += delta;
    }
  }
  function select(k, follow) {
    var t = state.timeline;
    if (!t || k < 0 || k >= t.actionOfDecision.length) { return; }
    state.selected = k;
    if (follow) {  // keep the selection in view
      var a = t.actionOfDecision[k], v = state.view, d = Math.floor(t.begin[a] / DAY) - t.day0;
      var h = (t.begin[a] / DAY - t.day0 - d) * 24;
      if (d < v.d0 || d + 1 > v.d1) { pan(0, d - (v.d0 + v.d1) / 2 + 0.5); }
      if (h < v.h0 || h > v.h1) { pan(h - (v.h0 + v.h1) / 2, 0); }
    }
    showDecision(k);
    redraw(); drawCurve();
  }

  // -- the decision at hand -------------------------------------------------------------------
  function showDecision(k) {
    var t = state.timeline, a = t.actionOfDecision[k], box = document.getElementById("decision");
    box.textContent = "";
    var call = t.calls[t.call[a]];
    var head = el("p");
    head.appendChild(el("b", {}, "Decision " + (k + 1) + " of " + t.actionOfDecision.length + ", " + clockOf(t.begin[a]) + ": "));
    head.appendChild(document.createTextNode("the user then did " + call + "."));
    box.appendChild(head);
    var situation = t.set[a] >= 0 ? t.sets[t.set[a]].map(function (c) { return t.calls[c]; }) : null;
    box.appendChild(el("p", {}, situation ? "Imagined situation: " + situation.length + " tasks available (" + situation.join(", ") + ")."
      : "No imagined situation was logged for this action."));
    var d = state.decisions;
    if (!d) { box.appendChild(el("p", {}, "The predictor's ranking appears when the replay is done.")); return; }
    if (k >= d.rank.length) { return; }
    if (d.prior && d.prior.given) { box.appendChild(el("p", { class: "share" }, shareText(d.prior.shares[k]))); }
    var rank = d.rank[k], verdict = el("p");
    verdict.appendChild(el("span", { class: rank === 1 ? "hit" : "miss" },
      rank === 0 ? "Not offered: the user's action was not among the candidates." :
        rank === 1 ? "Hit: ranked first." : "Ranked " + rank + (rank <= 3 ? " (in the top 3)." : rank <= 5 ? " (in the top 5)." : " (a miss).")));
    verdict.appendChild(document.createTextNode(" " + d.candidates[k] + " candidates; the predictor (" + d.method + ") ranked:"));
    box.appendChild(verdict);
    var list = el("ol");
    d.ranked[k].forEach(function (c) {
      var li = el("li", {}, d.calls[c]);
      if (c === d.truth[k]) { li.className = "truth"; li.appendChild(document.createTextNode(" (what the user did)")); }
      list.appendChild(li);
    });
    box.appendChild(list);
  }

  function pctOf(v) { return Math.round(v * 100) + " %"; }
  function shareText(share) {
    if (share === null || share === undefined) { return "The shared prior took no part in this ranking (the routine predictor ranked alone)."; }
    return "Where the ranking came from: " + pctOf(share) + " the shared prior (what other people usually do next), " +
      pctOf(1 - share) + " the user's own history.";
  }

  // -- the curve ------------------------------------------------------------------------------
  var CURVES = [["top1", "Top-1", "#1b6e2d", []], ["top3", "Top-3", "#2f6db5", [6, 3]], ["top5", "Top-5", "#b26b00", [2, 3]]];
  function drawCurveOn(p, width, height) {
    var d = state.decisions;
    p.rect(0, 0, width, height, "#ffffff");
    if (!d || !d.rank.length) { p.text(12, 24, d ? "No decisions." : "Replaying the NEEM...", "#333"); return; }
    var left = 44, top = 12, plotW = width - left - 110, plotH = height - top - 28, n = d.rank.length;
    var xOf = function (i) { return left + (n > 1 ? i / (n - 1) : 0) * plotW; };
    var yOf = function (v) { return top + (1 - v) * plotH; };
    [0, 0.25, 0.5, 0.75, 1].forEach(function (v) {
      p.line([left, yOf(v), left + plotW, yOf(v)], "#e3e0d8", 1);
      p.text(left - 6, yOf(v) + 4, Math.round(v * 100) + " %", "#333", "right");
    });
    p.text(left + plotW / 2, height - 6, "decision (1 to " + n + "), rolling window " + d.window, "#333", "center");
    var stride = Math.max(1, Math.floor(n / (plotW * 2)));
    CURVES.forEach(function (c, ci) {
      var values = d.rolling[c[0]], pts = [];
      for (var i = 0; i < n; i += stride) { pts.push(xOf(i), yOf(values[i])); }
      pts.push(xOf(n - 1), yOf(values[n - 1]));
      p.line(pts, c[2], 2, c[3]);
      p.line([left + plotW + 10, top + 14 + ci * 18, left + plotW + 34, top + 14 + ci * 18], c[2], 2, c[3]);
      p.text(left + plotW + 40, top + 18 + ci * 18, c[1], "#111");
    });
    if (d.prior && d.prior.given) {  // the prior's share, rolling over the same window (a decision it took no part in: 0)
      var shares = d.prior.shares, sum = 0, sp = [], w = d.window;
      for (var j = 0; j < n; j++) {
        sum += shares[j] || 0;
        if (j >= w) { sum -= shares[j - w] || 0; }
        if (j % stride === 0 || j === n - 1) { sp.push(xOf(j), yOf(sum / Math.min(j + 1, w))); }
      }
      p.line(sp, "#5a5a5a", 1.5, [1, 2]);
      p.line([left + plotW + 10, top + 14 + 3 * 18, left + plotW + 34, top + 14 + 3 * 18], "#5a5a5a", 1.5, [1, 2]);
      p.text(left + plotW + 40, top + 18 + 3 * 18, "prior share", "#111");
    }
    if (state.selected >= 0 && state.selected < n) {
      p.line([xOf(state.selected), top, xOf(state.selected), top + plotH], "#c25400", 1, [3, 3]);
    }
    p.frame(left, top, plotW, plotH, "#8a8478", 1);
  }
  function drawCurve() {
    var canvas = document.getElementById("curve"), size = fitCanvas(canvas);
    drawCurveOn(canvasPainter(canvas.getContext("2d")), size.w, size.h);
  }
  function bindCurve() {
    var canvas = document.getElementById("curve");
    document.getElementById("curve-png").addEventListener("click", function () {
      canvas.toBlob(function (blob) { download("curve.png", blob); }, "image/png");
    });
    document.getElementById("curve-svg").addEventListener("click", function () {
      var p = svgPainter(canvas.clientWidth, canvas.clientHeight);
      drawCurveOn(p, canvas.clientWidth, canvas.clientHeight);
      download("curve.svg", new Blob([p.done()], { type: "image/svg+xml" }));
    });
    document.getElementById("window").addEventListener("change", function () { if (state.decisions) { loadDecisions(state.neem); } });
    canvas.addEventListener("click", function (event) {
      var d = state.decisions; if (!d) { return; }
      var r = canvas.getBoundingClientRect(), plotW = r.width - 44 - 110;
      var k = Math.round((event.clientX - r.left - 44) / plotW * (d.rank.length - 1));
      select(Math.min(Math.max(k, 0), d.rank.length - 1), true);
    });
  }
  function showFigures() {
    var d = state.decisions, f = document.getElementById("figures");
    if (!d) { f.textContent = "Replaying the NEEM as evaluate would (this takes a while for a long NEEM)..."; return; }
    var pct = function (v) { return (v * 100).toFixed(1) + " %"; };
    f.textContent = "Over the whole NEEM (" + d.n_predictions + " decisions, predictor " + d.method + "): Top-1 " + pct(d.summary.top1) +
      ", Top-3 " + pct(d.summary.top3) + ", Top-5 " + pct(d.summary.top5);
    var p = d.prior || { given: false };
    f.textContent += p.given ? " (evaluate's replay of this NEEM's chains with the same prior)." :
      " (what python -m oracle evaluate prints for this NEEM's chains).";
    f.textContent += p.given ? (p.decisions ? " The shared prior took part in " + p.decisions + " of " + d.rank.length +
      " rankings, on average " + pct(p.mean) + " of each (the rest: the user's own history)." :
      " A shared prior was given but took part in no ranking.") : " No shared prior was used: every ranking is the user's own.";
  }

  // -- loading a NEEM -------------------------------------------------------------------------
  function loadNeem() {
    var neem = state.neem, status = document.getElementById("timeline-status");
    state.decisions = null; state.selected = -1; state.routines = [];
    status.textContent = "Loading the timeline...";
    document.getElementById("neem-shown").textContent = "";
    getJSON("/explore/api/neems/" + encodeURIComponent(neem) + "/timeline").then(function (r) {
      if (neem !== state.neem) { return; }
      if (r.status === 202) {  // nothing kept for this NEEM: the service reads its history once, through Prolog
        status.textContent = "Reading the history of " + (r.body.user || neem) + " (" + r.body.actions +
          " actions) through Prolog: " + r.body.seconds + " s so far. " + (r.body.kept_after === false ?
          "This store keeps no view of a NEEM (a MongoDB server): each open reads it again." :
          "Nothing was kept for this NEEM yet (a loaded dump, or a NEEM from an older version); the next open is quick.");
        if (!performance.getEntriesByName("timeline-reading").length) { performance.mark("timeline-reading"); }
        var canvas = document.getElementById("timeline"), size = fitCanvas(canvas), p = canvasPainter(canvas.getContext("2d"));
        p.rect(0, 0, size.w, size.h, "#ffffff");  // where the timeline will be: what is being read, and for how long
        p.text(size.w / 2, size.h / 2 - 8, "Reading " + r.body.actions + " actions through Prolog (" + r.body.seconds + " s so far)...", "#333", "center");
        p.text(size.w / 2, size.h / 2 + 12, "The timeline appears when the read is done.", "#333", "center");
        setTimeout(function () { if (neem === state.neem) { loadNeem(); } }, 1000);
        return;
      }
      if (r.status !== 200) { status.textContent = r.body.error || "error"; return; }
      state.timeline = buildTimeline(r.body);
      state.view = wholeView(state.timeline);
      document.getElementById("neem-shown").textContent = "of " + (r.body.user || neem);
      status.textContent = state.timeline.actionOfDecision.length + " actions over " + state.timeline.days + " days.";
      legend();
      redraw();
      showFigures(); drawCurve();
      loadDecisions(neem);
      loadRoutines(neem);
    });
  }
  function loadDecisions(neem) {
    var windowSize = Math.min(Math.max(parseInt(document.getElementById("window").value, 10) || 100, 5), 5000);
    getJSON("/explore/api/neems/" + encodeURIComponent(neem) + "/decisions?window=" + windowSize).then(function (r) {
      if (neem !== state.neem) { return; }
      if (r.status === 202) { setTimeout(function () { loadDecisions(neem); }, 1000); return; }
      if (r.status !== 200) { document.getElementById("figures").textContent = r.body.error || "error"; return; }
      state.decisions = r.body;
      showFigures(); drawCurve(); redraw();
      if (state.selected >= 0) { showDecision(state.selected); }
    });
  }
  function loadRoutines(neem) {
    var list = document.getElementById("routines");
    list.textContent = "";
    getJSON("/api/neems/" + encodeURIComponent(neem) + "/routines").then(function (r) {
      if (neem !== state.neem) { return; }
      if (r.status !== 200) { list.appendChild(el("li", {}, r.body.error || "error")); return; }
      state.routines = r.body.routines.map(function (x) { x.shown = true; return x; });
      if (!state.routines.length) { list.appendChild(el("li", {}, "No routine found.")); }
      state.routines.forEach(function (x, i) {
        var li = el("li"), id = "routine-" + i;
        var box = el("input", { type: "checkbox", id: id, checked: "" });
        box.addEventListener("change", function () { x.shown = box.checked; redraw(); });
        var label = el("label", { for: id });
        var swatch = el("span", { class: "swatch", "aria-hidden": "true" });
        swatch.style.background = ROUTINE_COLOURS[i % ROUTINE_COLOURS.length];
        label.appendChild(swatch);
        label.appendChild(document.createTextNode(x.name + ": " + x.steps.join(" \u2192 ") + " (" + x.episodes + " times on " + x.days +
          " days, usually " + x.usual_time + ")"));
        li.appendChild(box); li.appendChild(label); list.appendChild(li);
      });
      redraw();
    });
  }
  function legend() {
    var ul = document.getElementById("legend"), t = state.timeline;
    ul.textContent = "";
    function item(colour, text) {
      var li = el("li"), s = el("span", { class: "swatch", "aria-hidden": "true" });
      s.style.background = colour; li.appendChild(s); li.appendChild(document.createTextNode(text)); ul.appendChild(li);
    }
    t.tasks.forEach(function (task, i) { if (task !== "idle") { item(PALETTE[i % PALETTE.length], task); } });
    item("#cfcac0", "idle gap");
    item(RANK_COLOURS[1], "mark: predicted first");
    item(RANK_COLOURS[3], "mark: top 3");
    item(RANK_COLOURS[5], "mark: top 5");
    item(RANK_COLOURS.miss, "mark: miss");
    item(RANK_COLOURS.none, "mark: not offered");
  }

  // -- the console ----------------------------------------------------------------------------
  var RECENT_KEY = "neem-oracle-explore-queries";
  function recent() { try { return JSON.parse(localStorage.getItem(RECENT_KEY) || "[]"); } catch (e) { return []; } }
  function showRecent() {
    var ul = document.getElementById("recent");
    ul.textContent = "";
    recent().forEach(function (q) {
      var b = el("button", { type: "button" }, q);
      b.addEventListener("click", function () { document.getElementById("query").value = q; run(); });
      ul.appendChild(el("li")).appendChild(b);
    });
  }
  function remember(q) {
    var list = recent().filter(function (x) { return x !== q; });
    list.unshift(q);
    localStorage.setItem(RECENT_KEY, JSON.stringify(list.slice(0, 10)));
    showRecent();
  }
  function variables(query) {  // the query's named variables, in order: the columns even of no answer
    var bare = query.replace(/'(?:[^'\\]|\\.)*'|"(?:[^"\\]|\\.)*"/g, " "), found = [], m, re = /(^|[^A-Za-z0-9_])([A-Z][A-Za-z0-9_]*)/g;
    while ((m = re.exec(bare)) !== null) { if (found.indexOf(m[2]) < 0) { found.push(m[2]); } }
    return found;
  }
  function cell(value) {
    if (value === null || value === undefined) { return ""; }
    if (typeof value === "object") { return shortIri(JSON.stringify(value)); }
    return shortIri(value);
  }
  function run() {
    var q = document.getElementById("query").value.trim().replace(/\.\s*$/, "").replace(/^\?-\s*/, "");
    var error = document.getElementById("query-error"), table = document.getElementById("answers");
    if (!q) { return; }
    error.textContent = "";
    remember(q);
    fetch("/api/prolog", { method: "POST", headers: headers({ "Content-Type": "application/json" }),
      body: JSON.stringify({ query: q, neem: state.neem, limit: 1000 }) }).then(function (r) {
      return r.json().then(function (body) { return { status: r.status, body: body }; });
    }).then(function (r) {
      table.textContent = "";
      if (r.status !== 200) {
        error.textContent = "error: " + String(r.body.error || r.status).split("\n")[0];
        state.answers = null; document.getElementById("answers-csv").disabled = true; return;
      }
      var solutions = r.body.solutions, names = variables(q);
      solutions.forEach(function (s) { Object.keys(s).forEach(function (k) { if (names.indexOf(k) < 0) { names.push(k); } }); });
      table.appendChild(el("caption", {}, solutions.length === 0 ? "no answer (false)" :
        solutions.length + (r.body.more ? " answers shown, more exist" : solutions.length === 1 ? " answer" : " answers") +
        (names.length ? "" : " (true; the query has no variables)")));
      var head = el("thead"), tr = el("tr");
      names.forEach(function (n) { tr.appendChild(el("th", { scope: "col" }, n)); });
      head.appendChild(tr); table.appendChild(head);
      var body = el("tbody"), rows = [];
      solutions.forEach(function (s) {
        var row = el("tr"), values = names.map(function (n) { return cell(s[n]); });
        values.forEach(function (v) { row.appendChild(el("td", {}, v)); });
        body.appendChild(row); rows.push(values);
      });
      table.appendChild(body);
      state.answers = { names: names, rows: rows };
      document.getElementById("answers-csv").disabled = !names.length;
    }).catch(function (e) { error.textContent = "error: " + e; });
  }
  function csv() {
    var a = state.answers; if (!a) { return; }
    var quote = function (v) { return /[",\n\r]/.test(v) ? '"' + v.replace(/"/g, '""') + '"' : v; };
    var text = [a.names.map(quote).join(",")].concat(a.rows.map(function (r) { return r.map(quote).join(","); })).join("\r\n") + "\r\n";
    download("answers.csv", new Blob([text], { type: "text/csv" }));
  }
  function bindConsole() {
    document.getElementById("console").addEventListener("submit", function (event) { event.preventDefault(); run(); });
    document.getElementById("query").addEventListener("keydown", function (event) {
      if (event.key === "Enter" && (event.ctrlKey || event.metaKey)) { event.preventDefault(); run(); }
    });
    document.querySelectorAll("#examples button").forEach(function (b) {
      b.addEventListener("click", function () { document.getElementById("query").value = b.textContent; run(); });
    });
    document.getElementById("answers-csv").addEventListener("click", csv);
    showRecent();
  }

  bindTimeline(); bindCurve(); bindConsole();
  if (state.neem) { loadNeem(); }  // the page names the NEEM to show first: list and timeline at once
  loadNeems().then(function (neem) {
    if (!neem) { document.getElementById("timeline-status").textContent = "The store holds no NEEM."; }
    else if (!state.timeline && !config.neem) { loadNeem(); }
  });
  window.neemExplorer = { state: state, select: select, zoomHours: zoomHours, zoomDays: zoomDays, pan: pan };
})();
