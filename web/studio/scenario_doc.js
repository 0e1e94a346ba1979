// The scenario's YAML as a document that keeps what the user wrote — key order, comments, the
// form of each value — and changes only the keys an edit names (the `yaml` package's Document).
import { parseDocument, isMap, isSeq } from 'yaml';

export class ScenarioDoc {
  constructor(text) {
    this.doc = parseDocument(text);
    if (this.doc.errors.length > 0) throw new Error(this.doc.errors[0].message);
  }

  text() {
    return this.doc.toString({ lineWidth: 0, flowCollectionPadding: false });
  }

  get(path) {
    const node = this.doc.getIn(path, false);
    return node && typeof node.toJSON === 'function' ? node.toJSON() : node;
  }

  set(path, value) {
    this.doc.setIn(path, this.doc.createNode(value, { flow: typeof value === 'object' }));
  }

  // A flow-style map node ({lat: …, lon: …}) as a user would type it.
  flow(value) {
    const node = this.doc.createNode(value);
    node.flow = true;
    return node;
  }

  // Appends `item` to the list at `path` (made when absent); returns its index.
  append(path, item) {
    const list = this.doc.getIn(path, true);
    const node = this.doc.createNode(item);
    node.flow = true;
    if (!isSeq(list)) {
      this.doc.setIn(path, this.doc.createNode([]));
      this.doc.getIn(path, true).items.push(node);
      return 0;
    }
    list.items.push(node);
    return list.items.length - 1;
  }

  remove(path) {
    this.doc.deleteIn(path);
  }

  // The items of the list at `path` (plain values), [] when absent.
  list(path) {
    const node = this.doc.getIn(path, true);
    return isSeq(node) ? node.toJSON() : [];
  }

  // A position key written as {lat, lon}, keeping other keys of a map (h) when it was one.
  setPosition(path, [lat, lon]) {
    const node = this.doc.getIn(path, true);
    const position = { lat: round(lat, 8), lon: round(lon, 8) };
    if (isMap(node) && node.has('h')) position.h = node.get('h');
    this.doc.setIn(path, this.flow(position));
  }
}

export function round(value, digits) {
  const scale = 10 ** digits;
  return Math.round(value * scale) / scale;
}

// A new id for the list at `path`: `prefix-N`, the first N not taken.
export function freshId(doc, path, prefix) {
  const taken = new Set(doc.list(path).map((item) => item && item.id));
  for (let n = 1; ; n += 1) {
    if (!taken.has(`${prefix}-${n}`)) return `${prefix}-${n}`;
  }
}
