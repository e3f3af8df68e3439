#!/usr/bin/python3
"""Summarises vdec_bench's Google Benchmark JSON into reports/bench/throughput.json.

usage: write_throughput.py BENCHMARK_JSON OUTPUT_JSON

The output names the machine (CPU model from /proc/cpuinfo, logical CPUs, compiler, build type,
commit), gives the headline figures at 10 000 blocks (contact_cycle_ns, block_cycle_ns) and, in
"lattices", every size's figures with its per-stage split. A lattice whose run failed appears
with its error and null figures, and the script then exits with status 1 after writing the file.
Standard library only.
"""
import json
import os
import platform
import sys

TARGET_CONTACT_CYCLE_NS = 60.0
HEADLINE_BLOCKS = 10000


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def lattice(run):
    label = run.get("label", "")
    entry = {
        "name": run["run_name"] if "run_name" in run else run["name"],
        "lattice": label,
        "blocks": None,
        "contacts": None,
        "closed_contacts": None,
        "cycles_per_iteration": None,
        "iterations": run.get("iterations"),
        "contact_cycle_ns": None,
        "block_cycle_ns": None,
        "best_contact_cycle_ns": None,
        "best_block_cycle_ns": None,
        "detection_scans_per_iteration": None,
        "stage_share": {},
        "stage_ns_per_cycle": {},
    }
    if run.get("error_occurred"):
        entry["error"] = run.get("error_message", "unknown error")
        # The block count is in the benchmark's name: RigidLattice/columns:C/rows:R/...
        parts = dict(p.split(":", 1) for p in entry["name"].split("/") if ":" in p)
        if "columns" in parts and "rows" in parts:
            entry["blocks"] = int(parts["columns"]) * int(parts["rows"])
        return entry
    entry.update({
        "blocks": int(round(run["blocks"])),
        "contacts": round(run["contacts"], 1),
        "closed_contacts": round(run["closed_contacts"], 1),
        "cycles_per_iteration": int(round(run["cycles"])),
        "contact_cycle_ns": round(run["ns_per_contact_cycle"], 2),
        "block_cycle_ns": round(run["ns_per_block_cycle"], 2),
        "best_contact_cycle_ns": round(run["best_ns_per_contact_cycle"], 2),
        "best_block_cycle_ns": round(run["best_ns_per_block_cycle"], 2),
        "detection_scans_per_iteration": round(run["detection_scans"], 2),
        "iteration_ms": round(run["real_time"], 2) if run.get("time_unit") == "ms" else None,
    })
    for key, value in run.items():
        if key.startswith("share_"):
            entry["stage_share"][key[len("share_"):]] = round(value, 4)
        elif key.startswith("ns_") and key.endswith("_per_cycle") and not key.startswith("ns_per_"):
            entry["stage_ns_per_cycle"][key[len("ns_"):-len("_per_cycle")]] = round(value, 1)
    return entry


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1], encoding="utf-8") as f:
        bench = json.load(f)
    context = bench.get("context", {})
    runs = [r for r in bench.get("benchmarks", []) if r.get("run_type", "iteration") == "iteration"]
    lattices = sorted((lattice(r) for r in runs), key=lambda e: e["blocks"] or 0)
    headline = next((e for e in lattices if e["blocks"] == HEADLINE_BLOCKS), None)
    contact_ns = headline["contact_cycle_ns"] if headline else None
    out = {
        "machine": {
            "cpu": cpu_model(),
            "cores": context.get("num_cpus", os.cpu_count()),
            "mhz_per_cpu": context.get("mhz_per_cpu"),
            "compiler": context.get("vdec_compiler", "unknown"),
            "build_type": context.get("vdec_build_type", "unknown"),
            "host": context.get("host_name", platform.node()),
            "kernel": platform.release(),
        },
        "vdec_version": context.get("vdec_version"),
        "vdec_commit": context.get("vdec_commit"),
        "date": context.get("date"),
        "threads": 1,
        "settle_cycles": int(context["vdec_settle_cycles"]) if "vdec_settle_cycles" in context else None,
        "contact_cycle_ns": contact_ns,
        "block_cycle_ns": headline["block_cycle_ns"] if headline else None,
        "target_contact_cycle_ns": TARGET_CONTACT_CYCLE_NS,
        "meets_target": (contact_ns is not None and contact_ns < TARGET_CONTACT_CYCLE_NS),
        "lattices": lattices,
    }
    os.makedirs(os.path.dirname(os.path.abspath(argv[2])), exist_ok=True)
    with open(argv[2], "w", encoding="utf-8") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    failed = [e for e in lattices if "error" in e]
    for e in lattices:
        if "error" in e:
            print(f"{e['name']}: FAILED: {e['error']}", file=sys.stderr)
        else:
            print(f"{e['lattice']:>8} ({e['blocks']} blocks, {e['contacts']:.0f} contacts): "
                  f"{e['contact_cycle_ns']:.1f} ns/contact-cycle, {e['block_cycle_ns']:.1f} ns/block-cycle")
    print(f"wrote {argv[2]}" + ("" if out["meets_target"] else
          f" (target {TARGET_CONTACT_CYCLE_NS:.0f} ns/contact-cycle not met)"))
    return 1 if failed or not lattices else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
