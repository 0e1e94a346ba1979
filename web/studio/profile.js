// The flight's profile under the map: height above the ground (or above the origin's height where
// the ground is unknown) and ground speed over time, the selected segment shaded, the cursor.
export function drawProfile(canvas, track, segment, cursorS) {
  const g = canvas.getContext('2d');
  const { width, height } = canvas;
  g.clearRect(0, 0, width, height);
  const t = track.t;
  if (t.length < 2) return;
  const heights = track.agl.map((v, k) => (v ?? track.h[k]));
  const left = 36;
  const right = width - 36;
  const top = 8;
  const bottom = height - 18;
  const x = (s) => left + ((s - track.start_s) / (track.end_s - track.start_s)) * (right - left);
  const range = (values) => {
    const finite = values.filter(Number.isFinite);
    const lo = Math.min(0, ...finite);
    const hi = Math.max(lo + 1, ...finite);
    return [lo, hi];
  };
  const [hLo, hHi] = range(heights);
  const [vLo, vHi] = range(track.speed);
  g.fillStyle = 'rgba(241, 196, 15, 0.25)';
  g.fillRect(x(segment.start), top, x(segment.end) - x(segment.start), bottom - top);
  const plot = (values, lo, hi, colour) => {
    g.strokeStyle = colour;
    g.lineWidth = 1.5;
    g.beginPath();
    values.forEach((v, k) => {
      const y = bottom - ((v - lo) / (hi - lo)) * (bottom - top);
      if (k === 0) g.moveTo(x(t[k]), y);
      else g.lineTo(x(t[k]), y);
    });
    g.stroke();
  };
  plot(heights, hLo, hHi, '#2c7fb8');
  plot(track.speed, vLo, vHi, '#d95f0e');
  g.fillStyle = '#333';
  g.font = '11px system-ui, sans-serif';
  g.fillText(`${Math.round(hHi)} m`, 2, top + 9);
  g.fillText(`${Math.round(hLo)} m`, 2, bottom);
  g.fillStyle = '#d95f0e';
  g.fillText(`${Math.round(vHi)} m/s`, right + 2, top + 9);
  g.fillStyle = '#333';
  g.fillText(`${track.start_s.toFixed(0)} s`, left, height - 4);
  g.fillText(`${track.end_s.toFixed(0)} s`, right - 30, height - 4);
  g.fillStyle = '#2c7fb8';
  g.fillText(track.agl.some((v) => v !== null) ? 'height above ground' : 'height', left + 50, height - 4);
  g.fillStyle = '#d95f0e';
  g.fillText('ground speed', left + 170, height - 4);
  if (Number.isFinite(cursorS)) {
    g.strokeStyle = '#000';
    g.beginPath();
    g.moveTo(x(cursorS), top);
    g.lineTo(x(cursorS), bottom);
    g.stroke();
  }
}
