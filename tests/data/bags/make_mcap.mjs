// Generate the MCAP fixtures with npm's @mcap/core (an independent writer).
// Run `python3 make_db3.py` first (it writes payloads/*.bin), then `node make_mcap.mjs`.
// Deterministic: no wall-clock values are written; re-running gives identical bytes.
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(HERE, "node", "package.json"));
const { McapWriter, McapIndexedReader } = require("@mcap/core");
const lz4 = require("lz4js");
const zstd = require("@bokuweb/zstd-wasm");

const CHUNK_SIZE = 4096;
const LIBRARY = "idbench-fixtures make_mcap.mjs (@mcap/core)";

const JOINT_STATE_DEF = `# This is a message that holds data to describe the state of a set of torque controlled joints.
std_msgs/Header header

string[] name
float64[] position
float64[] velocity
float64[] effort

================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id

================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
`;
const STRING_DEF = "string data\n";

// In-memory IWritable + IReadable.
class MemWritable {
  constructor() { this.parts = []; this.size = 0n; }
  async write(buf) { this.parts.push(Buffer.from(buf)); this.size += BigInt(buf.byteLength); }
  position() { return this.size; }
  bytes() { return Buffer.concat(this.parts); }
}
class MemReadable {
  constructor(buf) { this.buf = buf; }
  async size() { return BigInt(this.buf.length); }
  async read(offset, length) {
    return new Uint8Array(this.buf.subarray(Number(offset), Number(offset + length)));
  }
}

function readPayloads(file) {
  const d = fs.readFileSync(path.join(HERE, "payloads", file));
  const out = [];
  let o = 0;
  while (o < d.length) {
    const t = d.readBigUInt64LE(o);
    const n = d.readUInt32LE(o + 8);
    out.push({ logTime: t, data: new Uint8Array(d.subarray(o + 12, o + 12 + n)) });
    o += 12 + n;
  }
  return out;
}

const compressors = {
  none: undefined,
  lz4: (data) => ({ compression: "lz4", compressedData: new Uint8Array(lz4.compress(data)) }),
  zstd: (data) => ({ compression: "zstd", compressedData: new Uint8Array(zstd.compress(data, 3)) }),
};

async function writeMcap(outFile, { compression = "none", jointPayloads = "joint_states_good.bin",
  jointSchemaName = "sensor_msgs/msg/JointState", jointSchemaDef = JOINT_STATE_DEF } = {}) {
  const w = new MemWritable();
  const writer = new McapWriter({ writable: w, chunkSize: CHUNK_SIZE, compressChunk: compressors[compression] });
  await writer.start({ profile: "ros2", library: LIBRARY });
  const jsSchema = await writer.registerSchema({
    name: jointSchemaName, encoding: "ros2msg", data: new TextEncoder().encode(jointSchemaDef) });
  const strSchema = jointSchemaName === "std_msgs/msg/String" ? jsSchema : await writer.registerSchema({
    name: "std_msgs/msg/String", encoding: "ros2msg", data: new TextEncoder().encode(STRING_DEF) });
  // /other is registered first so /joint_states is not channel 0.
  const otherCh = await writer.registerChannel({
    topic: "/other", schemaId: strSchema, messageEncoding: "cdr", metadata: new Map() });
  const jsCh = await writer.registerChannel({
    topic: "/joint_states", schemaId: jsSchema, messageEncoding: "cdr", metadata: new Map() });
  const msgs = [
    ...readPayloads(jointPayloads).map((m) => ({ ...m, channelId: jsCh, prio: 0 })),
    ...readPayloads("other.bin").map((m) => ({ ...m, channelId: otherCh, prio: 1 })),
  ];
  msgs.sort((a, b) => (a.logTime < b.logTime ? -1 : a.logTime > b.logTime ? 1 : a.prio - b.prio));
  const seq = new Map();
  for (const m of msgs) {
    const s = seq.get(m.channelId) ?? 0;
    seq.set(m.channelId, s + 1);
    await writer.addMessage({ channelId: m.channelId, sequence: s, logTime: m.logTime,
      publishTime: m.logTime, data: m.data });
  }
  await writer.end();
  const bytes = w.bytes();
  fs.mkdirSync(path.dirname(outFile), { recursive: true });
  fs.writeFileSync(outFile, bytes);
  return bytes;
}

async function chunkIndexes(bytes) {
  const r = await McapIndexedReader.Initialize({ readable: new MemReadable(bytes) });
  return [...r.chunkIndexes].sort((a, b) => (a.chunkStartOffset < b.chunkStartOffset ? -1 : 1));
}

// Chunk record layout: op(1) len(8) start(8) end(8) usize(8) ucrc(4) compression(str) rlen(8) records.
function chunkRecordsOffset(ci) {
  return Number(ci.chunkStartOffset) + 1 + 8 + 8 + 8 + 8 + 4 + 4 + ci.compression.length + 8;
}

function writeBagMetadata(dir, file, storage, bytesCount) {
  // Minimal rosbag2 metadata.yaml (version 5) pointing at one storage file.
  const qos = "- history: 3\\n  depth: 0\\n  reliability: 1\\n  durability: 2\\n  deadline:\\n    sec: 2147483647\\n    nsec: 4294967295\\n  lifespan:\\n    sec: 2147483647\\n    nsec: 4294967295\\n  liveliness: 1\\n  liveliness_lease_duration:\\n    sec: 2147483647\\n    nsec: 4294967295\\n  avoid_ros_namespace_conventions: false";
  const start = 1000000000, end = 2990000000;
  const y = [
    "rosbag2_bagfile_information:",
    "  version: 5",
    `  storage_identifier: ${storage}`,
    "  duration:", `    nanoseconds: ${end - start}`,
    "  starting_time:", `    nanoseconds_since_epoch: ${start}`,
    `  message_count: ${bytesCount}`,
    "  topics_with_message_count:",
    "    - topic_metadata:", "        name: /other", "        type: std_msgs/msg/String",
    "        serialization_format: cdr", `        offered_qos_profiles: "${qos}"`, "      message_count: 4",
    "    - topic_metadata:", "        name: /joint_states", "        type: sensor_msgs/msg/JointState",
    "        serialization_format: cdr", `        offered_qos_profiles: "${qos}"`, "      message_count: 200",
    '  compression_format: ""', '  compression_mode: ""',
    "  relative_file_paths:", `    - ${file}`,
    "  files:", `    - path: ${file}`, "      starting_time:", `        nanoseconds_since_epoch: ${start}`,
    "      duration:", `        nanoseconds: ${end - start}`, `      message_count: ${bytesCount}`, "",
  ].join("\n");
  fs.writeFileSync(path.join(dir, "metadata.yaml"), y);
}

async function main() {
  await zstd.init();
  const out = (f) => path.join(HERE, f);
  const info = {};
  const none = await writeMcap(out("joint_states_none.mcap"), { compression: "none" });
  await writeMcap(out("joint_states_lz4.mcap"), { compression: "lz4" });
  const zst = await writeMcap(out("joint_states_zstd.mcap"), { compression: "zstd" });
  fs.rmSync(out("bag_mcap"), { recursive: true, force: true });
  await writeMcap(out("bag_mcap/bag_mcap_0.mcap"), { compression: "zstd" });
  writeBagMetadata(out("bag_mcap"), "bag_mcap_0.mcap", "mcap", 204);
  await writeMcap(out("wrong_type.mcap"), { compression: "none", jointSchemaName: "std_msgs/msg/String",
    jointSchemaDef: STRING_DEF });
  await writeMcap(out("ragged.mcap"), { compression: "none", jointPayloads: "joint_states_ragged.bin" });
  await writeMcap(out("missing_joint.mcap"), { compression: "none", jointPayloads: "joint_states_missing_joint.bin" });

  // truncated.mcap: joint_states_zstd.mcap cut in the middle of its 3rd chunk (chunk index 2).
  const zci = await chunkIndexes(zst);
  const c2 = zci[2];
  const cut = Number(c2.chunkStartOffset) + Math.floor(Number(c2.chunkLength) / 2);
  fs.writeFileSync(out("truncated.mcap"), zst.subarray(0, cut));
  info.truncated = { cutAt: cut, chunk: 2, chunkStartOffset: Number(c2.chunkStartOffset),
    chunkLength: Number(c2.chunkLength), chunkCount: zci.length };

  // bad_crc.mcap: joint_states_none.mcap with one byte of the first /joint_states message of
  // chunk index 1 XOR 0x01 (byte 6 of position[0]); the chunk's uncompressed_crc no longer matches
  // (nor does DataEnd.data_section_crc). Lengths/opcodes are untouched, so only a CRC check sees it.
  const nci = await chunkIndexes(none);
  const c1 = nci[1];
  const bad = Buffer.from(none);
  const rec0 = chunkRecordsOffset(c1);
  // First record in the chunk is a Message: op(1) len(8) channel(2) seq(4) log(8) pub(8) data...
  if (bad[rec0] !== 0x05 || bad.readUInt16LE(rec0 + 9) !== 1) {
    throw new Error("expected a /joint_states Message record at start of chunk records");
  }
  const dataStart = rec0 + 1 + 8 + 2 + 4 + 8 + 8;
  const flipAt = dataStart + 0x84 + 6; // CDR payload offset 0x84 = position[0] (a chain joint), byte 6
  bad[flipAt] ^= 0x01;
  fs.writeFileSync(out("bad_crc.mcap"), bad);
  info.bad_crc = { chunk: 1, chunkStartOffset: Number(c1.chunkStartOffset), flippedFileOffset: flipAt,
    firstMessageLogTime: c1.messageStartTime.toString(), chunkCount: nci.length };
  fs.writeFileSync(out("mcap_layout.json"), JSON.stringify(info, null, 2) + "\n");
}

main().catch((e) => { console.error(e); process.exit(1); });
