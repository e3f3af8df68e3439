#!/usr/bin/python3
"""Summarises vdec_bench's Google Benchmark JSON into reports/bench/throughput.json.

usage: write_throughput.py BENCHMARK_JSON OUTPUT_JSON

The output names the machine (CPU model from /proc/cpuinfo, logical CPUs, compiler, build type,
commit), gives the rigid-block headline figures at 10 000 blocks (contact_cycle_ns,
block_cycle_ns) and, in "lattices", every lattice's figures with its per-stage split, with
"simply_deformable_over_rigid" the best cost per block-cycle of each lattice of simply-deformable
blocks over the rigid lattice's of its size. For the
deformable-block benchmark (ElasticZones) it gives the headline figures at 99 856 zones
(zone_cycle_ns on one thread, zone_cycle_ns_two_threads) and, in "zone_meshes", every size and
thread count with its per-stage split and, at two threads, the speed-up over one; in
"zone_vector_units", the 99 856-zone block on one thread with each vector unit's version of the
zone and gridpoint loops (ZoneVectorUnits). A run that
failed appears with its error and null figures, and the script then exits with status 1 after
writing the file. Standard library only.
"""
import json
import os
import platform
import sys

TARGET_CONTACT_CYCLE_NS = 35.0  # issue 19
HEADLINE_BLOCKS = 10000
TARGET_ZONE_CYCLE_NS = 20.0  # issue 19
HEADLINE_ZONES = 4 * 158 * 158  # 99 856 zones: n = 158 crossed cells a side
VECTOR_UNITS = ["baseline", "avx2", "avx512"]  # vdec::VectorUnit's order


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


def name_args(name):
    """The benchmark's arguments from its name: ElasticZones/n:158/threads:1/cycles:400/..."""
    return dict(p.split(":", 1) for p in name.split("/") if ":" in p)


def zone_mesh(run):
    name = run["run_name"] if "run_name" in run else run["name"]
    args = name_args(name)
    n = int(args["n"]) if "n" in args else None
    entry = {
        "name": name,
        "mesh": run.get("label", ""),
        "n": n,
        "zones": 4 * n * n if n is not None else None,
        "gridpoints": (n + 1) ** 2 + n * n if n is not None else None,
        "threads": int(args["threads"]) if "threads" in args else None,
        "cycles_per_iteration": int(args["cycles"]) if "cycles" in args else None,
        "warmup_cycles": None,
        "iterations": run.get("iterations"),
        "zone_cycle_ns": None,
        "best_zone_cycle_ns": None,
        "gridpoint_cycle_ns": None,
        "iteration_ms": None,
        "speedup_vs_one_thread": None,
        "stage_share": {},
        "stage_ns_per_zone_cycle": {},
    }
    if run.get("error_occurred"):
        entry["error"] = run.get("error_message", "unknown error")
        return entry
    entry.update({
        "zones": int(round(run["zones"])),
        "gridpoints": int(round(run["gridpoints"])),
        "threads": int(round(run["threads"])),
        "cycles_per_iteration": int(round(run["cycles"])),
        "warmup_cycles": int(round(run["warmup_cycles"])),
        "zone_cycle_ns": round(run["ns_per_zone_cycle"], 2),
        "best_zone_cycle_ns": round(run["best_ns_per_zone_cycle"], 2),
        "gridpoint_cycle_ns": round(run["ns_per_gridpoint_cycle"], 2),
        "iteration_ms": round(run["real_time"], 1) if run.get("time_unit") == "ms" else None,
        "dt": run.get("dt"),
    })
    for key, value in run.items():
        if key.startswith("share_"):
            entry["stage_share"][key[len("share_"):]] = round(value, 4)
        elif key.startswith("ns_") and key.endswith("_per_zone_cycle") and not key.startswith("ns_per_"):
            entry["stage_ns_per_zone_cycle"][key[len("ns_"):-len("_per_zone_cycle")]] = round(value, 2)
    return entry


def zone_figure(meshes, zones, threads):
    e = next((m for m in meshes if m["zones"] == zones and m["threads"] == threads), None)
    return e["zone_cycle_ns"] if e else None


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1], encoding="utf-8") as f:
        bench = json.load(f)
    context = bench.get("context", {})
    runs = [r for r in bench.get("benchmarks", []) if r.get("run_type", "iteration") == "iteration"]
    zone_runs = [r for r in runs if r.get("name", "").startswith("ElasticZones")]
    unit_runs = [r for r in runs if r.get("name", "").startswith("ZoneVectorUnits")]
    lattices = sorted((lattice(r) for r in runs if r not in zone_runs and r not in unit_runs),
                      key=lambda e: e["blocks"] or 0)
    units = []
    for r in unit_runs:
        entry = zone_mesh(r)
        entry["vector_unit"] = VECTOR_UNITS[int(name_args(entry["name"]).get("unit", 0))]
        units.append(entry)
    meshes = sorted((zone_mesh(r) for r in zone_runs), key=lambda e: (e["zones"] or 0, e["threads"] or 0))
    for m in meshes:
        one = zone_figure(meshes, m["zones"], 1)
        if m["threads"] != 1 and one is not None and m["zone_cycle_ns"]:
            m["speedup_vs_one_thread"] = round(one / m["zone_cycle_ns"], 2)
    zone_ns = zone_figure(meshes, HEADLINE_ZONES, 1)
    headline = next((e for e in lattices if e["blocks"] == HEADLINE_BLOCKS and e["name"].startswith("RigidLattice")), None)
    # Each simply-deformable lattice's best cost per block-cycle over the rigid lattice's of its size.
    strained = []
    for e in lattices:
        rigid = next((r for r in lattices if r["name"].startswith("RigidLattice") and r["blocks"] == e["blocks"]), None)
        if e["name"].startswith("SimplyDeformableLattice") and rigid and rigid["best_block_cycle_ns"] and e["best_block_cycle_ns"]:
            strained.append({"blocks": e["blocks"], "ratio": round(e["best_block_cycle_ns"] / rigid["best_block_cycle_ns"], 3)})
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
        "simply_deformable_over_rigid": strained,
        "zone_headline_zones": HEADLINE_ZONES,
        "zone_cycle_ns": zone_ns,
        "zone_cycle_ns_two_threads": zone_figure(meshes, HEADLINE_ZONES, 2),
        "target_zone_cycle_ns": TARGET_ZONE_CYCLE_NS,
        "zone_meets_target": (zone_ns is not None and zone_ns < TARGET_ZONE_CYCLE_NS),
        "zone_meshes": meshes,
        "zone_vector_units": units,
    }
    os.makedirs(os.path.dirname(os.path.abspath(argv[2])), exist_ok=True)
    with open(argv[2], "w", encoding="utf-8") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    failed = [e for e in lattices + meshes if "error" in e]
    for e in lattices:
        if "error" in e:
            print(f"{e['name']}: FAILED: {e['error']}", file=sys.stderr)
        else:
            print(f"{e['lattice']:>8} ({e['blocks']} blocks, {e['contacts']:.0f} contacts): "
                  f"{e['contact_cycle_ns']:.1f} ns/contact-cycle, {e['block_cycle_ns']:.1f} ns/block-cycle")
    for e in meshes:
        if "error" in e:
            print(f"{e['name']}: FAILED: {e['error']}", file=sys.stderr)
        else:
            speedup = f", speed-up {e['speedup_vs_one_thread']:.2f}" if e["speedup_vs_one_thread"] else ""
            print(f"{e['zones']:>8} zones, {e['threads']} thread(s): {e['zone_cycle_ns']:.1f} ns/zone-cycle{speedup}")
    notes = []
    if lattices and not out["meets_target"]:
        notes.append(f"target {TARGET_CONTACT_CYCLE_NS:.0f} ns/contact-cycle not met")
    if meshes and not out["zone_meets_target"]:
        notes.append(f"target {TARGET_ZONE_CYCLE_NS:.0f} ns/zone-cycle not met")
    print(f"wrote {argv[2]}" + (f" ({'; '.join(notes)})" if notes else ""))
    return 1 if failed or not (lattices or meshes) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
