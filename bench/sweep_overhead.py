"""The cost of `vdec sweep` itself: everything but the solver, per run, on the local executor.

A trivial scene (one block, one cycle) is swept over N values of a key, one run at a time
(--jobs 1), and the same N vdec commands are run directly one after the other. The difference,
over N, is the sweep's overhead per run: its process start, design, task bookkeeping, files,
reading results.json, table, statistics and plots. Two sizes of sweep separate the cost per run
from the fixed cost (the interpreter, imports, plots).

    VDEC_EXECUTABLE=build/vdec /usr/bin/python3 bench/sweep_overhead.py [--runs 20 100] [--executor slurm]
"""
import argparse
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENE = """title = "One block, one cycle: a run that is all overhead"
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "joint"
kn = 1e9
ks = 1e9
[[block]]
name = "a"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
"""


def frac_values(n):
    return [f"{0.1 + 0.0001 * k:.4f}" for k in range(n)]


def direct_seconds(vdec, scene, folder, n):
    start = time.perf_counter()
    for k, value in enumerate(frac_values(n)):
        subprocess.run([vdec, "run", str(scene), "--out", str(folder / f"{k:04d}"), f"--set=solver.frac={value}"],
                       check=True, capture_output=True)
    return time.perf_counter() - start


def sweep_seconds(vdec, scene, folder, n, executor):
    command = [sys.executable, "-m", "vdec_sweep", str(scene), "--set", "solver.frac=" + ",".join(frac_values(n)),
               "--output", "run.cycles", "--output", "blocks.a.centroid.1", "--out", str(folder), "--jobs", "1",
               "--executor", executor]
    env = {**os.environ, "VDEC_EXECUTABLE": vdec,
           "PYTHONPATH": os.pathsep.join([str(ROOT / "python"), str(ROOT / "verification" / "harness")])}
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env)
    return time.perf_counter() - start


def cpu_model():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, nargs=2, default=[20, 100], metavar=("SMALL", "LARGE"))
    parser.add_argument("--executor", choices=("local", "slurm"), default="local")
    args = parser.parse_args()
    vdec = os.environ.get("VDEC_EXECUTABLE") or shutil.which("vdec")
    if not vdec:
        sys.exit("set VDEC_EXECUTABLE to the vdec to run")
    print(f"machine: {cpu_model()}, {os.cpu_count()} CPUs, {platform.system()} {platform.release()}")
    work = Path(tempfile.mkdtemp(prefix="sweep-overhead-", dir=os.environ.get("SWEEP_BENCH_DIR")))
    scene = work / "scene.toml"
    scene.write_text(SCENE)
    overheads = {}
    for n in args.runs:
        solver = direct_seconds(vdec, scene, work / f"direct-{n}", n)
        total = sweep_seconds(vdec, scene, work / f"sweep-{n}", n, args.executor)
        overheads[n] = total - solver
        print(f"{n:4d} runs: sweep {total:7.3f} s, the same vdec runs alone {solver:7.3f} s, "
              f"overhead {overheads[n]:7.3f} s = {overheads[n] / n * 1e3:6.1f} ms a run")
    small, large = args.runs
    per_run = (overheads[large] - overheads[small]) / (large - small)
    fixed = overheads[small] - per_run * small
    print(f"overhead: {per_run * 1e3:.1f} ms a run and {fixed:.2f} s a sweep ({args.executor} executor)")
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
