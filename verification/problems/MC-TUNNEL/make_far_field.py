"""Writes far_field_change.csv for MC-TUNNEL: the exact Salencon stresses at r = 5 m, less the
in-situ stress (-30 MPa, tension positive), every 0.1 degree from 0 to 90, in Cartesian
components for the scene's stress_table. Run from this folder with /usr/bin/python3 after
changing the geometry, the load or the material; the file is committed.
"""
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))
from analytic.plasticity import salencon_tunnel  # noqa: E402

A, R, P0, PI = 1.0, 5.0, 30e6, 0.0
K, G = 3.9e9, 2.8e9
MATERIAL = dict(E=9.0 * K * G / (3.0 * K + G), nu=(3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G)), cohesion=3.45e6,
                friction_deg=30.0, dilation_deg=0.0)

angles = np.linspace(0.0, 90.0, 901)
theta = np.radians(angles)
far = salencon_tunnel(r=np.full(theta.shape, R), a=A, p0=P0, pi=PI, **MATERIAL)
srr, stt = far["srr"], far["stt"]
c, s = np.cos(theta), np.sin(theta)
sxx = srr * c * c + stt * s * s + P0
syy = srr * s * s + stt * c * c + P0
sxy = (srr - stt) * s * c
with open(HERE / "far_field_change.csv", "w") as out:
    out.write("angle_deg,sxx,syy,sxy\n")
    for row in zip(angles, sxx, syy, sxy):
        out.write(",".join(f"{v:.17g}" for v in row) + "\n")
