"""Configuration control of the verification evidence (REQ-CM-001): summary.json records the
SHA-256 of every input of every run, counts untracked files as uncommitted work, marks a run
from outside the repository as not qualified; the audit catches the issue-12 case of a changed
copy of the problems run against a clean checkout."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import audit
from vdec_verify import provenance
from vdec_verify.problem import load_problem

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "verification/problems"
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))

pytestmark = pytest.mark.requirements("REQ-CM-001")


def git(root, *args):
    command = ["git", "-C", str(root), "-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"]
    return subprocess.run(command + list(args), capture_output=True, text=True, check=True).stdout.strip()


def test_an_untracked_file_makes_the_checkout_dirty(tmp_path, monkeypatch):
    (tmp_path / "tracked.txt").write_text("x\n")
    git(tmp_path, "init", "-q")
    git(tmp_path, "add", "-A")
    git(tmp_path, "commit", "-qm", "one")
    monkeypatch.setattr(provenance, "HARNESS_REPOSITORY", tmp_path)
    assert provenance.harness_info()["git_dirty"] is False
    (tmp_path / "copy-of-a-problem.toml").write_text("ks = 0.55e10\n")
    assert provenance.harness_info()["git_dirty"] is True


def test_a_problem_records_its_toml_scene_tables_and_analytic_module():
    problem = load_problem(PROBLEMS / "MC-TUNNEL-CONVERGENCE/problem.toml")
    inputs = provenance.problem_inputs(problem, problem.runs)
    tables = [p for p in inputs if p.endswith(".csv")]
    # The scene of this problem reads a table of the MC-TUNNEL folder: found, and its hash right.
    assert tables == ["verification/problems/MC-TUNNEL/far_field_change.csv"]
    assert inputs[tables[0]] == provenance.sha256_of(ROOT / tables[0])
    assert {"verification/problems/MC-TUNNEL-CONVERGENCE/problem.toml",
            "verification/problems/MC-TUNNEL-CONVERGENCE/scene.toml", "verification/analytic/__init__.py"} <= set(inputs)
    modules = {p for p in inputs if p.startswith("verification/analytic/") and not p.endswith("__init__.py")}
    used = {c.reference.function_name.rpartition(".")[0] for c in problem.checks if c.reference.function_name}
    assert modules == {f"verification/analytic/{m}.py" for m in used} and modules


def test_the_reference_program_of_a_module_is_recorded(tmp_path, monkeypatch):
    program = tmp_path / "vdec_cy_reference"
    program.write_text("#!/bin/sh\n")
    program.chmod(0o755)
    monkeypatch.setenv("VDEC_CY_REFERENCE", str(program))
    problem = load_problem(PROBLEMS / "CY-SHEAR/problem.toml")
    inputs = provenance.problem_inputs(problem, problem.runs)
    assert inputs[str(program)] == provenance.sha256_of(program)
    assert "verification/analytic/joints.py" in inputs
    monkeypatch.setenv("VDEC_CY_REFERENCE", str(tmp_path / "absent"))
    inputs = provenance.problem_inputs(problem, problem.runs)
    assert inputs["analytic.joints.reference_programs()"] is None   # the audit makes this a gap


def test_a_table_named_by_an_override_is_an_input(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text('title = "t"\n[[boundary]]\nstress_table = "a.csv"\n')
    (tmp_path / "a.csv").write_text("1\n")
    (tmp_path / "b.csv").write_text("2\n")
    found = provenance.scene_files(scene, ["boundary[0].stress_table=b.csv", "solver.frac=0.5"])
    assert sorted(p.name for p in found) == ["a.csv", "b.csv"]


def test_a_run_from_outside_the_repository_is_not_qualified(tmp_path):
    configuration = provenance.run_configuration(Path(sys.executable), tmp_path, [])
    assert configuration["problems_dir_in_repository"] is False
    info = provenance.harness_info(configuration)
    assert info["qualified"] is False
    assert f"the problems folder {tmp_path} is outside the repository" in info["not_qualified_because"]
    inside = provenance.run_configuration(Path(sys.executable), PROBLEMS, ["RB"])
    assert inside["problems_dir"] == "verification/problems" and inside["problems_dir_in_repository"]
    reasons = provenance.not_qualified_because(dict(inside, git_commit="a" * 40, git_dirty=False))
    assert reasons == ["only the problems matching the filter ['RB'] ran"]
    assert provenance.not_qualified_because(dict(inside, git_commit="a" * 40, git_dirty=False, filter=[])) == []
    assert set(inside["files"]) == {f"verification/harness/vdec_verify/{p.name}"
                                    for p in (ROOT / "verification/harness/vdec_verify").glob("*.py")}


@pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
def test_a_changed_copy_of_the_problems_is_caught_by_the_audit(tmp_path):
    """Issue 12's case: a copy of the problems with a joint shear stiffness at 0.55 of its value
    gave a summary with the same commit, git_dirty false and the same scene hash. Now its inputs
    are recorded as files outside the repository, the run is not qualified, and the audit fails."""
    copy = tmp_path / "problems"
    shutil.copytree(PROBLEMS / "RB-INCLINE-STICK", copy / "RB-INCLINE-STICK")
    problem_toml = copy / "RB-INCLINE-STICK/problem.toml"
    # The scene stays byte for byte the repository's: the change is an override in problem.toml.
    text = problem_toml.read_text()
    assert 'scene = "scene.toml"' in text
    problem_toml.write_text(text.replace('scene = "scene.toml"',
                                         'scene = "scene.toml"\noverrides = ["joint_material[0].ks=5.5e9"]', 1))
    out = tmp_path / "out"
    environment = dict(os.environ, PYTHONPATH=f"{ROOT / 'verification/harness'}:{ROOT / 'verification'}")
    subprocess.run([sys.executable, "-m", "vdec_verify", "run", "--vdec", VDEC, "--problems", copy, "--level",
                    "base", "--out", out], capture_output=True, text=True, env=environment, cwd=ROOT)
    summary = json.loads((out / "summary.json").read_text())
    record = summary["problems"][0]
    assert record["scene_sha256"] == provenance.sha256_of(PROBLEMS / "RB-INCLINE-STICK/scene.toml")
    assert summary["harness"]["qualified"] is False
    assert record["inputs"][str(problem_toml)] == provenance.sha256_of(problem_toml)
    code = audit.main(["--root", str(ROOT), "--mode", "test-suite", "--summary", str(out / "summary.json"),
                       "--junit", str(tmp_path / "none*.xml"), "--out", str(tmp_path / "rtm")])
    page = (tmp_path / "rtm/rtm.html").read_text()
    assert code == 1
    assert f"the problems folder {copy} is outside the repository" in page
    assert ("its runs did not read the repository&#x27;s verification/problems/RB-INCLINE-STICK/problem.toml"
            in page)


def test_the_analytic_module_of_a_derived_extract_is_recorded(tmp_path):
    folder = tmp_path / "DB-UNIAXIAL"
    shutil.copytree(PROBLEMS / "DB-UNIAXIAL", folder)
    text = (folder / "problem.toml").read_text()
    # The inversion formula of the derived extracts from another module than the references'.
    assert 'kind = "derived", function = "elastic.young_poisson_from_plane_strain_uniaxial"' in text
    (folder / "problem.toml").write_text(text.replace("elastic.young_poisson_from_plane_strain_uniaxial",
                                                      "rocking.block_radius_and_slenderness"))
    problem = load_problem(folder / "problem.toml")
    assert "rocking" not in " ".join(c.reference.function_name for c in problem.checks)
    inputs = provenance.problem_inputs(problem, problem.runs)
    assert inputs["verification/analytic/rocking.py"] == provenance.sha256_of(ROOT / "verification/analytic/rocking.py")


@pytest.mark.requirements("REQ-QA-010")
def test_every_scene_of_a_problem_and_its_tables_are_inputs():
    problem = load_problem(PROBLEMS / "BE-JOINTED-TUNNEL/problem.toml")
    scenes = {run.name: run.scene for run in problem.runs if run.scene}
    assert scenes == {"large-stress": PROBLEMS / "BE-JOINTED-TUNNEL/large-stress.toml",
                      "large-fixed": PROBLEMS / "BE-JOINTED-TUNNEL/large-fixed.toml"}
    inputs = provenance.problem_inputs(problem, problem.runs)
    folder = "verification/problems/BE-JOINTED-TUNNEL/"
    assert {folder + name for name in ("problem.toml", "scene.toml", "large-stress.toml", "large-fixed.toml",
                                       "unload.csv")} <= set(inputs)
    assert inputs[folder + "large-fixed.toml"] == provenance.sha256_of(PROBLEMS / "BE-JOINTED-TUNNEL/large-fixed.toml")
