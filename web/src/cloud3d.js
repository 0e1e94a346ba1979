// Section 4: the 3D view — the returns (coloured by class, range or height), the flight path and
// the scene's wires, with orbit (drag), zoom (wheel) and pan (right drag). Rendered on demand
// (only when the view changes), so a page with millions of points stays idle between moves.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { CLASS_NAMES, classRgb, css, formatNumber, rampRgb } from './colours.js';
import { el } from './summary.js';

const WIDTH = 900;
const HEIGHT = 600;

export function cloudSection(meta, points, step) {
  const section = el('section', { id: 'cloud' }, el('h2', {}, '3D view'));
  const cloud = meta.cloud;
  const colourBy = el('select', { id: 'cloud-colour' },
    el('option', { value: 'class' }, 'colour by class'),
    el('option', { value: 'range' }, 'colour by range'),
    el('option', { value: 'height' }, 'colour by height'));
  const size = el('input', { type: 'range', id: 'cloud-size', min: 1, max: 6, value: 2, step: 1 });
  const reset = el('button', { type: 'button', id: 'cloud-reset' }, 'Reset view');
  const shown = cloud.total > cloud.shown
    ? `${formatNumber(cloud.shown)} of ${formatNumber(cloud.total)} returns shown (see the notes for which).`
    : `${formatNumber(cloud.shown)} returns.`;
  section.append(el('div', { class: 'controls' }, colourBy, el('label', {}, 'point size ', size), reset),
    el('p', { class: 'caption', id: 'cloud-caption' }, `${shown} Drag to orbit, wheel to zoom, right-drag to pan. Magenta: flight path; white: the scene's wires. Positions to ${formatNumber(Math.max(...step) * 100, 1)} cm.`));
  // The class colours of the classes the cloud holds (noise: false returns).
  section.append(el('div', { class: 'legend', id: 'cloud-legend' },
    ...Object.keys(cloud.by_class ?? {}).map((name) => {
      const s = el('span', { class: 'swatch' });
      s.style.background = css(classRgb(CLASS_NAMES.indexOf(name)));
      return el('span', { class: 'legend-item' }, s, name);
    })));
  const holder = el('div', { class: 'gl-holder', id: 'cloud-holder' });
  section.append(holder);

  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
  } catch (error) {
    holder.append(el('p', { class: 'empty' }, `No 3D view: this browser offers no WebGL (${error.message}).`));
    return { section, orbit: () => {} };
  }
  renderer.setPixelRatio(1);
  renderer.setSize(WIDTH, HEIGHT);
  renderer.setClearColor(0x101418);
  renderer.domElement.id = 'cloud-canvas';
  holder.append(renderer.domElement);

  // Everything relative to the centre of the points' box (float32 keeps millimetres there).
  const centre = [0, 1, 2].map((a) => (cloud.box_min[a] + cloud.box_max[a]) / 2);
  const scene = new THREE.Scene();
  const n = points.n;
  const positions = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) {
    for (let a = 0; a < 3; a++) positions[3 * i + a] = cloud.box_min[a] + points.xyz[3 * i + a] * step[a] - centre[a];
  }
  const colours = new Uint8Array(3 * n);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3, true));
  const material = new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: true });
  scene.add(new THREE.Points(geometry, material));

  const addLine = (xyz, colour) => {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(xyz), 3));
    scene.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: colour })));
  };
  const traj = meta.trajectory;
  if (traj) {
    const xyz = [];
    traj.e_m.forEach((e, i) => xyz.push(e - centre[0], traj.n_m[i] - centre[1], traj.u_m[i] - centre[2]));
    addLine(xyz, 0xff00ff);
  }
  if (meta.scene) {
    for (const w of meta.scene.wires) addLine(w.points.flatMap((p) => [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]]), 0xeeeeee);
  }

  const heightSpan = Math.max(cloud.box_max[2] - cloud.box_min[2], 1e-6);
  function paint(mode) {
    for (let i = 0; i < n; i++) {
      let rgb;
      if (mode === 'class') rgb = classRgb(points.surface[i]);
      else if (mode === 'range') rgb = points.rangeDm[i] > 0 ? rampRgb(points.rangeDm[i] / 10 / meta.sensor.timeout_range_m * 2) : [128, 128, 128];
      else rgb = rampRgb(1 - points.xyz[3 * i + 2] * step[2] / heightSpan);
      colours[3 * i] = rgb[0];
      colours[3 * i + 1] = rgb[1];
      colours[3 * i + 2] = rgb[2];
    }
    geometry.attributes.color.needsUpdate = true;
  }

  const extent = Math.max(cloud.box_max[0] - cloud.box_min[0], cloud.box_max[1] - cloud.box_min[1], 50);
  const camera = new THREE.PerspectiveCamera(50, WIDTH / HEIGHT, extent / 1e4, extent * 20);
  camera.up.set(0, 0, 1);
  const home = () => {
    camera.position.set(-0.3 * extent, -0.45 * extent, 0.3 * extent);
    controls.target.set(0, 0, 0);
    controls.update();
  };
  const controls = new OrbitControls(camera, renderer.domElement);
  let frames = 0;
  const render = () => {
    renderer.render(scene, camera);
    frames += 1;
    renderer.domElement.dataset.renders = String(frames);
    renderer.domElement.dataset.azimuth = controls.getAzimuthalAngle().toFixed(4);
  };
  controls.addEventListener('change', render);
  home();
  paint('class');
  colourBy.addEventListener('change', () => { paint(colourBy.value); render(); });
  size.addEventListener('input', () => { material.size = Number(size.value); render(); });
  reset.addEventListener('click', () => { home(); render(); });
  render();
  return {
    section,
    // Turns the view about the vertical by `radians` (the test drives the 3D view through it too).
    orbit: (radians) => {
      const offset = camera.position.clone().sub(controls.target);
      offset.applyAxisAngle(new THREE.Vector3(0, 0, 1), radians);
      camera.position.copy(controls.target).add(offset);
      controls.update();
      render();
    },
  };
}
