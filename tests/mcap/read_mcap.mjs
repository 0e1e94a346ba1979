// read_mcap.mjs SAMPLE_PROGRAM DIR: runs tests/mcap/mcap_sample.cpp's program into DIR, then
// reads DIR/flight.mcap with the reference readers — npm's @mcap/core (the indexed reader through
// the summary, CRCs validated, and the stream reader over every record) and
// @foxglove/rosmsg2-serialization (each message decoded against the file's own ros2msg schema,
// parsed by @foxglove/rosmsg) — and compares every value with DIR/expected.json. Exit 0 when all
// agree; otherwise the first difference.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { isDeepStrictEqual } from 'node:util';
import { crc32 } from 'node:zlib';

import { decompressHandlers } from './zstd_handlers.mjs';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { McapIndexedReader, McapStreamReader } = require('@mcap/core');
const { MessageReader } = require('@foxglove/rosmsg2-serialization');
const { parse } = require('@foxglove/rosmsg');
const YAML = require('yaml');

const [program, dir] = process.argv.slice(2);
execFileSync(program, [dir], { stdio: 'inherit' });
const bytes = new Uint8Array(readFileSync(join(dir, 'flight.mcap')));
const expected = JSON.parse(readFileSync(join(dir, 'expected.json'), 'utf8'));

let failures = 0;
function check(condition, what) {
  if (!condition) {
    failures += 1;
    console.error(`FAIL: ${what}`);
  }
}
function plain(value) {  // typed arrays as arrays, bigints as strings, recursively
  if (ArrayBuffer.isView(value)) return Array.from(value);
  if (typeof value === 'bigint') return value.toString();
  if (Array.isArray(value)) return value.map(plain);
  if (value && typeof value === 'object') {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, plain(v)]));
  }
  return value;
}
// The first path where two values differ, or null.
function difference(actual, wanted, path = '') {
  if (typeof wanted === 'number' && typeof actual === 'number') {
    return actual === wanted || (Number.isNaN(actual) && Number.isNaN(wanted))
      ? null : `${path}: ${actual} != ${wanted}`;
  }
  if (wanted && typeof wanted === 'object') {
    if (!actual || typeof actual !== 'object') return `${path}: ${JSON.stringify(actual)} is not an object`;
    const keys = new Set([...Object.keys(wanted), ...Object.keys(actual)]);
    for (const key of keys) {
      if (!(key in actual)) return `${path}.${key}: missing`;
      if (!(key in wanted)) return `${path}.${key}: unexpected`;
      const found = difference(actual[key], wanted[key], `${path}.${key}`);
      if (found) return found;
    }
    return null;
  }
  return isDeepStrictEqual(actual, wanted) ? null : `${path}: ${JSON.stringify(actual)} != ${JSON.stringify(wanted)}`;
}


// Every record from the start, CRCs validated (chunks, data section, summary).
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true, includeChunks: true });
stream.append(bytes);
const kinds = [];
for (let record; (record = stream.nextRecord()); ) kinds.push(record.type);
check(stream.done(), 'the stream reader reached the trailing magic');
const dataKinds = kinds.slice(0, kinds.indexOf('DataEnd') + 1).filter((k) => k !== 'Schema' && k !== 'Channel' && k !== 'Message');
check(dataKinds[0] === 'Header', `the file starts with a Header (${dataKinds[0]})`);
for (let i = 0; i < dataKinds.length; i++) {
  if (dataKinds[i] === 'Chunk') check(dataKinds[i + 1] === 'MessageIndex', `chunk ${i} is followed by its message indexes`);
}

const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
check(reader.header.profile === 'ros2', `profile ${reader.header.profile}`);
check(/^owsim \d/.test(reader.header.library), `library ${reader.header.library}`);
// The CRCs against node's own zlib: data section up to Data End, summary through the footer's
// summary_offset_start.
const dataEnd = Number(reader.dataEndOffset);
check(reader.dataSectionCrc === crc32(bytes.subarray(0, dataEnd)), 'data section CRC');
const footerAt = bytes.length - 8 - 29;
check(reader.footer.summaryCrc === crc32(bytes.subarray(Number(reader.footer.summaryStart), footerAt + 25)), 'summary CRC');
check(reader.chunkIndexes.length === expected.chunks && expected.chunks > 1,
  `${reader.chunkIndexes.length} chunk indexes for ${expected.chunks} chunks`);
check(reader.chunkIndexes.every((c) => c.compression === 'zstd' && c.messageIndexOffsets.size > 0),
  'every chunk zstd-compressed and message-indexed');
check(reader.statistics.chunkCount === expected.chunks, 'statistics: chunk count');
check(Number(reader.statistics.messageCount) === expected.messages.length, 'statistics: message count');

// Channels and schemas.
const decoders = new Map();
for (const [id, channel] of reader.channelsById) {
  const topic = expected.topics[channel.topic];
  check(topic !== undefined, `unexpected topic ${channel.topic}`);
  const schema = reader.schemasById.get(channel.schemaId);
  check(schema.name === topic.type && schema.encoding === 'ros2msg', `${channel.topic}: schema ${schema.name} ${schema.encoding}`);
  check(channel.messageEncoding === 'cdr', `${channel.topic}: encoding ${channel.messageEncoding}`);
  const qos = YAML.parse(channel.metadata.get('offered_qos_profiles'));
  check(Array.isArray(qos) && qos.length === 1 && qos[0].durability === (topic.latched ? 1 : 2) &&
        qos[0].reliability === 1 && qos[0].history === 1,
        `${channel.topic}: offered_qos_profiles ${JSON.stringify(qos)}`);
  const text = new TextDecoder().decode(schema.data);
  decoders.set(id, new MessageReader(parse(text, { ros2: true })));
}
check(decoders.size === Object.keys(expected.topics).length, 'one channel per topic');

// Every message through the index, in log-time order, decoded and compared in each channel's
// sequence order with what was written.
const byTopic = new Map();
for await (const message of reader.readMessages({ validateCrcs: true })) {
  const topic = reader.channelsById.get(message.channelId).topic;
  if (!byTopic.has(topic)) byTopic.set(topic, []);
  byTopic.get(topic).push(message);
}
for (const [topic, list] of byTopic) list.sort((a, b) => a.sequence - b.sequence);
const written = new Map();
for (const entry of expected.messages) {
  if (!written.has(entry.topic)) written.set(entry.topic, []);
  written.get(entry.topic).push(entry);
}
let points = 0;
for (const [topic, wanted] of written) {
  const read = byTopic.get(topic) ?? [];
  check(read.length === wanted.length, `${topic}: ${read.length} messages read, ${wanted.length} written`);
  for (let i = 0; i < Math.min(read.length, wanted.length); i++) {
    check(read[i].sequence === i, `${topic}: sequence ${read[i].sequence} at ${i}`);
    check(read[i].logTime.toString() === wanted[i].log_time && read[i].publishTime === read[i].logTime,
      `${topic}[${i}]: log time ${read[i].logTime}`);
    const decoder = decoders.get(read[i].channelId);
    const message = plain(decoder.readMessage(read[i].data));
    check(!decoder.lastReadHadTrailingBytes(), `${topic}[${i}]: trailing bytes after the message`);
    let want = wanted[i].message;
    if (topic === '/owsim/points') {  // unpack the cloud by its own fields
      const view = new DataView(Uint8Array.from(message.data).buffer);
      const read = { 1: 'getInt8', 2: 'getUint8', 3: 'getInt16', 4: 'getUint16', 5: 'getInt32', 6: 'getUint32', 7: 'getFloat32', 8: 'getFloat64' };
      const rows = [];
      for (let p = 0; p < message.width; p++) {
        rows.push(message.fields.map((f) => view[read[f.datatype]](p * message.point_step + f.offset, !message.is_bigendian)));
      }
      delete message.data;
      message.points = rows;
      points += rows.length;
      check(isDeepStrictEqual(message.fields.map((f) => f.name), ['x', 'y', 'z', 'intensity', 'ring', 'return', 'class', 'time']),
        'point fields');
    }
    const found = difference(message, want);
    check(found === null, `${topic}[${i}]${found}`);
  }
}
check(points > 0, 'points were compared');
if (failures > 0) {
  console.error(`${failures} checks failed`);
  process.exit(1);
}
console.log(`ok: ${expected.messages.length} messages on ${written.size} topics (${points} points) over ${expected.chunks} chunks read and decoded by @mcap/core and @foxglove/rosmsg2-serialization`);
