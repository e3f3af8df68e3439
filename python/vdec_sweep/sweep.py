"""The command `vdec sweep`: reads the sweep, hands its runs to an executor, and writes the table,
the statistics over seeds and the plots (see the package docstring and docs/user-manual/sweeps.md)."""
import argparse
import json
import os
import sys
from dataclasses import dataclass, field
from pathlib import Path

from vdec_sweep import __doc__ as PACKAGE_DOC
from vdec_sweep.design import (build_runs, check_distinct, check_seed_keys, combine, parse_set_option,
                               region_count)
from vdec_sweep.errors import BAD_OUTPUT, EXECUTOR, OK, RUNS_FAILED, USAGE, SweepError
from vdec_sweep.paths import parse_output_path
from vdec_sweep.plots import write_plots
from vdec_sweep.runs import run_one, run_spec
from vdec_sweep.sweepfile import load_sweep_file
from vdec_sweep.tabulate import (RunRecord, output_values, read_results, seed_statistics, statistics_rows,
                                 table_rows, write_csv)
from vdec_verify.executors import (ExecutorError, SlurmOptions, add_executor_options, make_executor,
                                   slurm_options_from)

SCHEMA = "vdec.sweep/1"
DEFAULT_QUANTILES = (0.05, 0.5, 0.95)


@dataclass
class Sweep:
    scene: Path
    out: Path
    vdec: Path
    keys: list                  # the swept scene keys, in order
    runs: list                  # of design.SweepRun
    outputs: list               # of paths.OutputPath
    seeds: int = None
    quantiles: tuple = DEFAULT_QUANTILES
    timeout: float = None
    executor: object = None
    design: str = "product"
    parameters: dict = field(default_factory=dict)   # key -> value texts, as given


def build_parser():
    parser = argparse.ArgumentParser(prog="vdec sweep", description=PACKAGE_DOC.split("\n\n")[0],
                                     epilog="docs/user-manual/sweeps.md: the sweep file, output paths, "
                                            "statistics, executors and exit codes")
    parser.add_argument("scene", nargs="?", help="scene file (TOML); or give --file")
    parser.add_argument("--file", metavar="SWEEP.toml", help="a sweep file instead of SCENE, --set, --seeds, --output")
    parser.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=V1,V2,...",
                        help="a scene key and its values (TOML values, comma-separated); repeatable")
    parser.add_argument("--design", choices=("product", "zip"), default=None,
                        help="product: every combination of the --set values (default); zip: their i-th values")
    parser.add_argument("--seeds", type=int, default=None, metavar="N",
                        help="N realisations of each combination, each with its own seeds of the scene's regions")
    parser.add_argument("--output", dest="outputs", action="append", default=[], metavar="PATH",
                        help="a value of results.json to tabulate, e.g. histories.NAME.last; repeatable")
    parser.add_argument("--quantiles", default=None, metavar="Q1,Q2,...",
                        help="quantiles of the seed statistics (default 0.05,0.5,0.95)")
    parser.add_argument("--out", required=True, metavar="DIR", help="the sweep's folder (not one holding a sweep)")
    parser.add_argument("--vdec", default=os.environ.get("VDEC_EXECUTABLE"),
                        help="the vdec to run (default $VDEC_EXECUTABLE, set by `vdec sweep`)")
    parser.add_argument("--timeout", type=float, default=None, metavar="SECONDS", help="stop a run after this long")
    parser.add_argument("--jobs", type=int, default=None, help="local executor: runs at a time (default: the CPUs)")
    add_executor_options(parser, "DIR/slurm")
    return parser


def _quantiles(text):
    try:
        values = tuple(float(q) for q in text.split(","))
    except ValueError:
        values = ()
    if not values or not all(0.0 < q < 1.0 for q in values):
        raise SweepError(USAGE, f"--quantiles '{text}': comma-separated numbers between 0 and 1")
    return values


def configure(args):
    """The Sweep of the command line (and sweep file); SweepError for bad input."""
    if args.file:
        given = [name for name, value in (("SCENE", args.scene), ("--set", args.sets), ("--seeds", args.seeds),
                                          ("--output", args.outputs), ("--design", args.design)) if value]
        if given:
            raise SweepError(USAGE, f"--file {args.file}: {', '.join(given)} belong in the sweep file")
        settings = load_sweep_file(args.file)
    elif not args.scene:
        raise SweepError(USAGE, "give SCENE (with --set and --output) or --file SWEEP.toml")
    else:
        settings = {"scene": Path(args.scene), "parameters": [parse_set_option(s) for s in args.sets],
                    "design": args.design or "product", "runs": None, "outputs": args.outputs,
                    "seeds": args.seeds, "quantiles": None, "timeout": args.timeout, "executor": {}}
        check_distinct(settings["parameters"], "--set")
    if args.quantiles:
        settings["quantiles"] = _quantiles(args.quantiles)
    seeds = settings["seeds"]
    if seeds is not None and seeds < 1:
        raise SweepError(USAGE, f"--seeds {seeds}: at least 1")
    scene = settings["scene"].resolve()
    if not scene.is_file():
        raise SweepError(USAGE, f"scene {settings['scene']}: no such file")
    if not args.vdec:
        raise SweepError(USAGE, "no vdec to run: give --vdec or set VDEC_EXECUTABLE (`vdec sweep` sets it)")
    vdec = Path(args.vdec).resolve()
    if not (vdec.is_file() and os.access(vdec, os.X_OK)):
        raise SweepError(USAGE, f"--vdec {args.vdec}: no executable file there")
    outputs = [parse_output_path(text) for text in settings["outputs"]]
    if settings["runs"] is not None:
        combinations = settings["runs"]
        keys = list(dict.fromkeys(key for run in combinations for key in run))
        parameters = {key: [run[key][0] for run in combinations if key in run] for key in keys}
    else:
        combinations = combine(settings["parameters"], settings["design"])
        keys = [p.key for p in settings["parameters"]]
        parameters = {p.key: list(p.texts) for p in settings["parameters"]}
    check_seed_keys(keys, seeds)
    regions = 0
    if seeds:
        regions = region_count(scene)
        if regions == 0:
            raise SweepError(USAGE, f"--seeds {seeds}: the scene {settings['scene']} has no [[region]] to seed")
    out = Path(args.out)
    file_executor = settings["executor"]
    kind = args.executor or file_executor.get("kind", "local")
    jobs = args.jobs or file_executor.get("jobs") or os.cpu_count() or 1
    if jobs < 1:
        raise SweepError(USAGE, f"--jobs {jobs}: at least 1")
    base = SlurmOptions(shared_dir=file_executor.get("shared_dir", out / "slurm"),
                        partition=file_executor.get("partition", ""), account=file_executor.get("account", ""),
                        time_limit=file_executor.get("time", ""), sbatch_args=file_executor.get("sbatch_args", []),
                        job_name="vdec-sweep")
    executor = make_executor(kind, jobs, slurm_options_from(args, out / "slurm", base))
    return Sweep(scene=scene, out=out, vdec=vdec, keys=keys, runs=build_runs(combinations, seeds, regions),
                 outputs=outputs, seeds=seeds, quantiles=tuple(settings["quantiles"] or DEFAULT_QUANTILES),
                 timeout=args.timeout if args.timeout is not None else settings["timeout"],
                 executor=executor, design="list" if settings["runs"] is not None else settings["design"],
                 parameters=parameters)


def _describe(run):
    parts = [f"{k}={t}" for k, t in run.settings.items()] + ([f"seed {run.seed}"] if run.seed is not None else [])
    return ", ".join(parts)


def execute(sweep, progress=True):
    """Runs the sweep's runs on its executor; their RunRecords, in order."""
    folders = [sweep.out.resolve() / "runs" / run.name for run in sweep.runs]
    specs = [run_spec(sweep.vdec, sweep.scene, folder, run.overrides, sweep.timeout)
             for run, folder in zip(sweep.runs, folders)]
    done = 0

    def report(index, task):
        nonlocal done
        done += 1
        if progress:
            value = task.value or {}
            ended = f"exit {value.get('exit_code')}" if task.ok else f"Slurm task {task.state}"
            seconds = value.get("wall_seconds", 0.0)
            print(f"[{done}/{len(specs)}] run {sweep.runs[index].name} ({_describe(sweep.runs[index])}): "
                  f"{ended} in {seconds:.2f} s", file=sys.stderr, flush=True)

    try:
        tasks = sweep.executor.run(run_one, specs, report)
    except ExecutorError as e:
        raise SweepError(EXECUTOR, f"--executor {sweep.executor.name}: {e}") from None
    records = []
    for run, folder, task in zip(sweep.runs, folders, tasks):
        if task.ok:
            value = task.value
            records.append(RunRecord(run, folder, value["exit_code"], value["wall_seconds"], value["stderr_tail"],
                                     value["reason"], read_results(folder)))
        else:
            records.append(RunRecord(run, folder, reason=task.error))
    return records


def _write_json(path, data):
    path.write_text(json.dumps(data, indent=1, allow_nan=True) + "\n")


def write_outputs(sweep, records):
    """table.csv/json, statistics.csv/json (with seeds), plots/ and sweep.json; returns
    {output text: why} of the outputs found in no run."""
    values, unknown = output_values(records, sweep.outputs)
    rows = table_rows(records, sweep.keys, values, sweep.seeds)
    write_csv(sweep.out / "table.csv", rows)
    _write_json(sweep.out / "table.json", {"columns": list(rows[0]) if rows else [], "rows": rows})
    if sweep.seeds:
        entries = seed_statistics(records, sweep.keys, values, sweep.quantiles)
        _write_json(sweep.out / "statistics.json", {"confidence": 0.95, "quantiles": list(sweep.quantiles),
                                                    "statistics": entries})
        write_csv(sweep.out / "statistics.csv", statistics_rows(entries, sweep.keys))
    write_plots(sweep.out / "plots", records, sweep.keys, values)
    _write_json(sweep.out / "sweep.json", {
        "schema": SCHEMA, "scene": str(sweep.scene), "vdec": str(sweep.vdec), "design": sweep.design,
        "parameters": sweep.parameters, "seeds": sweep.seeds, "outputs": [p.text for p in sweep.outputs],
        "executor": sweep.executor.name,
        "runs": [{"run": r.run.name, "folder": str(r.folder), "overrides": r.run.overrides, "seed": r.run.seed,
                  "status": row["status"], "exit_code": r.exit_code, "wall_seconds": r.wall_seconds,
                  "stderr_tail": r.stderr_tail, "reason": r.reason} for r, row in zip(records, rows)],
        "unknown_outputs": unknown})
    return unknown


def run_sweep(sweep, progress=True):
    if (sweep.out / "sweep.json").exists():
        raise SweepError(USAGE, f"--out {sweep.out}: already holds a sweep (sweep.json); choose another folder")
    try:
        sweep.out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise SweepError(USAGE, f"--out {sweep.out}: cannot be created: {e.strerror}") from None
    records = execute(sweep, progress)
    unknown = write_outputs(sweep, records)
    failed = [r for r in records if not r.ok]
    for r in failed:
        why = f"exit {r.exit_code}" if r.exit_code is not None else "did not finish"
        detail = r.reason or r.stderr_tail or ("no results.json" if r.exit_code == 0 else "no message")
        print(f"run {r.run.name} ({_describe(r.run)}) failed: {why}: {detail}", file=sys.stderr)
    for text, why in unknown.items():
        print(f"vdec sweep: --output '{text}': not in any run's results.json: {why}", file=sys.stderr)
    print(f"{len(records) - len(failed)} of {len(records)} runs ended with exit code 0; "
          f"table in {sweep.out}/table.csv")
    if unknown:
        return BAD_OUTPUT
    return RUNS_FAILED if failed else OK


def main(argv=None):
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as e:  # argparse: 0 after --help, 2 on a usage error
        return e.code if isinstance(e.code, int) else USAGE
    try:
        return run_sweep(configure(args))
    except SweepError as e:
        print(f"vdec sweep: {e}", file=sys.stderr)
        return e.code
