// Section 1: what the flight was and what it saw — the run summary (summary.json), the notes on
// what the page leaves out, and the ground-truth table, sortable by any column.
import { CLASS_NAMES, classRgb, css, formatNumber } from './colours.js';

function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') node.className = v;
    else if (k.startsWith('data-')) node.setAttribute(k, v);
    else node[k] = v;
  }
  for (const child of children) node.append(child);
  return node;
}
export { el };

// The receiver's false returns (class noise, SENSOR-SPEC §11): the count, per pulse and per second
// of flight.
function falseReturns(s) {
  const seconds = s.frames * s.frame_period_s;
  const perS = seconds > 0 ? `, ${(s.returns.noise / seconds).toPrecision(3)} per second of flight` : '';
  return `${formatNumber(s.returns.noise)} (${Number(s.false_returns_per_pulse ?? 0).toPrecision(3)} per pulse${perS})`;
}

function facts(meta) {
  const s = meta.summary;
  const rows = [];
  const add = (label, value, key) => rows.push([label, value, key]);
  add('Scenario', s?.scenario ?? meta.title, 'scenario');
  add('Sensor', meta.sensor.model, 'sensor');
  if (s) {
    add('Frames', formatNumber(s.frames), 'frames');
    add('Pulses', `${formatNumber(s.pulses)} (${formatNumber(s.pulses_per_frame)} per frame)`, 'pulses');
    const returns = Object.entries(s.returns ?? {})
      .filter(([, n]) => n > 0)
      .map(([name, n]) => `${name} ${formatNumber(n)}`)
      .join(' · ');
    add('Returns by class', returns || 'none', 'returns');
    add('Second returns', formatNumber(s.second_returns), 'second_returns');
    if (s.returns?.noise !== undefined) add('False returns', falseReturns(s), 'false_returns');
    add('Throughput', `${formatNumber(s.pulses_per_s / 1e6, 2)} M pulses/s, ${formatNumber(s.realtime_factor, 1)}× sensor real time`, 'throughput');
    add('Run', `${formatNumber(s.wall_s, 2)} s wall on ${s.threads} thread(s)${s.processes > 1 ? ` × ${s.processes} processes` : ''}, seed ${s.seed}, owsim ${s.version}`, 'run');
  } else {
    const byClass = meta.cloud?.by_class ?? {};
    const returns = Object.entries(byClass).map(([name, c]) => `${name} ${formatNumber(c.total)}`).join(' · ');
    add('Returns by class', returns || 'none', 'returns');
  }
  add('Folder', meta.folder, 'folder');
  return el('table', { class: 'facts' }, ...rows.map(([label, value, key]) =>
    el('tr', { 'data-key': key }, el('th', {}, label), el('td', {}, String(value)))));
}

const COLUMNS = [
  ['id', 'object', 'text'],
  ['class', 'class', 'text'],
  ['returns', 'returns', 'int'],
  ['frames_seen', 'frames seen', 'int'],
  ['first_seen_s', 'first seen (s)', 3],
  ['first_seen_range_m', 'first-seen range (m)', 1],
  ['min_range_m', 'closest range (m)', 1],
];

function groundTruth(meta) {
  const objects = meta.objects ?? [];
  const box = el('div', { class: 'ground-truth' });
  if (!meta.summary) {
    box.append(el('p', { class: 'empty' }, 'No ground truth: this folder has no summary.json (a recording decoded from real data has none).'));
    return box;
  }
  const caption = objects.length < meta.objects_total
    ? `Ground truth: ${formatNumber(objects.length)} of ${formatNumber(meta.objects_total)} objects (first seen first). Click a column to sort.`
    : `Ground truth: ${formatNumber(objects.length)} objects. Click a column to sort.`;
  const table = el('table', { class: 'objects', id: 'objects-table' });
  table.append(el('caption', {}, caption));
  const headRow = el('tr');
  const body = el('tbody');
  let sortKey = null;
  let ascending = true;
  const render = () => {
    const rows = objects.slice();
    if (sortKey) {
      rows.sort((a, b) => {
        const x = a[sortKey];
        const y = b[sortKey];
        if (x === null || x === undefined) return (y === null || y === undefined) ? 0 : 1;
        if (y === null || y === undefined) return -1;
        const order = typeof x === 'string' ? x.localeCompare(y) : x - y;
        return ascending ? order : -order;
      });
    }
    body.replaceChildren(...rows.map((o) => linkToStudio(el('tr', { 'data-object': o.id }, ...COLUMNS.map(([key, , kind]) => {
      const v = o[key];
      if (key === 'class') {
        const swatch = el('span', { class: 'swatch' });
        const code = CLASS_NAMES.indexOf(v);
        swatch.style.background = css(classRgb(code < 0 ? 255 : code));
        return el('td', {}, swatch, String(v));
      }
      const text = kind === 'text' ? String(v) : kind === 'int' ? formatNumber(v) : formatNumber(v, kind);
      return el('td', { class: kind === 'text' ? '' : 'number' }, text);
    })), o.id)));
    for (const th of headRow.children) {
      th.dataset.sorted = th.dataset.key === sortKey ? (ascending ? 'ascending' : 'descending') : '';
    }
  };
  for (const [key, label] of COLUMNS) {
    const th = el('th', { 'data-key': key, title: 'sort' }, label);
    th.addEventListener('click', () => {
      ascending = sortKey === key ? !ascending : true;
      sortKey = key;
      render();
    });
    headRow.append(th);
  }
  table.append(el('thead', {}, headRow), body);
  render();
  box.append(table);
  return box;
}

// Inside owsim studio (the page in a frame of the studio's own origin), a row of the ground-truth
// table picks its object on the studio's map (web/studio/studio.js listenToReport).
function linkToStudio(row, id) {
  const origin = window.location.origin;
  if (window.parent === window || !origin.startsWith('http')) return row;
  row.classList.add('linked');
  row.title = 'show on the studio\'s map';
  row.addEventListener('click', () => window.parent.postMessage({ owsimObject: id }, origin));
  return row;
}

export function summarySection(meta) {
  const section = el('section', { id: 'summary' }, el('h2', {}, 'Summary'));
  section.append(facts(meta));
  if (meta.notes?.length) {
    section.append(el('ul', { class: 'notes', id: 'notes' }, ...meta.notes.map((n) => el('li', {}, n))));
  }
  section.append(groundTruth(meta));
  return section;
}
