// The studio keeps a hand-written scenario's meaning (web/studio/scenario_doc.js): every bundled
// example opened and written back unchanged parses to the same data, and keeps its comments and
// key order (the spaces that align comments into a column are not kept); then an edit changes
// only the key it names.
//   node tests/web/scenario_doc_roundtrip.mjs EXAMPLES_DIR
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { isDeepStrictEqual } from 'node:util';
import { parse } from '../../web/node_modules/yaml/dist/index.js';
import { ScenarioDoc } from '../../web/studio/scenario_doc.js';

const dir = process.argv[2];
const failures = [];
let identical = 0;
const files = readdirSync(dir).filter((name) => name.endsWith('.yaml'));
for (const name of files) {
  const text = readFileSync(join(dir, name), 'utf8');
  const written = new ScenarioDoc(text).text();
  if (!isDeepStrictEqual(parse(written), parse(text))) failures.push(`${name}: its meaning changed`);
  // Every comment's text, in order (the library may move a comment after a list's key to the
  // line below it, and it does not keep the spaces that aligned comments into a column).
  const comments = (t) => t.split('\n').map((l) => /(?:^|\s)(#.*)$/.exec(l)?.[1]).filter(Boolean);
  if (!isDeepStrictEqual(comments(written), comments(text))) failures.push(`${name}: comments lost`);
  const keys = (t) => Object.keys(parse(t));
  if (!isDeepStrictEqual(keys(written), keys(text))) failures.push(`${name}: key order changed`);
  if (written === text) identical += 1;
  // An edit changes the key it names and nothing else (a sweep file has no trajectory).
  if (!parse(text).trajectory) continue;
  const doc = new ScenarioDoc(text);
  doc.set(['trajectory', 'duration_s'], 12.5);
  const before = parse(text);
  const after = parse(doc.text());
  if (after.trajectory.duration_s !== 12.5) failures.push(`${name}: the edit did not take`);
  after.trajectory.duration_s = before.trajectory.duration_s;
  if (before.trajectory.duration_s === undefined) delete after.trajectory.duration_s;
  if (!isDeepStrictEqual(after, before)) failures.push(`${name}: the edit changed other keys`);
}
console.log(JSON.stringify({ files: files.length, byte_identical: identical }));
if (files.length < 5) failures.push(`only ${files.length} examples found in ${dir}`);
if (failures.length > 0) {
  console.error(failures.join('\n'));
  process.exit(1);
}
