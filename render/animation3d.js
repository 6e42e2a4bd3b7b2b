(function () {
'use strict';
// The 3-D view of a spatial robot: three.js (inlined before this script) draws each frame's
// joint points, given in micrometres in the base frame (z up).
const D = JSON.parse(document.getElementById('nocdyn-data').textContent);
const $ = (id) => document.getElementById(id);
const T = D.frames.t, F = T.length, P = D.frames.points, S = D.stride, REF = D.reference;
const n = D.actuators.length, TAU = D.frames.tau, L = D.limbs.length;
const COLORS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf', '#7f7f7f'];
const view = {
  frame: 0, time: T[0], playing: false, speed: 1, slowMotion: D.slowMotion, magnify: D.magnify, draws: 0,
  webgl: false, drawnPoint: null, legColors: [],
  setFrame(i) { setFrame(i); },
};
window.nocdynView = view;
document.title = 'nocdyn: ' + D.robot + ' - ' + D.source;
$('title').textContent = D.robot + ': ' + D.source;
$('subtitle').textContent = D.samples + ' samples over ' + D.duration.toPrecision(4) + ' s; ' + F +
  ' frames shown, the plots keep every sample\'s extremes (min and max per ' + D.plots.t.length + ' buckets)';
if (D.warnings.length) $('warnings').textContent = 'Limits exceeded: ' + D.warnings.join('; ');

// point o (an offset into a frame) of frame i [m], displacements from the mean pose magnified
function pt(i, o) {
  const M = view.magnify, b = i * S + o;
  return [0, 1, 2].map((c) => (REF[o + c] + M * (P[b + c] - REF[o + c])) * 1e-6);
}
const PLATFORM = S - 3;  // the platform point's offset
function chain(i, j) {
  const limb = D.limbs[j], out = [];
  for (let k = 0; k < limb.joints.length; ++k) out.push(pt(i, limb.at + 3 * k));
  return out;
}

// forces as colours: blue (pulling, negative) through light grey (0) to red (pushing,
// positive), scaled by the largest force of the motion (per actuator when their units differ)
const units = D.actuators.map((a) => a.forceUnit).filter((v, k, all) => all.indexOf(v) === k);
const common = units.length === 1;
const peakAll = Math.max(1e-12, ...D.actuators.map((a) => a.peakTau));
const scaleOf = (a) => common ? peakAll : Math.max(1e-12, D.actuators[a].peakTau);
function forceColor(f) {
  const x = Math.max(-1, Math.min(1, f)), g = [221, 221, 221], hi = x >= 0 ? [178, 24, 43] : [33, 102, 172];
  const w = Math.abs(x);
  return 'rgb(' + g.map((c, k) => Math.round(c + w * (hi[k] - c))).join(',') + ')';
}

// the scale's legend
(function legend() {
  const c = $('scale'), g = c.getContext('2d'), x0 = 10, w = c.width - 20;
  for (let x = 0; x < w; ++x) { g.fillStyle = forceColor(2 * x / (w - 1) - 1); g.fillRect(x0 + x, 18, 1, 14); }
  g.strokeStyle = '#888'; g.strokeRect(x0, 18, w, 14);
  g.fillStyle = '#222'; g.font = '12px sans-serif';
  g.fillText(common ? 'actuator force tau [' + units[0] + ']' : 'actuator force tau / its peak', x0, 12);
  const label = (v) => common ? v.toPrecision(3) : (v / peakAll >= 0 ? '+' : '') + v.toFixed(0) + '%';
  const ends = common ? [-peakAll, 0, peakAll] : [-100, 0, 100];
  g.fillText(label(ends[0]), x0, 46);
  g.fillText(common ? '0' : '0%', x0 + w / 2 - 4, 46);
  const right = label(ends[2]);
  g.fillText(right, x0 + w - g.measureText(right).width, 46);
})();
const forceRows = D.actuators.map((a, k) => {
  const row = document.createElement('div'), swatch = document.createElement('span'), text = document.createElement('span');
  swatch.className = 'swatch';
  row.appendChild(swatch); row.appendChild(text); $('forces').appendChild(row);
  return { swatch, text };
});
function showForces() {
  view.legColors = [];
  D.actuators.forEach((a, k) => {
    const tau = TAU[view.frame * n + k], color = forceColor(tau / scaleOf(k));
    view.legColors.push(color);
    forceRows[k].swatch.style.background = color;
    forceRows[k].text.textContent = 'tau' + (k + 1) + ' (' + a.limb + ') = ' + tau.toPrecision(5) + ' ' + a.forceUnit +
      (a.effort !== null ? ' (' + (100 * Math.abs(tau) / a.effort).toFixed(0) + '% of ' + a.effort.toPrecision(4) + ' ' + a.forceUnit + ')' : '');
  });
}

// the scene, when the browser gives WebGL
const host = $('view'), W = 640, H = 520;
const probe = document.createElement('canvas');
view.webgl = typeof THREE !== 'undefined' && !!(probe.getContext('webgl') || probe.getContext('experimental-webgl'));
let renderer = null, scene, camera, controls, home, legs = [], joints = [], platform, outline, trace, marker;
let radius = 1e-3;
function bounds() {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < F; ++i) {
    for (let o = 0; o < S; o += 3) {
      const p = pt(i, o);
      for (let c = 0; c < 3; ++c) { lo[c] = Math.min(lo[c], p[c]); hi[c] = Math.max(hi[c], p[c]); }
    }
  }
  return { centre: lo.map((v, c) => (v + hi[c]) / 2), size: Math.max(1e-6, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2])) };
}
function place(mesh, a, b) {  // a cylinder of unit radius and height from a to b
  const A = new THREE.Vector3(...a), B = new THREE.Vector3(...b), d = B.clone().sub(A), len = d.length();
  mesh.position.copy(A).add(B).multiplyScalar(0.5);
  if (len > 0) mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.divideScalar(len));
  mesh.scale.set(radius, Math.max(len, 1e-9), radius);
}
function around(points, order) {  // the polygon's vertices in order, and their centroid first
  const c = [0, 0, 0];
  for (const p of points) for (let k = 0; k < 3; ++k) c[k] += p[k] / points.length;
  return [c, ...order.map((j) => points[j])];
}
function fan(geometry, vertices) {  // a triangle fan about vertices[0], closed
  const pos = geometry.attributes.position;
  vertices.forEach((v, k) => pos.setXYZ(k, v[0], v[1], v[2]));
  pos.needsUpdate = true;
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
}
function fanGeometry(count) {
  const g = new THREE.BufferGeometry(), index = [];
  g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * (count + 1)), 3));
  for (let k = 1; k <= count; ++k) index.push(0, k, k % count + 1);
  g.setIndex(index);
  return g;
}
function traceGeometry() {
  const positions = new Float32Array(3 * F);
  for (let i = 0; i < F; ++i) positions.set(pt(i, PLATFORM), 3 * i);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  return g;
}
if (view.webgl) {
  renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(W, H);
  renderer.setClearColor(0xffffff, 1);
  host.appendChild(renderer.domElement);
  scene = new THREE.Scene();
  const box = bounds();
  radius = 0.006 * box.size;
  camera = new THREE.PerspectiveCamera(40, W / H, box.size / 200, box.size * 200);
  camera.up.set(0, 0, 1);
  const c = box.centre;
  home = { position: [c[0] + 0.75 * box.size, c[1] - 1.0 * box.size, c[2] + 0.45 * box.size], target: c };
  camera.position.set(...home.position);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const light = new THREE.DirectionalLight(0xffffff, 0.55);
  light.position.set(0.3, 0.5, 1);
  camera.add(light);  // lit from the viewer's side, whichever way the view turns
  const cylinder = new THREE.CylinderBufferGeometry(1, 1, 1, 14), ball = new THREE.SphereBufferGeometry(1, 14, 10);
  const jointMaterial = new THREE.MeshLambertMaterial({ color: 0x444444 });
  D.limbs.forEach((limb) => {
    const material = new THREE.MeshLambertMaterial({ color: 0x999999 }), segments = [], balls = [];
    for (let k = 0; k + 1 < limb.joints.length; ++k) { const m = new THREE.Mesh(cylinder, material); scene.add(m); segments.push(m); }
    for (let k = 0; k < limb.joints.length; ++k) {
      const m = new THREE.Mesh(ball, jointMaterial); m.scale.setScalar(1.7 * radius); scene.add(m); balls.push(m);
    }
    legs.push({ material, segments });
    joints.push(balls);
  });
  // the base: the limbs' first joints (fixed), in the order of their angle about their centroid
  const first = D.limbs.map((limb) => pt(0, limb.at));
  const bc = first.reduce((s, p) => [s[0] + p[0] / L, s[1] + p[1] / L, s[2] + p[2] / L], [0, 0, 0]);
  const baseOrder = first.map((p, j) => j).sort((a, b) =>
    Math.atan2(first[a][1] - bc[1], first[a][0] - bc[0]) - Math.atan2(first[b][1] - bc[1], first[b][0] - bc[0]));
  if (L >= 3) {
    const base = fanGeometry(L);
    fan(base, around(first, baseOrder));
    scene.add(new THREE.Mesh(base, new THREE.MeshLambertMaterial({ color: 0x888888, transparent: true, opacity: 0.35, side: THREE.DoubleSide })));
  }
  platform = new THREE.Mesh(fanGeometry(L), new THREE.MeshLambertMaterial({ color: 0xff9900, transparent: true, opacity: 0.6, side: THREE.DoubleSide }));
  scene.add(platform);
  outline = new THREE.LineLoop(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xc77800 }));
  outline.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * L), 3));
  scene.add(outline);
  trace = new THREE.Line(traceGeometry(), new THREE.LineBasicMaterial({ color: 0x8b0000 }));
  scene.add(trace);
  // the platform point now: flat red, drawn over everything (last of the transparent objects)
  marker = new THREE.Mesh(ball, new THREE.MeshBasicMaterial({ color: 0xff0000, depthTest: false, depthWrite: false, transparent: true, opacity: 1 }));
  marker.scale.setScalar(2.2 * radius);
  marker.renderOrder = 10;
  scene.add(marker);
  controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.set(...c);
  controls.update();
  controls.addEventListener('change', render);
} else {
  host.textContent = 'This browser gives no WebGL: the 3-D view cannot be drawn (the forces and plots still show the motion).';
}
function render() {
  if (!renderer) return;
  renderer.render(scene, camera);
  view.draws += 1;
}
// the pixel [CSS px, from the canvas' top left] where a point [m] is drawn
view.project = (p) => {
  const v = new THREE.Vector3(...p).project(camera);
  return [(v.x + 1) / 2 * W, (1 - v.y) / 2 * H];
};
view.cameraPosition = () => (camera ? camera.position.toArray() : null);
view.cameraDistance = () => (camera ? camera.position.distanceTo(controls.target) : null);
function drawRobot() {
  const i = view.frame;
  view.drawnPoint = pt(i, PLATFORM);
  if (!renderer) { view.draws += 1; return; }
  const ends = [];
  D.limbs.forEach((limb, j) => {
    const points = chain(i, j);
    legs[j].segments.forEach((m, k) => place(m, points[k], points[k + 1]));
    joints[j].forEach((m, k) => m.position.set(...points[k]));
    legs[j].material.color.set(limb.actuator >= 0 ? forceColor(TAU[i * n + limb.actuator] / scaleOf(limb.actuator)) : '#999999');
    ends.push(points[points.length - 1]);
  });
  fan(platform.geometry, around(ends, D.around));
  const line = outline.geometry.attributes.position;
  D.around.forEach((j, k) => line.setXYZ(k, ...ends[j]));
  line.needsUpdate = true;
  outline.geometry.computeBoundingSphere();
  marker.position.set(...view.drawnPoint);
  render();
}
// plots of u and tau: every bucket's min and max, a cursor at the current time
function plot(id, series, label, unitsText) {
  const c = $(id), g = c.getContext('2d'), tb = D.plots.t, B = tb.length, m = { l: 52, r: 8, t: 16, b: 22 };
  let lo = Infinity, hi = -Infinity;
  for (const s of series) for (let b = 0; b < B; ++b) { lo = Math.min(lo, s.lo[b]); hi = Math.max(hi, s.hi[b]); }
  if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
  const t0 = T[0], t1 = D.tEnd > t0 ? D.tEnd : t0 + 1;
  const X = (t) => m.l + (c.width - m.l - m.r) * (t - t0) / (t1 - t0);
  const Y = (v) => c.height - m.b - (c.height - m.t - m.b) * (v - lo) / (hi - lo);
  return function draw() {
    g.clearRect(0, 0, c.width, c.height);
    g.font = '11px sans-serif'; g.fillStyle = '#222';
    g.fillText(label + ' [' + unitsText + ']', m.l, 11);
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
const drawU = plot('plot-u', D.plots.u, 'actuator variables u', uUnits);
const drawTau = plot('plot-tau', D.plots.tau, 'actuator forces tau', units.join(', '));
function draw() { drawRobot(); showForces(); drawU(); drawTau(); }
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
  if (m >= 0 && isFinite(m)) {
    view.magnify = m;
    if (trace) { trace.geometry.dispose(); trace.geometry = traceGeometry(); }
    draw();
  } else $('magnify').value = String(view.magnify);
  showFactors();
});
$('reset').addEventListener('click', () => {
  if (!controls) return;
  camera.position.set(...home.position);
  controls.target.set(...home.target);
  controls.update();
  render();
});
showFactors();
setFrame(0);
})();
