#!/usr/bin/env python3
"""Read back the sqlite3 bags with python's sqlite3 and a CDR decoder that shares no code with
make_db3.py's encoder; compare /joint_states against expected.csv. Exit 0 = all checks passed."""
import csv
import os
import sqlite3
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CHAIN = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]


def decode_joint_state(buf):
    if buf[:4] != b"\x00\x01\x00\x00":
        raise ValueError("bad encapsulation header %r" % buf[:4])
    o = 4

    def align(n):
        nonlocal o
        o += (-(o - 4)) % n

    def take(fmt, size):
        nonlocal o
        align(size)
        if o + size > len(buf):
            raise ValueError("CDR overrun at %d" % o)
        (v,) = struct.unpack_from(fmt, buf, o)
        o += size
        return v

    def string():
        nonlocal o
        n = take("<I", 4)
        if n == 0 or o + n > len(buf) or buf[o + n - 1] != 0:
            raise ValueError("bad string at %d" % o)
        s = buf[o:o + n - 1].decode("utf-8")
        o += n
        return s

    def seq(f):
        return [f() for _ in range(take("<I", 4))]

    sec = take("<i", 4)
    nanosec = take("<I", 4)
    frame_id = string()
    name = seq(string)
    pos = seq(lambda: take("<d", 8))
    vel = seq(lambda: take("<d", 8))
    eff = seq(lambda: take("<d", 8))
    if o != len(buf):
        raise ValueError("%d trailing bytes" % (len(buf) - o))
    return sec, nanosec, frame_id, name, pos, vel, eff


def to_row(msg):
    sec, nanosec, _, name, pos, vel, eff = msg
    if not (len(pos) == len(vel) == len(eff) == len(name)):
        raise ValueError("ragged: name=%d position=%d velocity=%d effort=%d"
                         % (len(name), len(pos), len(vel), len(eff)))
    missing = [j for j in CHAIN if j not in name]
    if missing:
        raise ValueError("missing chain joint(s) %s" % missing)
    idx = [name.index(j) for j in CHAIN]
    return [sec + nanosec * 1e-9] + [pos[i] for i in idx] + [vel[i] for i in idx] + \
        [eff[i] for i in idx]


def read_bag(d):
    base = os.path.basename(d)
    meta = open(os.path.join(d, "metadata.yaml")).read()
    assert "storage_identifier: sqlite3" in meta and "version: 5" in meta
    db = sqlite3.connect("file:%s?mode=ro" % os.path.join(d, base + "_0.db3"), uri=True)
    topics = {r[1]: (r[0], r[2], r[3]) for r in
              db.execute("SELECT id, name, type, serialization_format FROM topics")}
    tid, ttype, fmt = topics["/joint_states"]
    assert ttype == "sensor_msgs/msg/JointState" and fmt == "cdr", (ttype, fmt)
    rows = db.execute("SELECT timestamp, data FROM messages WHERE topic_id = ? "
                      "ORDER BY timestamp, id", (tid,)).fetchall()
    n_other = db.execute("SELECT COUNT(*) FROM messages WHERE topic_id = ?",
                         (topics["/other"][0],)).fetchone()[0]
    return rows, n_other, topics


def main():
    os.chdir(HERE)
    with open("expected.csv") as f:
        r = csv.reader(f)
        header = next(r)
        expected = [[float(x) for x in row] for row in r]
    assert header[0] == "t" and len(header) == 19
    fails = 0

    rows, n_other, topics = read_bag("bag_db3")
    got = [to_row(decode_joint_state(bytes(d))) for _, d in rows]
    max_err = max(abs(a - b) for g, e in zip(got, expected) for a, b in zip(g, e))
    ts_ok = all(ts == 1_000_000_000 + k * 10_000_000 for k, (ts, _) in enumerate(rows))
    ok = len(got) == 200 and max_err <= 1e-12 and ts_ok and n_other == 4
    print("%s bag_db3: %d msgs, max err %g, /other=%d, topics=%s"
          % ("PASS" if ok else "FAIL", len(got), max_err, n_other, sorted(topics)))
    fails += not ok

    # The MCAP fixtures carry payloads/joint_states_good.bin; the db3 blobs must be the same bytes.
    pay, o, raw = [], 0, open("payloads/joint_states_good.bin", "rb").read()
    while o < len(raw):
        t, n = struct.unpack_from("<QI", raw, o)
        pay.append((t, raw[o + 12:o + 12 + n]))
        o += 12 + n
    ok = pay == [(ts, bytes(d)) for ts, d in rows]
    print("%s bag_db3 blobs == payloads/joint_states_good.bin (the MCAP payloads)" % ("PASS" if ok else "FAIL"))
    fails += not ok

    rows, _, _ = read_bag("ragged_db3")
    bad = []
    for k, (_, d) in enumerate(rows):
        try:
            to_row(decode_joint_state(bytes(d)))
        except ValueError as e:
            bad.append((k, str(e)))
    ok = len(bad) == 1 and bad[0][0] == 57
    print("%s ragged_db3: bad messages %s" % ("PASS" if ok else "FAIL", bad))
    fails += not ok

    rows, _, _ = read_bag("missing_joint_db3")
    errs = set()
    for _, d in rows:
        try:
            to_row(decode_joint_state(bytes(d)))
        except ValueError as e:
            errs.add(str(e))
    ok = len(rows) == 200 and errs == {"missing chain joint(s) ['joint4']"}
    print("%s missing_joint_db3: %s" % ("PASS" if ok else "FAIL", errs))
    fails += not ok
    print("ALL DB3 CHECKS PASSED" if fails == 0 else "%d FAILURES" % fails)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
