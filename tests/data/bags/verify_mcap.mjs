// Independent read-back of the MCAP fixtures with @mcap/core readers (fzstd / lz4js for
// decompression, NOT the zstd-wasm compressor) and a CDR decoder written here from scratch.
// Compares against expected.csv. Usage: node verify_mcap.mjs   (exit 0 = all checks passed)
import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(HERE, "node", "package.json"));
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const lz4 = require("lz4js");
const fzstd = require("fzstd");

const decompressHandlers = {
  lz4: (buf, size) => new Uint8Array(lz4.decompress(buf, Number(size))),
  zstd: (buf, size) => fzstd.decompress(buf, new Uint8Array(Number(size))),
};
const CHAIN = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"];

class MemReadable {
  constructor(buf) { this.buf = buf; }
  async size() { return BigInt(this.buf.length); }
  async read(offset, length) { return new Uint8Array(this.buf.subarray(Number(offset), Number(offset + length))); }
}

// ---- CDR (XCDR1, little endian) decoder; alignment relative to byte 4 (after encapsulation).
function decodeJointState(u8) {
  const dv = new DataView(u8.buffer, u8.byteOffset, u8.byteLength);
  if (u8[0] !== 0 || u8[1] !== 1) throw new Error(`bad encapsulation ${u8[0]} ${u8[1]}`);
  let o = 4;
  const al = (n) => { o = 4 + Math.ceil((o - 4) / n) * n; };
  const need = (n) => { if (o + n > u8.length) throw new Error(`CDR overrun at ${o}+${n} > ${u8.length}`); };
  const u32 = () => { al(4); need(4); const v = dv.getUint32(o, true); o += 4; return v; };
  const i32 = () => { al(4); need(4); const v = dv.getInt32(o, true); o += 4; return v; };
  const f64 = () => { al(8); need(8); const v = dv.getFloat64(o, true); o += 8; return v; };
  const str = () => {
    const n = u32(); need(n);
    if (n === 0 || u8[o + n - 1] !== 0) throw new Error("string not NUL terminated");
    const s = Buffer.from(u8.subarray(o, o + n - 1)).toString("utf8"); o += n; return s;
  };
  const seq = (f) => { const n = u32(); const a = []; for (let i = 0; i < n; i++) a.push(f()); return a; };
  const sec = i32(), nanosec = u32(), frame_id = str();
  const name = seq(str), position = seq(f64), velocity = seq(f64), effort = seq(f64);
  if (o !== u8.length) throw new Error(`trailing bytes: ${u8.length - o}`);
  return { sec, nanosec, frame_id, name, position, velocity, effort };
}

function loadExpected() {
  const lines = fs.readFileSync(path.join(HERE, "expected.csv"), "utf8").trim().split("\n");
  return lines.slice(1).map((l) => l.split(",").map(Number));
}

function compareToExpected(rows, expected, tag) {
  if (rows.length !== expected.length) throw new Error(`${tag}: ${rows.length} rows, expected ${expected.length}`);
  let maxErr = 0;
  rows.forEach((r, k) => r.forEach((v, i) => { maxErr = Math.max(maxErr, Math.abs(v - expected[k][i])); }));
  if (!(maxErr <= 1e-12)) throw new Error(`${tag}: max abs error ${maxErr}`);
  return maxErr;
}

function toRow(js) {
  const idx = CHAIN.map((j) => js.name.indexOf(j));
  if (idx.some((i) => i < 0)) throw new Error(`missing chain joint in [${js.name}]`);
  const n = js.name.length;
  if (js.position.length !== n || js.velocity.length !== n || js.effort.length !== n) {
    throw new Error(`ragged arrays name=${n} pos=${js.position.length} vel=${js.velocity.length} eff=${js.effort.length}`);
  }
  return [js.sec + js.nanosec * 1e-9, ...idx.map((i) => js.position[i]), ...idx.map((i) => js.velocity[i]),
    ...idx.map((i) => js.effort[i])];
}

async function readIndexed(file) {
  const buf = fs.readFileSync(path.join(HERE, file));
  const r = await McapIndexedReader.Initialize({ readable: new MemReadable(buf), decompressHandlers });
  const chans = [...r.channelsById.values()];
  const js = chans.find((c) => c.topic === "/joint_states");
  const schema = r.schemasById.get(js.schemaId);
  const msgs = [];
  for await (const m of r.readMessages({ topics: ["/joint_states"], validateCrcs: true })) msgs.push(m);
  return { r, schema, js, msgs, chunkCount: r.chunkIndexes.length, compressions: [...new Set(r.chunkIndexes.map((c) => c.compression))] };
}

function readStream(file) {
  const buf = fs.readFileSync(path.join(HERE, file));
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(buf);
  const channels = new Map();
  const msgs = [];
  let error = null;
  try {
    for (let rec; (rec = reader.nextRecord()); ) {
      if (rec.type === "Channel") channels.set(rec.id, rec);
      if (rec.type === "Message" && channels.get(rec.channelId)?.topic === "/joint_states") msgs.push(rec);
    }
  } catch (e) { error = e.message; }
  return { msgs, error, done: reader.done(), pending: reader.bytesRemaining() };
}

let failures = 0;
const ok = (c, what) => { console.log(`${c ? "PASS" : "FAIL"} ${what}`); if (!c) failures++; };

async function main() {
  const expected = loadExpected();
  for (const f of ["joint_states_none.mcap", "joint_states_lz4.mcap", "joint_states_zstd.mcap", "bag_mcap/bag_mcap_0.mcap"]) {
    const { schema, js, msgs, chunkCount, compressions, r } = await readIndexed(f);
    const rows = msgs.map((m) => toRow(decodeJointState(m.data)));
    const err = compareToExpected(rows, expected, f);
    const logOk = msgs.every((m, k) => m.logTime === BigInt(1_000_000_000 + k * 10_000_000));
    ok(schema.name === "sensor_msgs/msg/JointState" && schema.encoding === "ros2msg" && js.messageEncoding === "cdr"
      && r.header.profile === "ros2" && logOk,
      `${f}: indexed reader, ${msgs.length} msgs, ${chunkCount} chunks [${compressions}], max err ${err}`);
    const s = readStream(f);
    const srows = s.msgs.map((m) => toRow(decodeJointState(m.data)));
    ok(!s.error && s.done && compareToExpected(srows, expected, f + " stream") === 0, `${f}: stream reader, validateCrcs, ${s.msgs.length} msgs`);
  }

  { // wrong_type
    const { schema, msgs } = await readIndexed("wrong_type.mcap");
    ok(schema.name === "std_msgs/msg/String" && msgs.length === 200, `wrong_type.mcap: /joint_states schema is ${schema.name}`);
  }
  { // ragged
    const { msgs } = await readIndexed("ragged.mcap");
    const bad = [];
    msgs.forEach((m, k) => { try { toRow(decodeJointState(m.data)); } catch (e) { bad.push([k, e.message]); } });
    ok(bad.length === 1 && bad[0][0] === 57, `ragged.mcap: bad messages ${JSON.stringify(bad)}`);
  }
  { // missing_joint
    const { msgs } = await readIndexed("missing_joint.mcap");
    const d = decodeJointState(msgs[0].data);
    let err = ""; try { toRow(d); } catch (e) { err = e.message; }
    ok(msgs.length === 200 && !d.name.includes("joint4") && err.startsWith("missing chain joint"),
      `missing_joint.mcap: names [${d.name}] -> ${err}`);
  }
  { // truncated
    let idxErr = ""; try { await readIndexed("truncated.mcap"); } catch (e) { idxErr = e.message; }
    const s = readStream("truncated.mcap");
    ok(idxErr !== "" && !s.done && s.error === null, `truncated.mcap: indexed reader throws "${idxErr}"; stream reader yields ${s.msgs.length} /joint_states msgs then waits for more data (${s.pending} bytes pending)`);
    const rows = s.msgs.map((m) => toRow(decodeJointState(m.data)));
    compareToExpected(rows, expected.slice(0, rows.length), "truncated prefix");
  }
  { // bad_crc
    let e1 = ""; try { await readIndexed("bad_crc.mcap"); } catch (e) { e1 = e.message; }
    const s = readStream("bad_crc.mcap");
    ok(e1 !== "" && s.error !== null, `bad_crc.mcap: indexed "${e1}"; stream after ${s.msgs.length} msgs: "${s.error}"`);
    const buf = fs.readFileSync(path.join(HERE, "bad_crc.mcap"));
    const r = await McapIndexedReader.Initialize({ readable: new MemReadable(buf), decompressHandlers });
    const msgs = []; for await (const m of r.readMessages({ topics: ["/joint_states"], validateCrcs: false })) msgs.push(m);
    const rows = msgs.map((m) => toRow(decodeJointState(m.data)));
    const diff = rows.map((row, k) => row.some((v, i) => v !== expected[k][i]) ? k : -1).filter((k) => k >= 0);
    ok(diff.length === 1, `bad_crc.mcap without CRC check: differing message index ${diff}, q value ${rows[diff[0]]?.slice(1, 7)}`);
  }
  console.log(failures === 0 ? "ALL MCAP CHECKS PASSED" : `${failures} FAILURES`);
  process.exit(failures ? 1 : 0);
}
main().catch((e) => { console.error(e); process.exit(1); });
