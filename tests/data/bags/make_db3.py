#!/usr/bin/env python3
"""Generate the idbench ROS 2 bag fixtures that do not need @mcap/core.

Writes (all deterministic, re-running gives identical bytes):
  expected.csv                 reference data in chain order (%.17g)
  payloads/*.bin               CDR payloads consumed by node/make_mcap.mjs
  bag_db3/                     rosbag2 sqlite3 bag (good data + /other topic)
  ragged_db3/                  same, message 57 of /joint_states has 5 positions
  missing_joint_db3/           same, joint4 absent from every JointState message

Only the python3 standard library is used.  The CDR encoder below is written
from the OMG XCDR1 rules (plain CDR, little endian, encapsulation 00 01 00 00),
with alignment measured from the first byte AFTER the 4-byte encapsulation
header.
"""
import math
import os
import shutil
import sqlite3
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

N = 200
CHAIN = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]  # idbench default (puma560.cc)
PERM = [3, 0, 5, 2, 4, 1]          # order in which the chain joints appear in each message
EXTRA = "gripper_finger_joint"     # extra non-chain joint, appended last
FRAME_ID = ""                      # joint_state_publisher leaves it empty
RAGGED_INDEX = 57                  # message index (0-based, /joint_states only) that is ragged
MISSING = "joint4"                 # joint dropped in missing_joint fixtures
OTHER_STRINGS = ["hello", "idbench", "not a joint state", "x"]
OTHER_TIMES_NS = [1_000_000_000, 1_500_000_000, 2_000_000_000, 2_985_000_000]


# --------------------------------------------------------------------------- CDR
class CdrWriter:
    def __init__(self):
        self.body = bytearray()  # bytes after the encapsulation header

    def align(self, n):
        pad = (-len(self.body)) % n
        self.body += b"\x00" * pad

    def u32(self, v):
        self.align(4)
        self.body += struct.pack("<I", v)

    def i32(self, v):
        self.align(4)
        self.body += struct.pack("<i", v)

    def f64(self, v):
        self.align(8)
        self.body += struct.pack("<d", v)

    def string(self, s):
        b = s.encode("utf-8")
        self.u32(len(b) + 1)          # length includes the terminating NUL
        self.body += b + b"\x00"

    def string_seq(self, xs):
        self.u32(len(xs))
        for s in xs:
            self.string(s)

    def f64_seq(self, xs):
        self.u32(len(xs))
        for v in xs:
            self.f64(v)

    def bytes(self):
        return b"\x00\x01\x00\x00" + bytes(self.body)


def encode_joint_state(sec, nanosec, frame_id, names, pos, vel, eff):
    w = CdrWriter()
    w.i32(sec)
    w.u32(nanosec)
    w.string(frame_id)
    w.string_seq(names)
    w.f64_seq(pos)
    w.f64_seq(vel)
    w.f64_seq(eff)
    return w.bytes()


def encode_string_msg(s):
    w = CdrWriter()
    w.string(s)
    return w.bytes()


# --------------------------------------------------------------------------- data
def sample(k):
    sec = 1 + k // 100
    nanosec = (k % 100) * 10_000_000
    t = sec + nanosec * 1e-9          # what a reader computes from the stamp
    w = 2.0 * math.pi * 0.5
    q = [0.3 * math.sin(w * t + j) for j in range(6)]
    qd = [0.3 * w * math.cos(w * t + j) for j in range(6)]
    tau = [2.0 * math.cos(t + 0.5 * j) for j in range(6)]
    return sec, nanosec, t, q, qd, tau


def joint_state_payload(k, variant="good"):
    sec, nanosec, _, q, qd, tau = sample(k)
    order = [p for p in PERM if not (variant == "missing_joint" and CHAIN[p] == MISSING)]
    names = [CHAIN[p] for p in order] + [EXTRA]
    pos = [q[p] for p in order] + [0.01]
    vel = [qd[p] for p in order] + [0.0]
    eff = [tau[p] for p in order] + [0.0]
    if variant == "ragged" and k == RAGGED_INDEX:
        pos = pos[:5]
    return encode_joint_state(sec, nanosec, FRAME_ID, names, pos, vel, eff)


def stamp_ns(k):
    sec, nanosec, *_ = sample(k)
    return sec * 1_000_000_000 + nanosec


def write_expected_csv(path):
    cols = ["t"] + [f"q{i}" for i in range(1, 7)] + [f"qd{i}" for i in range(1, 7)] + \
        [f"tau{i}" for i in range(1, 7)]
    with open(path, "w", newline="\n") as f:
        f.write(",".join(cols) + "\n")
        for k in range(N):
            _, _, t, q, qd, tau = sample(k)
            f.write(",".join("%.17g" % v for v in [t] + q + qd + tau) + "\n")


def write_payloads(dirpath):
    """Length-prefixed records: u64 log_time_ns, u32 len, payload."""
    os.makedirs(dirpath, exist_ok=True)
    for variant in ["good", "ragged", "missing_joint"]:
        with open(os.path.join(dirpath, f"joint_states_{variant}.bin"), "wb") as f:
            for k in range(N):
                p = joint_state_payload(k, variant)
                f.write(struct.pack("<QI", stamp_ns(k), len(p)) + p)
    with open(os.path.join(dirpath, "other.bin"), "wb") as f:
        for t, s in zip(OTHER_TIMES_NS, OTHER_STRINGS):
            p = encode_string_msg(s)
            f.write(struct.pack("<QI", t, len(p)) + p)


# --------------------------------------------------------------------------- rosbag2 sqlite3
QOS = ("- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n"
       "  deadline:\n    sec: 2147483647\n    nsec: 4294967295\n"
       "  lifespan:\n    sec: 2147483647\n    nsec: 4294967295\n"
       "  liveliness: 1\n  liveliness_lease_duration:\n    sec: 2147483647\n"
       "    nsec: 4294967295\n  avoid_ros_namespace_conventions: false")


def yaml_quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def write_db3_bag(dirpath, variant):
    if os.path.exists(dirpath):
        shutil.rmtree(dirpath)
    os.makedirs(dirpath)
    base = os.path.basename(dirpath)
    dbname = f"{base}_0.db3"
    db = sqlite3.connect(os.path.join(dirpath, dbname), isolation_level=None)
    db.execute("PRAGMA journal_mode=DELETE")
    db.execute("BEGIN")
    # Table layout as rosbag2_storage_default_plugins (Humble, db schema version 3) creates it.
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);")
    db.execute("CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,"
               "metadata TEXT NOT NULL);")
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
               "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
               "timestamp INTEGER NOT NULL, data BLOB NOT NULL);")
    db.execute("CREATE INDEX timestamp_idx ON messages (timestamp ASC);")
    db.execute("INSERT INTO schema (schema_version, ros_distro) VALUES (3, 'humble')")
    # /other is created first so that the JointState topic is NOT topic id 1.
    db.execute("INSERT INTO topics(name, type, serialization_format, offered_qos_profiles) "
               "VALUES (?, ?, ?, ?)", ("/other", "std_msgs/msg/String", "cdr", QOS))
    db.execute("INSERT INTO topics(name, type, serialization_format, offered_qos_profiles) "
               "VALUES (?, ?, ?, ?)", ("/joint_states", "sensor_msgs/msg/JointState", "cdr", QOS))
    rows = [(stamp_ns(k), 2, joint_state_payload(k, variant)) for k in range(N)]
    rows += [(t, 1, encode_string_msg(s)) for t, s in zip(OTHER_TIMES_NS, OTHER_STRINGS)]
    rows.sort(key=lambda r: (r[0], -r[1]))  # insertion (= id) order by time, like a recorder
    for ts, tid, data in rows:
        db.execute("INSERT INTO messages (timestamp, topic_id, data) VALUES (?, ?, ?);",
                   (ts, tid, data))
    start = min(r[0] for r in rows)
    end = max(r[0] for r in rows)
    meta = "\n".join([
        "rosbag2_bagfile_information:",
        "  version: 5",
        "  storage_identifier: sqlite3",
        "  duration:",
        f"    nanoseconds: {end - start}",
        "  starting_time:",
        f"    nanoseconds_since_epoch: {start}",
        f"  message_count: {len(rows)}",
        "  topics_with_message_count:",
        "    - topic_metadata:",
        "        name: /other",
        "        type: std_msgs/msg/String",
        "        serialization_format: cdr",
        f"        offered_qos_profiles: {yaml_quote(QOS)}",
        f"      message_count: {len(OTHER_STRINGS)}",
        "    - topic_metadata:",
        "        name: /joint_states",
        "        type: sensor_msgs/msg/JointState",
        "        serialization_format: cdr",
        f"        offered_qos_profiles: {yaml_quote(QOS)}",
        f"      message_count: {N}",
        "  compression_format: \"\"",
        "  compression_mode: \"\"",
        "  relative_file_paths:",
        f"    - {dbname}",
        "  files:",
        f"    - path: {dbname}",
        "      starting_time:",
        f"        nanoseconds_since_epoch: {start}",
        "      duration:",
        f"        nanoseconds: {end - start}",
        f"      message_count: {len(rows)}",
        "",
    ])
    db.execute("INSERT INTO metadata (metadata_version, metadata) VALUES (?, ?)", (5, meta))
    db.execute("COMMIT")
    db.execute("VACUUM")
    db.close()
    with open(os.path.join(dirpath, "metadata.yaml"), "w", newline="\n") as f:
        f.write(meta)


def main():
    os.chdir(HERE)
    write_expected_csv("expected.csv")
    write_payloads("payloads")
    write_db3_bag("bag_db3", "good")
    write_db3_bag("ragged_db3", "ragged")
    write_db3_bag("missing_joint_db3", "missing_joint")


if __name__ == "__main__":
    main()
