// Section 5: detection evidence, when the folder holds it — `owsim pd`'s curves with their
// Clopper–Pearson bands and demonstrated ranges, `owsim roc`'s Pd against false returns per second
// by threshold, and `owsim score`'s detector figures (Pd by class with intervals, false alarms per
// hour, the confusion table). Definitions: docs/evidence.md.
import { formatNumber } from './colours.js';
import { el } from './summary.js';

const SVG = 'http://www.w3.org/2000/svg';

function svg(tag, attrs = {}) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}

// The box both evidence plots draw in: the whole figure, and the plot area inside its margins.
const PLOT = { width: 720, height: 360, left: 56, top: 16, plotW: 720 - 56 - 16, plotH: 360 - 16 - 44 };

// The probability axis at the left, 0 to 1 in tenths, with its grid lines; y maps p to the figure.
function probabilityGrid(root, y) {
  const { left, plotW } = PLOT;
  for (let t = 0; t <= 10; t += 1) {
    root.append(svg('line', { x1: left, x2: left + plotW, y1: y(t / 10), y2: y(t / 10), stroke: '#e4e4e4' }));
    const label = svg('text', { x: left - 6, y: y(t / 10) + 4, 'text-anchor': 'end', 'font-size': 11 });
    label.textContent = (t / 10).toFixed(1);
    root.append(label);
  }
}

// pd.rows, pd.csv's bins: [lo, hi, windows, detected, pd, lo, hi, trials, detected, pd, lo, hi].
function pdPlot(pd) {
  const { width, height, left, top, plotW, plotH } = PLOT;
  const lo = pd.bins.lo_m ?? 0;
  const hi = pd.bins.hi_m ?? 1300;
  const x = (r) => left + ((r - lo) / (hi - lo)) * plotW;
  const y = (p) => top + (1 - p) * plotH;
  const root = svg('svg', { width, height, viewBox: `0 0 ${width} ${height}`, id: 'pd-plot', role: 'img',
    'aria-label': `Probability of detection of ${pd.target} versus range, ${pd.confidence * 100} % Clopper–Pearson bands` });
  root.append(svg('rect', { width, height, fill: 'white' }));
  probabilityGrid(root, y);
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

// roc.rows, one per value of roc.by: Pd within the window (y) against false returns per second
// (x, log scale; values without false returns in a "0" column at the left), with the intervals.
function rocPlot(roc) {
  const { width, height, left, top, plotW, plotH } = PLOT;
  const points = roc.rows.filter((r) => r.windows > 0 && r.false_returns_per_s !== null);
  const positive = points.map((r) => r.false_returns_per_s).filter((v) => v > 0);
  const zeros = points.some((r) => r.false_returns_per_s === 0);
  const d0 = positive.length ? Math.floor(Math.log10(Math.min(...positive))) : -1;
  let d1 = positive.length ? Math.ceil(Math.log10(Math.max(...positive))) : 0;
  if (d1 <= d0) d1 = d0 + 1;
  const zeroColumn = zeros ? 40 : 0;
  const axis0 = left + zeroColumn;
  const decades0 = axis0 + zeroColumn / 3;
  const x = (v) => (v <= 0 ? left + zeroColumn / 2 : decades0 + ((Math.log10(v) - d0) / (d1 - d0)) * (left + plotW - decades0));
  const y = (p) => top + (1 - p) * plotH;
  const root = svg('svg', { width, height, viewBox: `0 0 ${width} ${height}`, id: 'roc-plot', role: 'img',
    'aria-label': `Pd within ${roc.window_s} s of ${roc.target} against false returns per second, by ${roc.by}` });
  root.append(svg('rect', { width, height, fill: 'white' }));
  probabilityGrid(root, y);
  const tick = (v, text) => {
    root.append(svg('line', { x1: x(v), x2: x(v), y1: top, y2: top + plotH, stroke: '#e4e4e4' }));
    const label = svg('text', { x: x(v), y: top + plotH + 16, 'text-anchor': 'middle', 'font-size': 11 });
    label.textContent = text;
    root.append(label);
  };
  for (let d = d0; d <= d1; d += 1) tick(10 ** d, String(10 ** d));
  if (zeros) {
    tick(0, '0');
    root.append(svg('line', { x1: axis0, x2: axis0, y1: top, y2: top + plotH, stroke: '#444', 'stroke-dasharray': '4 3' }));
  }
  const axis = svg('text', { x: left + plotW / 2, y: height - 8, 'text-anchor': 'middle', 'font-size': 12 });
  axis.textContent = 'false returns per second (log scale)';
  root.append(axis, svg('rect', { x: left, y: top, width: plotW, height: plotH, fill: 'none', stroke: '#444' }));
  const colour = '#1f5fbf';
  if (points.length > 1) {
    const band = points.map((r) => `${x(r.false_returns_per_s).toFixed(1)},${y(r.pd_window_hi).toFixed(1)}`)
      .concat(points.slice().reverse().map((r) => `${x(r.false_returns_per_s).toFixed(1)},${y(r.pd_window_lo).toFixed(1)}`));
    root.append(svg('polygon', { points: band.join(' '), fill: colour, 'fill-opacity': 0.15 }));
    root.append(svg('polyline', { id: 'roc-curve', fill: 'none', stroke: colour, 'stroke-width': 2,
      points: points.map((r) => `${x(r.false_returns_per_s).toFixed(1)},${y(r.pd_window).toFixed(1)}`).join(' ') }));
  }
  for (const r of points) {
    const px = x(r.false_returns_per_s);
    root.append(svg('line', { x1: px, x2: px, y1: y(r.pd_window_lo), y2: y(r.pd_window_hi), stroke: colour }));
    root.append(svg('circle', { class: 'roc-point', cx: px, cy: y(r.pd_window), r: 3.5, fill: colour }));
    // Below the point, or above it near the axis.
    const label = svg('text', { x: px + 6, y: y(r.pd_window) + (r.pd_window < 0.15 ? -8 : 14), 'font-size': 11 });
    label.textContent = String(r.value);
    root.append(label);
  }
  return root;
}

function rocPart(roc) {
  const box = el('div', { id: 'roc' });
  box.append(el('h3', {}, `Pd against false returns: ${roc.target}, by ${roc.by}`));
  box.append(el('p', { class: 'caption' },
    `Windows starting at ${roc.range_m[0]}–${roc.range_m[1]} m, at least ${roc.returns} return(s) within `
    + `${roc.window_s} s, over ${formatNumber(roc.flights)} flight(s); ${roc.interval} intervals at `
    + `${roc.confidence * 100} %. False returns: the sensor's, before any detector.`));
  box.append(rocPlot(roc));
  const table = el('table', { class: 'objects', id: 'roc-table' });
  table.append(el('tr', {}, ...[roc.by, 'members', 'windows', 'Pd within W', 'interval', 'false returns',
    'per second'].map((h) => el('th', {}, h))));
  for (const r of roc.rows) {
    table.append(el('tr', {}, el('td', {}, String(r.value)), el('td', { class: 'number' }, formatNumber(r.members)),
      el('td', { class: 'number' }, formatNumber(r.windows)), el('td', { class: 'number' }, percent(r.pd_window, 2)),
      el('td', { class: 'number' }, `[${percent(r.pd_window_lo, 2)}, ${percent(r.pd_window_hi, 2)}]`),
      el('td', { class: 'number' }, formatNumber(r.false_returns)),
      el('td', { class: 'number' }, r.false_returns_per_s === null ? '—' : r.false_returns_per_s.toPrecision(3))));
  }
  box.append(table);
  return box;
}

function percent(p, digits = 1) {
  return p === null || p === undefined ? '—' : `${(100 * p).toFixed(digits)} %`;
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
  if (!meta.pd && !meta.roc && !meta.score) return null;
  const section = el('section', { id: 'evidence' }, el('h2', {}, 'Detection evidence'));
  if (meta.pd) section.append(pdPart(meta.pd));
  if (meta.roc) section.append(rocPart(meta.roc));
  if (meta.score) section.append(scorePart(meta.score));
  return section;
}
