"""vdec_verify: runs vdec's verification problems, compares them with closed forms, reports.

Run from the repository root:
    PYTHONPATH=verification/harness:verification /usr/bin/python3 -m vdec_verify run --vdec build/vdec

THE PASS RULE (the same for every check): pass when e_abs <= atol + rtol * s, where
  scalar:      e_abs = |x_h - x|,                          s = |x|
  L2:          e_abs = sqrt(sum w (f_h - f)^2 / sum w),     s = sqrt(sum w f^2 / sum w)   (w: trapezoid weights)
  Linf:        e_abs = max |f_h - f|,                       s = max |f|
  upper_bound: pass when x_h <= x + atol + rtol |x|
  equal:       pass when x_h == x (exit codes)
The reported error is e_abs / s (e_abs when s == 0) and the tolerance (atol + rtol s) / s.
"""
PASS_RULE = ("pass when e_abs <= atol + rtol * s; scalar: e_abs = |x_h - x|, s = |x|; "
             "L2: root-mean-square difference and value with trapezoid weights; Linf: largest difference "
             "and value; upper_bound: x_h <= x + atol + rtol |x|; equal: x_h == x. "
             "Reported error = e_abs / s, tolerance = (atol + rtol s) / s.")
