// The studio server's JSON API (studio/studio_server.cpp). The session token travels as the
// cookie the page set; every call is same-origin.
async function call(method, path, body) {
  const response = await fetch(path, {
    method,
    credentials: 'same-origin',
    headers: body === undefined ? {} : { 'Content-Type': 'text/plain; charset=utf-8' },
    body,
  });
  const text = await response.text();
  try {
    return JSON.parse(text);
  } catch {
    return { ok: false, problem: { message: text.trim() || `HTTP ${response.status}` } };
  }
}

export const session = () => call('GET', '/api/session');
export const view = (yaml) => call('POST', '/api/view', yaml);
export const save = (yaml) => call('POST', '/api/save', yaml);
export const fly = (yaml) => call('POST', '/api/fly', yaml);
export const runStatus = () => call('GET', '/api/run');
export const models = () => call('GET', '/api/models');
export const cancel = () => call('POST', '/api/cancel', '');
export const enu = (origin, points) =>
  call('POST', '/api/enu', JSON.stringify({ origin, points }));
