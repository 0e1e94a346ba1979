// `owsim studio` as a user works with it, in headless Chromium (Debian's, driven by the pinned
// playwright-core of web/): opened on a recorded flight, a 60 s segment selected, a span placed
// across the track by two clicks, a bad diameter refused beside its field and mended, Fly with
// its progress, wire returns in the report, a truth row back to the map, Save. No console errors; no request leaves the
// studio's own address. Screenshots in SHOT_DIR.
//   node tests/web/studio_flow.mjs URL SHOT_DIR
//   node tests/web/studio_flow.mjs URL SHOT_DIR --terrain   a scenario with a DEM: its hillshade
//                                                           and contours under the flight, and
//                                                           a mesh from its folder placed
// Prints one JSON line of what it saw; exits non-zero with the failed checks listed.
import { createRequire } from 'node:module';
import { mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const require = createRequire(join(here, '..', '..', 'web', 'package.json'));
const { chromium } = require('playwright-core');

const [address, shotDir, mode] = process.argv.slice(2);
mkdirSync(shotDir, { recursive: true });
const origin = new URL(address).origin;
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };

const browser = await chromium.launch({
  executablePath: process.env.OWSIM_CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic'],
});
const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
const consoleErrors = [];
const foreign = [];
page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
page.on('pageerror', (e) => consoleErrors.push(String(e)));
page.on('request', (r) => {
  const url = r.url();
  if (!url.startsWith(origin) && !url.startsWith('data:') && !url.startsWith('blob:') && !url.startsWith('about:')) foreign.push(url);
});

page.on('console', (m) => { if (process.env.STUDIO_DEBUG) console.error(`[${m.type()}] ${m.text()}`); });

// Waits until the map's select mode holds a feature of `kind` (the object under the click).
async function waitForSelected(kind) {
  await page.waitForFunction((k) => window.owsimStudio.drawing.draw.getSnapshot()
    .some((f) => f.properties.selected && f.properties.kind === k), kind, { timeout: 90000 });
}

// Selects the feature of `kind` under `from` and drags it ten steps of `step` pixels, until
// `moved(arg)` holds in the page. Under load a drag now and then moves nothing (seen once in CI:
// the barn's drag, 90 s without a change; never reproduced, loaded or not); a drag that has moved
// nothing after 20 s is tried again, twice at most, and each retry is reported on stderr.
async function dragSelected(what, kind, from, step, moved, arg) {
  for (let attempt = 1; ; attempt += 1) {
    await page.locator('#tools button[data-tool="select"]').click();
    await page.mouse.click(from.x, from.y);
    // The drag starts once the map has selected it (a fixed pause was too short under load).
    await waitForSelected(kind);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    for (let s = 1; s <= 10; s += 1) await page.mouse.move(from.x + step.x * s, from.y + step.y * s);
    await page.mouse.up();
    try {
      await page.waitForFunction(moved, arg, { timeout: attempt < 3 ? 20000 : 90000 });
      return;
    } catch (error) {
      if (attempt === 3) throw error;
      console.error(`studio_flow: dragging ${what} moved nothing in 20 s; again (attempt ${attempt + 1})`);
    }
  }
}

// On any step that fails: a screenshot, the document and the console, to see why.
async function explain(error) {
  console.error(`studio_flow: ${error.message}`);
  try {
    await page.screenshot({ path: join(shotDir, 'failure.png') });
    console.error(await page.evaluate(() => window.owsimStudio?.doc?.text()));
    console.error(`problem: ${await page.locator('#problem').innerText()}`);
  } catch {}
  console.error(`console: ${consoleErrors.join(' | ')}`);
  process.exit(1);
}

let track;
let spans;
let wires;
try {
await page.goto(address);
await page.waitForSelector('body[data-ready="true"]', { timeout: 60000 });
if (mode === '--terrain') {
  const shading = await page.locator('img.hillshade').count();
  const lines = await page.locator('path.contour').count();
  const interval = await page.evaluate(() => window.owsimStudio.map.terrainLayer.getLayers()[0]?.contourInterval);
  check(shading === 1, `${shading} hillshade images`);
  check(lines >= 5, `${lines} contour lines`);
  // A second barn from the scenario's folder, placed by the Mesh tool 150 m north of the track's
  // start: the scenario gains it and the map draws it as built.
  const models = await page.locator('#mesh-file option').allTextContents();
  check(models.includes('data/real_corridor_barn.obj'), `model files offered: ${models.join(', ')}`);
  await page.locator('#mesh-file').selectOption('data/real_corridor_barn.obj');
  const spot = await page.evaluate(() => {
    const studio = window.owsimStudio;
    const [lat, lon] = studio.view.track.points[Math.floor(studio.view.track.points.length / 2)];
    const p = studio.map.map.latLngToContainerPoint([lat + 150 / 111320, lon]);
    const box = document.getElementById('map').getBoundingClientRect();
    return { x: box.left + p.x, y: box.top + p.y };
  });
  await page.locator('#tools button[data-tool="mesh"]').click();
  await page.mouse.click(spot.x, spot.y);
  await page.waitForSelector('select[name="scene.meshes[1].file"]', { timeout: 90000 });
  await page.waitForFunction(() => window.owsimStudio.view.objects.filter((o) => o.class === 'building').length === 2, null, { timeout: 90000 });
  const problem = await page.locator('#problem').innerText();
  check(problem === '', `a problem after placing the mesh: ${problem}`);
  // The new barn dragged 60 px south by its origin: its `at` moves south.
  const barnBefore = await page.evaluate(() => window.owsimStudio.doc.get(['scene', 'meshes', 1, 'at']));
  const barn = await page.evaluate(([lat, lon]) => {
    const p = window.owsimStudio.map.map.latLngToContainerPoint([lat, lon]);
    const box = document.getElementById('map').getBoundingClientRect();
    return { x: box.left + p.x, y: box.top + p.y };
  }, [barnBefore.lat, barnBefore.lon]);
  await dragSelected('the barn', 'mesh', barn, { x: 0, y: 6 },
    (lat) => window.owsimStudio.doc.get(['scene', 'meshes', 1, 'at']).lat < lat - 1e-5, barnBefore.lat);

  // The forest dragged east by its area: its east range moves, its north range stays.
  const before = await page.evaluate(() => window.owsimStudio.doc.get(['scene', 'forest', 'area']));
  const grip = await page.evaluate(() => {
    const studio = window.owsimStudio;
    const corners = studio.view.handles.areas.find((a) => a.kind === 'forest').corners;
    const map = studio.map.map;
    const box = document.getElementById('map').getBoundingClientRect();
    const [lat, lon] = corners[0];
    const p = map.latLngToContainerPoint([lat + 0.0004, lon + 0.0006]);  // just inside its SW corner
    return { x: box.left + p.x, y: box.top + p.y };
  });
  await dragSelected('the forest', 'forest', grip, { x: 8, y: 0 },
    (e0) => window.owsimStudio.doc.get(['scene', 'forest', 'area', 'e'])[0] !== e0, before.e[0]);
  const after = await page.evaluate(() => window.owsimStudio.doc.get(['scene', 'forest', 'area']));
  const moved = after.e[0] - before.e[0];
  check(moved > 20 && Math.abs(after.e[1] - before.e[1] - moved) < 1 && Math.abs(after.n[0] - before.n[0]) < 5,
    `the forest's area after a drag east: ${JSON.stringify(before)} → ${JSON.stringify(after)}`);
  await page.screenshot({ path: join(shotDir, 'studio_terrain.png') });
  check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
  check(foreign.length === 0, `requests leaving the studio: ${foreign.join(' ')}`);
  await browser.close();
  console.log(JSON.stringify({ shading, lines, interval }));
  if (failures.length > 0) {
    console.error(`studio_flow: ${failures.length} check(s) failed:\n  ${failures.join('\n  ')}`);
    process.exit(1);
  }
  process.exit(0);
}
track = await page.evaluate(() => {
  const t = window.owsimStudio.view.track;
  return { start: t.start_s, end: t.end_s, samples: t.t.length };
});
check(track.end - track.start > 100, `the recorded flight is ${track.end - track.start} s long`);

// 1. A 60 s segment: 40 s to 100 s, set on the two sliders as a user would (keyboard).
const setSlider = async (id, value) => {
  await page.locator(`#${id}`).evaluate((input, v) => {
    input.value = String(v);
    input.dispatchEvent(new Event('input', { bubbles: true }));
    input.dispatchEvent(new Event('change', { bubbles: true }));
  }, value);
};
await setSlider('seg-end', 100);
await page.waitForFunction(() => /duration_s: 100\b/.test(window.owsimStudio.doc.text()), null, { timeout: 90000 });
await setSlider('seg-start', 40);
await page.waitForFunction(() => /duration_s: 60\b/.test(window.owsimStudio.doc.text()), null, { timeout: 90000 });
await setSlider('cursor', 70);

// 2. A span across the track at 70 s: two clicks 120 m either side of it, across its heading.
const clicks = await page.evaluate(() => {
  const studio = window.owsimStudio;
  const t = studio.view.track;
  let k = 0;
  while (k + 1 < t.t.length && t.t[k] < 70) k += 1;
  const [lat, lon] = t.points[k];
  const [lat2, lon2] = t.points[Math.min(t.t.length - 1, k + 4)];
  const m = 111320;
  const de = (lon2 - lon) * m * Math.cos((lat * Math.PI) / 180);
  const dn = (lat2 - lat) * m;
  const length = Math.hypot(de, dn) || 1;
  const across = [-dn / length, de / length];  // unit vector across the heading (east, north)
  const at = (s) => [lat + (s * across[1]) / m, lon + (s * across[0]) / (m * Math.cos((lat * Math.PI) / 180))];
  const map = studio.map.map;
  map.setView([lat, lon], 16, { animate: false });
  const box = document.getElementById('map').getBoundingClientRect();
  return [at(-120), at(120)].map(([a, b]) => {
    const p = map.latLngToContainerPoint([a, b]);
    return { x: box.left + p.x, y: box.top + p.y };
  });
});
await page.waitForTimeout(300);
await page.locator('#tools button[data-tool="span"]').click();
await page.mouse.click(clicks[0].x, clicks[0].y);
await page.waitForTimeout(200);
await page.mouse.click(clicks[1].x, clicks[1].y);
await page.waitForSelector('input[name="scene.spans[0].conductor.diameter_mm"]', { timeout: 90000 });
spans = await page.evaluate(() => window.owsimStudio.doc.list(['scene', 'spans']).length);
// The pointer's coordinates: WGS-84 and the scenario's east/north, from the server.
await page.mouse.move(clicks[1].x + 3, clicks[1].y + 3);
await page.waitForFunction(() => /°.*e -?\d+\.\d m, n -?\d+\.\d m/.test(document.querySelector('#cursor-coords').textContent), null, { timeout: 90000 });
check(spans === 1, `${spans} spans after two clicks`);

// 3. A bad diameter: the loader's message beside its field; then a good one.
const diameter = page.locator('input[name="scene.spans[0].conductor.diameter_mm"]');
await diameter.fill('-3');
await diameter.press('Tab');
await page.waitForFunction(() => document.querySelector('.field.bad .field-problem')?.textContent, null, { timeout: 90000 });
const beside = await page.locator('.field.bad .field-problem').innerText();
check(/must be in \[1, 200\] mm/.test(beside), `the bad diameter's message: '${beside}'`);
await page.screenshot({ path: join(shotDir, 'studio_problem.png') });
await diameter.fill('30');
await diameter.press('Tab');
await page.waitForFunction(() => !document.querySelector('.field.bad'), null, { timeout: 90000 });
// Undo brings the bad diameter back with its message; Redo the good one.
await page.locator('#undo').click();
await page.waitForFunction(() => document.querySelector('.field.bad') && /diameter_mm: -3\b/.test(window.owsimStudio.doc.text()), null, { timeout: 90000 });
await page.locator('#redo').click();
await page.waitForFunction(() => !document.querySelector('.field.bad') && /diameter_mm: 30\b/.test(window.owsimStudio.doc.text()), null, { timeout: 90000 });
await page.screenshot({ path: join(shotDir, 'studio_span.png') });

// 4. Fly: progress, then the report with wire returns.
await page.locator('#fly').click();
await page.waitForSelector('#report-pane:not([hidden])', { timeout: 600000 });
const frame = page.frameLocator('#report');
await frame.locator('body[data-ready="1"]').waitFor({ timeout: 180000 });
const facts = await frame.locator('#summary table.facts').innerText();
wires = Number((/wire ([\d,]+)/.exec(facts)?.[1] ?? '0').replace(/,/g, ''));
check(wires > 0, `wire returns in the report: ${wires}`);
await page.screenshot({ path: join(shotDir, 'studio_report.png') });

// 5. A row of the report's ground-truth table picks its object on the map: the wire's span, its
//    form and its cross-section against the ground.
await frame.locator('tr[data-object="span-1/1"]').click();
await page.waitForSelector('#report-pane[hidden]', { state: 'attached', timeout: 30000 });
await page.waitForSelector('#cross-section:not([hidden])', { timeout: 90000 });
const picked = await page.evaluate(() => window.owsimStudio.selected);
check(picked?.kind === 'span' && picked?.id === 'span-1', `the truth row picked ${JSON.stringify(picked)}`);
await page.screenshot({ path: join(shotDir, 'studio_section.png') });

// 6. Save.
await page.locator('#save').click();
await page.waitForFunction(() => /saved/.test(document.querySelector('#status').textContent), null, { timeout: 90000 });

} catch (error) {
  await explain(error);
}

check(consoleErrors.length === 0, `console errors: ${consoleErrors.join(' | ')}`);
check(foreign.length === 0, `requests leaving the studio: ${foreign.join(' ')}`);
await browser.close();
console.log(JSON.stringify({ track, spans, wires, consoleErrors: consoleErrors.length, foreign: foreign.length }));
if (failures.length > 0) {
  console.error(`studio_flow: ${failures.length} check(s) failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
