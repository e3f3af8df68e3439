"""Checks that can fail (issue 12): mutations the checks must reject, the expected stop reason,
the tolerance's basis, zero tolerances, cycle bounds below the cycle limit, loose tolerances
flagged, and abscissae that do not come from the solver's own joint measures (REQ-QA-008)."""
import json
import os
from pathlib import Path

import numpy as np
import pytest

from vdec_verify.extract import extract
from vdec_verify.problem import ProblemError, load_problem
from vdec_verify.report import public_record
from vdec_verify.runner import LOOSE_TOLERANCE_RATIO, discover, run_suite
from problem_files import write_problem

FAKE_VDEC = Path(__file__).parent / "fixtures" / "harness" / "fake_vdec.py"
REQ = pytest.mark.requirements("REQ-QA-008")

# The fake's normal force is m g = 25000 N/m within its 1e-7 noise.
VALID = '''id = "X-1"
title = "t"
requirements = ["REQ-QA-002"]
scene = "scene.toml"
expect_stop = "time"

[[check]]
quantity = "q"
extract = { kind = "final", history = "normal_force" }
reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }
norm = "scalar"
rtol = 1e-5
justification = "j"
tolerance_basis = "derived"

[[mutation]]
name = "mass-up"
overrides = ["oscillator.mass=2600.0"]
why = "4 % more mass: the normal force must be 4 % off."
'''


def mutated(old, new, text=VALID):
    assert old in text, old
    return text.replace(old, new, 1)


def run(tmp_path, text, level="full"):
    write_problem(tmp_path / "problems", text)
    return run_suite(discover(tmp_path / "problems"), FAKE_VDEC, tmp_path / "out", jobs=1, progress=None,
                     level=level)[0]


@REQ
@pytest.mark.parametrize("old, new, key, phrase", [
    (VALID[VALID.index("[[mutation]]"):], "", "mutation", "at least one \\[\\[mutation\\]\\] table is required"),
    ('overrides = ["oscillator.mass=2600.0"]\n', "", r"mutation\[0\]\.overrides", "at least one override"),
    ('overrides = ["oscillator.mass=2600.0"]\n', 'overrides = []\n', r"mutation\[0\]\.overrides",
     "at least one override"),
    ('why = "4 % more mass: the normal force must be 4 % off."\n', "", r"mutation\[0\]\.why", "is required"),
    ('why = "4', 'runs = ["fast"]\nwhy = "4', r"mutation\[0\]\.runs", "no run named 'fast'"),
    ('name = "mass-up"', 'name = "a/b"', r"mutation\[0\]\.name", "names a folder"),
    ('why = "4', 'stiffness = 2\nwhy = "4', r"mutation\[0\]\.stiffness", "unknown key"),
    ('tolerance_basis = "derived"\n', "", r"check\[0\]\.tolerance_basis", "is required"),
    ('tolerance_basis = "derived"', 'tolerance_basis = "guessed"', r"check\[0\]\.tolerance_basis",
     "'guessed' is not allowed"),
    ("rtol = 1e-5\n", "rtol = 0.0\n", r"check\[0\]\.rtol", "both zero"),
    ("rtol = 1e-5\n", "rtol = 0.0\natol = 0\n", r"check\[0\]\.rtol", "both zero"),
    ('expect_stop = "time"\n', "", "expect_stop", "is required for a run that exits 0"),
    ("[[check]]", '[[variant]]\nname = "unstable"\nexpect_exit = 5\n\n[[check]]', r"variant\[0\]\.expect_message",
     "is required with expect_exit = 5"),
    ('expect_stop = "time"', 'expect_stop = "converged"', "expect_stop", "is not a stop reason"),
    ('extract = { kind = "final", history = "normal_force" }',
     'extract = { kind = "curve", x = "us", x_rate = 1.0, y = "tau" }', r"check\[0\]\.extract\.x",
     "exactly one abscissa"),
    ('extract = { kind = "final", history = "normal_force" }',
     'extract = { kind = "final", history = "normal_force", scale = 0.0 }', r"check\[0\]\.extract\.scale",
     "not a finite nonzero number"),
])
def test_the_loader_refuses_checks_that_cannot_fail(tmp_path, old, new, key, phrase):
    with pytest.raises(ProblemError, match=rf"key '{key}': .*{phrase}"):
        load_problem(write_problem(tmp_path, mutated(old, new)))


@REQ
def test_zero_tolerance_is_allowed_for_equal_and_for_an_upper_bound(tmp_path):
    bound = mutated('norm = "scalar"\nrtol = 1e-5\n', 'norm = "upper_bound"\nrtol = 0.0\natol = 0.0\n')
    assert load_problem(write_problem(tmp_path, bound)).checks[0].rtol == 0.0
    assert load_problem(write_problem(tmp_path, VALID)).checks[0].tolerance_basis == "derived"


@REQ
def test_a_cycle_bound_at_the_cycle_limit_is_refused(tmp_path):
    text = mutated('extract = { kind = "final", history = "normal_force" }',
                   'extract = { kind = "run_meta", path = "run.cycles" }')
    text = mutated('{ function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }',
                   '{ constant = 5000 }', text).replace('norm = "scalar"\nrtol = 1e-5\n', 'norm = "upper_bound"\nrtol = 0.0\n')
    path = write_problem(tmp_path, text)
    path.with_name("scene.toml").write_text("[stop]\ncycles = 5000\n")
    with pytest.raises(ProblemError, match=r"check\[0\]\.reference.*not below the run's cycle limit stop.cycles = 5000"):
        load_problem(path)
    # An override of the limit counts; a bound below the limit is accepted.
    path.write_text(text.replace('expect_stop = "time"\n', 'expect_stop = "time"\noverrides = ["stop.cycles=6000"]\n'))
    assert load_problem(path).checks[0].reference.constant == 5000


@REQ
def test_a_mutation_the_checks_reject_is_caught(tmp_path):
    record = run(tmp_path, VALID)
    assert record["status"] == "pass", record["message"]
    (mutation,) = record["mutations"]
    assert mutation["caught"] and mutation["name"] == "mass-up" and mutation["runs"] == ["plain"]
    assert mutation["overrides"] == ["oscillator.mass=2600.0"]
    assert mutation["rejected_by"][0].startswith("check: q (error 0.04 > tolerance 1e-05)")
    # Its run is made in its own folder with the mutation's override last.
    command = (tmp_path / "out" / "mutations" / "X-1" / "mass-up" / "command.txt").read_text()
    assert command.rstrip().endswith("--set oscillator.mass=2600.0")
    assert public_record(record)["mutations"] == record["mutations"]


@REQ
def test_a_mutation_every_check_passes_fails_the_problem(tmp_path):
    # A change that leaves the normal force alone (the settlement's stiffness) passes every check:
    # the checks cannot tell this model from the right one, which is a failure of the suite.
    record = run(tmp_path, mutated('overrides = ["oscillator.mass=2600.0"]', 'overrides = ["oscillator.kn=2e8"]'))
    assert record["status"] == "fail"
    assert not record["mutations"][0]["caught"]
    assert "mutation mass-up not caught: all 1 checks on its runs passed" in record["message"]


@REQ
def test_a_mutation_that_makes_a_run_end_otherwise_is_caught(tmp_path):
    record = run(tmp_path, mutated('overrides = ["oscillator.mass=2600.0"]', 'overrides = ["fake.exit_code=5"]'))
    assert record["status"] == "pass" and record["mutations"][0]["caught"]
    assert "exited 5 (numerical instability), expected 0" in record["mutations"][0]["rejected_by"][0]


@REQ
def test_the_base_suite_runs_no_mutations(tmp_path):
    record = run(tmp_path, VALID, level="base")
    assert record["status"] == "pass" and "mutations" not in record
    assert not (tmp_path / "out" / "mutations").exists()


@REQ
def test_a_run_that_stops_for_another_reason_fails(tmp_path):
    # The run reached its time limit: a check on a run that should have met its ratio passes
    # on numbers that were never converged, unless the stop reason is judged.
    record = run(tmp_path, mutated('expect_stop = "time"', 'expect_stop = "ratio"'), level="base")
    assert record["status"] == "fail"
    assert "stopped on 'time' (run.stop_reason), expected 'ratio' (expect_stop)" in record["message"]
    assert run(tmp_path, VALID.replace('expect_stop = "time"', 'expect_stop = "ratio"\noverrides = '
                                       '["fake.stop_reason=\\"ratio\\""]'), level="base")["status"] == "pass"


@REQ
def test_each_check_records_its_basis_and_how_loose_its_tolerance_is(tmp_path):
    # The fake's error is at most 1e-7: a tolerance of 1e-5 is 100 times it or more.
    metric = run(tmp_path, VALID, level="base")["metrics"][0]
    assert metric["tolerance_basis"] == "derived"
    assert metric["tolerance_over_error"] > LOOSE_TOLERANCE_RATIO and metric["loose"] is True
    # Five times the error it meets is not loose.
    tight = run(tmp_path, mutated("rtol = 1e-5", f"rtol = {5.0 * metric['error']!r}").replace('"derived"', '"measured"'),
                level="base")
    metric = tight["metrics"][0]
    assert metric["tolerance_basis"] == "measured" and metric["loose"] is False
    assert metric["tolerance_over_error"] == pytest.approx(metric["tolerance"] / metric["error"])
    json.dumps(public_record(tight), allow_nan=False)


@REQ
def test_an_abscissa_from_the_prescribed_motion_or_a_scale_shows_a_scaled_displacement():
    t = np.linspace(0.0, 1.0, 11)
    results = {"histories": {"sn": {"t": list(t), "value": list(3.0 * t)},
                             "un": {"t": list(t), "value": list(0.5 * t)},     # the solver's, half the motion
                             "rise": {"t": list(t), "value": list(-t)}}}
    own = extract({"kind": "curve", "x": "un", "y": "sn"}, results, 0)
    prescribed = extract({"kind": "curve", "x_rate": 2.0, "y": "sn"}, results, 0)
    block = extract({"kind": "curve", "x": "rise", "x_scale": -1.0, "y": "sn"}, results, 0)
    np.testing.assert_allclose(own.x, 0.5 * t)
    np.testing.assert_allclose(prescribed.x, 2.0 * t)
    np.testing.assert_allclose(block.x, t)
    assert prescribed.x_label == "2 t"
    assert extract({"kind": "final", "history": "rise", "scale": -1.0}, results, 0) == 1.0
    assert extract({"kind": "value_at", "history": "rise", "t": 0.5, "scale": -2.0}, results, 0) == 1.0


@REQ
def test_the_reports_list_the_mutations_and_flag_loose_tolerances(tmp_path):
    from vdec_verify.report import write_reports
    record = run(tmp_path, VALID)
    write_reports([record], tmp_path / "out", level="full")
    page = (tmp_path / "out" / "index.html").read_text()
    assert "mutation mass-up (oscillator.mass=2600.0): caught by check: q (error 0.04 &gt; tolerance 1e-05)" in page
    assert "tolerance derived, tolerance/error" in page and "LOOSE (for review)" in page
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    (problem,) = summary["problems"]
    assert problem["mutations"][0]["caught"] is True and problem["metrics"][0]["loose"] is True


VDEC = Path(os.environ.get("VDEC_EXECUTABLE", str(Path(__file__).resolve().parents[2] / "build" / "vdec")))
PROBLEMS = Path(__file__).resolve().parents[2] / "verification" / "problems"
# Problems whose runs take a fraction of a second: their mutations run in the test suite too.
QUICK = ["RB-INCLINE-STICK", "RB-INCLINE-COHESION", "RB-TENSION", "RB-REST-SETTLE", "RB-STABILITY-FRAC",
         "CY-CLOSURE", "RB-SHEAR-CNS"]


@REQ
@pytest.mark.skipif(not VDEC.is_file(), reason="vdec is not built")
def test_the_quick_problems_catch_their_mutations(tmp_path):
    # A shear stiffness at 0.55 of its value passed both incline problems when they bounded the
    # slide by twice a kn-based value; the instability variants' runs must not finish normally.
    entries = [e for e in discover(PROBLEMS) if e.id in QUICK]
    assert [e.id for e in entries] == sorted(QUICK)
    records = run_suite(entries, VDEC, tmp_path, jobs=2, progress=None, level="full")
    for record in records:
        assert record["status"] == "pass", (record["id"], record["message"])
        assert record["mutations"] and all(m["caught"] for m in record["mutations"]), record["id"]
