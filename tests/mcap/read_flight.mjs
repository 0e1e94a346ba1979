// read_flight.mjs OWSIM SCENARIO DIR: flies SCENARIO for a few frames with
// `owsim run --outputs mcap,csv,trajectory` into DIR, then reads DIR/flight.mcap with the
// reference readers — npm's @mcap/core (indexed reader through the summary and stream reader over
// every record, CRCs validated) and @foxglove/rosmsg2-serialization (every message decoded against
// the file's own ros2msg schema) — and checks it against the run's own files: each frame's cloud
// holds exactly that frame's rows of points.csv, /tf and /owsim/nav the poses of trajectory.csv,
// /tf_static the scenario's mount, /owsim/scene a marker for every object the points name, and
// metadata.yaml the file's counts. Exit 0 when all agree; otherwise every difference found.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { crc32 } from 'node:zlib';

import { decompressHandlers } from './zstd_handlers.mjs';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { McapIndexedReader, McapStreamReader } = require('@mcap/core');
const { MessageReader } = require('@foxglove/rosmsg2-serialization');
const { parse } = require('@foxglove/rosmsg');
const YAML = require('yaml');

const FRAMES = 3;
const [owsim, scenario, dir] = process.argv.slice(2);
execFileSync(owsim, ['run', scenario, '--frames', String(FRAMES), '--outputs', 'mcap,csv,trajectory',
  '--out', dir, '--quiet'], { stdio: 'inherit' });
const bytes = new Uint8Array(readFileSync(join(dir, 'flight.mcap')));

let failures = 0;
function check(condition, what) {
  if (!condition) {
    failures += 1;
    if (failures <= 30) console.error(`FAIL: ${what}`);
  }
}
const near = (a, b, tolerance) => Math.abs(a - b) <= tolerance;

function csv(name) {
  const lines = readFileSync(join(dir, name), 'utf8').trimEnd().split('\n');
  const header = lines[0].split(',');
  return lines.slice(1).map((line) => Object.fromEntries(line.split(',').map((v, i) => [header[i], v])));
}
const pointRows = csv('points.csv');
const poses = csv('trajectory.csv');
const flown = YAML.parse(readFileSync(join(dir, 'scenario.yaml'), 'utf8'));

// ----- The file, record by record and through its summary, CRCs validated.
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true, includeChunks: true });
stream.append(bytes);
let records = 0;
for (let record; (record = stream.nextRecord()); ) records += 1;
check(stream.done() && records > 0, 'the stream reader reached the trailing magic');
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
check(reader.header.profile === 'ros2', `profile ${reader.header.profile}`);
check(reader.dataSectionCrc === crc32(bytes.subarray(0, Number(reader.dataEndOffset))), 'data section CRC');
// One chunk of schemas, channels and latched messages, then one a frame.
check(reader.chunkIndexes.length === FRAMES + 1, `${reader.chunkIndexes.length} chunks for ${FRAMES} frames`);

const topics = {
  '/owsim/points': 'sensor_msgs/msg/PointCloud2', '/tf': 'tf2_msgs/msg/TFMessage',
  '/owsim/nav': 'sensor_msgs/msg/NavSatFix', '/tf_static': 'tf2_msgs/msg/TFMessage',
  '/owsim/scene': 'visualization_msgs/msg/MarkerArray',
};
const latched = new Set(['/tf_static', '/owsim/scene']);
const decoders = new Map();
const topicOf = new Map();
for (const [id, channel] of reader.channelsById) {
  const schema = reader.schemasById.get(channel.schemaId);
  check(topics[channel.topic] === schema.name && schema.encoding === 'ros2msg' && channel.messageEncoding === 'cdr',
    `${channel.topic}: ${schema.name} ${schema.encoding} ${channel.messageEncoding}`);
  const qos = YAML.parse(channel.metadata.get('offered_qos_profiles'));
  check(qos[0].durability === (latched.has(channel.topic) ? 1 : 2), `${channel.topic}: durability ${qos[0].durability}`);
  decoders.set(id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
  topicOf.set(id, channel.topic);
}
check(decoders.size === Object.keys(topics).length, `${decoders.size} channels`);

const byTopic = new Map(Object.keys(topics).map((t) => [t, []]));
for await (const message of reader.readMessages({ validateCrcs: true })) {
  const decoder = decoders.get(message.channelId);
  const decoded = decoder.readMessage(message.data);
  check(!decoder.lastReadHadTrailingBytes(), `${topicOf.get(message.channelId)}: trailing bytes`);
  byTopic.get(topicOf.get(message.channelId)).push({ ...message, decoded });
}
for (const list of byTopic.values()) list.sort((a, b) => a.sequence - b.sequence);
const stampNs = (stamp) => BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec);

// ----- Poses: /tf and /owsim/nav against trajectory.csv, at each frame's start.
const rad = Math.PI / 180;
const mul = (a, b) => a.map((row) => [0, 1, 2].map((j) => row[0] * b[0][j] + row[1] * b[1][j] + row[2] * b[2][j]));
const transpose = (a) => [0, 1, 2].map((i) => [0, 1, 2].map((j) => a[j][i]));
const rx = (t) => [[1, 0, 0], [0, Math.cos(t), -Math.sin(t)], [0, Math.sin(t), Math.cos(t)]];
const ry = (t) => [[Math.cos(t), 0, Math.sin(t)], [0, 1, 0], [-Math.sin(t), 0, Math.cos(t)]];
const rz = (t) => [[Math.cos(t), -Math.sin(t), 0], [Math.sin(t), Math.cos(t), 0], [0, 0, 1]];
const flip = [[1, 0, 0], [0, -1, 0], [0, 0, -1]];  // body (x fwd, y right, z down) ↔ REP-103
const enuFromNed = [[0, 1, 0], [1, 0, 0], [0, 0, -1]];
const ecefFromEnu = (lat, lon) => {  // columns e, n, u at (lat, lon)
  const [p, l] = [lat * rad, lon * rad];
  return [[-Math.sin(l), -Math.sin(p) * Math.cos(l), Math.cos(p) * Math.cos(l)],
    [Math.cos(l), -Math.sin(p) * Math.sin(l), Math.cos(p) * Math.sin(l)],
    [0, Math.cos(p), Math.sin(p)]];
};
const fromQuaternion = ({ x, y, z, w }) => [
  [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]];
const sameRotation = (a, b, tolerance) => a.every((row, i) => row.every((v, j) => near(v, b[i][j], tolerance)));
const originToEcef = transpose(ecefFromEnu(flown.origin.lat, flown.origin.lon));

const tfs = byTopic.get('/tf');
const navs = byTopic.get('/owsim/nav');
check(tfs.length === FRAMES && navs.length === FRAMES && poses.length === FRAMES,
  `${tfs.length} /tf, ${navs.length} /owsim/nav, ${poses.length} trajectory rows for ${FRAMES} frames`);
for (let f = 0; f < Math.min(FRAMES, tfs.length, navs.length); f++) {
  const pose = poses[f];
  const timeNs = BigInt(Math.round(Number(pose.time_s) * 1e9));
  const [transform] = tfs[f].decoded.transforms;
  check(tfs[f].decoded.transforms.length === 1 && transform.header.frame_id === 'map' && transform.child_frame_id === 'base_link',
    `/tf[${f}]: ${transform.header.frame_id} → ${transform.child_frame_id}`);
  check(stampNs(transform.header.stamp) === timeNs && tfs[f].logTime === timeNs, `/tf[${f}]: stamp ${stampNs(transform.header.stamp)} at ${pose.time_s} s`);
  const t = transform.transform.translation;
  check(near(t.x, Number(pose.e_m), 5e-5) && near(t.y, Number(pose.n_m), 5e-5) && near(t.z, Number(pose.u_m), 5e-5),
    `/tf[${f}]: position ${t.x} ${t.y} ${t.z}`);
  const attitude = mul(mul(rz(Number(pose.heading_deg) * rad), ry(Number(pose.pitch_deg) * rad)), rx(Number(pose.roll_deg) * rad));
  const frameFromLocal = mul(originToEcef, ecefFromEnu(Number(pose.lat_deg), Number(pose.lon_deg)));
  const wanted = mul(mul(mul(frameFromLocal, enuFromNed), attitude), flip);
  check(sameRotation(fromQuaternion(transform.transform.rotation), wanted, 1e-8), `/tf[${f}]: rotation ${JSON.stringify(transform.transform.rotation)}`);

  const fix = navs[f].decoded;
  check(stampNs(fix.header.stamp) === timeNs && navs[f].logTime === timeNs, `/owsim/nav[${f}]: stamp`);
  check(near(fix.latitude, Number(pose.lat_deg), 5e-10) && near(fix.longitude, Number(pose.lon_deg), 5e-10) &&
        near(fix.altitude, Number(pose.h_m), 5e-5), `/owsim/nav[${f}]: ${fix.latitude} ${fix.longitude} ${fix.altitude}`);
  check(fix.status.status === 0 && fix.status.service === 1 && fix.position_covariance_type === 0,
    `/owsim/nav[${f}]: status ${JSON.stringify(fix.status)}`);
}

// ----- Points: each frame's cloud against that frame's rows of points.csv, row for row.
const lasClass = { ground: 2, tree: 5, building: 6, noise: 7, wire: 14, pole: 15, fog: 18 };
const clouds = byTopic.get('/owsim/points');
check(clouds.length === FRAMES, `${clouds.length} clouds`);
const typeName = { 2: 'getUint8', 4: 'getUint16', 7: 'getFloat32', 8: 'getFloat64' };
let compared = 0;
for (let f = 0; f < clouds.length; f++) {
  const cloud = clouds[f].decoded;
  check(cloud.header.frame_id === 'map' && stampNs(cloud.header.stamp) === clouds[f].logTime &&
        clouds[f].logTime === BigInt(Math.round(Number(poses[f].time_s) * 1e9)), `/owsim/points[${f}]: header`);
  check(cloud.fields.map((field) => `${field.name}:${field.datatype}`).join(' ') ===
        'x:8 y:8 z:8 intensity:7 ring:4 return:2 class:2 time:8', `/owsim/points[${f}]: fields`);
  const rows = pointRows.filter((row) => Number(row.frame) === f);
  check(cloud.width === rows.length && cloud.height === 1 && cloud.row_step === cloud.width * cloud.point_step,
    `/owsim/points[${f}]: ${cloud.width} points, points.csv has ${rows.length}`);
  const view = new DataView(cloud.data.buffer, cloud.data.byteOffset, cloud.data.byteLength);
  const value = (p, name) => {
    const field = cloud.fields.find((x) => x.name === name);
    return view[typeName[field.datatype]](p * cloud.point_step + field.offset, true);
  };
  for (let p = 0; p < Math.min(rows.length, cloud.width); p++) {
    const row = rows[p];
    const ok = near(value(p, 'x'), Number(row.e_m), 5e-5) && near(value(p, 'y'), Number(row.n_m), 5e-5) &&
      near(value(p, 'z'), Number(row.u_m), 5e-5) &&
      near(value(p, 'intensity'), Number(row.energy_rel), 1e-6 * Math.abs(Number(row.energy_rel)) + 5e-11) &&
      value(p, 'ring') === Number(row.fiber) && value(p, 'return') === Number(row.return) &&
      value(p, 'class') === lasClass[row.class] && near(value(p, 'time'), Number(row.time_s), 5e-10);
    check(ok, `/owsim/points[${f}] point ${p} differs from points.csv row ${JSON.stringify(row)}`);
    compared += 1;
  }
}
check(compared === pointRows.length && compared > 1000, `${compared} points compared of ${pointRows.length}`);

// ----- Latched: the mount and the scene, once, at the flight's start.
const start = BigInt(Math.round(Number(poses[0].time_s) * 1e9));
const [stat] = byTopic.get('/tf_static');
check(byTopic.get('/tf_static').length === 1 && stat.logTime === start, '/tf_static: once at the start');
const mountTf = stat.decoded.transforms[0];
check(mountTf.header.frame_id === 'base_link' && mountTf.child_frame_id === 'owsim_sensor', '/tf_static: frames');
const mount = flown.sensor?.mount ?? {};
const mountRotation = mul(mul(rz((mount.yaw_deg ?? 0) * rad), ry((mount.pitch_deg ?? 0) * rad)), rx((mount.roll_deg ?? 0) * rad));
check(sameRotation(fromQuaternion(mountTf.transform.rotation), mul(mul(flip, mountRotation), flip), 1e-12),
  `/tf_static: rotation ${JSON.stringify(mountTf.transform.rotation)} for mount ${JSON.stringify(mount)}`);
const lever = mount.lever_arm_m ?? [0, 0, 0];
check(mountTf.transform.translation.x === lever[0] && mountTf.transform.translation.y === -lever[1] &&
      mountTf.transform.translation.z === -lever[2], '/tf_static: lever arm');

const [scene] = byTopic.get('/owsim/scene');
check(byTopic.get('/owsim/scene').length === 1 && scene.logTime === start, '/owsim/scene: once at the start');
const markers = scene.decoded.markers;
const kinds = { 1: 'CUBE', 3: 'CYLINDER', 4: 'LINE_STRIP', 11: 'TRIANGLE_LIST' };
for (const marker of markers) {
  check(marker.header.frame_id === 'map' && marker.ns !== '' && marker.text === marker.ns && marker.color.a > 0 &&
        kinds[marker.type] !== undefined, `marker ${marker.ns}: ${marker.type}`);
  if (marker.type === 4) check(marker.points.length >= 2 && marker.scale.x >= 0.1, `line strip ${marker.ns}`);
  if (marker.type === 3) check(marker.scale.z > 0 && marker.scale.x > 0, `cylinder ${marker.ns}`);
}
const marked = new Set(markers.map((m) => m.ns));
check(marked.size === markers.length, 'one marker an object');
const hitObjects = new Set(pointRows.filter((r) => ['wire', 'pole', 'tree', 'building'].includes(r.class)).map((r) => r.object));
for (const id of hitObjects) check(marked.has(id), `object ${id}, hit in points.csv, has a marker`);
check(markers.some((m) => m.type === 4) && markers.some((m) => m.type === 3), 'conductors and cylinders drawn');

// ----- metadata.yaml: what ros2 bag play reads.
const metadata = YAML.parse(readFileSync(join(dir, 'metadata.yaml'), 'utf8')).rosbag2_bagfile_information;
const total = [...byTopic.values()].reduce((n, list) => n + list.length, 0);
check(metadata.storage_identifier === 'mcap' && metadata.relative_file_paths[0] === 'flight.mcap' &&
      metadata.message_count === total && metadata.message_count === Number(reader.statistics.messageCount),
  `metadata.yaml: ${JSON.stringify(metadata).slice(0, 200)}`);
check(BigInt(metadata.starting_time.nanoseconds_since_epoch) === reader.statistics.messageStartTime &&
      BigInt(metadata.duration.nanoseconds) === reader.statistics.messageEndTime - reader.statistics.messageStartTime,
  'metadata.yaml: start and duration');
for (const entry of metadata.topics_with_message_count) {
  const name = entry.topic_metadata.name;
  check(entry.message_count === byTopic.get(name)?.length && entry.topic_metadata.type === topics[name] &&
        YAML.parse(entry.topic_metadata.offered_qos_profiles)[0].durability === (latched.has(name) ? 1 : 2),
  `metadata.yaml: ${name}`);
}

if (failures > 0) {
  console.error(`${failures} checks failed`);
  process.exit(1);
}
console.log(`ok: ${total} messages, ${compared} points equal to points.csv, ${FRAMES} poses equal to trajectory.csv, ${markers.length} scene markers`);
