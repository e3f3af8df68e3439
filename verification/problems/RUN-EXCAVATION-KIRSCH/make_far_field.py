"""Writes far_field.csv for RUN-EXCAVATION-KIRSCH: the Kirsch stresses on the outer boundary
r = 4 m once the hole is excavated, every 0.1 degree from 0 to 90, for the second phase's
stress_table; and prints the hole's radius. The hole is the ring of gridpoints the annulus
zoning puts nearest r = 1 m: with radial = 20, grading = 1.1 from r = 0.25 to 4 (the rule of
docs/user-manual/scene-format.md#blockannulus: zone k is grading^k times as deep as the first),
ring 8, at r = 0.99875 m; the excavation's circle of radius 1 m takes exactly the zones inside it.
Run from this folder with /usr/bin/python3 after changing the geometry or the load; the file is
committed.
"""
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
from analytic.elastic import kirsch_cartesian_stress  # noqa: E402

INNER, OUTER, RADIAL, GRADING, RING = 0.25, 4.0, 20, 1.1, 8
S_X, S_Y = -10e3, -4e3

depths = GRADING ** np.arange(RADIAL)
A = INNER + (OUTER - INNER) * depths[:RING].sum() / depths.sum()

if __name__ == "__main__":
    angles = np.linspace(0.0, 90.0, 901)
    theta = np.radians(angles)
    sxx, syy, sxy = kirsch_cartesian_stress(x=OUTER * np.cos(theta), y=OUTER * np.sin(theta), a=A, S_x=S_X, S_y=S_Y)
    with open(HERE / "far_field.csv", "w") as out:
        out.write("angle_deg,sxx,syy,sxy\n")
        for row in zip(angles, sxx, syy, sxy):
            out.write(",".join(f"{v:.17g}" for v in row) + "\n")
    print(f"hole radius a = {A!r} m")
