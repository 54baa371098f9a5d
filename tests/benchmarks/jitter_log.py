#!/usr/bin/env python3
"""Turns a simulated joint log into one shaped like a real controller's, for
the whole-command benchmark of `idbench identify` (BENCHMARKS.md): the qdd
columns dropped (measured qd only), every time stamp moved by up to
+-0.4 steps (seeded, uniform) and one sample in 1000 dropped. The values stay
those of the regular grid, so the log is only good for timing.

usage: jitter_log.py IN.csv OUT.csv [SEED]"""
import random
import sys


def main():
    source, target = sys.argv[1], sys.argv[2]
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    with open(source) as f:
        header = f.readline().strip().split(",")
        keep = [c for c, name in enumerate(header) if not name.startswith("qdd")]
        rows = [line.strip().split(",") for line in f if line.strip()]
    step = float(rows[1][0]) - float(rows[0][0])
    with open(target, "w") as out:
        out.write(",".join(header[c] for c in keep) + "\n")
        for i, row in enumerate(rows):
            if i % 1000 == 500:
                continue
            jitter = 0.0 if i in (0, len(rows) - 1) else rng.uniform(-0.4, 0.4) * step
            row[0] = repr(float(row[0]) + jitter)
            out.write(",".join(row[c] for c in keep) + "\n")


if __name__ == "__main__":
    main()
