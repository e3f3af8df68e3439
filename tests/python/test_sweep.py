"""vdec sweep: the runs of a design, the table of outputs, the output path syntax, the statistics
over seeds with their sampling errors, and its errors (python/vdec_sweep)."""
import csv
import json
import shlex

import numpy as np
import pytest
from scipy import stats
from scene_runs import ROOT, VDEC, needs_vdec

from vdec_sweep.errors import BAD_OUTPUT, BAD_SET, BAD_SWEEP_FILE, EMPTY_VALUES, RUNS_FAILED, USAGE
from vdec_sweep.paths import PathNotFound, parse_output_path, resolve
from vdec_sweep.sweep import main
from vdec_sweep.tabulate import describe, quantile_interval

INCLINE = ROOT / "verification" / "problems" / "RB-INCLINE-SLIP" / "scene.toml"
# A block sliding down a 45-degree incline: 0.05 s (500 cycles) is enough to tell frictions apart.
SHORT = "stop.time=0.05"
JOINTED = """title = "A small jointed mass settling on a fixed base"
[model]
gravity = [0.0, -9.81]
rounding = 0.01
[solver]
frac = 0.1
mass_damping = 20.0
[stop]
cycles = 200
[[block_material]]
name = "rock"
density = 2600.0
[[joint_material]]
name = "joint"
kn = 1e10
ks = 5e9
friction = 35.0
[[block]]
name = "base"
material = "rock"
vertices = [[-1.0, -1.0], [5.0, -1.0], [5.0, 0.0], [-1.0, 0.0]]
fix = ["x", "y", "rotation"]
[[region]]
name = "mass"
material = "rock"
vertices = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]
[[region.joint_set]]
angle = 60.0
angle_variation = 10.0
spacing = 1.0
spacing_variation = 0.3
"""


def sweep(*args):
    return main([*map(str, args), "--vdec", VDEC, "--jobs", "2"])


def table(out):
    return json.loads((out / "table.json").read_text())["rows"]


def overrides_of(folder):
    command = shlex.split((folder / "command.txt").read_text())
    return [a.removeprefix("--set=") for a in command if a.startswith("--set=")]


@needs_vdec
@pytest.mark.requirements("REQ-RUN-011")
def test_product_sweep_runs_every_combination_and_tabulates_its_results(tmp_path, capsys):
    out = tmp_path / "sweep"
    code = sweep(INCLINE, "--set", "joint_material[0].friction=10.0,30.0", "--set", "solver.frac=0.1,0.2",
                 "--set", f"{SHORT},0.1", "--output", "histories.slide.last", "--output", "run.cycles",
                 "--output", "blocks[top].centroid.0", "--out", out)
    assert code == 0
    rows = table(out)
    assert len(rows) == 8
    designed = [(f, frac, t) for f in (10.0, 30.0) for frac in (0.1, 0.2) for t in (0.05, 0.1)]
    assert [(r["joint_material[0].friction"], r["solver.frac"], r["stop.time"]) for r in rows] == designed
    for row in rows:
        folder = out / "runs" / row["run"]
        assert overrides_of(folder) == [f"joint_material[0].friction={row['joint_material[0].friction']}",
                                        f"solver.frac={row['solver.frac']}", f"stop.time={row['stop.time']}"]
        results = json.loads((folder / "results.json").read_text())
        assert row["histories.slide.last"] == results["histories"]["slide"]["value"][-1]
        assert row["run.cycles"] == results["run"]["cycles"]
        assert row["blocks[top].centroid.0"] == results["blocks"][1]["centroid"][0]
        assert row["status"] == "ok" and row["exit_code"] == 0
    # the block slides further on the weaker joint, and further in the longer run
    slide = {(r["joint_material[0].friction"], r["solver.frac"], r["stop.time"]): r["histories.slide.last"]
             for r in rows}
    assert slide[(10.0, 0.1, 0.05)] > slide[(30.0, 0.1, 0.05)] > 0.0
    assert slide[(10.0, 0.1, 0.1)] > slide[(10.0, 0.1, 0.05)]
    with open(out / "table.csv") as f:
        csv_rows = list(csv.DictReader(f))
    assert [float(r["histories.slide.last"]) for r in csv_rows] == [r["histories.slide.last"] for r in rows]
    plots = sorted(p.name for p in (out / "plots").glob("*.png"))
    assert len(plots) == 3 * 3 and "histories.slide.last__solver.frac.png" in plots
    assert "8 of 8 runs ended with exit code 0" in capsys.readouterr().out


@needs_vdec
@pytest.mark.requirements("REQ-RUN-011")
def test_sweep_file_lists_its_runs_or_zips_its_parameters(tmp_path):
    listed = tmp_path / "listed.toml"
    listed.write_text(f'scene = "{INCLINE}"\noutputs = ["run.cycles"]\n'
                      '[[run]]\n"stop.time" = 0.01\n"solver.frac" = 0.1\n'
                      '[[run]]\n"stop.time" = 0.02\n'
                      '[[run]]\n"model.gravity" = [0.0, -9.81]\n"stop.time" = 0.01\n')
    assert sweep("--file", listed, "--out", tmp_path / "a") == 0
    assert [overrides_of(tmp_path / "a" / "runs" / r) for r in ("0000", "0001", "0002")] == [
        ["stop.time=0.01", "solver.frac=0.1"], ["stop.time=0.02"], ["model.gravity=[0.0, -9.81]", "stop.time=0.01"]]
    assert [r["run.cycles"] for r in table(tmp_path / "a")] == [100, 200, 100]
    zipped = tmp_path / "zipped.toml"
    zipped.write_text(f'scene = "{INCLINE}"\noutputs = ["run.time"]\ndesign = "zip"\n'
                      '[parameters]\n"stop.time" = [0.01, 0.02]\n"solver.frac" = [0.1, 0.2]\n')
    assert sweep("--file", zipped, "--out", tmp_path / "z") == 0
    assert [(r["stop.time"], r["solver.frac"]) for r in table(tmp_path / "z")] == [(0.01, 0.1), (0.02, 0.2)]


@pytest.mark.requirements("REQ-RUN-011")
def test_output_paths_reach_members_indices_names_and_history_reductions():
    results = {"run": {"cycles": 7, "error": None},
               "blocks": [{"name": "base", "centroid": [0.0, -0.5]}, {"name": "mass.2", "centroid": [1.5, 2.5]}],
               "histories": {"slide": {"every": 1, "t": [0.0, 1.0, 2.0], "value": [3.0, 1.0, 2.0]}}}

    def value(text):
        return resolve(parse_output_path(text), results)

    assert value("run.cycles") == 7
    assert value("run.error") is None
    assert value("blocks.1.centroid.1") == 2.5
    assert value("blocks.-1.centroid.0") == 1.5
    assert value("blocks.base.centroid.1") == -0.5
    assert value("blocks[mass.2].centroid.0") == 1.5
    assert [value(f"histories.slide.{r}") for r in ("first", "last", "min", "max", "mean")] == [3.0, 2.0, 1.0, 3.0, 2.0]
    assert value("histories.slide.t.last") == 2.0
    for missing, where in [("run.cycle", "run has no member 'cycle'"), ("blocks.2.centroid", "no index 2"),
                           ("blocks[mass.9].name", "no element named 'mass.9'"),
                           ("histories.slide", "is an object, not a value"), ("run.cycles.x", "is a value (7)")]:
        with pytest.raises(PathNotFound, match=f".*{where.replace('(', '.').replace(')', '.')}"):
            value(missing)


@pytest.mark.requirements("REQ-RUN-012")
def test_quantile_interval_is_the_order_statistic_interval_of_the_binomial():
    x = np.arange(1.0, 21.0)
    (low, high), coverage = quantile_interval(x, 0.5)
    # the classic table: with 20 samples, x(6) to x(15) holds the median with probability 0.9586
    assert (low, high) == (6.0, 15.0)
    assert coverage == pytest.approx(stats.binom.cdf(14, 20, 0.5) - stats.binom.cdf(5, 20, 0.5), rel=1e-12, abs=0)
    assert coverage == pytest.approx(0.9586, abs=1e-4)
    # too few samples for the upper end of the 0.95 quantile's interval: it stays open
    (low, high), _ = quantile_interval(x, 0.95)
    assert high is None and low is not None
    summary = describe([1.0, 2.0, 4.0, 7.0], [0.5])
    assert summary["std"] == pytest.approx(np.std([1.0, 2.0, 4.0, 7.0], ddof=1), rel=1e-14, abs=0)
    assert summary["sem"] == pytest.approx(summary["std"] / 2.0, rel=1e-14, abs=0)
    half = stats.t.ppf(0.975, 3) * summary["sem"]
    assert summary["mean_interval"] == pytest.approx([3.5 - half, 3.5 + half], rel=1e-14, abs=0)


@needs_vdec
@pytest.mark.requirements("REQ-RUN-012")
def test_seeds_give_each_region_its_own_stream_and_statistics_with_their_sampling_errors(tmp_path):
    scene = tmp_path / "jointed.toml"
    scene.write_text(JOINTED)
    out = tmp_path / "seeds"
    code = sweep(scene, "--seeds", 12, "--set", "solver.frac=0.1,0.2", "--output", "blocks.-1.centroid.0",
                 "--output", "energy.kinetic", "--out", out)
    rows = table(out)
    assert len(rows) == 24
    assert [r["seed"] for r in rows[:12]] == list(range(1, 13)) == [r["seed"] for r in rows[12:]]
    assert overrides_of(out / "runs" / "0013") == ["solver.frac=0.2", "region[0].seed=2"]
    # with these joint scatters some seeds cut blocks too thin (exit code 4): those are marked and left out
    failed = [r for r in rows if r["status"] != "ok"]
    assert code == (RUNS_FAILED if failed else 0)
    assert all(r["exit_code"] == 4 for r in failed)
    entries = json.loads((out / "statistics.json").read_text())["statistics"]
    assert len(entries) == 4
    for entry in entries:
        ok = [r[entry["output"]] for r in rows if r["status"] == "ok" and r["solver.frac"] == entry["parameters"]["solver.frac"]]
        assert entry["n"] == len(ok) and entry["failed"] == 12 - len(ok)
        assert entry["mean"] == pytest.approx(np.mean(ok), rel=1e-14, abs=0)
        assert entry["sem"] == pytest.approx(np.std(ok, ddof=1) / np.sqrt(len(ok)), rel=1e-12, abs=0)
        median = next(q for q in entry["quantiles"] if q["q"] == 0.5)
        assert median["value"] == pytest.approx(np.median(ok), rel=1e-14, abs=0)
        assert median["coverage"] >= 0.95
    # the seeds vary the blocks: the last block's centroid is not the same in every realisation
    assert len({r["blocks.-1.centroid.0"] for r in rows if r["status"] == "ok"}) > 3
    assert (out / "statistics.csv").is_file()


@needs_vdec
@pytest.mark.requirements("REQ-RUN-013")
def test_failed_runs_are_reported_with_exit_code_and_stderr_and_marked_in_the_table(tmp_path, capsys):
    out = tmp_path / "failing"
    code = sweep(INCLINE, "--set", f"{SHORT}", "--set", "solver.frac=0.1,-1.0,0.2", "--output", "run.cycles",
                 "--out", out)
    assert code == RUNS_FAILED
    rows = table(out)
    assert [r["status"] for r in rows] == ["ok", "failed", "ok"]
    assert [r["exit_code"] for r in rows] == [0, 3, 0]
    assert rows[1]["run.cycles"] is None and rows[0]["run.cycles"] == 500
    runs = json.loads((out / "sweep.json").read_text())["runs"]
    assert "solver.frac" in runs[1]["stderr_tail"]
    assert "run 0001 (stop.time=0.05, solver.frac=-1.0) failed: exit 3: vdec: error:" in capsys.readouterr().err
    # an unknown key is vdec's own error, reported for each run
    out = tmp_path / "unknown"
    assert sweep(INCLINE, "--set", "solver.fracc=0.1,0.2", "--output", "run.cycles", "--out", out) == RUNS_FAILED
    err = capsys.readouterr().err
    assert err.count("key 'solver.fracc': unknown key") == 2


def _bad(tmp_path, *args):
    return sweep(INCLINE, *args, "--out", tmp_path / "bad")


@pytest.mark.parametrize("args, code, message", [
    (["--set", "solver.frac"], BAD_SET, "--set 'solver.frac': no '='"),
    (["--set", "=0.1"], BAD_SET, "'' is not a scene key path"),
    (["--set", "solver.frac=0.1,,0.2"], BAD_SET, "value 2 is empty"),
    (["--set", "solver.frac=fast"], BAD_SET, "value 1 'fast' is not a TOML value"),
    (["--set", "solver.frac=0.1", "--set", "solver.frac=0.2"], BAD_SET, "--set 'solver.frac' is given twice"),
    (["--set", "solver.frac=0.1,0.2", "--set", "stop.time=1.0", "--design", "zip"], BAD_SET,
     "solver.frac has 2, stop.time has 1"),
    (["--set", "solver.frac="], EMPTY_VALUES, "--set 'solver.frac=': no values"),
    (["--set", "solver.frac= "], EMPTY_VALUES, "no values after '='"),
    (["--output", "run..cycles"], BAD_OUTPUT, "--output 'run..cycles': an empty segment"),
    (["--output", "blocks[top"], BAD_OUTPUT, "'[' at character 7 is not closed"),
    (["--seeds", "3"], USAGE, "has no [[region]] to seed"),
    (["--quantiles", "0.5,1.5"], USAGE, "--quantiles '0.5,1.5'"),
])
@pytest.mark.requirements("REQ-RUN-013")
def test_bad_sweep_input_names_the_option_with_its_own_exit_code(tmp_path, capsys, args, code, message):
    assert _bad(tmp_path, *args) == code
    assert message in capsys.readouterr().err
    assert not (tmp_path / "bad" / "runs").exists()


@needs_vdec
@pytest.mark.requirements("REQ-RUN-013")
def test_an_output_found_in_no_run_is_an_error_after_the_runs(tmp_path, capsys):
    code = _bad(tmp_path, "--set", SHORT, "--output", "run.cycles", "--output", "histories.slid.last")
    assert code == BAD_OUTPUT
    err = capsys.readouterr().err
    assert "--output 'histories.slid.last': not in any run's results.json" in err
    assert "histories has no member 'slid' (members: slide, velocity)" in err
    assert table(tmp_path / "bad")[0]["run.cycles"] == 500   # the good output is still tabulated
    # the folder now holds a sweep: a second sweep into it is refused before any run
    assert _bad(tmp_path, "--set", SHORT, "--output", "run.cycles") == USAGE
    assert "already holds a sweep" in capsys.readouterr().err


@pytest.mark.parametrize("text, code, message", [
    ('scene = "s.toml"\nseed = 3\n', BAD_SWEEP_FILE, "key 'seed': unknown key"),
    ('outputs = ["run.cycles"]\n', BAD_SWEEP_FILE, "key 'scene': required"),
    ('scene = "s.toml"\n[parameters]\n"solver.frac" = []\n', EMPTY_VALUES,
     "key 'parameters.\"solver.frac\"': the list of values is empty"),
    ('scene = "s.toml"\n[parameters]\n"solver.frac" = 0.1\n', BAD_SWEEP_FILE, "must be a list"),
    ('scene = "s.toml"\n[executor]\nkind = "pbs"\n', BAD_SWEEP_FILE, "key 'executor.kind'"),
    ('scene = "s.toml"\noutputs = ["a..b"]\n', BAD_OUTPUT, "--output 'a..b'"),
    ('scene = "s.toml"\nseeds = [3\n', BAD_SWEEP_FILE, "not TOML"),
])
@pytest.mark.requirements("REQ-RUN-013")
def test_bad_sweep_file_names_the_file_and_key(tmp_path, capsys, text, code, message):
    (tmp_path / "s.toml").write_text(INCLINE.read_text())
    path = tmp_path / "sweep.toml"
    path.write_text(text)
    assert main(["--file", str(path), "--out", str(tmp_path / "o"), "--vdec", VDEC]) == code
    err = capsys.readouterr().err
    assert message in err
    if code == BAD_SWEEP_FILE:
        assert str(path) in err
