#!/usr/bin/env python3
"""`idbench benchmark` as a Slurm job array (docs/commands/benchmark.md, "Beyond one machine"): four shards
submitted as the page submits them (`sbatch --array=0-3`, then `benchmark merge` as a job that depends on the
array), merged, give the benchmark.json of the run on one machine, but for its wall times.

Needs a Slurm controller with a node to run on (a single-node Slurm from Debian's slurm-wlm will do); exits 77
(skipped, with a message) when sbatch is not on PATH or no controller answers. IDBENCH names the binary.
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

SKIP = 77


def without_times(path):
    """benchmark.json with every wall time removed: what a run determines."""
    j = json.loads(path.read_text())
    for r in j["results"]:
        r.pop("seconds")
    for t in j["trial_values"]:
        for e in t["estimates"]:
            e.pop("seconds")
    return j


def main():
    if shutil.which("sbatch") is None:
        print("benchmark_slurm_test: skipped: sbatch is not on PATH (Slurm is not installed; CI need not install it)")
        return SKIP
    try:
        states = subprocess.run(["sinfo", "-h", "-o", "%t"], capture_output=True, text=True, timeout=20)
    except (OSError, subprocess.TimeoutExpired) as error:
        print(f"benchmark_slurm_test: skipped: sinfo did not answer ({error})")
        return SKIP
    if states.returncode != 0 or not any(s.strip().rstrip("*") in ("idle", "mix") for s in states.stdout.split()):
        print(f"benchmark_slurm_test: skipped: no Slurm node to run on (sinfo: {states.stdout.strip() or states.stderr.strip()})")
        return SKIP

    idbench = pathlib.Path(os.environ["IDBENCH"]).resolve()
    source = pathlib.Path(__file__).resolve().parents[3]
    robot = source / "tests/data/table_arm/table_arm.urdf"
    env = dict(os.environ, PATH=f"{idbench.parent}{os.pathsep}{os.environ.get('PATH', '')}")
    with tempfile.TemporaryDirectory(prefix="idbench_slurm_") as work:
        work = pathlib.Path(work)
        (work / "pid.json").write_text('{"kp": [400, 400, 200], "kd": [10, 10, 5], "feedforward": "model"}\n')
        (work / "short.json").write_text(
            '{"family": "fourier", "f0": 0.5, "duration": 1, "rest_to_rest": false, "q0": [0, 0, 0],'
            ' "a": [[0.6, 0.25], [0.55, -0.25], [0.5, 0.25]], "b": [[0.3, -0.15], [0.34, -0.12], [0.38, -0.09]]}\n')
        run = (f"--robot {robot} --trajectory short.json --controller pid.json --friction none "
               "--estimators ols,wls,irls --trials 2 --preset low,high --threads 1")
        # The page's job script, on this run.
        (work / "bench.sh").write_text(
            "#!/bin/bash\n#SBATCH --array=0-3\n#SBATCH --cpus-per-task=1\n"
            f"idbench benchmark {run} --shard ${{SLURM_ARRAY_TASK_ID}}/4 --out shard${{SLURM_ARRAY_TASK_ID}}\n")

        def call(argv, timeout=300):
            done = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True, timeout=timeout)
            if done.returncode != 0:
                raise SystemExit(f"benchmark_slurm_test: {' '.join(argv)} exited {done.returncode}: {done.stderr}")
            return done.stdout

        call(["idbench", "benchmark", *run.split(), "--out", "single"])
        jobid = call(["sbatch", "--parsable", "--output=slurm-%A_%a.out", "bench.sh"]).strip().split(";")[0]
        call(["sbatch", "--wait", f"--dependency=afterok:{jobid}", "--output=merge.out",
              "--wrap", "idbench benchmark merge shard0 shard1 shard2 shard3 --out merged"])
        merged, single = without_times(work / "merged/benchmark.json"), without_times(work / "single/benchmark.json")
        if merged != single:
            print("benchmark_slurm_test: the merged shards differ from the single run")
            return 1
        trials = sum(r["trials"] for r in single["results"])
        print(f"benchmark_slurm_test: ok: job {jobid}, 4 array tasks merged = the single run "
              f"({len(single['trial_values'])} trials, {trials} estimates)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
