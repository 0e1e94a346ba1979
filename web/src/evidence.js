// Section 5: detection evidence, when the folder holds it — `owsim pd`'s curves with their
// Clopper–Pearson bands and demonstrated ranges, and `owsim score`'s detector figures (Pd by class
// with intervals, false alarms per hour, the confusion table). Definitions: docs/evidence.md.
import { formatNumber } from './colours.js';
import { el } from './summary.js';

const SVG = 'http://www.w3.org/2000/svg';

function svg(tag, attrs = {}) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}

// pd.rows, pd.csv's bins: [lo, hi, windows, detected, pd, lo, hi, trials, detected, pd, lo, hi].
function pdPlot(pd) {
  const width = 720;
  const height = 360;
  const left = 56;
  const top = 16;
  const plotW = width - left - 16;
  const plotH = height - top - 44;
  const lo = pd.bins.lo_m ?? 0;
  const hi = pd.bins.hi_m ?? 1300;
  const x = (r) => left + ((r - lo) / (hi - lo)) * plotW;
  const y = (p) => top + (1 - p) * plotH;
  const root = svg('svg', { width, height, viewBox: `0 0 ${width} ${height}`, id: 'pd-plot', role: 'img',
    'aria-label': `Probability of detection of ${pd.target} versus range, ${pd.confidence * 100} % Clopper–Pearson bands` });
  root.append(svg('rect', { width, height, fill: 'white' }));
  for (let t = 0; t <= 10; t += 1) {
    root.append(svg('line', { x1: left, x2: left + plotW, y1: y(t / 10), y2: y(t / 10), stroke: '#e4e4e4' }));
    const label = svg('text', { x: left - 6, y: y(t / 10) + 4, 'text-anchor': 'end', 'font-size': 11 });
    label.textContent = (t / 10).toFixed(1);
    root.append(label);
  }
  const step = [50, 100, 200, 250, 500, 1000].find((s) => (hi - lo) / s <= 10) ?? 2000;
  for (let r = Math.ceil(lo / step) * step; r <= hi; r += step) {
    root.append(svg('line', { x1: x(r), x2: x(r), y1: top, y2: top + plotH, stroke: '#e4e4e4' }));
    const label = svg('text', { x: x(r), y: top + plotH + 16, 'text-anchor': 'middle', 'font-size': 11 });
    label.textContent = String(r);
    root.append(label);
  }
  const axis = svg('text', { x: left + plotW / 2, y: height - 8, 'text-anchor': 'middle', 'font-size': 12 });
  axis.textContent = 'range (m)';
  root.append(axis, svg('rect', { x: left, y: top, width: plotW, height: plotH, fill: 'none', stroke: '#444' }));
  const curve = (offset, colour, id) => {
    const points = pd.rows.filter((b) => b[offset] > 0)
      .map((b) => [x((b[0] + b[1]) / 2), b[offset + 2], b[offset + 3], b[offset + 4]]);
    if (points.length === 0) return;
    const band = points.map(([px, , , up]) => `${px.toFixed(1)},${y(up).toFixed(1)}`)
      .concat(points.slice().reverse().map(([px, , low]) => `${px.toFixed(1)},${y(low).toFixed(1)}`));
    root.append(svg('polygon', { points: band.join(' '), fill: colour, 'fill-opacity': 0.2 }));
    root.append(svg('polyline', { id, points: points.map(([px, p]) => `${px.toFixed(1)},${y(p).toFixed(1)}`).join(' '),
      fill: 'none', stroke: colour, 'stroke-width': 2 }));
  };
  curve(2, '#1f5fbf', 'pd-window');
  curve(7, '#d9730d', 'pd-cumulative');
  return root;
}

function pdPart(pd) {
  const box = el('div', { id: 'pd' });
  box.append(el('h3', {}, `Probability of detection: ${pd.target}`));
  box.append(el('p', { class: 'caption' },
    `At least ${pd.returns} return(s) within ${pd.window_s} s; ${formatNumber(pd.windows)} windows and `
    + `${formatNumber(pd.trials)} trials in ${formatNumber(pd.flights)} flight(s); ${pd.interval} intervals at `
    + `${pd.confidence * 100} %. Blue: Pd within the window; orange: cumulative Pd.`));
  box.append(pdPlot(pd));
  const demonstrated = Object.entries(pd.demonstrated_range_m ?? {}).map(([p, range]) => el('tr', {},
    el('th', {}, `Pd ≥ ${p}`),
    el('td', {}, range === null
      ? `not demonstrated (a bin needs ${formatNumber(pd.windows_needed_without_misses?.[p] ?? 0)} windows without a miss)`
      : `demonstrated to ${formatNumber(range)} m`)));
  box.append(el('table', { class: 'facts', id: 'pd-demonstrated' }, ...demonstrated));
  return box;
}

function percent(p) {
  return p === null || p === undefined ? '—' : `${(100 * p).toFixed(1)} %`;
}

function scorePart(score) {
  const box = el('div', { id: 'score' });
  box.append(el('h3', {}, 'Detector score'));
  box.append(el('p', { class: 'caption' },
    `${formatNumber(score.detections)} detections in ${formatNumber(score.flights)} flight(s), gate ${score.gate_m} m: `
    + `${formatNumber(score.false_alarms)} false alarms, `
    + `${score.false_alarms_per_hour === null ? '—' : formatNumber(score.false_alarms_per_hour, 1)} per flight hour.`));
  const table = el('table', { class: 'objects', id: 'score-by-class' });
  table.append(el('tr', {}, ...['class', 'objects in view', 'detected', 'Pd', 'interval'].map((h) => el('th', {}, h))));
  for (const [name, c] of Object.entries(score.by_class ?? {})) {
    table.append(el('tr', {}, el('td', {}, name), el('td', { class: 'number' }, formatNumber(c.objects)),
      el('td', { class: 'number' }, formatNumber(c.detected)), el('td', { class: 'number' }, percent(c.pd)),
      el('td', { class: 'number' }, `[${percent(c.pd_lo)}, ${percent(c.pd_hi)}]`)));
  }
  box.append(table);
  const confusion = score.confusion ?? {};
  const reported = [...new Set(Object.values(confusion).flatMap((row) => Object.keys(row)))].sort();
  if (reported.length > 0) {
    const matrix = el('table', { class: 'objects', id: 'score-confusion' });
    matrix.append(el('caption', {}, 'Confusion: true class (rows; none = false alarm) by reported class (columns)'));
    matrix.append(el('tr', {}, el('th', {}, ''), ...reported.map((r) => el('th', {}, r))));
    for (const [truth, row] of Object.entries(confusion)) {
      matrix.append(el('tr', {}, el('th', {}, truth),
        ...reported.map((r) => el('td', { class: 'number' }, formatNumber(row[r] ?? 0)))));
    }
    box.append(matrix);
  }
  return box;
}

export function evidenceSection(meta) {
  if (!meta.pd && !meta.score) return null;
  const section = el('section', { id: 'evidence' }, el('h2', {}, 'Detection evidence'));
  if (meta.pd) section.append(pdPart(meta.pd));
  if (meta.score) section.append(scorePart(meta.score));
  return section;
}
