#!/usr/bin/env python3
"""Generate epoch_1ms.db3 and epoch_1ms.csv: the same 200 samples as a bag
stamped after a real epoch (header.stamp sec = 1_700_000_000, exactly 1 ms
apart) and as a CSV whose t counts from the first stamp (k / 1000 s).

A reader that keeps the stamps in integer nanoseconds relative to the first
one reads the bag as exactly the CSV; one that forms sec + nanosec * 1e-9 in
a double (resolution 2.4e-7 s at 1.7e9 s) jitters every step.

Uses make_db3.py's CDR encoder and sqlite3 layout (python3 standard library
only, no idbench code); deterministic like it.
"""
import math
import os
import sqlite3

import make_db3

HERE = os.path.dirname(os.path.abspath(__file__))
N = 200
EPOCH_SEC = 1_700_000_000


def sample(k):
    sec = EPOCH_SEC + k // 1000
    nanosec = (k % 1000) * 1_000_000
    t = "%d.%03d" % (k // 1000, k % 1000)  # exact decimal seconds since the first stamp
    tf = float(t)
    q = [0.3 * math.sin(math.pi * tf + j) for j in range(6)]
    qd = [0.3 * math.pi * math.cos(math.pi * tf + j) for j in range(6)]
    tau = [2.0 * math.cos(tf + 0.5 * j) for j in range(6)]
    return sec, nanosec, t, q, qd, tau


def main():
    os.chdir(HERE)
    with open("epoch_1ms.csv", "w", newline="\n") as f:
        f.write(",".join(["t"] + [f"q{i}" for i in range(1, 7)] + [f"qd{i}" for i in range(1, 7)] +
                         [f"tau{i}" for i in range(1, 7)]) + "\n")
        for k in range(N):
            _, _, t, q, qd, tau = sample(k)
            f.write(",".join([t] + ["%.17g" % v for v in q + qd + tau]) + "\n")
    path = "epoch_1ms.db3"
    if os.path.exists(path):
        os.remove(path)
    db = sqlite3.connect(path, isolation_level=None)
    db.execute("PRAGMA journal_mode=DELETE")
    db.execute("BEGIN")
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);")
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
               "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
               "timestamp INTEGER NOT NULL, data BLOB NOT NULL);")
    db.execute("INSERT INTO schema (schema_version, ros_distro) VALUES (3, 'humble')")
    db.execute("INSERT INTO topics(name, type, serialization_format, offered_qos_profiles) "
               "VALUES (?, ?, ?, ?)", ("/joint_states", "sensor_msgs/msg/JointState", "cdr", make_db3.QOS))
    for k in range(N):
        sec, nanosec, _, q, qd, tau = sample(k)
        data = make_db3.encode_joint_state(sec, nanosec, "", make_db3.CHAIN, q, qd, tau)
        # received 0.3 ms after the stamp
        db.execute("INSERT INTO messages (timestamp, topic_id, data) VALUES (?, 1, ?);",
                   (sec * 1_000_000_000 + nanosec + 300_000, data))
    db.execute("COMMIT")
    db.execute("VACUUM")
    db.close()


if __name__ == "__main__":
    main()
