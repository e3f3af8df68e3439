"""Where a second thread starts to pay, and whether it ever costs, on this machine.

Runs `vdec run --threads 1` and `--threads 2` on an elastic square block of n x n crossed cells
(4 n^2 zones, (n + 1)^2 + n^2 gridpoints; the ElasticZones scene of elastic_zone_bench.cpp with
a gravity and a top load), over and over, interleaved, for each vdec given (`--vdec` NAME=PATH,
repeatable: two builds compared side by side). Each run is timed by its own `run.wall_seconds`
(the time loop, set-up excluded) and takes about half a second at one thread. A shared machine
changes speed from one second to the next, so each run also records how much CPU other
processes took while it ran (from /proc/stat, less vdec's own CPU time), in cores: 0 on an idle
machine, about 1 when another job holds one of two cores. `--busy` makes that other job itself
(a process spinning on the CPU for the whole measurement). The summary sorts the runs by that
load.

    /usr/bin/python3 bench/thread_threshold.py --vdec new=build/vdec --runs 5 --out reports/bench/threads.jsonl
    /usr/bin/python3 bench/thread_threshold.py --vdec new=build/vdec --runs 5 --busy --out reports/bench/threads.jsonl
    /usr/bin/python3 bench/thread_threshold.py --summary reports/bench/threads.jsonl

The standard library only.
"""
import argparse
import collections
import json
import os
import resource
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

SIZES = [23, 32, 40, 50, 60, 71, 85, 100, 158]
LOADS = [("idle", -1.0, 0.15), ("one core busy", 0.8, 1.2), ("more than one core busy", 1.2, 99.0)]


def block(n, cycles):
    return f"""title = "elastic block {n} x {n}"
[model]
gravity = [0.0, -9.81]
rounding = 0.01
[solver]
mass_damping = 400.0
[stop]
cycles = {cycles}
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[block]]
name = "block"
material = "rock"
vertices = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
zoning = {{ nx = {n}, ny = {n} }}
[[boundary]]
block = "block"
y = [0.0, 0.0]
fix = ["x", "y"]
[[boundary]]
block = "block"
y = [10.0, 10.0]
stress = [2e5, -1e6, 0.0]
"""


def busy_seconds():
    fields = [int(v) for v in open("/proc/stat").readline().split()[1:]]
    return (fields[0] + fields[1] + fields[2] + fields[5] + fields[6]) / os.sysconf("SC_CLK_TCK")


def environment():
    return {k: v for k, v in os.environ.items() if k != "OMP_NUM_THREADS"}


def measure(builds, runs, sizes, out):
    with tempfile.TemporaryDirectory() as work, open(out, "a") as log:
        for run in range(runs):
            for n in sizes:
                zones = 4 * n * n
                cycles = max(20, round(1.5e7 / zones))
                scene = Path(work) / f"block{n}.toml"
                scene.write_text(block(n, cycles))
                for label, vdec in builds:
                    for threads in (1, 2):
                        before = resource.getrusage(resource.RUSAGE_CHILDREN)
                        busy0, wall0 = busy_seconds(), time.monotonic()
                        done = subprocess.run([vdec, "run", str(scene), "--out", f"{work}/out", "--threads",
                                               str(threads)], capture_output=True, text=True, env=environment())
                        wall, busy = time.monotonic() - wall0, busy_seconds() - busy0
                        after = resource.getrusage(resource.RUSAGE_CHILDREN)
                        own = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
                        if done.returncode != 0:
                            raise SystemExit(f"vdec failed on n = {n}: {done.stderr}")
                        results = json.loads(Path(f"{work}/out/results.json").read_text())
                        log.write(json.dumps({
                            "run": run, "n": n, "zones": zones, "work": zones + (n + 1) ** 2 + n * n,
                            "cycles": cycles, "build": label, "threads": threads,
                            "threads_used": results["environment"]["threads"],
                            "ns_per_zone_cycle": 1e9 * results["run"]["wall_seconds"] / (zones * cycles),
                            "own_cpu_per_wall": own / wall, "others_cores": (busy - own) / wall,
                            "time": time.strftime("%Y-%m-%dT%H:%M:%S")}) + "\n")
                        log.flush()


def summary(path):
    records = [json.loads(line) for line in open(path)]
    for name, low, high in LOADS:
        groups = collections.defaultdict(list)
        for r in records:
            if low <= r["others_cores"] < high:
                groups[(r["n"], r["build"], r["threads"])].append(r["ns_per_zone_cycle"])
        policies = sorted({k[1] for k in groups})  # the builds' labels
        print(f"\n{name}: median ns per zone-cycle at 1 / 2 threads, speed-up (runs at 1, 2 threads)")
        print(f"{'zones':>9} {'work':>9}  " + "  ".join(f"{p:<28}" for p in policies))
        for n in sorted({k[0] for k in groups}):
            cells = []
            for p in policies:
                one, two = groups.get((n, p, 1)), groups.get((n, p, 2))
                if one and two:
                    a, b = statistics.median(one), statistics.median(two)
                    cells.append(f"{a:5.1f} / {b:6.1f}  {a / b:4.2f} ({len(one)}, {len(two)})")
                else:
                    cells.append("-")
            print(f"{4 * n * n:>9} {4 * n * n + (n + 1) ** 2 + n * n:>9}  " + "  ".join(f"{c:<28}" for c in cells))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vdec", action="append", default=None, metavar="NAME=PATH",
                        help="a vdec to measure, labelled NAME (repeatable; default build=build/vdec)")
    parser.add_argument("--runs", type=int, default=10, help="passes over every size, vdec and thread count")
    parser.add_argument("--busy", action="store_true", help="keep one core busy with a spinning process meanwhile")
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)), help="n of the n x n blocks")
    parser.add_argument("--out", default="reports/bench/threads.jsonl", help="one JSON line per run (appended)")
    parser.add_argument("--summary", metavar="JSONL", help="only summarise an earlier --out")
    args = parser.parse_args()
    if args.summary:
        summary(args.summary)
        return
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    builds = [tuple(v.split("=", 1)) if "=" in v else (v, v) for v in (args.vdec or ["build=build/vdec"])]
    hog = subprocess.Popen(["/bin/sh", "-c", "while :; do :; done"]) if args.busy else None
    try:
        measure(builds, args.runs, [int(s) for s in args.sizes.split(",")], args.out)
    finally:
        if hog:
            hog.kill()
    summary(args.out)


if __name__ == "__main__":
    main()
