// The page `owsim view` writes (owsim/flight_report.hpp): reads what the page carries and builds
// its four sections, and a fifth with the detection evidence when the folder holds it. Any failure shows as a message in the page, never as a blank or half page.
import style from './report.css';
import { cloudStep, inflateBlob, readMeta, unpackCloud } from './data.js';
import { cloudSection } from './cloud3d.js';
import { evidenceSection } from './evidence.js';
import { framesSection } from './frames.js';
import { mapSection } from './map.js';
import { el, summarySection } from './summary.js';

async function main() {
  const started = performance.now();
  document.head.append(el('style', {}, style));
  const root = document.getElementById('owsim-report');
  const meta = readMeta();
  root.append(el('header', {},
    el('h1', {}, `owsim — ${meta.title}`),
    el('p', { class: 'generator' }, `${meta.generator} · ${meta.sensor.model}${meta.scenario_file ? ` · scenario ${meta.scenario_file}` : ''}`),
    el('nav', {}, ...[['summary', 'Summary'], ['frames', 'Frame player'], ['map', 'Map'], ['cloud', '3D view'],
      ...(meta.pd || meta.roc || meta.score ? [['evidence', 'Detection evidence']] : [])]
      .map(([id, label]) => el('a', { href: `#${id}` }, label)))));
  const report = { meta };
  window.owsimReport = report;
  const fail = (where, error) => {
    root.append(el('p', { class: 'error' }, `${where}: ${error.message}`));
  };
  root.append(summarySection(meta));
  try {
    const planes = await inflateBlob('owsim-frames');
    const player = framesSection(meta, planes);
    root.append(player.section);
    report.setFrame = player.setFrame;
  } catch (error) {
    fail('frame player', error);
  }
  let points = { n: 0, xyz: new Uint16Array(0), rangeDm: new Uint16Array(0), surface: new Uint8Array(0) };
  try {
    points = unpackCloud(await inflateBlob('owsim-cloud'), meta.cloud);
  } catch (error) {
    fail('points', error);
  }
  const step = cloudStep(meta.cloud);
  try {
    const map = mapSection(meta, points, step);
    root.append(map.section);
    report.zoomMap = map.zoom;
  } catch (error) {
    fail('map', error);
  }
  try {
    const view = cloudSection(meta, points, step);
    root.append(view.section);
    report.orbit = view.orbit;
  } catch (error) {
    fail('3D view', error);
  }
  try {
    const evidence = evidenceSection(meta);
    if (evidence) root.append(evidence);
  } catch (error) {
    fail('detection evidence', error);
  }
  report.readyMs = performance.now() - started;
  document.body.dataset.ready = '1';
}

main().catch((error) => {
  const root = document.getElementById('owsim-report');
  root.append(document.createTextNode(`The report could not be shown: ${error.message}`));
  document.body.dataset.ready = 'failed';
});
