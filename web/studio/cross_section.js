// A span's cross-section against the ground (scene_view.cpp span_section): its conductors and
// the terrain under the line between its supports, heights in metres over distance along it.
export function drawCrossSection(canvas, section) {
  const g = canvas.getContext('2d');
  const { width, height } = canvas;
  g.clearRect(0, 0, width, height);
  if (!section) return;
  const ground = section.ground.filter(([, u]) => u !== null);
  const heights = [...ground.map(([, u]) => u), ...section.conductors.flatMap((c) => c.line.map(([, u]) => u))];
  if (heights.length === 0) return;
  const lo = Math.min(...heights) - 2;
  const hi = Math.max(...heights) + 2;
  const left = 40;
  const right = width - 8;
  const top = 6;
  const bottom = height - 16;
  const x = (d) => left + (d / Math.max(1, section.length_m)) * (right - left);
  const y = (u) => bottom - ((u - lo) / (hi - lo)) * (bottom - top);
  g.fillStyle = '#d9c9a3';
  g.beginPath();
  g.moveTo(x(0), bottom);
  for (const [d, u] of ground) g.lineTo(x(d), y(u));
  g.lineTo(x(section.length_m), bottom);
  g.closePath();
  g.fill();
  g.strokeStyle = '#c0392b';
  g.lineWidth = 1.5;
  for (const conductor of section.conductors) {
    g.beginPath();
    conductor.line.forEach(([d, u], k) => (k === 0 ? g.moveTo(x(d), y(u)) : g.lineTo(x(d), y(u))));
    g.stroke();
  }
  g.fillStyle = '#333';
  g.font = '11px system-ui, sans-serif';
  g.fillText(`${Math.round(hi)} m`, 2, top + 9);
  g.fillText(`${Math.round(lo)} m`, 2, bottom);
  g.fillText(`${Math.round(section.length_m)} m along the span`, left, height - 3);
}
