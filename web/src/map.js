// Section 3: the map — top-down, east right and north up, local ENU metres from the scenario
// origin: the returns (by class), the scene's objects when the page has them, the flight path;
// with a scale bar, a north arrow, the cursor's coordinates, wheel/button zoom and drag pan.
import { classRgb, css, formatNumber, niceStep } from './colours.js';
import { el } from './summary.js';

const WIDTH = 900;
const HEIGHT = 640;
// ground, building, unknown, fog, tree, pole, wire; false returns (noise, 6) are no places, as on
// the quick-look map: not drawn.
const DRAW_ORDER = [3, 4, 255, 5, 2, 1, 0];
// The warnings' marks (detections.csv), pure colours the tests find on the canvas.
const WARNING_COLOURS = { wire: '#ff2020', pole: '#ffffff', tree: '#40ff40' };

export function mapSection(meta, points, step) {
  const section = el('section', { id: 'map' }, el('h2', {}, 'Map'));
  const canvas = el('canvas', { id: 'map-canvas', width: WIDTH, height: HEIGHT });
  const ctx = canvas.getContext('2d');
  canvas.setAttribute('role', 'img');
  canvas.setAttribute('aria-label', 'Map: east right, north up (north arrow), scale bar in metres, coordinates E and N in metres from the scenario origin');
  const zoomIn = el('button', { type: 'button', id: 'map-zoom-in' }, '+');
  const zoomOut = el('button', { type: 'button', id: 'map-zoom-out' }, '−');
  const reset = el('button', { type: 'button', id: 'map-reset' }, 'Reset');
  const cursor = el('span', { id: 'map-cursor', class: 'hover' }, 'E — N — m');
  section.append(el('div', { class: 'controls' }, zoomIn, zoomOut, reset, cursor), canvas,
    el('p', { class: 'caption' }, 'East right, north up; coordinates in metres east (E) and north (N) of the scenario origin; false returns (noise) are not drawn. Wheel or buttons zoom, drag pans.' +
      (meta.warnings ? ` Warnings (detections.csv, ${meta.warnings.tracks_total} tracks): × wire, ◇ pole, △ tree, where each track was last reported.` : '')));

  // The extent: returns, flight path and scene objects.
  let e0 = Infinity, e1 = -Infinity, n0 = Infinity, n1 = -Infinity;
  const extend = (e, n) => {
    if (!Number.isFinite(e) || !Number.isFinite(n)) return;
    e0 = Math.min(e0, e); e1 = Math.max(e1, e); n0 = Math.min(n0, n); n1 = Math.max(n1, n);
  };
  const cloud = meta.cloud;
  if (points.n > 0) {
    extend(cloud.box_min[0], cloud.box_min[1]);
    extend(cloud.box_max[0], cloud.box_max[1]);
  }
  const traj = meta.trajectory;
  if (traj) traj.e_m.forEach((e, i) => extend(e, traj.n_m[i]));
  const scene = meta.scene;
  if (scene) {
    scene.wires.forEach((w) => w.points.forEach((p) => extend(p[0], p[1])));
    scene.cylinders.forEach((c) => extend(c[0], c[1]));
  }
  if (!Number.isFinite(e0)) { e0 = -50; e1 = 50; n0 = -50; n1 = 50; }
  const margin = 0.04 * Math.max(e1 - e0, n1 - n0, 10);
  const home = {
    cx: (e0 + e1) / 2,
    cy: (n0 + n1) / 2,
    scale: Math.min(WIDTH / (e1 - e0 + 2 * margin), HEIGHT / (n1 - n0 + 2 * margin)),  // px per m
  };
  let view = { ...home };
  const toPx = (e, n) => [WIDTH / 2 + (e - view.cx) * view.scale, HEIGHT / 2 - (n - view.cy) * view.scale];
  const toWorld = (x, y) => [view.cx + (x - WIDTH / 2) / view.scale, view.cy - (y - HEIGHT / 2) / view.scale];

  const pixels = new ImageData(WIDTH, HEIGHT);
  const pixel32 = new Uint32Array(pixels.data.buffer);
  const classColour32 = {};
  const colour32 = (code) => {
    if (!(code in classColour32)) {
      const [r, g, b] = classRgb(code);
      classColour32[code] = (255 << 24) | (b << 16) | (g << 8) | r;
    }
    return classColour32[code];
  };

  function drawPoints() {
    pixel32.fill(0xff2e3a2e);  // dark green-grey ground
    for (const code of DRAW_ORDER) {
      const colour = colour32(code);
      const size = code <= 2 ? 1 : 0;  // wires, poles and trees as 3 px dots
      for (let i = 0; i < points.n; i++) {
        if (points.surface[i] !== code) continue;
        const e = cloud.box_min[0] + points.xyz[3 * i] * step[0];
        const n = cloud.box_min[1] + points.xyz[3 * i + 1] * step[1];
        const x = Math.round(WIDTH / 2 + (e - view.cx) * view.scale);
        const y = Math.round(HEIGHT / 2 - (n - view.cy) * view.scale);
        for (let dy = -size; dy <= size; dy++) {
          for (let dx = -size; dx <= size; dx++) {
            const px = x + dx, py = y + dy;
            if (px >= 0 && py >= 0 && px < WIDTH && py < HEIGHT) pixel32[py * WIDTH + px] = colour;
          }
        }
      }
    }
    ctx.putImageData(pixels, 0, 0);
  }

  function drawScene() {
    if (!scene) return;
    ctx.strokeStyle = 'rgba(235,235,235,0.9)';
    ctx.lineWidth = 1;
    for (const w of scene.wires) {
      ctx.beginPath();
      w.points.forEach((p, i) => { const [x, y] = toPx(p[0], p[1]); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
      ctx.stroke();
    }
    for (const c of scene.cylinders) {
      const [x, y] = toPx(c[0], c[1]);
      const r = Math.max(c[4] * view.scale, c[5] === 1 ? 2 : 1.5);
      ctx.beginPath();
      ctx.arc(x, y, r, 0, 2 * Math.PI);
      ctx.strokeStyle = c[5] === 1 ? '#fff' : 'rgba(30,110,45,0.9)';
      ctx.stroke();
    }
    ctx.strokeStyle = css(classRgb(4));
    for (const m of scene.meshes) {
      const [x0, y0] = toPx(m.box[0], m.box[1]);
      const [x1, y1] = toPx(m.box[3], m.box[4]);
      ctx.strokeRect(x0, y1, x1 - x0, y0 - y1);
    }
  }

  // The detector's warned tracks where they were last reported, by class: a wire as a red bar
  // across, a pole as a white diamond, a tree as a green triangle (other classes: a grey ring).
  const warnings = meta.warnings ? meta.warnings.tracks : [];
  function drawWarnings() {
    ctx.lineWidth = 2;
    const drawn = { wire: 0, pole: 0, tree: 0, other: 0 };
    for (const w of warnings) {
      const [x, y] = toPx(w.e_m, w.n_m);
      if (x < -8 || y < -8 || x > WIDTH + 8 || y > HEIGHT + 8) continue;
      drawn[w.class in drawn ? w.class : 'other']++;
      ctx.beginPath();
      if (w.class === 'wire') {
        ctx.strokeStyle = WARNING_COLOURS.wire;
        ctx.moveTo(x - 6, y - 6); ctx.lineTo(x + 6, y + 6);
        ctx.moveTo(x - 6, y + 6); ctx.lineTo(x + 6, y - 6);
      } else if (w.class === 'pole') {
        ctx.strokeStyle = WARNING_COLOURS.pole;
        ctx.moveTo(x, y - 6); ctx.lineTo(x + 6, y); ctx.lineTo(x, y + 6); ctx.lineTo(x - 6, y); ctx.closePath();
      } else if (w.class === 'tree') {
        ctx.strokeStyle = WARNING_COLOURS.tree;
        ctx.moveTo(x, y - 6); ctx.lineTo(x + 6, y + 5); ctx.lineTo(x - 6, y + 5); ctx.closePath();
      } else {
        ctx.strokeStyle = '#aaa';
        ctx.arc(x, y, 5, 0, 2 * Math.PI);
      }
      ctx.stroke();
    }
    ctx.lineWidth = 1;
    canvas.dataset.warnings = JSON.stringify(drawn);  // what the tests read
  }

  function drawTrajectory() {
    if (!traj || traj.e_m.length === 0) return;
    ctx.strokeStyle = '#ff00ff';
    ctx.lineWidth = 3;
    ctx.beginPath();
    traj.e_m.forEach((e, i) => { const [x, y] = toPx(e, traj.n_m[i]); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
    ctx.stroke();
    const [sx, sy] = toPx(traj.e_m[0], traj.n_m[0]);
    ctx.fillStyle = '#ff00ff';
    ctx.beginPath();
    ctx.arc(sx, sy, 5, 0, 2 * Math.PI);
    ctx.fill();
    ctx.lineWidth = 1;
  }

  function drawFurniture() {
    // Scale bar, bottom left.
    const metres = niceStep(WIDTH / 5 / view.scale, 1);
    const length = metres * view.scale;
    ctx.fillStyle = 'rgba(255,255,255,0.85)';
    ctx.fillRect(10, HEIGHT - 44, length + 20, 34);
    ctx.fillStyle = '#000';
    ctx.fillRect(20, HEIGHT - 20, length, 4);
    ctx.fillRect(20, HEIGHT - 26, 2, 10);
    ctx.fillRect(20 + length - 2, HEIGHT - 26, 2, 10);
    ctx.font = '12px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'bottom';
    ctx.fillText(metres >= 1000 ? `${formatNumber(metres / 1000)} km` : `${formatNumber(metres)} m`, 20 + length / 2, HEIGHT - 26);
    canvas.dataset.scaleBar = String(metres);
    // North arrow, top right.
    const ax = WIDTH - 34, ay = 18;
    ctx.fillStyle = 'rgba(255,255,255,0.85)';
    ctx.fillRect(ax - 20, ay - 8, 40, 62);
    ctx.fillStyle = '#000';
    ctx.beginPath();
    ctx.moveTo(ax, ay + 4);
    ctx.lineTo(ax - 9, ay + 30);
    ctx.lineTo(ax, ay + 24);
    ctx.lineTo(ax + 9, ay + 30);
    ctx.closePath();
    ctx.fill();
    ctx.font = 'bold 14px sans-serif';
    ctx.textBaseline = 'top';
    ctx.fillText('N', ax, ay + 34);
    // Corner coordinates.
    const [le, tn] = toWorld(0, 0);
    const [re, bn] = toWorld(WIDTH, HEIGHT);
    ctx.font = '11px sans-serif';
    ctx.fillStyle = 'rgba(255,255,255,0.9)';
    ctx.textAlign = 'left';
    ctx.fillText(`E ${formatNumber(le)} N ${formatNumber(tn)}`, 6, 4);
    ctx.textAlign = 'right';
    ctx.textBaseline = 'bottom';
    ctx.fillText(`E ${formatNumber(re)} N ${formatNumber(bn)}`, WIDTH - 6, HEIGHT - 4);
  }

  function draw() {
    drawPoints();
    drawScene();
    drawWarnings();
    drawTrajectory();
    drawFurniture();
    canvas.dataset.scale = String(view.scale);
  }

  const zoomAbout = (factor, x, y) => {
    const [e, n] = toWorld(x, y);
    view.scale = Math.min(1e4, Math.max(1e-4, view.scale * factor));
    view.cx = e - (x - WIDTH / 2) / view.scale;
    view.cy = n + (y - HEIGHT / 2) / view.scale;
    draw();
  };
  const canvasXY = (event) => {
    const rect = canvas.getBoundingClientRect();
    return [(event.clientX - rect.left) * WIDTH / rect.width, (event.clientY - rect.top) * HEIGHT / rect.height];
  };
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    const [x, y] = canvasXY(event);
    zoomAbout(event.deltaY < 0 ? 1.25 : 0.8, x, y);
  }, { passive: false });
  zoomIn.addEventListener('click', () => zoomAbout(1.5, WIDTH / 2, HEIGHT / 2));
  zoomOut.addEventListener('click', () => zoomAbout(1 / 1.5, WIDTH / 2, HEIGHT / 2));
  reset.addEventListener('click', () => { view = { ...home }; draw(); });
  let drag = null;
  canvas.addEventListener('mousedown', (event) => { drag = { xy: canvasXY(event), cx: view.cx, cy: view.cy }; });
  window.addEventListener('mouseup', () => { drag = null; });
  canvas.addEventListener('mousemove', (event) => {
    const [x, y] = canvasXY(event);
    const [e, n] = toWorld(x, y);
    cursor.textContent = `E ${formatNumber(e, 1)} N ${formatNumber(n, 1)} m`;
    if (!drag) return;
    view.cx = drag.cx - (x - drag.xy[0]) / view.scale;
    view.cy = drag.cy + (y - drag.xy[1]) / view.scale;
    draw();
  });
  draw();
  return { section, zoom: (factor) => zoomAbout(factor, WIDTH / 2, HEIGHT / 2) };
}
