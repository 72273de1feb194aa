// The report page's script (page_assets.h). One replay per failed scene:
// golden and new overlaid on one canvas, a slider over the frames shown, the
// first divergence marked on it, and plots whose cursor follows the replay.
// Hooks for the browser test: ?autoplay plays the first replay; the <html>
// element carries data-ready and data-script-errors.
#include "page_assets.h"

namespace impulse::harness {

const char* page_error_hook() {
    return R"JS(
document.documentElement.setAttribute('data-script-errors', '0');
window.addEventListener('error', function (e) {
  var root = document.documentElement;
  root.setAttribute('data-script-errors', String(Number(root.getAttribute('data-script-errors')) + 1));
  root.setAttribute('data-script-error-text', String(e.message));
});
)JS";
}

// A constant, not a function body: the text is long, the function is one line.
constexpr const char* page_script_text = R"JS(
(function () {
  'use strict';
  var GOLD = '#c77c00', NEW = '#1565c0', DIVERGE = '#d32f2f';
  var replays = [], active = null;

  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) { e.className = cls; }
    if (text !== undefined) { e.textContent = text; }
    return e;
  }
  function fmt(v) { return v === null ? '-' : Number(v).toPrecision(4).replace(/\.?0+$/, ''); }
  function fmtT(v) { return Number(v).toFixed(4); }
  // The last index whose time is <= t (0 when none is).
  function indexAt(times, t) {
    var lo = 0, hi = times.length - 1;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) { lo = mid; } else { hi = mid - 1; }
    }
    return lo;
  }
  function sizeCanvas(canvas, w, h) {
    var r = window.devicePixelRatio || 1;
    canvas.width = Math.round(w * r); canvas.height = Math.round(h * r);
    canvas.style.width = w + 'px'; canvas.style.height = h + 'px';
    var g = canvas.getContext('2d');
    g.setTransform(r, 0, 0, r, 0, 0);
    return g;
  }

  // ---------------------------------------------------------------- plots
  // series: [{y: [...], colour, dash}], all over the times t; log: a log y axis.
  function Plot(parent, title, t, series, log, marks) {
    this.t = t; this.series = series; this.log = log; this.marks = marks;
    var box = el('div', 'plot');
    box.appendChild(el('div', 'plot-title', title));
    this.canvas = el('canvas');
    box.appendChild(this.canvas);
    parent.appendChild(box);
    this.w = 440; this.h = 150;
    var lo = Infinity, hi = -Infinity;
    series.forEach(function (s) {
      s.y.forEach(function (v) {
        if (v === null || !isFinite(v) || (log && v <= 0)) { return; }
        lo = Math.min(lo, v); hi = Math.max(hi, v);
      });
    });
    this.empty = !(lo <= hi);
    if (log && !this.empty) { lo = Math.log10(lo); hi = Math.log10(hi); lo = Math.floor(lo); hi = Math.ceil(hi); }
    if (hi - lo < 1e-300 || hi === lo) { var m = Math.abs(hi) * 1e-9 + (log ? 1 : 1e-12); lo -= m; hi += m; }
    this.lo = lo; this.hi = hi;
    this.t0 = t.length ? t[0] : 0; this.t1 = t.length ? t[t.length - 1] : 1;
    if (this.t1 <= this.t0) { this.t1 = this.t0 + 1; }
  }
  Plot.prototype.x = function (t) { return 58 + (t - this.t0) / (this.t1 - this.t0) * (this.w - 66); };
  Plot.prototype.y = function (v) {
    var u = this.log ? Math.log10(v) : v;
    return 8 + (this.hi - u) / (this.hi - this.lo) * (this.h - 30);
  };
  Plot.prototype.draw = function (cursor) {
    var g = sizeCanvas(this.canvas, this.w, this.h), self = this;
    g.fillStyle = '#fff'; g.fillRect(0, 0, this.w, this.h);
    g.strokeStyle = '#bbb'; g.lineWidth = 1; g.strokeRect(58, 8, this.w - 66, this.h - 30);
    g.fillStyle = '#555'; g.font = '10px sans-serif'; g.textAlign = 'right';
    if (this.empty) {
      g.textAlign = 'center';
      g.fillText(this.log ? 'no difference at the frames shown' : 'no values', this.w / 2, this.h / 2);
    } else {
      var top = this.log ? '1e' + this.hi : fmt(this.hi), bottom = this.log ? '1e' + this.lo : fmt(this.lo);
      g.fillText(top, 54, 14); g.fillText(bottom, 54, this.h - 22);
    }
    g.textAlign = 'left'; g.fillText(fmt(this.t0) + ' s', 58, this.h - 8);
    g.textAlign = 'right'; g.fillText(fmt(this.t1) + ' s', this.w - 8, this.h - 8);
    g.strokeStyle = 'rgba(0,0,0,0.18)';
    this.marks.events.forEach(function (te) {
      g.beginPath(); g.moveTo(self.x(te), 8); g.lineTo(self.x(te), self.h - 22); g.stroke();
    });
    if (this.marks.first !== null) {
      g.strokeStyle = DIVERGE; g.setLineDash([4, 3]);
      g.beginPath(); g.moveTo(this.x(this.marks.first), 8); g.lineTo(this.x(this.marks.first), this.h - 22); g.stroke();
      g.setLineDash([]);
    }
    if (!this.empty) {
      this.series.forEach(function (s) {
        g.strokeStyle = s.colour; g.lineWidth = s.width || 1.5; g.setLineDash(s.dash || []);
        g.beginPath();
        var pen = false;
        for (var i = 0; i < self.t.length; ++i) {
          var v = s.y[i];
          if (v === null || !isFinite(v) || (self.log && v <= 0)) { pen = false; continue; }
          if (pen) { g.lineTo(self.x(self.t[i]), self.y(v)); } else { g.moveTo(self.x(self.t[i]), self.y(v)); }
          pen = true;
        }
        g.stroke();
      });
      g.setLineDash([]);
    }
    g.strokeStyle = '#222'; g.lineWidth = 1;
    g.beginPath(); g.moveTo(this.x(cursor), 8); g.lineTo(this.x(cursor), this.h - 22); g.stroke();
  };

  // ---------------------------------------------------------------- replay
  function Replay(root, data) {
    var self = this;
    this.root = root; this.d = data;
    this.base = data.runs[0].t.length >= data.runs[1].t.length ? data.runs[0] : data.runs[1];
    this.i = 0; this.timer = null;
    var n = this.base.t.length;
    var controls = el('div', 'controls');
    function button(label, title, act) {
      var b = el('button', '', label); b.title = title; b.type = 'button';
      b.addEventListener('click', function () { active = self; act(); });
      controls.appendChild(b); return b;
    }
    button('\u21E4', 'first frame', function () { self.show(0); });
    button('\u25C0', 'previous frame (left arrow)', function () { self.step(-1); });
    this.playButton = button('\u25B6 play', 'play or pause (space)', function () { self.toggle(); });
    button('\u25B6', 'next frame (right arrow)', function () { self.step(1); });
    if (data.first) {
      button('jump to first divergence', 'the frame of the first divergence', function () { self.jump(); });
    }
    var clock = el('span', 'clock');
    clock.appendChild(document.createTextNode('t = '));
    this.timeText = el('b', 'time', '0'); clock.appendChild(this.timeText);
    clock.appendChild(document.createTextNode(' s \u00B7 frame '));
    this.frameText = el('b', 'frame', '0'); clock.appendChild(this.frameText);
    clock.appendChild(document.createTextNode(' of ' + (this.base.count - 1)));
    controls.appendChild(clock);
    root.appendChild(controls);
    var scrub = el('div', 'scrub');
    this.slider = el('input'); this.slider.type = 'range'; this.slider.min = 0; this.slider.max = n - 1; this.slider.value = 0;
    this.slider.setAttribute('aria-label', 'frame');
    this.slider.addEventListener('input', function () { active = self; self.pause(); self.show(Number(self.slider.value)); });
    scrub.appendChild(this.slider);
    if (data.first) {
      var mark = el('div', 'divergence-marker');
      var span = this.base.t[n - 1] - this.base.t[0];
      mark.style.left = (span > 0 ? (data.first.t - this.base.t[0]) / span * 100 : 0) + '%';
      mark.title = 'first divergence: ' + data.first.column + ' at t = ' + data.first.t + ' s';
      scrub.appendChild(mark);
    }
    root.appendChild(scrub);
    this.canvas = el('canvas', 'world');
    root.appendChild(this.canvas);
    var v = data.view, w = Math.max(v[2] - v[0], 1e-9), h = Math.max(v[3] - v[1], 1e-9);
    this.scale = Math.min(900 / w, 420 / h);
    this.cw = Math.max(w * this.scale, 420); this.ch = Math.max(h * this.scale, 120);
    var legend = el('p', 'legend');
    legend.innerHTML = '<span class="key gold">- - golden</span> <span class="key new">\u2014 new</span> ' +
      '\u25CB golden collision \u00B7 \u25CF new collision \u00B7 <span class="key diverge">| first divergence</span>';
    root.appendChild(legend);
    var counts = data.runs.map(function (r) { return r.label + ' ' + r.t.length + ' of ' + r.count + ' frames'; });
    var sampled = data.runs.some(function (r) { return r.t.length < r.count; });
    root.appendChild(el('p', 'sampling', (sampled ? 'Subsampled to fit the page: ' : 'Every frame: ') + counts.join(', ') + '.'));
    this.plots = [];
    var plots = el('div', 'plots');
    var events = data.runs[0].events.map(function (e) { return e[0]; });
    var marks = {events: events, first: data.first ? data.first.t : null};
    data.channels.list.forEach(function (c) {
      self.plots.push(new Plot(plots, c.name + ': golden (amber) and new (blue)', c.t,
        [{y: c.gold, colour: GOLD, width: 3}, {y: c.new, colour: NEW, dash: [5, 3]}], false, marks));
      self.plots.push(new Plot(plots, c.name + ': |new \u2212 golden|, log scale', c.t,
        [{y: c.diff, colour: DIVERGE}], true, marks));
    });
    if (data.channels.more > 0) {
      plots.appendChild(el('p', 'more', data.channels.more + ' more diverging channels are not plotted; the table above lists them.'));
    }
    var totals = [['E', 'total energy (J)'], ['px', 'momentum x (kg m/s)'], ['py', 'momentum y (kg m/s)'], ['L', 'angular momentum about the origin (kg m\u00B2/s)']];
    if (data.totals[0] && data.totals[1]) {
      var tg = data.totals[0], tn = data.totals[1];
      totals.forEach(function (q) {
        // The new run's values at the golden run's times, for one time axis.
        var yn = tg.t.map(function (t) { return tn[q[0]][indexAt(tn.t, t)]; });
        self.plots.push(new Plot(plots, q[1] + ': golden and new', tg.t,
          [{y: tg[q[0]], colour: GOLD, width: 3}, {y: yn, colour: NEW, dash: [5, 3]}], false, marks));
      });
    } else {
      plots.appendChild(el('p', 'more', 'Energy and momentum are not plotted: the scene is not known or a run lacks a body.'));
    }
    root.appendChild(plots);
    root.addEventListener('mousedown', function () { active = self; });
    this.show(0);
  }
  Replay.prototype.time = function () { return this.base.t[this.i]; };
  Replay.prototype.show = function (i) {
    var n = this.base.t.length;
    this.i = Math.max(0, Math.min(n - 1, i));
    this.slider.value = this.i;
    var t = this.time(), rawFrame = this.frameOf(t);
    this.timeText.textContent = fmtT(t);
    this.frameText.textContent = String(rawFrame);
    this.frameText.setAttribute('data-frame', String(rawFrame));
    this.root.setAttribute('data-frame', String(rawFrame));
    this.draw(t);
    this.plots.forEach(function (p) { p.draw(t); });
  };
  // The frame's index in the run (not among the frames shown): frames are
  // evenly spaced, so it is found from the times shown around it.
  Replay.prototype.frameOf = function (t) {
    var b = this.base, n = b.t.length;
    if (n < 2 || b.count < 2) { return 0; }
    var span = b.t[n - 1] - b.t[0];
    return span > 0 ? Math.round((t - b.t[0]) / span * (b.count - 1)) : 0;
  };
  Replay.prototype.step = function (k) { this.pause(); this.show(this.i + k); };
  Replay.prototype.jump = function () {
    this.pause();
    // The first frame at or after it: where the runs are seen to differ.
    var i = indexAt(this.base.t, this.d.first.t);
    this.show(this.base.t[i] < this.d.first.t ? i + 1 : i);
  };
  Replay.prototype.pause = function () {
    if (this.timer !== null) { clearInterval(this.timer); this.timer = null; }
    this.playButton.textContent = '\u25B6 play';
  };
  Replay.prototype.play = function () {
    var self = this, tick = 40;
    if (this.timer !== null) { return; }
    if (this.i >= this.base.t.length - 1) { this.show(0); }
    var clock = this.time();
    this.playButton.textContent = '\u2016 pause';
    this.timer = setInterval(function () {
      clock += tick / 1000;
      var next = indexAt(self.base.t, clock + 1e-12);
      if (next <= self.i) { next = Math.min(self.i + (self.base.t[self.i + 1] <= clock ? 1 : 0), self.base.t.length - 1); }
      self.show(next);
      if (self.i >= self.base.t.length - 1) { self.pause(); }
    }, tick);
  };
  Replay.prototype.toggle = function () { if (this.timer === null) { this.play(); } else { this.pause(); } };

  Replay.prototype.draw = function (t) {
    var d = this.d, v = d.view, s = this.scale, self = this;
    var g = sizeCanvas(this.canvas, this.cw, this.ch);
    var ox = (this.cw - (v[2] - v[0]) * s) / 2, oy = (this.ch - (v[3] - v[1]) * s) / 2;
    function X(x) { return ox + (x - v[0]) * s; }
    function Y(y) { return oy + (v[3] - y) * s; }
    g.fillStyle = '#fbfbf8'; g.fillRect(0, 0, this.cw, this.ch);
    g.fillStyle = '#b0bec5'; g.strokeStyle = '#78909c'; g.lineWidth = 1;
    d.statics.forEach(function (p) {
      g.beginPath();
      for (var k = 0; k < p.length; k += 2) { if (k) { g.lineTo(X(p[k]), Y(p[k + 1])); } else { g.moveTo(X(p[k]), Y(p[k + 1])); } }
      g.closePath(); g.fill(); g.stroke();
    });
    d.runs.forEach(function (run, r) {
      var colour = r === 0 ? GOLD : NEW, upto = indexAt(run.t, t + 1e-12);
      // A few bodies show their whole path; many (a gas) only the last half
      // second of it, or the picture is spaghetti.
      var from = d.bodies.length <= 4 ? 0 : indexAt(run.t, t - 0.5);
      g.strokeStyle = colour; g.globalAlpha = 0.45; g.lineWidth = r === 0 ? 3 : 1.2;
      d.bodies.forEach(function (b, j) {
        g.beginPath();
        var pen = false;
        for (var i = from; i <= upto; ++i) {
          var x = run.pose[i][3 * j], y = run.pose[i][3 * j + 1];
          if (x === null || y === null) { pen = false; continue; }
          if (pen) { g.lineTo(X(x), Y(y)); } else { g.moveTo(X(x), Y(y)); }
          pen = true;
        }
        g.stroke();
      });
      g.globalAlpha = 1;
      run.events.forEach(function (e) {
        if (e[0] > t + 1e-12) { return; }
        var recent = t - e[0] < 0.25;
        g.beginPath(); g.arc(X(e[1]), Y(e[2]), recent ? 5 : 2.5, 0, 2 * Math.PI);
        if (r === 0) { g.strokeStyle = GOLD; g.lineWidth = 1.5; g.stroke(); } else { g.fillStyle = NEW; g.fill(); }
      });
      var pose = run.pose[upto];
      d.bodies.forEach(function (b, j) { self.body(g, X, Y, b, pose[3 * j], pose[3 * j + 1], pose[3 * j + 2], r); });
    });
    if (d.first && t + 1e-12 >= d.first.t) {
      g.fillStyle = DIVERGE; g.font = 'bold 12px sans-serif'; g.textAlign = 'left';
      g.fillText('diverged at t = ' + fmtT(d.first.t) + ' s', 8, this.ch - 8);
    }
    g.fillStyle = '#222'; g.font = '13px sans-serif'; g.textAlign = 'right';
    g.fillText('t = ' + fmtT(t) + ' s', this.cw - 8, 18);
  };
  Replay.prototype.body = function (g, X, Y, b, x, y, a, r) {
    if (x === null || y === null) { return; }
    var s = this.scale, c = Math.cos(a), sn = Math.sin(a);
    g.strokeStyle = r === 0 ? GOLD : NEW; g.lineWidth = r === 0 ? 3 : 1.5;
    g.fillStyle = r === 0 ? 'rgba(199,124,0,0.12)' : 'rgba(21,101,192,0.12)';
    g.setLineDash(r === 0 ? [6, 4] : []);
    g.beginPath();
    if (b.v) {
      for (var k = 0; k < b.v.length; k += 2) {
        var px = x + c * b.v[k] - sn * b.v[k + 1], py = y + sn * b.v[k] + c * b.v[k + 1];
        if (k) { g.lineTo(X(px), Y(py)); } else { g.moveTo(X(px), Y(py)); }
      }
      g.closePath();
    } else {
      var rr = Math.max(b.r * s, 3);
      g.arc(X(x), Y(y), rr, 0, 2 * Math.PI);
      g.moveTo(X(x), Y(y)); g.lineTo(X(x) + c * rr, Y(y) - sn * rr);
    }
    g.fill(); g.stroke(); g.setLineDash([]);
  };

  // ---------------------------------------------------------------- page
  document.querySelectorAll('.replay').forEach(function (root) {
    var data = JSON.parse(document.getElementById(root.getAttribute('data-source')).textContent);
    replays.push(new Replay(root, data));
  });
  active = replays.length ? replays[0] : null;
  document.addEventListener('keydown', function (e) {
    if (!active || e.target.tagName === 'INPUT' && e.key !== ' ' || e.target.tagName === 'SUMMARY') { return; }
    if (e.key === ' ') { e.preventDefault(); active.toggle(); }
    else if (e.key === 'ArrowRight') { e.preventDefault(); active.step(1); }
    else if (e.key === 'ArrowLeft') { e.preventDefault(); active.step(-1); }
  });
  if (/[?&]at=divergence\b/.test(window.location.search) && active && active.d.first) { active.jump(); }
  if (/[?&]autoplay\b/.test(window.location.search) && active) { active.play(); }
  document.documentElement.setAttribute('data-ready', '1');
})();
)JS";

const char* page_script() {
    return page_script_text;
}

} // namespace impulse::harness
