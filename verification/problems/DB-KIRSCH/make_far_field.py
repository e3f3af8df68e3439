"""Writes far_field.csv: the Kirsch stresses on the outer boundary r = 4 m of DB-KIRSCH, every
0.1 degree from 0 to 90, for the scene's stress_table (exact far-field tractions, so that the
truncated domain adds no error). Run from this folder with /usr/bin/python3 after changing the
geometry or the load; the file is committed.
"""
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
from analytic.elastic import kirsch_cartesian_stress  # noqa: E402

A, R, S_X, S_Y = 1.0, 4.0, -10e3, 0.0

angles = np.linspace(0.0, 90.0, 901)
theta = np.radians(angles)
sxx, syy, sxy = kirsch_cartesian_stress(x=R * np.cos(theta), y=R * np.sin(theta), a=A, S_x=S_X, S_y=S_Y)
with open(HERE / "far_field.csv", "w") as out:
    out.write("angle_deg,sxx,syy,sxy\n")
    for row in zip(angles, sxx, syy, sxy):
        out.write(",".join(f"{v:.17g}" for v in row) + "\n")
