// The page's colours: classes as the quick-look PNGs draw them (io/images/quicklook.hpp), and
// the range ramp, light = near, dark navy = far.

export const CLASS_NAMES = ['wire', 'pole', 'tree', 'ground', 'building', 'fog', 'noise'];
export const UNKNOWN = 255;

export const CLASS_RGB = {
  wire: [255, 40, 40],
  pole: [255, 150, 0],
  tree: [60, 220, 80],
  ground: [120, 136, 170],
  building: [200, 170, 130],
  fog: [200, 200, 255],
  noise: [255, 230, 0],
  unknown: [170, 170, 170],
};

export function classRgb(code) {
  return CLASS_RGB[CLASS_NAMES[code] ?? 'unknown'] ?? CLASS_RGB.unknown;
}

const RAMP = [
  [0.0, [236, 246, 255]],
  [0.25, [140, 200, 240]],
  [0.5, [60, 130, 210]],
  [0.75, [30, 70, 150]],
  [1.0, [10, 20, 70]],
];

// The ramp at f in 0..1 (clamped).
export function rampRgb(f) {
  const x = Math.min(1, Math.max(0, f));
  for (let i = 1; i < RAMP.length; i++) {
    if (x <= RAMP[i][0]) {
      const [x0, c0] = RAMP[i - 1];
      const [x1, c1] = RAMP[i];
      const t = (x - x0) / (x1 - x0);
      return [0, 1, 2].map((k) => Math.round(c0[k] + t * (c1[k] - c0[k])));
    }
  }
  return RAMP[RAMP.length - 1][1];
}

export const css = (rgb) => `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;

// Round tick steps: 1, 2 or 5 × 10^k, about `count` of them over `span`.
export function niceStep(span, count) {
  const raw = span / Math.max(1, count);
  const power = 10 ** Math.floor(Math.log10(raw));
  for (const m of [1, 2, 5, 10]) if (m * power >= raw) return m * power;
  return 10 * power;
}

export function formatNumber(value, digits = 0) {
  if (value === null || value === undefined || Number.isNaN(value)) return '—';
  return Number(value).toLocaleString('en-US', { minimumFractionDigits: digits, maximumFractionDigits: digits });
}
