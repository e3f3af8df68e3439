"""Mutated scenes: every scene of verification/problems, broken one key at a time (wrong types,
NaN, infinities, 1e308, negative values, zero, 2^32, empty strings and arrays, missing and
unknown keys; scene_mutations.py), run by vdec for a few cycles, must end as every run must
(hostile_input.py): a documented exit code, never a signal or an internal error, and at exit 0
a results.json without null numbers. A value that is never valid (not finite, of the wrong
type) and an unknown key get exit code 3 and a message that names the file and the key, as the
manual says of every input error. Known failures are xfail by hostile_input.KNOWN_FAILURES.
"""
import os
import re
import threading
from concurrent.futures import ThreadPoolExecutor

import pytest

import hostile_input
import scene_mutations

CYCLES = 20
# Mutations no scene may accept: docs/user-manual/scene-format.md (numbers are finite, unknown
# keys are errors, types are checked) makes each an input error.
NEVER_VALID = {"nan", "inf", "-inf", "wrong-type", "unknown-key"}
WORKERS = 2  # runs in parallel, one thread each: the machine's two cores

# VDEC_MUTANTS_PER_PATTERN=all (or a number) runs more than the default selection (about 3 700
# runs, 20 s on two idle cores; all is about 11 100 runs, 90 s).
_PER_PATTERN = os.environ.get("VDEC_MUTANTS_PER_PATTERN", str(scene_mutations.PER_PATTERN))
_MUTANTS = scene_mutations.selected_mutants(per_pattern=None if _PER_PATTERN == "all" else int(_PER_PATTERN))
_outcomes = {}
_lock = threading.Lock()


def _limits(mutant):
    """--set overrides that end the run soon without hiding the mutated key: a mutant of
    stop.cycles stops on a time shorter than one step, one that removes [stop] gets nothing
    (it must then fail to read), every other one stops after CYCLES cycles. A scene in phases
    gets the same for each phase's stop."""
    return limits(mutant.base.document, mutant.path, mutant.mutation)


def limits(document, path=(), mutation=""):
    return _cycle_limits(document, path, mutation) + _thermal_limits(document, path)


def _thermal_limits(document, path):
    """A mutant of a thermal time (a huge heat_time is valid, and would take its steps) advances it
    in one implicit step, so that it ends soon without hiding the mutated key."""
    thermal_time = path[:2] == ("heat", "time") or (path[:1] == ("phase",) and path[2:3] == ("heat_time",))
    return ["heat.theta=1.0", "heat.step=1e300"] if thermal_time and "heat" in document else []


def _cycle_limits(document, path, mutation):
    if "phase" not in document:
        if path == ("stop",) and mutation in ("missing-key", "wrong-type"):
            return []
        if path[:2] == ("stop", "cycles"):
            return ["stop.time=1e-12"]
        return [f"stop.cycles={CYCLES}"]
    if path[:1] == ("phase",) and len(path) <= 2 and mutation in ("missing-key", "wrong-type"):
        return []  # the phases themselves are the mutant: the scene must fail to read
    sets = []
    for k, phase in enumerate(document["phase"]):
        replaced = mutation in ("missing-key", "wrong-type")
        if replaced and path in (("phase", k), ("phase", k, "stop")):
            continue  # the table itself is the mutant: an override would hide it
        if path[:4] == ("phase", k, "stop", "cycles"):
            sets.append(f"phase[{k}].stop.time=1e-12")
        else:
            sets.append(f"phase[{k}].stop.cycles={CYCLES}")
        # a phase cut short of the equilibrium it requires would stop the run with exit code 9
        if isinstance(phase, dict) and phase.get("require_equilibrium") and path[:3] != ("phase", k, "require_equilibrium"):
            sets.append(f"phase[{k}].require_equilibrium=false")
    return sets


def _run(mutant, folder):
    folder.mkdir(parents=True)
    scene = folder / "scene.toml"
    scene.write_text(scene_mutations.toml_text(mutant.document()))
    out = folder / "out"
    code, stderr = hostile_input.run_vdec(os.environ["VDEC_EXECUTABLE"], scene, out, _limits(mutant))
    return code, stderr, out


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    """Runs every selected mutant once, WORKERS at a time; id -> (code, stderr, out dir)."""
    root = tmp_path_factory.mktemp("mutants")
    with _lock:
        if not _outcomes:
            with ThreadPoolExecutor(WORKERS) as pool:
                runs = pool.map(lambda n: _run(_MUTANTS[n], root / str(n)), range(len(_MUTANTS)))
                for mutant, outcome in zip(_MUTANTS, runs):
                    _outcomes[mutant.id] = outcome
    return _outcomes


def _cases():
    return [pytest.param(m, id=m.id, marks=hostile_input.known_failure_marks(pytest, m.id)) for m in _MUTANTS]


def mutant_verdict(mutant, code, stderr, out, documented):
    """'' when the mutant's run ended as it must; else what went wrong."""
    verdict = hostile_input.run_verdict(code, stderr, out, documented)
    if verdict or mutant.mutation not in NEVER_VALID:
        return verdict
    key = scene_mutations.named_key(mutant)
    last = stderr.strip().splitlines()[-1] if stderr.strip() else "(no message)"
    if code != 3:
        return f"exit code {code}, not 3 (scene input): {last}"
    if "scene.toml:" not in stderr or f"key '{key}'" not in stderr:
        return f"the message does not name the file, the line and key '{key}': {last}"
    return ""


@pytest.mark.requirements("REQ-QA-007")
@pytest.mark.parametrize("mutant", _cases())
def test_mutated_scene_ends_with_a_documented_exit_code(mutant, outcomes):
    code, stderr, out = outcomes[mutant.id]
    verdict = mutant_verdict(mutant, code, stderr, out, hostile_input.documented_exit_codes())
    assert verdict == "", f"{mutant.id}: {verdict}"


@pytest.mark.requirements("REQ-QA-007")
def test_every_base_scene_runs_clean_as_written_by_the_generator(tmp_path):
    """The generator's TOML is the scene: each base, unmutated, runs to exit 0."""
    documented = hostile_input.documented_exit_codes()
    for index, base in enumerate(scene_mutations.bases()):
        scene = tmp_path / f"{index}.toml"
        scene.write_text(scene_mutations.toml_text(base.document))
        out = tmp_path / f"out{index}"
        code, stderr = hostile_input.run_vdec(os.environ["VDEC_EXECUTABLE"], scene, out, limits(base.document))
        assert code == 0, f"{base.name}: exit code {code}: {stderr}"
        assert hostile_input.run_verdict(code, stderr, out, documented) == ""


@pytest.mark.requirements("REQ-QA-007")
def test_selection_covers_every_mutation_and_key_and_is_deterministic():
    every = scene_mutations.all_mutants()
    chosen = scene_mutations.selected_mutants()
    assert [m.id for m in chosen] == [m.id for m in scene_mutations.selected_mutants()]
    assert {m.mutation for m in chosen} == set(scene_mutations.MUTATION_CLASSES)
    pairs = lambda ms: {(m.mutation, scene_mutations.pattern_text(m.path)) for m in ms}
    assert pairs(chosen) == pairs(every)
    assert len({m.base.name for m in chosen}) == len(scene_mutations.bases())


@pytest.mark.requirements("REQ-QA-007")
def test_known_failures_name_cases_that_exist():
    ids = [m.id for m in scene_mutations.all_mutants()]
    ids += [f"{p.name}:{kind}" for p in hostile_input.ROOT.joinpath("tests", "fuzz", "regressions").glob("*")
            for kind in ("reader", "run")]
    stale = [pattern for pattern, _ in hostile_input.KNOWN_FAILURES
             if not any(re.fullmatch(pattern, case) for case in ids)]
    assert not stale, f"KNOWN_FAILURES patterns that match no case; delete them: {stale}"


@pytest.mark.requirements("REQ-QA-007")
def test_verdicts_catch_signals_internal_errors_and_null_results(tmp_path):
    documented = hostile_input.documented_exit_codes()
    assert documented >= {0, 2, 3, 4, 5, 6, 7} and hostile_input.INTERNAL_ERROR not in documented
    assert "SIGFPE" in hostile_input.run_verdict(-8, "", tmp_path, documented)
    assert "internal error" in hostile_input.run_verdict(1, "vdec: internal error: x\n", tmp_path, documented)
    assert "not in the manual" in hostile_input.run_verdict(42, "", tmp_path, documented)
    assert "no end within" in hostile_input.run_verdict(None, "no end within 60 s", tmp_path, documented)
    assert hostile_input.run_verdict(3, "vdec: error: bad\n", tmp_path, documented) == ""
    assert "without results.json" in hostile_input.run_verdict(0, "", tmp_path, documented)
    (tmp_path / "results.json").write_text('{"run": {"static_solve_seconds": null, "time": 1.0}}')
    assert hostile_input.run_verdict(0, "", tmp_path, documented) == ""
    (tmp_path / "results.json").write_text('{"energy": {"kinetic": null}}')
    assert "energy.kinetic" in hostile_input.run_verdict(0, "", tmp_path, documented)
    (tmp_path / "results.json").write_text('{"energy": {"kinetic": NaN}}')
    assert "does not parse" in hostile_input.run_verdict(0, "", tmp_path, documented)
