// Section 2: the frame player — each frame's range image as the sensor sees it (rows = fibers by
// α, highest at the top; columns = lines by mirror angle β, left to right), coloured by the first
// return's range with wire, pole, tree and fog returns and false first returns (noise) marked,
// with labelled axes, a colour bar in metres, a legend, a slider and a play button, and the
// frame's time and pose.
import { CLASS_NAMES, classRgb, css, formatNumber, niceStep, rampRgb } from './colours.js';
import { el } from './summary.js';

const MARKED = ['wire', 'pole', 'tree', 'fog', 'noise'];
const CELL_W = 4;
const CELL_H = 4;
const MARGIN = { left: 70, right: 110, top: 30, bottom: 56 };

export function framesSection(meta, planes) {
  const section = el('section', { id: 'frames' }, el('h2', {}, 'Frame player'));
  const f = meta.frames;
  if (!f || !planes) {
    section.append(el('p', { class: 'empty' }, f ? 'No frames.' : 'No range images: the frame player needs points.csv (see the notes above).'));
    return { section, setFrame: () => {} };
  }
  const rows = f.rows;
  const lines = f.lines;
  const cells = rows * lines;
  const fullScale = meta.sensor.timeout_range_m;
  const plotW = lines * CELL_W;
  const plotH = rows * CELL_H;
  const canvas = el('canvas', { id: 'frame-canvas', width: MARGIN.left + plotW + MARGIN.right, height: MARGIN.top + plotH + MARGIN.bottom });
  canvas.setAttribute('role', 'img');
  canvas.setAttribute('aria-label', `Range image: mirror angle β (degrees) across from ${f.beta_first_deg}° to ${f.beta_last_deg}°, fiber elevation α (degrees) down from ${f.row_alpha_deg[0]}° to ${f.row_alpha_deg[rows - 1]}°, colour bar range (m) 0 to ${Math.round(fullScale)} m`);
  const ctx = canvas.getContext('2d');
  const image = new ImageData(lines, rows);
  const cellCanvas = el('canvas', { width: lines, height: rows });
  const cellCtx = cellCanvas.getContext('2d');

  const slider = el('input', { type: 'range', id: 'frame-slider', min: 0, max: f.shown.length - 1, value: 0, step: 1 });
  const play = el('button', { id: 'frame-play', type: 'button' }, 'Play');
  const label = el('div', { id: 'frame-label', class: 'frame-label' });
  const hover = el('div', { id: 'frame-hover', class: 'hover' }, 'Point at a cell for its fiber, angles and range.');
  // The detector's warnings of the frame (detections.csv: a track warns in every frame from its
  // first report to its last), by class.
  const warningTracks = meta.warnings ? meta.warnings.tracks : null;
  const warned = el('div', { id: 'frame-warnings', class: 'frame-warnings' });
  const legend = el('div', { class: 'legend', id: 'frame-legend' },
    ...MARKED.map((name) => {
      const s = el('span', { class: 'swatch' });
      s.style.background = css(classRgb(CLASS_NAMES.indexOf(name)));
      return el('span', { class: 'legend-item' }, s, name);
    }),
    (() => { const s = el('span', { class: 'swatch' }); s.style.background = '#000'; return el('span', { class: 'legend-item' }, s, 'no return'); })());
  section.append(el('div', { class: 'controls' }, play, slider, label), canvas, legend, hover,
    ...(warningTracks ? [warned] : []));

  const betaAt = (column) => f.beta_first_deg + (column + 0.5) / lines * (f.beta_last_deg - f.beta_first_deg);
  let current = 0;

  function drawAxes() {
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.fillStyle = '#222';
    ctx.strokeStyle = '#222';
    ctx.font = '12px sans-serif';
    // β across.
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    const span = f.beta_last_deg - f.beta_first_deg;
    const step = niceStep(Math.abs(span), 6);
    for (let b = Math.ceil(Math.min(f.beta_first_deg, f.beta_last_deg) / step) * step; b <= Math.max(f.beta_first_deg, f.beta_last_deg) + 1e-9; b += step) {
      const x = MARGIN.left + (b - f.beta_first_deg) / span * plotW;
      ctx.beginPath();
      ctx.moveTo(x, MARGIN.top + plotH);
      ctx.lineTo(x, MARGIN.top + plotH + 5);
      ctx.stroke();
      ctx.fillText(`${formatNumber(b, 0)}°`, x, MARGIN.top + plotH + 7);
    }
    ctx.fillText('mirror angle β (degrees, nominal sweep)', MARGIN.left + plotW / 2, MARGIN.top + plotH + 26);
    // α down.
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    const alphas = f.row_alpha_deg;
    const aStep = niceStep(Math.abs(alphas[0] - alphas[alphas.length - 1]), 8);
    for (let a = Math.floor(alphas[0] / aStep) * aStep; a >= alphas[alphas.length - 1] - 1e-9; a -= aStep) {
      let row = 0;
      for (let r = 0; r < alphas.length; r++) if (Math.abs(alphas[r] - a) < Math.abs(alphas[row] - a)) row = r;
      const y = MARGIN.top + (row + 0.5) * CELL_H;
      ctx.beginPath();
      ctx.moveTo(MARGIN.left - 5, y);
      ctx.lineTo(MARGIN.left, y);
      ctx.stroke();
      ctx.fillText(`${formatNumber(a, 0)}°`, MARGIN.left - 7, y);
    }
    ctx.save();
    ctx.translate(16, MARGIN.top + plotH / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textAlign = 'center';
    ctx.fillText('fiber elevation α (degrees)', 0, 0);
    ctx.restore();
    // Colour bar.
    const barX = MARGIN.left + plotW + 24;
    for (let y = 0; y < plotH; y++) {
      ctx.fillStyle = css(rampRgb(y / (plotH - 1)));
      ctx.fillRect(barX, MARGIN.top + y, 16, 1);
    }
    ctx.strokeRect(barX, MARGIN.top, 16, plotH);
    ctx.fillStyle = '#222';
    ctx.textAlign = 'left';
    const rStep = niceStep(fullScale, 6);
    for (let r = 0; r <= fullScale + 1e-9; r += rStep) {
      const y = MARGIN.top + r / fullScale * (plotH - 1);
      ctx.fillRect(barX + 16, y, 4, 1);
      ctx.fillText(`${formatNumber(r)}`, barX + 22, y);
    }
    ctx.textAlign = 'center';
    ctx.fillText('range (m)', barX + 8, MARGIN.top - 14);
  }

  function setFrame(index) {
    current = Math.max(0, Math.min(f.shown.length - 1, index | 0));
    slider.value = String(current);
    const base = current * 3 * cells;
    const px = image.data;
    for (let c = 0; c < cells; c++) {
      const dm = planes[base + 2 * c] | (planes[base + 2 * c + 1] << 8);
      const mark = planes[base + 2 * cells + c];
      const rgb = mark > 0 ? classRgb(mark - 1) : dm > 0 ? rampRgb(dm / 10 / fullScale) : [0, 0, 0];
      px[4 * c] = rgb[0];
      px[4 * c + 1] = rgb[1];
      px[4 * c + 2] = rgb[2];
      px[4 * c + 3] = 255;
    }
    cellCtx.putImageData(image, 0, 0);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(cellCanvas, MARGIN.left, MARGIN.top, plotW, plotH);
    const frame = f.shown[current];
    const t = f.time_s[current];
    const pose = f.pose[current];
    let text = `frame ${formatNumber(frame)} of ${formatNumber(f.total)}`;
    if (t !== null && t !== undefined) text += ` · t = ${formatNumber(t, 3)} s`;
    if (pose) {
      text += ` · E ${formatNumber(pose[0], 1)} N ${formatNumber(pose[1], 1)} U ${formatNumber(pose[2], 1)} m`;
      text += ` · roll ${formatNumber(pose[3], 1)}° pitch ${formatNumber(pose[4], 1)}° heading ${formatNumber(pose[5], 1)}°`;
    }
    label.textContent = text;
    canvas.dataset.frame = String(frame);
    if (warningTracks) {
      const byClass = {};
      for (const w of warningTracks) {
        if (w.first_frame <= frame && frame <= w.last_frame) (byClass[w.class] ||= []).push(w.track);
      }
      const names = Object.keys(byClass).sort();
      warned.textContent = names.length === 0 ? 'Warnings: none in this frame.'
        : `Warnings: ${names.map((k) => `${byClass[k].length} ${k} (track ${byClass[k].join(', ')})`).join(' · ')}`;
      warned.dataset.count = String(names.reduce((n, k) => n + byClass[k].length, 0));
    }
  }

  canvas.addEventListener('mousemove', (event) => {
    const rect = canvas.getBoundingClientRect();
    const x = (event.clientX - rect.left) * canvas.width / rect.width - MARGIN.left;
    const y = (event.clientY - rect.top) * canvas.height / rect.height - MARGIN.top;
    const column = Math.floor(x / CELL_W);
    const row = Math.floor(y / CELL_H);
    if (column < 0 || row < 0 || column >= lines || row >= rows) return;
    const c = row * lines + column;
    const base = current * 3 * cells;
    const dm = planes[base + 2 * c] | (planes[base + 2 * c + 1] << 8);
    const mark = planes[base + 2 * cells + c];
    hover.textContent = `fiber ${f.row_fiber[row]} (α ${formatNumber(f.row_alpha_deg[row], 2)}°) · β ≈ ${formatNumber(betaAt(column), 2)}° · ` +
      (dm > 0 ? `first return ${formatNumber(dm / 10, 1)} m` : 'no return') + (mark > 0 ? ` · ${CLASS_NAMES[mark - 1]}` : '');
  });
  slider.addEventListener('input', () => setFrame(Number(slider.value)));
  let timer = null;
  play.addEventListener('click', () => {
    if (timer) {
      clearInterval(timer);
      timer = null;
      play.textContent = 'Play';
      return;
    }
    play.textContent = 'Pause';
    timer = setInterval(() => setFrame((current + 1) % f.shown.length), 1000 / 6);
  });
  drawAxes();
  setFrame(0);
  return { section, setFrame };
}
