// Opens the page of `nocdyn animate` in Debian's headless chromium (driven by playwright-core,
// no browser download) and checks what a person would see: no console errors and no network
// request, the platform's operation point C drawn where the CSV pose puts it (to the pixel) at
// three slider times, play advancing time, a robot name from the file shown as text (never run
// as code); then saves a screenshot.
//
//   node animation.test.mjs --nocdyn BIN --source SOURCE_DIR --work DIR
//
// Exit status 77 (ctest SKIP_RETURN_CODE) with a message when chromium or playwright-core is absent;
// under CI=true (.ci/run) a missing tool fails the test instead (exit status 1), naming it.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const CHROMIUM = '/usr/bin/chromium';
// In CI nothing is skipped: a missing browser must fail the run, not pass it unseen.
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

// A motion large enough that C crosses many pixels: inverse dynamics of a 3-RPR along a
// 12 mm circle with a 0.15 rad swing, as a CSV like simulate's and control's.
fs.mkdirSync(work, { recursive: true });
const robot = path.join(source, 'robots', '3-rpr.yaml');
const trajectory = path.join(work, 'circle.yaml');
fs.writeFileSync(trajectory, [
  'name: circle', 'duration: 0.5',
  'x:     {offset: 0.0, harmonics: [{amplitude: 0.012, frequency: 2, phase: 1.5707963267948966}]}',
  'y:     {offset: 0.0, harmonics: [{amplitude: 0.012, frequency: 2, phase: 0.0}]}',
  'theta: {offset: 0.0, harmonics: [{amplitude: 0.15, frequency: 2, phase: 0.0}]}', ''].join('\n'));
const csv = path.join(work, 'circle.csv'), page = path.join(work, 'circle.html');
const run = (args) => execFileSync(nocdyn, args, { stdio: ['ignore', 'pipe', 'pipe'] });
run(['inverse-dynamics', '--robot', robot, '--trajectory', trajectory, '--rate', '4000', '--allow-limits', '-o', csv]);
run(['animate', '--robot', robot, '--motion', csv, '--out', page]);

// a robot whose name tries to leave the data script
const hostileRobot = path.join(work, 'hostile.yaml');
fs.writeFileSync(hostileRobot, fs.readFileSync(robot, 'utf8')
  .replace(/^name: .*$/m, 'name: "x</script><script>window.pwned = 1</script><!--"'));
const hostilePage = path.join(work, 'hostile.html');
run(['animate', '--robot', hostileRobot, '--trajectory', trajectory, '--rate', '200', '--out', hostilePage]);

const lines = fs.readFileSync(csv, 'utf8').trim().split('\n');
const header = lines[0].split(',');
const col = (name) => header.indexOf(name);
const rows = lines.slice(1).map((line) => line.split(',').map(Number));
const poseAt = (t) => {
  let best = rows[0];
  for (const r of rows) if (Math.abs(r[col('t')] - t) < Math.abs(best[col('t')] - t)) best = r;
  return { t: best[col('t')], x: best[col('x')], y: best[col('y')] };
};

const browser = await chromium.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: process.getuid && process.getuid() === 0 ? ['--no-sandbox'] : [],
});
try {
  const context = await browser.newContext({ viewport: { width: 1200, height: 820 }, deviceScaleFactor: 1 });
  const tab = await context.newPage();
  const errors = [], requests = [];
  tab.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  tab.on('pageerror', (e) => errors.push(String(e)));
  tab.on('request', (r) => { if (!r.url().startsWith('file:')) requests.push(r.url()); });

  const opened = Date.now();
  await tab.goto(pathToFileURL(page).href);
  await tab.waitForFunction(() => window.nocdynView && window.nocdynView.draws > 0);
  console.log(`page ${(fs.statSync(page).size / 1e6).toFixed(2)} MB drawn ${Date.now() - opened} ms after opening`);

  const frames = await tab.evaluate(() => Number(document.getElementById('slider').max) + 1);
  const seen = [];
  for (const fraction of [0.2, 0.5, 0.8]) {
    const state = await tab.evaluate((i) => {
      const s = document.getElementById('slider');
      s.value = String(i);
      s.dispatchEvent(new Event('input'));
      const v = window.nocdynView;
      return { time: v.time, scale: v.scale, ox: v.ox, oy: v.oy, drawn: v.drawnC, frame: v.frame };
    }, Math.round(fraction * (frames - 1)));
    const pose = poseAt(state.time);
    const px = state.ox + state.scale * pose.x, py = state.oy - state.scale * pose.y;
    check(Math.abs(pose.t - state.time) < 1e-9, `slider frame ${state.frame}: t = ${state.time} s is a CSV sample`);
    check(Math.abs(state.drawn[0] - px) < 0.5 && Math.abs(state.drawn[1] - py) < 0.5,
      `t = ${state.time} s: C drawn at (${state.drawn.map((v) => v.toFixed(2))}), CSV pose at (${px.toFixed(2)}, ${py.toFixed(2)})`);
    // what is on the canvas at that pixel is C's colour
    const rgba = await tab.evaluate(([x, y]) =>
      Array.from(document.getElementById('robot').getContext('2d').getImageData(x, y, 1, 1).data),
    [Math.floor(px), Math.floor(py)]);
    check(rgba[0] > 230 && rgba[1] < 40 && rgba[2] < 40, `t = ${state.time} s: canvas pixel at C is red (${rgba})`);
    seen.push([px, py]);
  }
  const apart = Math.min(...seen.map((a, i) => Math.hypot(a[0] - seen[(i + 1) % 3][0], a[1] - seen[(i + 1) % 3][1])));
  check(apart > 10, `the three positions of C are ${apart.toFixed(1)} px apart or more (the check can fail)`);

  // magnification: C drawn at mean + M (C - mean), the mean pose's C being the centre
  const mean = rows.reduce((m, r) => [m[0] + r[col('x')] / rows.length, m[1] + r[col('y')] / rows.length], [0, 0]);
  const magnified = await tab.evaluate(() => {
    const m = document.getElementById('magnify');
    m.value = '3';
    m.dispatchEvent(new Event('change'));
    const v = window.nocdynView;
    return { time: v.time, scale: v.scale, ox: v.ox, oy: v.oy, drawn: v.drawnC, magnify: v.magnify, text: document.getElementById('factors').textContent };
  });
  {
    const pose = poseAt(magnified.time);
    const x = mean[0] + 3 * (pose.x - mean[0]), y = mean[1] + 3 * (pose.y - mean[1]);
    const px = magnified.ox + magnified.scale * x, py = magnified.oy - magnified.scale * y;
    check(magnified.magnify === 3 && Math.abs(magnified.drawn[0] - px) < 0.5 && Math.abs(magnified.drawn[1] - py) < 0.5,
      `magnify x3: C drawn at (${magnified.drawn.map((v) => v.toFixed(2))}), expected (${px.toFixed(2)}, ${py.toFixed(2)})`);
    check(magnified.text.includes('magnified x3'), `the magnification is shown ("${magnified.text}")`);
  }
  await tab.evaluate(() => {
    const m = document.getElementById('magnify');
    m.value = '1';
    m.dispatchEvent(new Event('change'));
  });

  // play from the first frame: time advances, no faster than the slow-motion factor allows.
  // The viewer loops over the motion: on a loaded machine whose wait outlasts one loop the
  // time wraps, so the advance is taken modulo the loop (and only bounded within one loop).
  const before = await tab.evaluate(() => {
    const s = document.getElementById('slider');
    s.value = '0';
    s.dispatchEvent(new Event('input'));
    return window.nocdynView.time;
  });
  const slow = await tab.evaluate(() => window.nocdynView.slowMotion);
  const loop = rows[rows.length - 1][col('t')] - rows[0][col('t')];
  const started = Date.now();
  await tab.click('#play');
  await tab.waitForTimeout(600);
  const after = await tab.evaluate(() => ({ time: window.nocdynView.time, playing: window.nocdynView.playing }));
  await tab.click('#play');
  const wall = (Date.now() - started) / 1000;
  const advanced = (((after.time - before) % loop) + loop) % loop;
  const bound = 1.05 * wall / slow + 1e-3;
  check(after.playing && advanced > 0 && (bound >= loop || advanced <= bound),
    `play advances time by ${advanced.toFixed(4)} s (modulo the ${loop} s loop) in ${wall.toFixed(2)} s at slow motion x${slow}`);

  const shot = path.join(work, 'animation.png');
  await tab.screenshot({ path: shot, fullPage: true });
  check(fs.statSync(shot).size > 10000, `screenshot ${shot}`);

  // a replay (shake.csv's achieved pose beside the target): the robot drawn where the table
  // went, the target as a ghost; here the target is the circle at 80 % of its size
  {
    const replayCsv = path.join(work, 'replay.csv'), replayPage = path.join(work, 'replay.html');
    const taus = header.filter((name) => /^tau[0-9]+$/.test(name));
    const replayRows = rows.map((r) => [r[col('t')], 0.8 * r[col('x')], 0.8 * r[col('y')], 0.8 * r[col('theta')],
      r[col('x')], r[col('y')], r[col('theta')], ...taus.map((name) => r[col(name)])].join(','));
    fs.writeFileSync(replayCsv, ['t,x,y,theta,x_achieved,y_achieved,theta_achieved,' + taus.join(','),
      ...replayRows, ''].join('\n'));
    run(['animate', '--robot', robot, '--trajectory', replayCsv, '--out', replayPage]);
    await tab.goto(pathToFileURL(replayPage).href);
    await tab.waitForFunction(() => window.nocdynView && window.nocdynView.draws > 0);
    const state = await tab.evaluate((i) => {
      const s = document.getElementById('slider');
      s.value = String(i);
      s.dispatchEvent(new Event('input'));
      const v = window.nocdynView;
      return { time: v.time, scale: v.scale, ox: v.ox, oy: v.oy, drawn: v.drawnC, ghost: v.drawnGhostC,
        legend: document.getElementById('legend').textContent };
    }, Math.round(0.3 * (frames - 1)));
    const pose = poseAt(state.time);
    const px = state.ox + state.scale * pose.x, py = state.oy - state.scale * pose.y;
    const gx = state.ox + state.scale * 0.8 * pose.x, gy = state.oy - state.scale * 0.8 * pose.y;
    check(Math.abs(state.drawn[0] - px) < 0.5 && Math.abs(state.drawn[1] - py) < 0.5,
      `replay: C drawn at the achieved pose (${state.drawn.map((v) => v.toFixed(2))}), expected (${px.toFixed(2)}, ${py.toFixed(2)})`);
    check(state.ghost !== undefined && Math.abs(state.ghost[0] - gx) < 0.5 && Math.abs(state.ghost[1] - gy) < 0.5 &&
      Math.hypot(gx - px, gy - py) > 3,
      `replay: the target's C drawn as a ghost at (${state.ghost && state.ghost.map((v) => v.toFixed(2))}), expected (${gx.toFixed(2)}, ${gy.toFixed(2)})`);
    check(state.legend.includes('target'), `replay: the legend names the ghost ("${state.legend}")`);
  }

  await tab.goto(pathToFileURL(hostilePage).href);
  await tab.waitForFunction(() => window.nocdynView && window.nocdynView.draws > 0);
  const hostile = await tab.evaluate(() => ({ pwned: window.pwned, title: document.getElementById('title').textContent }));
  check(hostile.pwned === undefined && hostile.title.includes('</script><script>window.pwned'),
    `a robot name with </script> is shown as text, not run (title "${hostile.title}")`);

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
