"""vdec_verify: runs vdec's verification problems, compares them with closed forms, writes reports.

Usage, from the repository root:

    PYTHONPATH=verification/harness:verification /usr/bin/python3 -m vdec_verify run --vdec build/vdec \
        [--problems verification/problems] [--filter ID_SUBSTRING_OR_GLOB ...] [--level base|full] \
        [--jobs 2] [--out reports/verification] [--revision 1] [--executor local|slurm ...] \
        [--work-precision-baseline verification/baselines/work-precision.json]
    PYTHONPATH=verification/harness:verification /usr/bin/python3 -m vdec_verify check [--problems ...]

`run` runs every selected problem (one folder per problem under --problems, each with a
problem.toml; see vdec_verify.problem for its keys), compares each check with its closed-form
reference and writes summary.json, index.html, report.pdf, junit.xml, the PNG figures of each
problem and each run's results.json under OUT/runs/<ID>[/<variant>]/. It prints a table and ends with
the line "N passed, N failed". Exit status: 0 when every selected problem passes, 1 when any
fails or is invalid (a problem.toml that cannot be run as written is reported as "invalid",
never skipped), 2 on a usage error. `check` only loads and validates the problem files.

--level base runs the problems marked level = "base" (the test suite), and of a problem's
convergence study ([refinement]) the levels marked level = "base"; --level full (the default)
runs them all. --filter keeps the problems whose id contains one of the given
substrings or matches one of the given globs (case-insensitive).

Modules: problem (load and validate problem.toml), extract (what a check reads from a run),
norms (error norms, the pass rule and the independence guard), convergence (observed order,
GCI and asymptotic ratio of a convergence study), runner (runs the solver in parallel), executors
(where the runs go: a local pool or a Slurm job array), report
(the report files), figures (their figures), pdf_report (report.pdf, typeset with ReportLab),
provenance (software and harness information), work_precision (the committed work-precision
baseline, `baseline work-precision`, and the report's comparison with it); for the nightly run
(docs/user-manual/nightly.md: the `nightly`, `compare` and `baseline` commands) history, compare,
baseline, trend and nightly.
"""

__version__ = "1.0"

# THE PASS RULE, stated once; the reports print this text.
PASS_RULE = """\
A check passes when e_abs <= atol + rtol * s, with
  scalar:      e_abs = |x_h - x|                            s = |x|
  L2:          e_abs = sqrt(sum w (f_h - f)^2 / sum w)      s = sqrt(sum w f^2 / sum w)
               (w: trapezoid weights of the samples in t, or in x for a curve)
  Linf:        e_abs = max |f_h - f|                        s = max |f|
  upper_bound: passes when x_h <= x + atol + rtol |x|; e_abs = x_h - x (signed), s = |x|
  equal:       passes when x_h == x exactly (exit codes)
  order:       a convergence study ([refinement]) passes when |p_obs - p| <= order_tolerance, p_obs the
               least-squares slope of ln(error) against ln(h) over the asymptotic levels, p the
               expected order; error = |p_obs - p|, tolerance = order_tolerance (both absolute)
where x_h, f_h are vdec's values and x, f the closed-form reference. Reported error = e_abs / s
and tolerance = (atol + rtol s) / s (when s = 0: error = e_abs, tolerance = atol).
A problem passes when all its checks (and its convergence study, if any) pass and every run exits
with its expected code (and message) and stops for its expected reason (run.stop_reason); in the
full suite, also every one of its mutations (a deliberately wrong model) must be caught: some
check on its runs fails, or one of them ends otherwise than expected."""

__doc__ += "\nTHE PASS RULE\n\n" + PASS_RULE + "\n"
