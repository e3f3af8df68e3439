"""Checker guards of the verification harness: problem.toml validation and the
reference-independence guard (REQ-QA-002)."""
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from vdec_verify.extract import Series
from vdec_verify.norms import NOT_INDEPENDENT, ReferenceProblem, evaluate_reference
from vdec_verify.problem import ProblemError, Reference, load_problem
from vdec_verify.runner import Entry, discover, judge, run_suite, select
from problem_files import write_problem

FAKE_VDEC = Path(__file__).parent / "fixtures" / "harness" / "fake_vdec.py"

VALID = '''id = "X-1"
title = "t"
requirements = ["REQ-QA-002"]
scene = "scene.toml"
expect_stop = "time"

[[check]]
quantity = "q"
extract = { kind = "final", history = "h" }
reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }
norm = "scalar"
rtol = 1e-3
justification = "j"
tolerance_basis = "derived"

[[mutation]]
name = "error-10-percent"
overrides = ["fake.error=0.1"]
why = "Every history 10 % off: the checks must see it."
'''


def mutated(old, new):
    assert old in VALID, old
    return VALID.replace(old, new, 1)


@pytest.mark.requirements("REQ-QA-002")
def test_problem_without_tolerance_is_rejected(tmp_path):
    path = write_problem(tmp_path, mutated("rtol = 1e-3\n", ""))
    with pytest.raises(ProblemError, match=r"key 'check\[0\]\.rtol': the check has no tolerance") as e:
        load_problem(path)
    assert str(path) in str(e.value)
    path = write_problem(tmp_path, mutated("rtol = 1e-3\n", "atol = 0.5\n"))
    check = load_problem(path).checks[0]
    assert (check.rtol, check.atol) == (0.0, 0.5)


@pytest.mark.requirements("REQ-QA-002")
def test_reference_identical_to_output_is_rejected(monkeypatch):
    x = np.linspace(0.0, 1.0, 11)
    numerical = Series(x, x ** 2, "t", "h")
    module = types.ModuleType("analytic.harness_guard_refs")
    module.echo = lambda t, **params: t                      # the very array passed in
    module.view = lambda t, **params: t[:]                   # a view of it
    module.square = lambda t, **params: np.asarray(t) ** 2   # a fresh array equal to the output
    module.square_plus = lambda t, **params: np.asarray(t) ** 2 * (1 + 1e-6)
    monkeypatch.setitem(sys.modules, module.__name__, module)
    for name in ("echo", "view", "square"):
        with pytest.raises(ReferenceProblem, match="reference identical to the numerical output"):
            evaluate_reference(Reference(f"harness_guard_refs.{name}", {}, None, None), numerical, getattr(module, name))
    independent = evaluate_reference(Reference("harness_guard_refs.square_plus", {}, None, None), numerical,
                                     module.square_plus)
    assert independent.shape == x.shape
    # A constant typed into problem.toml cannot come from the output: equal values are allowed.
    zeros = Series(x, np.zeros_like(x), "t", "h")
    assert np.all(evaluate_reference(Reference("", {}, None, 0.0), zeros, None) == 0.0)


@pytest.mark.requirements("REQ-QA-002")
def test_reference_cannot_alter_the_numerical_data(monkeypatch):
    x = np.linspace(0.0, 1.0, 5)

    def in_place(t):
        t *= 2.0
        return t

    with pytest.raises(ReferenceProblem, match="raised ValueError"):
        evaluate_reference(Reference("m.in_place", {}, None, None), Series(x, x + 1, "t", "h"), in_place)
    assert x[-1] == 1.0


@pytest.mark.requirements("REQ-QA-002")
def test_identical_reference_makes_the_problem_invalid_in_a_run(tmp_path, monkeypatch):
    module = types.ModuleType("analytic.harness_guard_run")
    module.copy_of_x = lambda us, **params: np.array(us, dtype=float)
    monkeypatch.setitem(sys.modules, module.__name__, module)
    text = VALID.replace('extract = { kind = "final", history = "h" }', 'extract = { kind = "curve", x = "us", y = "us" }')
    text = text.replace('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
                        '{ function = "harness_guard_run.copy_of_x" }').replace('"scalar"', '"L2"')
    write_problem(tmp_path / "problems", text)
    records = run_suite(discover(tmp_path / "problems"), FAKE_VDEC, tmp_path / "out", jobs=1, progress=None)
    assert records[0]["status"] == "invalid"
    assert NOT_INDEPENDENT in records[0]["message"]


# (what to change in VALID, the key the error must name, a phrase of the message)
BAD_PROBLEMS = [
    ('title = "t"\n', 'title = "t"\ncolour = "red"\n', "colour", "unknown key"),
    ('justification = "j"\n', 'justification = "j"\ntolerance = 1\n', r"check\[0\]\.tolerance", "unknown key"),
    ('id = "X-1"\n', "", "id", "is required"),
    ('title = "t"\n', "", "title", "is required"),
    ('requirements = ["REQ-QA-002"]\n', "", "requirements", "is required"),
    ('scene = "scene.toml"\n', "", "scene", "is required"),
    ('id = "X-1"\n', 'id = "X-2"\n', "id", "must equal the folder name 'X-1'"),
    ('["REQ-QA-002"]', '["REQ-qa-2"]', "requirements", "not a requirement id"),
    ('["REQ-QA-002"]', '["REQ-QA-0021"]', "requirements", "not a requirement id"),
    ('["REQ-QA-002"]', "[]", "requirements", "at least one"),
    ('"scene.toml"', '"missing.toml"', "scene", "no file"),
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\nlevel = "nightly"\n', "level", "'base' or 'full'"),
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\nexpect_exit = "zero"\n', "expect_exit", "not an exit code"),
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\noverrides = ["solver.frac"]\n', "overrides", "key.path=value"),
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\ntimeout_seconds = -1\n', "timeout_seconds", "positive"),
    ('scene = "scene.toml"\n', 'scene = "scene.toml"\n[refinement]\nlevels = 3\n', r"refinement\.levels",
     "unknown key"),
    ('justification = "j"\n', "", r"check\[0\]\.justification", "is required"),
    ('justification = "j"', 'justification = "  "', r"check\[0\]\.justification", "why the tolerance is fair"),
    ('quantity = "q"\n', "", r"check\[0\]\.quantity", "is required"),
    ('reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }\n', "",
     r"check\[0\]\.reference", "is required"),
    ('norm = "scalar"\n', "", r"check\[0\]\.norm", "is required"),
    ('"final"', '"finale"', r"check\[0\]\.extract\.kind", "unknown extract kind 'finale'"),
    ('{ kind = "final", history = "h" }', '{ kind = "final" }', r"check\[0\]\.extract\.history", "is required"),
    ('{ kind = "final", history = "h" }', '{ kind = "final", history = "h", window = [0, 1] }',
     r"check\[0\]\.extract\.window", "unknown key"),
    ('{ kind = "final", history = "h" }', '{ kind = "max", history = "h", window = [1.0, 0.5] }',
     r"check\[0\]\.extract\.window", "t_start < t_end"),
    ('{ kind = "final", history = "h" }', '{ kind = "run_meta", path = "histories.h" }',
     r"check\[0\]\.extract\.path", "into run, energy, fluid, heat or phases"),
    ('{ kind = "final", history = "h" }', '{ kind = "value_at", history = "h", t = "late" }',
     r"check\[0\]\.extract\.t", "not a number"),
    ('norm = "scalar"', 'norm = "L3"', r"check\[0\]\.norm", "unknown norm 'L3'"),
    ('norm = "scalar"', 'norm = "L2"', r"check\[0\]\.norm", "does not apply to extract kind 'final'"),
    ('rtol = 1e-3', 'rtol = -1e-3', r"check\[0\]\.rtol", "not a tolerance"),
    ('"rigid_blocks.resting_normal_force"', '"rigid_blocks.no_such_function"', r"check\[0\]\.reference\.function",
     "has no function 'no_such_function'"),
    ('"rigid_blocks.resting_normal_force"', '"no_such_module.f"', r"check\[0\]\.reference\.function",
     "cannot import analytic.no_such_module"),
    ('"rigid_blocks.resting_normal_force"', '"resting_normal_force"', r"check\[0\]\.reference\.function",
     "module.function"),
    ("params = { mass = 1.0, g = 1.0 }", "params = { mas = 1.0, g = 1.0 }", r"check\[0\]\.reference\.params",
     "do not fit"),
    ("params = { mass = 1.0, g = 1.0 } }", "params = { mass = 1.0, g = 1.0 }, constant = 2.0 }",
     r"check\[0\]\.reference", "exactly one of function"),
    ('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
     '{ constant = "one" }', r"check\[0\]\.reference\.constant", "not a number"),
    ('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
     '{ constant = 1.0, params = { a = 1 } }', r"check\[0\]\.reference\.params", "not to a constant"),
    ("params = { mass = 1.0, g = 1.0 } }", 'params = { mass = 1.0 }, run_params = { g = "histories.h" } }',
     r"check\[0\]\.reference\.run_params\.g", "into run, energy, fluid, heat or phases"),
    ("params = { mass = 1.0, g = 1.0 } }", 'params = { mass = 1.0, g = 1.0 }, run_params = { g = "run.dt" } }',
     r"check\[0\]\.reference\.run_params\.g", "also given in params"),
    ("params = { mass = 1.0, g = 1.0 } }", 'params = { mass = 1.0, g = 1.0 }, run_params = { dt = "run.dt" } }',
     r"check\[0\]\.reference\.params", "do not fit"),
    ("params = { mass = 1.0, g = 1.0 } }", 'params = { mass = 1.0 }, run_params = "run.dt" }',
     r"check\[0\]\.reference\.run_params", "must be a table"),
    ('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
     '{ constant = 1.0, run_params = { dt = "run.dt" } }', r"check\[0\]\.reference\.run_params", "not to a constant"),
    ('justification = "j"\n', 'justification = "j"\nvariant = "fast"\n', r"check\[0\]\.variant",
     "no \\[\\[variant\\]\\] named 'fast'"),
    ('[[check]]', '[[variant]]\nname = "a/b"\n\n[[check]]', r"variant\[0\]\.name", "names a folder"),
    ('[[check]]', '[[variant]]\nname = "a"\nframes = 3\n\n[[check]]', r"variant\[0\]\.frames", "unknown key"),
    ('[[check]]', '[[variant]]\nname = "a"\n[[variant]]\nname = "a"\n\n[[check]]', r"variant\[1\]\.name",
     "used by an earlier variant"),
    ('[[check]]', '[[variant]]\nname = "a"\nscene = "large.toml"\n\n[[check]]', r"variant\[0\]\.scene", "no file"),
    ('[[check]]', '[[variant]]\nname = "a"\nscene = 3\n\n[[check]]', r"variant\[0\]\.scene",
     "file name relative to the problem folder"),
]


@pytest.mark.requirements("REQ-QA-002", "REQ-QA-010")
@pytest.mark.parametrize("old, new, key, phrase", BAD_PROBLEMS, ids=[f"{b[2]}: {b[3]}" for b in BAD_PROBLEMS])
def test_problem_errors_name_the_file_and_the_key(tmp_path, old, new, key, phrase):
    path = write_problem(tmp_path, mutated(old, new))
    with pytest.raises(ProblemError, match=rf"{key}': .*{phrase}") as e:
        load_problem(path)
    assert str(path) in str(e.value)


@pytest.mark.requirements("REQ-QA-002")
def test_a_problem_without_checks_is_rejected(tmp_path):
    path = write_problem(tmp_path, VALID[:VALID.index("[[check]]")])
    with pytest.raises(ProblemError, match="key 'check': is required"):
        load_problem(path)


@pytest.mark.requirements("REQ-QA-002")
def test_all_errors_of_a_file_are_reported_together(tmp_path):
    text = mutated('title = "t"\n', 'title = "t"\ncolour = "red"\n').replace('norm = "scalar"', 'norm = "L3"')
    with pytest.raises(ProblemError) as e:
        load_problem(write_problem(tmp_path, text))
    assert "key 'colour'" in str(e.value) and "key 'check[0].norm'" in str(e.value)


@pytest.mark.requirements("REQ-QA-002")
def test_norm_equal_takes_no_tolerance_and_needs_none(tmp_path):
    text = (mutated('{ kind = "final", history = "h" }', '{ kind = "exit_code" }')
            .replace('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
                     "{ constant = 5 }").replace('norm = "scalar"', 'norm = "equal"'))
    with pytest.raises(ProblemError, match=r"check\[0\]\.rtol': norm 'equal' means exact equality"):
        load_problem(write_problem(tmp_path, text))
    check = load_problem(write_problem(tmp_path, text.replace("rtol = 1e-3\n", ""))).checks[0]
    assert check.reference.constant == 5.0 and check.norm == "equal"


@pytest.mark.requirements("REQ-QA-002")
def test_invalid_problems_are_reported_not_skipped(tmp_path):
    root = tmp_path / "problems"
    write_problem(root, VALID)
    write_problem(root, VALID.replace('"X-1"', '"X-2"').replace('norm = "scalar"', 'norm = "L3"'), "X-2")
    write_problem(root, VALID.replace('"X-1"', '"X-3"').replace('scene = "scene.toml"', 'scene = "scene.toml"\n'
                                                                 'level = "full"\nbogus = 1'), "X-3")
    (root / "X-4").mkdir()                 # a folder without problem.toml
    (root / "_shared").mkdir()             # shared files: not a problem
    entries = select(discover(root), "base", [])
    assert [e.id for e in entries] == ["X-1", "X-2", "X-3", "X-4"]
    assert [e.problem is None for e in entries] == [False, True, True, True]
    record = judge(entries[1], {})
    assert record["status"] == "invalid" and "key 'check[0].norm'" in record["message"]
    assert record["requirements"] == ["REQ-QA-002"] and record["title"] == "t"
    assert judge(Entry("X-4", root / "X-4", error="no problem.toml"), {})["status"] == "invalid"


@pytest.mark.requirements("REQ-QA-001")
def test_an_expected_stop_for_another_reason_fails(tmp_path):
    text = VALID.replace('[[check]]', '[[variant]]\nname = "stop"\nexpect_exit = 5\n'
                         'overrides = ["fake.exit_code=5"]\nexpect_message = "joint stiffness grown"\n\n[[check]]', 1)
    text = text.replace('extract = { kind = "final", history = "h" }', 'extract = { kind = "exit_code" }\nvariant = "stop"')
    text = text.replace('reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
                        'reference = { constant = 5 }').replace('norm = "scalar"\nrtol = 1e-3\n', 'norm = "equal"\n')
    write_problem(tmp_path / "problems", text)
    records = run_suite(discover(tmp_path / "problems"), FAKE_VDEC, tmp_path / "out", jobs=1, progress=None)
    assert records[0]["status"] == "fail"
    assert "not with the expected message 'joint stiffness grown'" in records[0]["message"]
    assert "fake failure with exit code 5" in records[0]["message"]


@pytest.mark.requirements("REQ-QA-001")
def test_an_expected_message_needs_a_nonzero_exit(tmp_path):
    text = VALID.replace('[[check]]', '[[variant]]\nname = "v"\nexpect_message = "x"\n\n[[check]]', 1)
    with pytest.raises(ProblemError, match=r"variant\[0\]\.expect_message"):
        load_problem(write_problem(tmp_path, text))


@pytest.mark.requirements("REQ-QA-002")
def test_run_params_pass_a_value_of_the_checked_run_to_the_reference(tmp_path, monkeypatch):
    # The reference of a discrete scheme needs the step the solver chose: run_params reads it from
    # the run the check reads, each run its own, and a run without the field cannot be judged.
    from vdec_verify.runner import RunOutcome, judge_check
    module = types.ModuleType("analytic.harness_run_params")
    module.scaled = lambda t, *, dt, scale: scale * dt * np.ones_like(t)
    monkeypatch.setitem(sys.modules, module.__name__, module)
    text = mutated('{ function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }',
                   '{ function = "harness_run_params.scaled", params = { scale = 2.0 }, run_params = { dt = "run.dt" } }')
    text = text.replace('{ kind = "final", history = "h" }', '{ kind = "history", history = "h" }').replace('"scalar"', '"L2"')
    check = load_problem(write_problem(tmp_path, text)).checks[0]
    assert check.reference.run_params == {"dt": "run.dt"} and check.reference.params == {"scale": 2.0}

    def outcome(dt):
        results = {"run": {"dt": dt}, "histories": {"h": {"t": [0.0, 1.0], "value": [0.5, 0.5], "every": 1}}}
        return RunOutcome("", [], tmp_path, 0, exit_code=0, results=results)

    metric = judge_check(check, outcome(0.2501))              # 2 x 0.2501, within 1e-3 of the history's 0.5
    assert metric["pass"] and metric["reference"] == pytest.approx(0.5002)
    metric = judge_check(check, outcome(0.3))
    assert not metric["pass"] and metric["reference"] == pytest.approx(0.6)
    missing = outcome(0.2501)
    del missing.results["run"]["dt"]
    metric = judge_check(check, missing)
    assert not metric["pass"] and "run_params" in metric["message"] and "run.dt" in metric["message"]
    assert check.reference.params == {"scale": 2.0}           # the problem's own params are left as written


@pytest.mark.requirements("REQ-QA-002")
def test_fluid_fields_and_the_fluid_balance_can_be_checked(tmp_path):
    # Fracture-flow problems read the domains and knots as fields and the mass balance as run_meta.
    text = mutated('extract = { kind = "final", history = "h" }',
                   'extract = { kind = "field_mean", of = "knots", quantity = "flow" }')
    text += '''
[[check]]
quantity = "imbalance"
extract = { kind = "run_meta", path = "fluid.balance.imbalance" }
reference = { constant = 0.0 }
norm = "scalar"
atol = 1e-18
justification = "j"
tolerance_basis = "derived"

[[check]]
quantity = "pressures"
extract = { kind = "field", of = "domains", quantity = "pressure" }
reference = { constant = 0.0 }
norm = "Linf"
atol = 1.0
justification = "j"
tolerance_basis = "derived"
'''
    problem = load_problem(write_problem(tmp_path, text))
    assert [c.extract.get("of", c.extract.get("path")) for c in problem.checks] == \
        ["knots", "fluid.balance.imbalance", "domains"]
    with pytest.raises(ProblemError, match=r"check\[0\]\.extract\.of': 'voids' is not one of .*\"knots\""):
        load_problem(write_problem(tmp_path, text.replace('of = "knots"', 'of = "voids"')))
