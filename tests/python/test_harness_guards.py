import pytest

from vdec_verify.checks import evaluate
from vdec_verify.problem import Check, ProblemError, load_problem

PROBLEM = '''
id = "X-1"
title = "t"
requirements = ["REQ-QA-002"]
scene = "scene.toml"
[[check]]
quantity = "q"
extract = { kind = "final", history = "h" }
reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 1.0, g = 1.0 } }
norm = "scalar"
justification = "j"
'''


@pytest.mark.requirements("REQ-QA-002")
def test_problem_without_tolerance_is_rejected(tmp_path):
    folder = tmp_path / "X-1"
    folder.mkdir()
    (folder / "scene.toml").write_text("")
    (folder / "problem.toml").write_text(PROBLEM)
    with pytest.raises(ProblemError, match="tolerance"):
        load_problem(folder / "problem.toml")
    (folder / "problem.toml").write_text(PROBLEM.replace('norm = "scalar"', 'norm = "scalar"\nrtol = 1e-3'))
    assert load_problem(folder / "problem.toml").checks[0].rtol == 1e-3


@pytest.mark.requirements("REQ-QA-002")
def test_reference_identical_to_output_is_rejected():
    import numpy as np
    check = Check("q", {}, {}, "L2", 1e-3, 0.0, "j", "")
    x = np.linspace(0, 1, 5)
    y = x ** 2
    with pytest.raises(ProblemError, match="identical"):
        evaluate(check, (x, y), y.copy())
    assert evaluate(check, (x, y), y * (1 + 1e-4))["pass"]
