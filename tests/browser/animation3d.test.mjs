// Opens the 3-D page of `nocdyn animate` of a spatial robot in Debian's headless chromium
// (driven by playwright-core, no browser download) and checks what a person would see: the
// WebGL canvas drawn (not blank), the platform point's marker drawn where the inverse dynamics
// CSV puts it at three slider times, one frame per CSV sample, the legs' colours following the
// forces, drag rotating and the wheel zooming the view, play advancing time, no console error
// and no network request; then saves a screenshot.
//
//   node animation3d.test.mjs --nocdyn BIN --source SOURCE_DIR --work DIR
//
// Headless chromium has no GPU: WebGL comes from SwiftShader, its software renderer, which
// chromium only gives to a page with --enable-unsafe-swiftshader (--use-angle=swiftshader
// picks it). Exit status 77 (ctest SKIP_RETURN_CODE) with a message when chromium or
// playwright-core is absent; under CI=true a missing tool fails the test instead.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const CHROMIUM = '/usr/bin/chromium';
const SKIP = process.env.CI === 'true' ? 1 : 77;
const SKIPPED = SKIP === 77 ? 'SKIPPED' : 'FAILED (CI=true, nothing is skipped)';

function option(name) {
  const i = process.argv.indexOf(name);
  if (i < 0 || i + 1 >= process.argv.length) throw new Error(`missing ${name}`);
  return process.argv[i + 1];
}
const nocdyn = option('--nocdyn'), source = option('--source'), work = option('--work');

if (!fs.existsSync(CHROMIUM)) {
  console.log(`${SKIPPED}: ${CHROMIUM} is absent (apt-get install chromium, see scripts/install-deps.sh)`);
  process.exit(SKIP);
}
let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  console.log(`${SKIPPED}: playwright-core is not installed (npm ci --prefix tests/browser, as scripts/test.sh does)`);
  process.exit(SKIP);
}

const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}

// the Delta's pick-and-place cycle: the gripper swings 0.2 m, far across the view
fs.mkdirSync(work, { recursive: true });
const robot = path.join(source, 'robots', 'delta.yaml');
const trajectory = path.join(source, 'trajectories', 'delta-pick.yaml');
const csv = path.join(work, 'delta.csv'), page = path.join(work, 'delta.html');
const run = (args) => execFileSync(nocdyn, args, { stdio: ['ignore', 'pipe', 'pipe'] });
run(['inverse-dynamics', '--robot', robot, '--trajectory', trajectory, '--rate', '400', '-o', csv]);
run(['animate', '--robot', robot, '--trajectory', trajectory, '--rate', '400', '--out', page]);
const stewartPage = path.join(work, 'stewart.html');
run(['animate', '--robot', path.join(source, 'robots', 'stewart.yaml'), '--trajectory',
  path.join(source, 'trajectories', 'stewart-sway.yaml'), '--rate', '200', '--out', stewartPage]);

const lines = fs.readFileSync(csv, 'utf8').trim().split('\n');
const header = lines[0].split(',');
const col = (name) => header.indexOf(name);
const rows = lines.slice(1).map((line) => line.split(',').map(Number));

const args = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'];
if (process.getuid && process.getuid() === 0) args.push('--no-sandbox');
const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true, args });
try {
  const context = await browser.newContext({ viewport: { width: 1300, height: 900 }, deviceScaleFactor: 1 });
  const tab = await context.newPage();
  const errors = [], requests = [];
  tab.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  tab.on('pageerror', (e) => errors.push(String(e)));
  tab.on('request', (r) => { if (!r.url().startsWith('file:')) requests.push(r.url()); });

  // the WebGL canvas as pixels: its colours at points, and how many pixels are not background
  const pixels = (points) => tab.evaluate((at) => {
    const gl = document.querySelector('#view canvas'), c = document.createElement('canvas');
    c.width = gl.width; c.height = gl.height;
    const g = c.getContext('2d');
    g.drawImage(gl, 0, 0);
    const data = g.getImageData(0, 0, c.width, c.height).data;
    let drawn = 0;
    for (let k = 0; k < data.length; k += 4) if (data[k] < 245 || data[k + 1] < 245 || data[k + 2] < 245) ++drawn;
    const colour = ([x, y]) => Array.from(g.getImageData(Math.floor(x), Math.floor(y), 1, 1).data);
    return { drawn, total: c.width * c.height, colours: at.map(colour), sum: data.reduce((s, v, k) => s + v * (k % 7), 0) };
  }, points);

  const opened = Date.now();
  await tab.goto(pathToFileURL(page).href);
  await tab.waitForFunction(() => window.nocdynView && window.nocdynView.draws > 0);
  console.log(`page ${(fs.statSync(page).size / 1e6).toFixed(2)} MB drawn ${Date.now() - opened} ms after opening`);
  const webgl = await tab.evaluate(() => window.nocdynView.webgl);
  check(webgl, 'the browser gives WebGL (chromium with SwiftShader)');
  if (!webgl) throw new Error('no WebGL: nothing else to check');

  const first = await pixels([]);
  check(first.drawn > 0.01 * first.total, `the WebGL canvas is drawn: ${first.drawn} of ${first.total} pixels not background`);

  const frames = await tab.evaluate(() => Number(document.getElementById('slider').max) + 1);
  check(frames === rows.length, `${frames} frames, one per CSV sample (${rows.length})`);
  const seen = [], colours = [];
  for (const fraction of [0, 0.25, 0.75]) {  // the gripper at x = 0, +0.1 m, -0.1 m
    const state = await tab.evaluate((i) => {
      const s = document.getElementById('slider');
      s.value = String(i);
      s.dispatchEvent(new Event('input'));
      const v = window.nocdynView;
      return { frame: v.frame, time: v.time, point: v.drawnPoint, pixel: v.project(v.drawnPoint), legs: v.legColors,
        shown: document.getElementById('time').textContent };
    }, Math.round(fraction * (frames - 1)));
    const row = rows[state.frame];
    check(Math.abs(row[col('t')] - state.time) < 1e-12 && state.shown === state.time.toFixed(5),
      `slider frame ${state.frame}: t = ${state.time} s is the CSV's sample ${state.frame}`);
    const off = Math.max(...['x', 'y', 'z'].map((a, c) => Math.abs(state.point[c] - row[col(a)])));
    check(off < 1e-6, `t = ${state.time} s: the platform point drawn at (${state.point.map((v) => v.toFixed(4))}) m, ${off.toExponential(1)} m from the CSV's`);
    const px = await pixels([state.pixel]);
    const [r, g, b] = px.colours[0];
    check(r > 230 && g < 40 && b < 40, `t = ${state.time} s: the canvas pixel at the platform point (${state.pixel.map((v) => v.toFixed(1))}) is the red marker (${px.colours[0]})`);
    seen.push(state.pixel);
    colours.push(state.legs.join());
  }
  const apart = Math.min(...seen.map((a, i) => Math.hypot(a[0] - seen[(i + 1) % 3][0], a[1] - seen[(i + 1) % 3][1])));
  check(apart > 10, `the three marker positions are ${apart.toFixed(1)} px apart or more (the check can fail)`);
  check(new Set(colours).size === 3, 'the legs\' colours change with the forces');

  // drag rotates the view, the wheel zooms it
  const box = await tab.locator('#view canvas').boundingBox();
  const before = await tab.evaluate(() => ({ camera: window.nocdynView.cameraPosition(), draws: window.nocdynView.draws }));
  const imageBefore = await pixels([]);
  await tab.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await tab.mouse.down();
  await tab.mouse.move(box.x + box.width / 2 + 150, box.y + box.height / 2 + 40, { steps: 8 });
  await tab.mouse.up();
  const dragged = await tab.evaluate(() => ({ camera: window.nocdynView.cameraPosition(), draws: window.nocdynView.draws }));
  const imageAfter = await pixels([]);
  const turned = Math.hypot(...dragged.camera.map((v, k) => v - before.camera[k]));
  check(turned > 0.05 && dragged.draws > before.draws && imageAfter.sum !== imageBefore.sum,
    `drag turns the camera by ${turned.toFixed(3)} m and redraws (${dragged.draws - before.draws} draws)`);
  const distance = () => tab.evaluate(() => window.nocdynView.cameraDistance());
  const far = await distance();
  await tab.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  for (let k = 0; k < 5; ++k) {  // each wheel event brings the camera 5 % nearer its target
    await tab.mouse.wheel(0, -100);
    await tab.waitForTimeout(50);
  }
  const near = await distance();
  check(near < 0.85 * far, `the wheel zooms in: the camera from ${far.toFixed(3)} m to ${near.toFixed(3)} m of its target`);

  // play: time advances, the view redrawn
  await tab.evaluate(() => {
    const s = document.getElementById('slider');
    s.value = '0';
    s.dispatchEvent(new Event('input'));
  });
  await tab.click('#play');
  await tab.waitForTimeout(600);
  const after = await tab.evaluate(() => ({ time: window.nocdynView.time, playing: window.nocdynView.playing }));
  await tab.click('#play');
  check(after.playing && after.time > 0, `play advances time to ${after.time} s`);

  const shot = path.join(work, 'animation3d.png');
  await tab.screenshot({ path: shot, fullPage: true });
  check(fs.statSync(shot).size > 10000, `screenshot ${shot}`);

  // the hexapod: six legs, drawn
  await tab.goto(pathToFileURL(stewartPage).href);
  await tab.waitForFunction(() => window.nocdynView && window.nocdynView.draws > 0);
  const hexapod = await pixels([]);
  check(hexapod.drawn > 0.01 * hexapod.total, `the Stewart platform is drawn: ${hexapod.drawn} pixels not background`);
  await tab.screenshot({ path: path.join(work, 'animation3d-stewart.png'), fullPage: true });

  check(errors.length === 0, `no console errors ${JSON.stringify(errors)}`);
  check(requests.length === 0, `no network requests ${JSON.stringify(requests)}`);
} finally {
  await browser.close();
}
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
console.log('all browser checks passed');
