"""Convergence studies of the verification harness (REQ-QA-005): the arithmetic of
vdec_verify.convergence at known values, the validation of [refinement], and whole runs with the
fake solver (tests/python/fixtures/harness/fake_vdec.py), whose error is 0.01 h^p when a level
sets fake.h."""
import contextlib
import html
import io
import json
import math
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from vdec_verify.__main__ import main
from vdec_verify.convergence import (ConvergenceError, convergence_study, grid_convergence_index,
                                     observed_order)
from vdec_verify.problem import ProblemError, load_problem
from problem_files import write_problem

FIXTURES = Path(__file__).parent / "fixtures" / "harness"
FAKE_VDEC = FIXTURES / "fake_vdec.py"
STUDIES = FIXTURES / "convergence"


def run_main(*args):
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        code = main(list(map(str, args)))
    return code, stdout.getvalue(), stderr.getvalue()


def least_squares_slope(x, y):
    """The slope by its textbook formula, written out independently of numpy.polyfit."""
    x_mean, y_mean = sum(x) / len(x), sum(y) / len(y)
    return sum((a - x_mean) * (b - y_mean) for a, b in zip(x, y)) / sum((a - x_mean) ** 2 for a in x)


def study(h, error, numerical=None, expected=2.0, band=0.3, asymptotic=None, why=None):
    names = [f"L{i}" for i in range(len(h))]
    numerical = numerical if numerical is not None else [1.0 + (e or 0.0) for e in error]
    return convergence_study(names, h, error, numerical, [0.1 * (i + 1) for i in range(len(h))],
                             [100 * 4 ** i for i in range(len(h))], expected, band, asymptotic, why)


# ---------------------------------------------------------------- the arithmetic


@pytest.mark.requirements("REQ-QA-005")
def test_exact_second_order_sequence_gives_order_two_and_ratio_one():
    h = [0.4, 0.2, 0.1, 0.05]
    error = [3.0 * v ** 2 for v in h]
    assert observed_order(h, error) == pytest.approx(2.0, abs=1e-12)
    values = [7.0 + e for e in error]                 # phi = phi0 + C h^2
    result = grid_convergence_index(h[1:], values[1:])
    assert result.order == pytest.approx(2.0, abs=1e-10)
    assert result.asymptotic_ratio == pytest.approx(1.0, abs=1e-12)
    assert result.extrapolated == pytest.approx(7.0, abs=1e-12)
    # GCI_fine = Fs |e21 / phi1| / (r^p - 1), r = 2, p = 2
    phi1, phi2 = values[3], values[2]
    assert result.gci_fine == pytest.approx(1.25 * abs((phi2 - phi1) / phi1) / 3.0, rel=1e-10, abs=0)
    assert not result.oscillatory
    record = study(h, error, values)
    assert record["pass"] and record["observed_order"] == pytest.approx(2.0, abs=1e-12)
    assert record["gci"] == pytest.approx(result.gci_fine, rel=1e-12, abs=0)
    assert record["asymptotic_ratio"] == pytest.approx(1.0, abs=1e-12)
    assert record["gci_order"] == pytest.approx(2.0, abs=1e-10)


@pytest.mark.requirements("REQ-QA-005")
def test_first_order_and_noisy_sequences():
    h = [0.4, 0.2, 0.1, 0.05]
    first = [0.5 * v for v in h]
    assert observed_order(h, first) == pytest.approx(1.0, abs=1e-12)
    record = study(h, first)
    assert not record["pass"] and record["observed_order"] == pytest.approx(1.0, abs=1e-12)
    assert "observed order 1.000" in record["message"] and "expected 2 +- 0.3" in record["message"]
    # Second order with +-5 % noise: the least-squares slope, not the order of the last pair.
    noise = [1.05, 0.95, 1.05, 0.95]
    noisy = [v ** 2 * n for v, n in zip(h, noise)]
    expected = least_squares_slope([math.log(v) for v in h], [math.log(e) for e in noisy])
    assert observed_order(h, noisy) == pytest.approx(expected, rel=1e-12, abs=0)
    assert 1.9 < expected < 2.1 and expected != pytest.approx(2.0, abs=1e-3)
    assert math.log(noisy[2] / noisy[3]) / math.log(2.0) != pytest.approx(expected, abs=1e-2)
    # Within the band and outside it.
    assert study(h, noisy, band=0.1)["pass"]
    assert not study(h, noisy, band=abs(expected - 2.0) / 2)["pass"]


@pytest.mark.requirements("REQ-QA-005")
def test_the_asymptotic_levels_are_the_finest_ones():
    # The coarsest level is pre-asymptotic: error 10x what C h^2 gives.
    h = [0.8, 0.4, 0.2, 0.1]
    error = [v ** 2 for v in h]
    error[0] *= 10.0
    all_levels = study(h, error)
    assert all_levels["observed_order"] == pytest.approx(least_squares_slope(
        [math.log(v) for v in h], [math.log(e) for e in error]), rel=1e-12, abs=0)
    assert not all_levels["pass"]
    finest = study(h, error, asymptotic=3)
    assert finest["fit_levels"] == ["L1", "L2", "L3"] and finest["levels"] == ["L0", "L1", "L2", "L3"]
    assert finest["observed_order"] == pytest.approx(2.0, abs=1e-12) and finest["pass"]
    # The GCI comes from the three finest levels' values whatever the coarse one says.
    assert finest["asymptotic_ratio"] == pytest.approx(1.0, abs=1e-12)
    # Two asymptotic levels: an order, but no GCI.
    two = study(h, error, asymptotic=2)
    assert two["observed_order"] == pytest.approx(2.0, abs=1e-12) and two["gci"] is None
    assert two["asymptotic_ratio"] is None and "no GCI: it needs three levels" in two["message"]
    # More asymptotic levels than ran (a base suite): all that ran.
    ran = study(h[:2], error[:2], asymptotic=3)
    assert ran["fit_levels"] == ["L0", "L1"] and ran["gci"] is None
    # Records keep per-level lists, finest last.
    assert finest["h"] == h and finest["wall_seconds"] == pytest.approx([0.1, 0.2, 0.3, 0.4])
    assert finest["cycles"] == [100, 400, 1600, 6400]


@pytest.mark.requirements("REQ-QA-005")
def test_gci_hand_examples():
    # f = 1 + h^2 on h = 1, 2, 4: phi = 2, 5, 17; e21 = 3, e32 = 12, r = 2, p = ln(12/3)/ln 2 = 2;
    # extrapolated = (4 * 2 - 5) / 3 = 1; gci_fine = 1.25 * |3 / 2| / 3 = 0.625;
    # GCI_12 = 1.25 * 3 / 3 = 1.25, GCI_23 = 1.25 * 12 / 3 = 5, ratio = 5 / (4 * 1.25) = 1
    g = grid_convergence_index([1.0, 2.0, 4.0], [2.0, 5.0, 17.0])
    assert (g.order, g.extrapolated, g.gci_fine, g.asymptotic_ratio) == (
        pytest.approx(2.0, rel=1e-13, abs=0), pytest.approx(1.0, rel=1e-13, abs=0), pytest.approx(0.625, rel=1e-13, abs=0),
        pytest.approx(1.0, rel=1e-13, abs=0))
    assert not g.oscillatory
    # Grids given coarse first give the same answer.
    assert grid_convergence_index([4.0, 2.0, 1.0], [17.0, 5.0, 2.0]).gci_fine == pytest.approx(0.625, rel=1e-13, abs=0)
    # Oscillatory: phi = 1.0, 1.1, 0.7: e21 = 0.1, e32 = -0.4, s = -1; with r21 = r32, q = 0 and
    # p = ln 4 / ln 2 = 2; extrapolated = (4 * 1 - 1.1) / 3 = 0.9666667.
    g = grid_convergence_index([1.0, 2.0, 4.0], [1.0, 1.1, 0.7])
    assert (g.order, g.extrapolated) == (pytest.approx(2.0, rel=1e-13, abs=0), pytest.approx(0.96666666667, rel=1e-10, abs=0))
    assert g.oscillatory
    # f = f0 + C h^2 with unequal ratios, h = 0.1, 0.13, 0.2: the fixed point is p = 2 exactly;
    # extrapolated = f0 = 1; gci_fine = 1.25 C h1^2 / phi1 = 1.25 * 0.005 / 1.005 = 6.2189055e-3.
    h = np.array([0.1, 0.13, 0.2])
    g = grid_convergence_index(h, 1.0 + 0.5 * h ** 2)
    assert g.order == pytest.approx(2.0, rel=1e-10, abs=0) and g.extrapolated == pytest.approx(1.0, rel=1e-12, abs=0)
    assert g.gci_fine == pytest.approx(6.2189055e-3, rel=1e-7, abs=0) and g.asymptotic_ratio == pytest.approx(1.0, rel=1e-10, abs=0)
    # Celik et al. (2008), Table 1, first column: phi = 6.063, 5.972, 5.863 on r21 = 1.5,
    # r32 = 1.333; printed p = 1.53, phi_ext = 6.1685, GCI_fine = 2.2 %.
    g = grid_convergence_index([1.0, 1.5, 2.0], [6.063, 5.972, 5.863])
    assert g.order == pytest.approx(1.53, abs=0.005) and g.extrapolated == pytest.approx(6.1685, abs=5e-5)
    assert g.gci_fine == pytest.approx(0.022, abs=5e-4)


@pytest.mark.requirements("REQ-QA-005")
@pytest.mark.parametrize("error, phrase", [
    ([0.04, 0.01, 0.0], "level L2: the error is exactly 0"),
    ([0.04, float("nan"), 0.0025], "level L1: the error is not finite"),
    ([float("inf"), 0.01, 0.0025], "level L0: the error is not finite"),
    ([0.04, None, 0.0025], "level L1: no error (cannot extract: the run wrote no results.json)"),
    ([0.04, 0.01, -0.0025], "level L2: the error -0.0025 is negative"),
])
def test_errors_that_cannot_be_fitted_fail_the_study(error, phrase):
    why = ["", "cannot extract: the run wrote no results.json", ""]
    record = study([0.2, 0.1, 0.05], error, numerical=[1.0, 1.1, 1.2], why=why)
    assert record["pass"] is False and record["observed_order"] is None
    assert record["message"].startswith("cannot fit an order: ") and phrase in record["message"]
    with pytest.raises(ConvergenceError, match="no order can be fitted"):
        observed_order([0.2, 0.1, 0.05], [float("nan") if e is None else e for e in error])


@pytest.mark.requirements("REQ-QA-005")
def test_degenerate_inputs_are_convergence_errors():
    with pytest.raises(ConvergenceError, match="at least two levels"):
        observed_order([0.1], [0.01])
    with pytest.raises(ConvergenceError, match="distinct"):
        observed_order([0.1, 0.1], [0.01, 0.02])
    with pytest.raises(ConvergenceError, match="2 zone sizes but 3 errors"):
        observed_order([0.2, 0.1], [0.04, 0.01, 0.0025])
    with pytest.raises(ConvergenceError, match="same value"):
        grid_convergence_index([0.4, 0.2, 0.1], [1.0, 1.0, 1.1])
    with pytest.raises(ConvergenceError, match="finest value is 0"):
        grid_convergence_index([0.4, 0.2, 0.1], [0.2, 0.1, 0.0])
    with pytest.raises(ConvergenceError, match="exactly three"):
        grid_convergence_index([0.4, 0.2], [0.2, 0.1])
    # A GCI that cannot be had is noted, and does not decide the study.
    record = study([0.4, 0.2, 0.1], [0.16, 0.04, 0.01], numerical=[1.0, 1.0, 1.1])
    assert record["pass"] and record["gci"] is None and "no GCI: two grids give the same value" in record["message"]
    with pytest.raises(ConvergenceError):
        observed_order([0.2, 0.1], [0.0, 0.0])
    assert study([0.2], [0.04])["pass"] is False


@pytest.mark.requirements("REQ-QA-005")
def test_the_harness_does_not_import_the_analytic_package():
    source = (Path(__file__).resolve().parents[2] / "verification/harness/vdec_verify/convergence.py").read_text()
    assert not re.search(r"^\s*(from|import)\s+analytic", source, re.M)


# ---------------------------------------------------------------- validation of [refinement]

VALID = '''id = "X-1"
title = "t"
requirements = ["REQ-QA-005"]
scene = "scene.toml"
expect_stop = "time"
overrides = ["fake.error=1e-9"]

[refinement]
expected_order = 2.0
order_tolerance = 0.3
justification = "why"

[[refinement.level]]
name = "n8"
h = 0.125
overrides = ["fake.h=0.125"]
level = "base"

[[refinement.level]]
name = "n16"
h = 0.0625
overrides = ["fake.h=0.0625"]
level = "base"

[[refinement.level]]
name = "n32"
h = 0.03125
overrides = ["fake.h=0.03125"]

[[check]]
refinement = true
quantity = "q"
extract = { kind = "final", history = "normal_force" }
reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }
norm = "scalar"
rtol = 1e-3
justification = "j"
tolerance_basis = "derived"

[[mutation]]
name = "error-10-percent"
overrides = ["fake.error=0.1"]
why = "Every history 10 % off: the checks must see it."
'''

PLAIN_CHECK = '''
[[check]]
quantity = "other"
extract = { kind = "final", history = "normal_force" }
reference = { constant = 25000.0 }
norm = "scalar"
rtol = 1e-3
justification = "j"
tolerance_basis = "derived"
'''


def mutated(old, new, text=VALID):
    assert old in text, old
    return text.replace(old, new, 1)


@pytest.mark.requirements("REQ-QA-005")
def test_a_valid_study_loads_with_its_runs(tmp_path):
    problem = load_problem(write_problem(tmp_path, VALID))
    study = problem.refinement
    assert (study.expected_order, study.order_tolerance, study.justification, study.asymptotic_levels) == \
        (2.0, 0.3, "why", None)
    assert [(lv.name, lv.h, lv.level) for lv in study.levels] == [("n8", 0.125, "base"), ("n16", 0.0625, "base"),
                                                                    ("n32", 0.03125, "full")]
    # No plain run: the only check is the studied one. Level overrides follow the problem's.
    assert [run.name for run in problem.runs] == ["n8", "n16", "n32"]
    assert problem.runs[0].overrides == ("fake.error=1e-9", "fake.h=0.125") and problem.runs[0].expect_exit == 0
    assert [run.name for run in problem.runs_at("base")] == ["n8", "n16"]
    assert [run.name for run in problem.runs_at("full")] == ["n8", "n16", "n32"]
    assert problem.studied_check.quantity == "q" and problem.studied_check.refinement
    # Another check without a variant brings the plain run back, first.
    problem = load_problem(write_problem(tmp_path, VALID + PLAIN_CHECK))
    assert [run.label for run in problem.runs] == ["plain", "n8", "n16", "n32"]
    # asymptotic_levels, and a full-level problem whose levels are all full.
    text = mutated('justification = "why"\n', 'justification = "why"\nasymptotic_levels = 3\n')
    text = mutated('scene = "scene.toml"\n', 'scene = "scene.toml"\nlevel = "full"\n', text).replace(
        'level = "base"\n', "")
    problem = load_problem(write_problem(tmp_path, text))
    assert problem.refinement.asymptotic_levels == 3 and len(problem.runs_at("full")) == 3
    assert problem.runs_at("base") == []     # (a base suite does not select the problem at all)


BASE_ONE = '''[[refinement.level]]
name = "n16"
h = 0.0625
overrides = ["fake.h=0.0625"]
level = "base"
'''

# (what to change in VALID, the key the error must name, a phrase of the message)
BAD_STUDIES = [
    ('expected_order = 2.0\n', "", r"refinement\.expected_order", "is required"),
    ('order_tolerance = 0.3\n', "", r"refinement\.order_tolerance", "is required"),
    ('justification = "why"\n', "", r"refinement\.justification", "is required"),
    ('expected_order = 2.0', 'expected_order = 0.0', r"refinement\.expected_order", "not a finite number > 0"),
    ('order_tolerance = 0.3', 'order_tolerance = -0.3', r"refinement\.order_tolerance", "not a finite number > 0"),
    ('justification = "why"', 'justification = " "', r"refinement\.justification", "why the order band is fair"),
    ('justification = "why"\n', 'justification = "why"\nlevels = 3\n', r"refinement\.levels", "unknown key"),
    ('justification = "why"\n', 'justification = "why"\nasymptotic_levels = 1\n', r"refinement\.asymptotic_levels",
     "not a number of levels from 2 to the 3"),
    ('justification = "why"\n', 'justification = "why"\nasymptotic_levels = 4\n', r"refinement\.asymptotic_levels",
     "not a number of levels"),
    ('h = 0.0625\n', "", r"refinement\.level\[1\]\.h", "is required"),
    ('h = 0.0625\n', "h = 0.125\n", r"refinement\.level\[1\]\.h", "not smaller than the previous level's h 0.125"),
    ('h = 0.03125\n', "h = 0.5\n", r"refinement\.level\[2\]\.h", "strictly decreasing"),
    ('h = 0.125\n', "h = -0.125\n", r"refinement\.level\[0\]\.h", "not a finite number > 0"),
    ('name = "n16"', 'name = "n8"', r"refinement\.level\[1\]\.name", "used by an earlier level"),
    ('name = "n16"', 'name = "a/b"', r"refinement\.level\[1\]\.name", "names a folder"),
    ('name = "n16"', 'name = "results.json"', r"refinement\.level\[1\]\.name", "name of a file"),
    ('name = "n32"\n', "", r"refinement\.level\[2\]\.name", "is required"),
    ('name = "n32"\n', 'name = "n32"\nzones = 32\n', r"refinement\.level\[2\]\.zones", "unknown key"),
    ('name = "n32"\n', 'name = "n32"\nlevel = "nightly"\n', r"refinement\.level\[2\]\.level", "'base' or 'full'"),
    ('overrides = ["fake.h=0.03125"]', 'overrides = ["fake.h"]', r"refinement\.level\[2\]\.overrides",
     "key.path=value"),
    ('[[check]]', '[[variant]]\nname = "n16"\n\n[[check]]', r"refinement\.level\[1\]\.name", "used by a \\[\\[variant\\]\\]"),
    # fewer than two levels
    (VALID[VALID.index("[[refinement.level]]"):VALID.index("[[check]]")], BASE_ONE + "\n", "refinement\\.level",
     "at least two \\[\\[refinement.level\\]\\] tables \\(found 1\\)"),
    # a base problem whose base suite would run fewer than two levels
    ('h = 0.0625\noverrides = ["fake.h=0.0625"]\nlevel = "base"\n', 'h = 0.0625\noverrides = ["fake.h=0.0625"]\n',
     "refinement\\.level", "1 of its levels are: give at least two levels level = \"base\""),
    # a full problem with a base level
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\nlevel = "full"\n', r"refinement\.level\[0\]\.level",
     "'base' has no effect: the problem's level is 'full'"),
    # [refinement] without a studied check
    ("refinement = true\n", "", "refinement", "no \\[\\[check\\]\\] has refinement = true"),
    ("refinement = true\n", "refinement = 1\n", r"check\[0\]\.refinement", "not true or false"),
    ('justification = "j"\n', 'justification = "j"\nvariant = "fast"\n', r"check\[0\]\.variant",
     "names no variant"),
    ('norm = "scalar"\nrtol = 1e-3', 'norm = "upper_bound"\nrtol = 1e-3', r"check\[0\]\.norm",
     "needs norm scalar, L2, Linf"),
]


@pytest.mark.requirements("REQ-QA-005")
@pytest.mark.parametrize("old, new, key, phrase", BAD_STUDIES, ids=[f"{b[2]}: {b[3]}"[:80] for b in BAD_STUDIES])
def test_refinement_errors_name_the_file_and_the_key(tmp_path, old, new, key, phrase):
    path = write_problem(tmp_path, mutated(old, new))
    with pytest.raises(ProblemError, match=rf"{key}': .*{phrase}") as e:
        load_problem(path)
    assert str(path) in str(e.value)


@pytest.mark.requirements("REQ-QA-005")
def test_a_studied_check_needs_a_study_and_only_one_check_is_studied(tmp_path):
    without = VALID[:VALID.index("[refinement]")] + VALID[VALID.index("[[check]]"):]
    with pytest.raises(ProblemError, match=r"check\[0\]\.refinement': there is no \[refinement\] table"):
        load_problem(write_problem(tmp_path, without))
    twice = VALID + PLAIN_CHECK.replace("[[check]]\n", "[[check]]\nrefinement = true\n")
    with pytest.raises(ProblemError, match=r"check\[1\]\.refinement': only one check .*check\[0\] already is"):
        load_problem(write_problem(tmp_path, twice))
    not_a_table = mutated('overrides = ["fake.error=1e-9"]\n', 'overrides = ["fake.error=1e-9"]\nrefinement = "yes"\n',
                          without)
    with pytest.raises(ProblemError, match=r"key 'refinement': must be a table"):
        load_problem(write_problem(tmp_path, not_a_table))


# ---------------------------------------------------------------- whole runs with the fake solver


@pytest.fixture(scope="module")
def full_suite(tmp_path_factory):
    out = tmp_path_factory.mktemp("convergence")
    code, stdout, stderr = run_main("run", "--vdec", FAKE_VDEC, "--problems", STUDIES, "--out", out,
                                    "--level", "full", "--jobs", "3")
    summary = json.loads((out / "summary.json").read_text())
    return {"code": code, "stdout": stdout, "stderr": stderr, "out": out, "summary": summary,
            "problems": {p["id"]: p for p in summary["problems"]}}


@pytest.mark.requirements("REQ-QA-005")
def test_a_second_order_study_passes_end_to_end(full_suite):
    problem = full_suite["problems"]["FX-ORDER-TWO"]
    assert problem["status"] == "pass", problem["message"]
    study = problem["convergence"]
    assert study["levels"] == ["h0.5", "h0.25", "h0.125", "h0.0625"]
    assert study["fit_levels"] == ["h0.25", "h0.125", "h0.0625"]
    assert study["h"] == [0.5, 0.25, 0.125, 0.0625]
    # The fake's relative error is 0.01 h^2 (plus 1e-9 noise).
    assert study["error"] == pytest.approx([0.01 * h ** 2 for h in study["h"]], rel=1e-3, abs=0)
    assert study["observed_order"] == pytest.approx(2.0, abs=1e-3)
    assert (study["expected_order"], study["order_tolerance"], study["pass"]) == (2.0, 0.1, True)
    assert study["gci"] == pytest.approx(1.25 * (0.01 * 0.125 ** 2 - 0.01 * 0.0625 ** 2) / 3.0, rel=1e-3, abs=0)
    assert study["asymptotic_ratio"] == pytest.approx(1.0, abs=1e-3)
    assert len(study["wall_seconds"]) == 4 and all(s > 0 for s in study["wall_seconds"])
    assert study["cycles"] == [round(4010 / h ** 2) for h in study["h"]]
    # The check's metric on the finest level, then the order's.
    check, order = problem["metrics"]
    assert check["quantity"] == "final normal force m g (level h0.0625)" and check["pass"]
    assert check["error"] == pytest.approx(study["error"][-1])
    assert order["quantity"] == "observed order of final normal force m g" and order["norm"] == "order"
    assert order["numerical"] == study["observed_order"] and order["reference"] == 2.0
    assert order["error"] == pytest.approx(abs(study["observed_order"] - 2.0), rel=1e-12, abs=0) and order["tolerance"] == 0.1
    assert order["pass"] and order["justification"].startswith("The fake's error is 0.01 h^2")
    # One run folder per level, no plain run.
    runs = full_suite["out"] / "runs" / "FX-ORDER-TWO"
    assert sorted(p.name for p in runs.iterdir() if p.is_dir()) == sorted(study["levels"])
    assert not (runs / "results.json").exists()
    assert "--set fake.h=0.125" in (runs / "h0.125" / "command.txt").read_text()


@pytest.mark.requirements("REQ-QA-005")
def test_a_first_order_solver_fails_a_second_order_study(full_suite):
    assert full_suite["code"] == 1
    assert full_suite["stdout"].strip().splitlines()[-1] == "1 passed, 1 failed"
    problem = full_suite["problems"]["FX-ORDER-ONE"]
    assert problem["status"] == "fail"
    study = problem["convergence"]
    assert study["observed_order"] == pytest.approx(1.0, abs=1e-3) and study["pass"] is False
    check, order = problem["metrics"]
    assert check["pass"]                      # the finest level alone is within its tolerance
    assert not order["pass"] and order["error"] == pytest.approx(1.0, abs=1e-3)
    assert "failed: observed order of final normal force m g (observed order 1.000" in problem["message"]
    assert "expected 2 +- 0.1" in problem["message"]


@pytest.mark.requirements("REQ-QA-005")
def test_summary_html_and_pdf_show_the_studies(full_suite):
    out, summary = full_suite["out"], full_suite["summary"]
    assert summary["schema"] == "vdec.verification/1"
    for study in (p["convergence"] for p in summary["problems"]):
        assert {"h", "error", "wall_seconds", "cycles", "observed_order", "expected_order", "order_tolerance", "gci",
                "asymptotic_ratio", "levels", "pass"} <= set(study)
    json.loads((out / "summary.json").read_text(), parse_constant=lambda c: pytest.fail(c))
    page = (out / "index.html").read_text()
    assert "<h2>Convergence studies</h2>" in page
    section = page[page.index("<h2>Convergence studies</h2>"):]
    for header in ("observed order", "expected order", "band", "GCI (fine)", "asymptotic ratio"):
        assert f"<th>{header}</th>" in section or f"<th>{header}" in section
    two = full_suite["problems"]["FX-ORDER-TWO"]["convergence"]
    assert f'{two["observed_order"]:.3f}' in section and "+- 0.1" in section and f'{two["gci"]:.3e}' in section
    assert html.escape("observed order of final normal force m g") in page
    for pid in ("FX-ORDER-ONE", "FX-ORDER-TWO"):
        assert (out / f"{pid}-convergence.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert f'src="{pid}-convergence.png"' in page
    pdf = (out / "report.pdf").read_bytes()
    assert pdf.startswith(b"%PDF")
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (poppler-utils) is not installed")
    text = " ".join(subprocess.run(["pdftotext", str(out / "report.pdf"), "-"], capture_output=True, text=True,
                                   check=True).stdout.split())
    assert "5 Convergence studies" in text and "work-precision" in text
    assert f'{two["observed_order"]:.3f}' in text and f'{two["gci"]:.3e}' in text


@pytest.mark.requirements("REQ-QA-005")
def test_the_base_suite_runs_the_base_levels_only(tmp_path):
    code, stdout, _ = run_main("run", "--vdec", FAKE_VDEC, "--problems", STUDIES, "--filter", "FX-ORDER-TWO",
                               "--out", tmp_path, "--level", "base", "--jobs", "2")
    assert code == 0, stdout
    problem = json.loads((tmp_path / "summary.json").read_text())["problems"][0]
    study = problem["convergence"]
    assert study["levels"] == ["h0.5", "h0.25"] and study["fit_levels"] == ["h0.5", "h0.25"]
    assert study["observed_order"] == pytest.approx(2.0, abs=1e-3) and study["pass"]
    assert study["gci"] is None and study["asymptotic_ratio"] is None
    assert problem["metrics"][0]["quantity"].endswith("(level h0.25)")
    assert [r["variant"] for r in problem["runs"]] == ["h0.5", "h0.25"]
    assert not (tmp_path / "runs" / "FX-ORDER-TWO" / "h0.125").exists()


@pytest.mark.requirements("REQ-QA-005")
def test_a_study_with_zero_errors_or_a_failed_level_fails(tmp_path):
    root = tmp_path / "problems"
    # A constant reference equal to the fake's value: every level's error is exactly zero.
    zero = VALID.replace('extract = { kind = "final", history = "normal_force" }',
                         'extract = { kind = "run_meta", path = "energy.largest_excess" }').replace(
        '{ function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }',
        "{ constant = 0.25 }")
    write_problem(root, zero.replace('"X-1"', '"Z-1"'), "Z-1")
    # The middle level crashes without results.
    crash = mutated('overrides = ["fake.h=0.0625"]',
                    'overrides = ["fake.h=0.0625", "fake.exit_code=5", "fake.write_results=false"]')
    write_problem(root, crash.replace('"X-1"', '"Z-2"'), "Z-2")
    code, stdout, _ = run_main("run", "--vdec", FAKE_VDEC, "--problems", root, "--out", tmp_path / "out",
                               "--level", "full")
    assert code == 1 and stdout.strip().splitlines()[-1] == "0 passed, 2 failed"
    problems = {p["id"]: p for p in json.loads((tmp_path / "out" / "summary.json").read_text())["problems"]}
    zero_study = problems["Z-1"]["convergence"]
    assert zero_study["error"] == [0.0, 0.0, 0.0] and zero_study["pass"] is False
    assert zero_study["observed_order"] is None
    assert "cannot fit an order: level n8: the error is exactly 0" in zero_study["message"]
    assert problems["Z-1"]["metrics"][0]["pass"]    # the check itself is met; the study is not
    assert problems["Z-1"]["status"] == "fail"
    crashed = problems["Z-2"]
    assert crashed["status"] == "fail" and crashed["convergence"]["error"][1] is None
    assert "level n16: no error (cannot extract: the run wrote no results.json)" in crashed["convergence"]["message"]
    assert "run n16: exited 5" in crashed["message"]


@pytest.mark.requirements("REQ-QA-005")
def test_check_command_lists_the_study():
    code, stdout, _ = run_main("check", "--problems", STUDIES)
    assert code == 0 and stdout.strip().splitlines()[-1] == "2 valid, 0 invalid"
    assert ("valid    FX-ORDER-TWO (base; 1 checks; runs: h0.5, h0.25, h0.125, h0.0625; refinement: 4 levels "
            "(2 base), expected order 2 +- 0.1)") in stdout


@pytest.mark.requirements("REQ-QA-005")
def test_a_studied_derived_check_reads_another_run_of_the_problem(tmp_path):
    """Each level's error may be measured against another run (FL-SCHEMES: an implicit run over
    the explicit plain run), through a derived extract whose input names that run."""
    from vdec_verify.runner import RunOutcome, judge_study
    text = mutated('extract = { kind = "final", history = "normal_force" }\nreference = { function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }',
                   'extract = { kind = "derived", function = "ratio", inputs = { numerator = { kind = "run_meta", path = "run.time" }, '
                   'denominator = { kind = "run_meta", path = "run.time", variant = "" } } }\nreference = { constant = 1.0 }')
    problem = load_problem(write_problem(tmp_path, text + PLAIN_CHECK))
    outcome = lambda name, time: RunOutcome(name, [], tmp_path, 0, 0, {"run": {"time": time}}, 1.0)
    # errors 0.01 h^2 against the plain run's 1.0
    outcomes = {"": outcome("", 1.0)}
    outcomes.update({lv.name: outcome(lv.name, 1.0 + 0.01 * lv.h ** 2) for lv in problem.refinement.levels})
    metrics, study, invalid = judge_study(problem, problem.studied_check, outcomes, "full")
    assert invalid == [] and study["pass"], study
    assert metrics[0]["error"] == pytest.approx(0.01 * 0.03125 ** 2, rel=1e-9, abs=0)
    assert study["observed_order"] == pytest.approx(2.0, abs=1e-6)


# ---------------------------------------------------------------- [[work_precision]] figures

WORK = '''
[[work_precision]]
title = "fast against slow"
series = [{ label = "plain", checks = [2] }]
'''

BAD_WORK = [
    ('title = "fast against slow"\n', "", r"work_precision\[0\]\.title", "is required"),
    ("checks = [2]", "checks = [3]", r"work_precision\[0\]\.series\[0\]\.checks", "not a \\[\\[check\\]\\] number from 1 to 2"),
    ("checks = [2]", "checks = [1]", r"work_precision\[0\]\.series\[0\]\.checks", "not the studied check"),
    ("checks = [2]", "checks = []", r"work_precision\[0\]\.series\[0\]\.checks", "must be a list"),
    ('label = "plain", ', "", r"work_precision\[0\]\.series\[0\]\.label", "is required"),
    ('title = "fast against slow"\n', 'title = "fast against slow"\nkind = "x"\n', r"work_precision\[0\]\.kind", "unknown key"),
]


@pytest.mark.requirements("REQ-QA-005")
def test_a_work_precision_figure_loads_its_series_of_checks(tmp_path):
    problem = load_problem(write_problem(tmp_path, VALID + PLAIN_CHECK + WORK))
    assert [(w.title, w.series) for w in problem.work_precision] == [("fast against slow", (("plain", (1,)),))]


@pytest.mark.requirements("REQ-QA-005")
@pytest.mark.parametrize("old, new, key, phrase", BAD_WORK, ids=[f"{b[2]}: {b[3]}"[:80] for b in BAD_WORK])
def test_work_precision_errors_name_the_key(tmp_path, old, new, key, phrase):
    path = write_problem(tmp_path, mutated(old, new, VALID + PLAIN_CHECK + WORK))
    with pytest.raises(ProblemError, match=rf"{key}': .*{phrase}"):
        load_problem(path)
