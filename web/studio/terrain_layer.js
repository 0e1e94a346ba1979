// The ground under the flight when the scenario has a DEM or a height grid (scene_view.cpp
// terrain_view): a hillshade (light from the north-west, 45° up) as an image over the map, and
// contour lines by d3-contour at a round interval, labelled in metres. Nothing for flat ground.
import L from 'leaflet';
import { contours } from 'd3-contour';

// An interval of 1, 2 or 5 × 10^k metres giving about `count` lines over [lo, hi].
export function contourInterval(lo, hi, count = 12) {
  const raw = Math.max((hi - lo) / count, 1e-3);
  const power = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * power).find((step) => step >= raw);
}

export function terrainLayer(terrain) {
  const group = L.layerGroup();
  if (!terrain) return group;
  const { cols, rows, step_m: step, heights } = terrain;
  const at = (col, row) => heights[row * cols + col];  // row 0 south
  // Hillshade, north up: canvas row y is lattice row rows − 1 − y.
  const canvas = document.createElement('canvas');
  canvas.width = cols;
  canvas.height = rows;
  const g = canvas.getContext('2d');
  const image = g.createImageData(cols, rows);
  const azimuth = (315 * Math.PI) / 180;
  const altitude = (45 * Math.PI) / 180;
  for (let y = 0; y < rows; y += 1) {
    const row = rows - 1 - y;
    for (let col = 0; col < cols; col += 1) {
      const u = at(col, row);
      const pixel = 4 * (y * cols + col);
      if (u === null) continue;  // transparent: no ground known here
      const east = (at(Math.min(cols - 1, col + 1), row) ?? u) - (at(Math.max(0, col - 1), row) ?? u);
      const north = (at(col, Math.min(rows - 1, row + 1)) ?? u) - (at(col, Math.max(0, row - 1)) ?? u);
      const dzdx = east / (2 * step);
      const dzdy = north / (2 * step);
      const slope = Math.atan(Math.hypot(dzdx, dzdy));
      const aspect = Math.atan2(dzdy, -dzdx);
      const shade = Math.cos(altitude) * Math.cos(slope) +
        Math.sin(altitude) * Math.sin(slope) * Math.cos(azimuth - Math.PI / 2 - aspect);
      const v = Math.round(255 * Math.max(0, Math.min(1, shade)));
      image.data.set([v, v, v, 150], pixel);
    }
  }
  g.putImageData(image, 0, 0);
  const [[south, west], [north, east]] = terrain.bounds;
  L.imageOverlay(canvas.toDataURL('image/png'), [[south, west], [north, east]], { interactive: false, className: 'hillshade' })
    .addTo(group);
  // Contours over the same lattice, north row first as d3-contour reads an image.
  const values = new Float64Array(cols * rows);
  for (let y = 0; y < rows; y += 1) {
    for (let col = 0; col < cols; col += 1) values[y * cols + col] = at(col, rows - 1 - y) ?? NaN;
  }
  const interval = contourInterval(terrain.lowest_m, terrain.highest_m);
  const levels = [];
  for (let level = Math.ceil(terrain.lowest_m / interval) * interval; level <= terrain.highest_m; level += interval) levels.push(level);
  const toLatLng = ([x, y]) => [
    north - (Math.min(rows - 1, Math.max(0, y - 0.5)) / Math.max(1, rows - 1)) * (north - south),
    west + (Math.min(cols - 1, Math.max(0, x - 0.5)) / Math.max(1, cols - 1)) * (east - west),
  ];
  for (const contour of contours().size([cols, rows]).thresholds(levels)(values)) {
    for (const polygon of contour.coordinates) {
      for (const ring of polygon) {
        L.polyline(ring.map(toLatLng), { color: '#8d6e63', weight: 0.8, opacity: 0.8, interactive: false, className: 'contour' })
          .addTo(group);
      }
    }
  }
  group.contourInterval = interval;
  return group;
}
