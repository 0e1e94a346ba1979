// What the page carries (io/report/report_page.hpp): the JSON meta element and the two
// deflate + base64 blobs, unpacked with the browser's own DecompressionStream.

export function readMeta() {
  return JSON.parse(document.getElementById('owsim-meta').textContent);
}

export async function inflateBlob(id) {
  const text = document.getElementById(id).textContent.trim();
  if (!text) return null;
  const binary = atob(text);
  const packed = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) packed[i] = binary.charCodeAt(i);
  const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream('deflate'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// The 3D points: 3 × uint16 positions, uint16 ranges (dm), uint8 classes (report_cloud.hpp).
export function unpackCloud(bytes, cloud) {
  const n = cloud.shown;
  if (!bytes || n === 0) return { n: 0, xyz: new Uint16Array(0), rangeDm: new Uint16Array(0), surface: new Uint8Array(0) };
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const xyz = new Uint16Array(3 * n);
  for (let i = 0; i < 3 * n; i++) xyz[i] = view.getUint16(2 * i, true);
  const rangeDm = new Uint16Array(n);
  for (let i = 0; i < n; i++) rangeDm[i] = view.getUint16(6 * n + 2 * i, true);
  const surface = bytes.slice(8 * n, 9 * n);
  return { n, xyz, rangeDm, surface };
}

// Position of point i in local ENU metres.
export function cloudStep(cloud) {
  return [0, 1, 2].map((a) => (cloud.box_max[a] - cloud.box_min[a]) / 65535 || 0);
}
