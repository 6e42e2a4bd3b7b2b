(function () {
'use strict';
const D = JSON.parse(document.getElementById('nocdyn-data').textContent);
const $ = (id) => document.getElementById(id);
const T = D.frames.t, F = T.length, P = D.frames.points, S = D.stride, REF = D.reference;
const GHOST = D.frames.ghost || null;
const n = D.actuators.length, TAU = D.frames.tau;
const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf', '#7f7f7f'];
const C_COLOR = '#ff0000';
const view = {
  frame: 0, time: T[0], playing: false, speed: 1, slowMotion: D.slowMotion, magnify: D.magnify,
  scale: 1, ox: 0, oy: 0, drawnC: [0, 0], draws: 0, cColor: C_COLOR,
  toPixel(x, y) { return [this.ox + this.scale * x, this.oy - this.scale * y]; },
  setFrame(i) { setFrame(i); },
};
window.nocdynView = view;
document.title = 'nocdyn: ' + D.robot + ' - ' + D.source;
$('title').textContent = D.robot + ': ' + D.source;
$('subtitle').textContent = D.samples + ' samples over ' + D.duration.toPrecision(4) + ' s; ' + F +
  ' frames shown, the plots keep every sample\'s extremes (min and max per ' + D.plots.t.length + ' buckets)';
if (D.warnings.length) $('warnings').textContent = 'Limits exceeded: ' + D.warnings.join('; ');
// point o of frame i [m], displacements from the mean pose magnified
function pt(i, o, points) {
  const M = view.magnify, b = i * S + o, Q = points || P;
  return [(REF[o] + M * (Q[b] - REF[o])) * 1e-6, (REF[o + 1] + M * (Q[b + 1] - REF[o + 1])) * 1e-6];
}
if (GHOST) $('legend').textContent += '; dashed grey: the target (the replay\'s goal), the robot drawn where the table went';
const canvas = $('robot'), ctx = canvas.getContext('2d');
function fit() {
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (let i = 0; i < F; ++i) {
    for (let o = 0; o < S; o += 2) {
      const p = pt(i, o);
      x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
    }
  }
  const m = 24, W = canvas.width - 2 * m, H = canvas.height - 2 * m;
  const w = Math.max(x1 - x0, 1e-9), h = Math.max(y1 - y0, 1e-9);
  view.scale = Math.min(W / w, H / h);
  view.ox = m + (W - view.scale * w) / 2 - view.scale * x0;
  view.oy = canvas.height - m - (H - view.scale * h) / 2 + view.scale * y0;
}
function line(a, b, color, width) {
  const p = view.toPixel(a[0], a[1]), q = view.toPixel(b[0], b[1]);
  ctx.strokeStyle = color; ctx.lineWidth = width; ctx.beginPath(); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
}
function dot(a, r, fill, stroke) {
  const p = view.toPixel(a[0], a[1]);
  ctx.beginPath(); ctx.arc(p[0], p[1], r, 0, 2 * Math.PI); ctx.fillStyle = fill; ctx.fill();
  if (stroke) { ctx.strokeStyle = stroke; ctx.lineWidth = 1.5; ctx.stroke(); }
  return p;
}
function drawRobot() {
  const i = view.frame;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  // scale bar
  const decade = Math.pow(10, Math.floor(Math.log10(150 / view.scale)));
  const bar = [5, 2, 1].map((f) => f * decade).find((b) => b * view.scale <= 150);
  ctx.fillStyle = '#444'; ctx.font = '12px sans-serif';
  ctx.fillRect(10, canvas.height - 12, bar * view.scale, 3);
  ctx.fillText(String(Number((bar * 1000).toPrecision(3))) + ' mm', 14 + bar * view.scale, canvas.height - 8);
  // the target as a ghost, behind the achieved motion
  if (GHOST) {
    ctx.save(); ctx.setLineDash([5, 4]);
    ctx.beginPath();
    D.layout.forEach((limb, j) => {
      const p = pt(i, limb[2].pos, GHOST), q = view.toPixel(p[0], p[1]);
      if (j === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
    });
    ctx.closePath(); ctx.strokeStyle = '#888'; ctx.lineWidth = 1.5; ctx.stroke();
    for (const limb of D.layout) {
      line(pt(i, limb[0].pos, GHOST), pt(i, limb[1].pos, GHOST), '#aaa', 2);
      line(pt(i, limb[1].pos, GHOST), pt(i, limb[2].pos, GHOST), '#aaa', 2);
    }
    ctx.restore();
    view.drawnGhostC = dot(pt(i, S - 2, GHOST), 3, '#888');
  }
  // platform polygon
  ctx.beginPath();
  D.layout.forEach((limb, j) => {
    const p = pt(i, limb[2].pos), q = view.toPixel(p[0], p[1]);
    if (j === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
  });
  ctx.closePath(); ctx.fillStyle = 'rgba(255,165,0,0.35)'; ctx.fill(); ctx.strokeStyle = '#c77800'; ctx.lineWidth = 2; ctx.stroke();
  for (const limb of D.layout) {
    for (const joint of limb) if (joint.rail >= 0) line(pt(i, joint.rail), pt(i, joint.rail + 2), '#999', 7);
    line(pt(i, limb[0].pos), pt(i, limb[1].pos), '#1f4e9c', 4);
    line(pt(i, limb[1].pos), pt(i, limb[2].pos), '#1f4e9c', 4);
    limb.forEach((joint, k) => {
      const p = pt(i, joint.pos);
      if (joint.rail >= 0) {
        const q = view.toPixel(p[0], p[1]);
        ctx.fillStyle = joint.actuator >= 0 ? '#333' : '#777'; ctx.fillRect(q[0] - 6, q[1] - 6, 12, 12);
      } else {
        dot(p, k === 0 ? 6 : 4.5, joint.actuator >= 0 ? '#333' : '#fff', '#1f4e9c');
      }
    });
  }
  view.drawnC = dot(pt(i, S - 2), 4, C_COLOR);
  view.draws += 1;
}
// actuator forces as bars, coloured by the fraction of the effort limit
const bars = $('bars'), bctx = bars.getContext('2d');
bars.height = 26 * n + 8;
// wide enough for the longest label ("tau1 = -1.234e+00 N m (100% of 12.00 N m)"), not clipped
bctx.font = '12px sans-serif';
bars.width = Math.max(bars.width, Math.ceil(170 + Math.max(...D.actuators.map((a, k) => bctx.measureText(
  'tau' + (k + 1) + ' = -0.000e+00 ' + a.forceUnit + ' (100% of ' +
  (a.effort !== null ? a.effort.toPrecision(4) + ' ' + a.forceUnit : 'no effort limit') + ')').width))));
function drawBars() {
  bctx.clearRect(0, 0, bars.width, bars.height);
  bctx.font = '12px sans-serif';
  D.actuators.forEach((a, k) => {
    const tau = TAU[view.frame * n + k], limit = a.effort !== null ? a.effort : a.peakTau;
    const f = limit > 0 ? Math.min(Math.abs(tau) / limit, 1) : 0, y = 4 + 26 * k, w = 160;
    bctx.fillStyle = '#eee'; bctx.fillRect(0, y, w, 20);
    bctx.fillStyle = 'hsl(' + Math.round(120 * (1 - f)) + ',80%,45%)'; bctx.fillRect(0, y, w * f, 20);
    bctx.fillStyle = '#222';
    const pct = a.effort !== null ? (100 * Math.abs(tau) / a.effort).toFixed(0) + '% of ' + a.effort.toPrecision(4) + ' ' + a.forceUnit : 'no effort limit';
    bctx.fillText('tau' + (k + 1) + ' = ' + tau.toPrecision(4) + ' ' + a.forceUnit + ' (' + pct + ')', w + 6, y + 14);
  });
}
// plots of u and tau: every bucket's min and max, a cursor at the current time
function plot(id, series, label, units) {
  const c = $(id), g = c.getContext('2d'), tb = D.plots.t, B = tb.length, m = {l: 52, r: 8, t: 16, b: 22};
  let lo = Infinity, hi = -Infinity;
  for (const s of series) for (let b = 0; b < B; ++b) { lo = Math.min(lo, s.lo[b]); hi = Math.max(hi, s.hi[b]); }
  if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
  const t0 = T[0], t1 = D.tEnd > t0 ? D.tEnd : t0 + 1;
  const X = (t) => m.l + (c.width - m.l - m.r) * (t - t0) / (t1 - t0);
  const Y = (v) => c.height - m.b - (c.height - m.t - m.b) * (v - lo) / (hi - lo);
  return function draw() {
    g.clearRect(0, 0, c.width, c.height);
    g.font = '11px sans-serif'; g.fillStyle = '#222';
    g.fillText(label + ' [' + units + ']', m.l, 11);
    g.fillText(hi.toPrecision(3), 2, m.t + 8); g.fillText(lo.toPrecision(3), 2, c.height - m.b);
    g.fillText(t0.toPrecision(3) + ' s', m.l, c.height - 6); g.fillText(t1.toPrecision(3) + ' s', c.width - 50, c.height - 6);
    g.strokeStyle = '#ddd'; g.strokeRect(m.l, m.t, c.width - m.l - m.r, c.height - m.t - m.b);
    series.forEach((s, k) => {
      g.strokeStyle = COLORS[k % COLORS.length]; g.lineWidth = 1.2; g.beginPath();
      for (let b = 0; b < B; ++b) {
        const x = X(tb[b]);
        if (b === 0) g.moveTo(x, Y(s.lo[b])); else g.lineTo(x, Y(s.lo[b]));
        g.lineTo(x, Y(s.hi[b]));
      }
      g.stroke();
      g.fillStyle = COLORS[k % COLORS.length]; g.fillText(s.name, c.width - m.r - 40 * (series.length - k), 11);
    });
    g.strokeStyle = '#000'; g.lineWidth = 1; g.beginPath(); g.moveTo(X(view.time), m.t); g.lineTo(X(view.time), c.height - m.b); g.stroke();
  };
}
const uUnits = D.actuators.map((a) => a.unit).filter((v, k, all) => all.indexOf(v) === k).join(', ');
const fUnits = D.actuators.map((a) => a.forceUnit).filter((v, k, all) => all.indexOf(v) === k).join(', ');
const drawU = plot('plot-u', D.plots.u, 'actuator variables u', uUnits);
const drawTau = plot('plot-tau', D.plots.tau, 'actuator forces tau', fUnits);
function draw() { drawRobot(); drawBars(); drawU(); drawTau(); }
function showFactors() {
  $('factors').textContent = 'slow motion x' + view.slowMotion + ' (1 s of motion plays in ' + view.slowMotion +
    ' s) at speed x' + view.speed + '; displacements about the mean pose magnified x' + view.magnify;
}
function setFrame(i) {
  view.frame = Math.max(0, Math.min(F - 1, Math.round(i)));
  view.time = T[view.frame];
  $('slider').value = String(view.frame);
  $('time').textContent = view.time.toFixed(5);
  draw();
}
function frameAt(t) {
  let a = 0, b = F - 1;
  while (a < b) { const mid = (a + b + 1) >> 1; if (T[mid] <= t) a = mid; else b = mid - 1; }
  return a;
}
let last = null, simTime = T[0];
function tick(now) {
  if (!view.playing) { last = null; return; }
  if (last !== null) {
    simTime += (now - last) / 1000 * view.speed / view.slowMotion;
    if (simTime > D.tEnd) simTime = T[0] + (simTime - D.tEnd) % Math.max(D.tEnd - T[0], 1e-9);
    setFrame(frameAt(simTime));
  }
  last = now;
  requestAnimationFrame(tick);
}
$('play').addEventListener('click', () => {
  view.playing = !view.playing;
  $('play').textContent = view.playing ? 'Pause' : 'Play';
  if (view.playing) { simTime = view.time; requestAnimationFrame(tick); }
});
$('slider').max = String(F - 1);
$('slider').addEventListener('input', () => { setFrame(Number($('slider').value)); simTime = view.time; });
$('speed').addEventListener('change', () => { view.speed = Number($('speed').value); showFactors(); });
$('slow').value = String(view.slowMotion);
$('slow').addEventListener('change', () => {
  const k = Number($('slow').value);
  if (k >= 1 && isFinite(k)) view.slowMotion = k; else $('slow').value = String(view.slowMotion);
  showFactors();
});
$('magnify').value = String(view.magnify);
$('magnify').addEventListener('change', () => {
  const m = Number($('magnify').value);
  if (m >= 0 && isFinite(m)) { view.magnify = m; fit(); draw(); } else $('magnify').value = String(view.magnify);
  showFactors();
});
fit();
showFactors();
setFrame(0);
})();
