"""Work against precision of the thermal schemes on TH-DECAYING-SOURCE's scene (a canister's decaying
heat over 100 years, rings from 0.1 m by the canister to 600 m): the explicit scheme at its stable
step, Crank-Nicolson and backward Euler at steps of a quarter, one and four years. Each run's error
is the relative L2 error of the temperature 5 to 50 m from the canister at 100 years against
heat.decaying_line_source_temperature; its cost the run's `run.wall_seconds` (the thermal advance
of the phases; set-up excluded), with the thermal steps taken.

    /usr/bin/python3 bench/heat_schemes.py --vdec build/vdec --out reports/bench/heat_schemes.json

numpy and the verification/analytic package (Debian's python3-numpy, python3-scipy).
"""
import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "verification"))
from analytic import heat  # noqa: E402

SCENE = ROOT / "verification" / "problems" / "TH-DECAYING-SOURCE" / "scene.toml"
YEAR = 3.15576e7
RUNS = [("explicit", 0.0, None), ("crank-nicolson", 0.5, 0.25), ("crank-nicolson", 0.5, 1.0),
        ("crank-nicolson", 0.5, 4.0), ("backward-euler", 1.0, 1.0), ("backward-euler", 1.0, 0.25)]


def error_of(results):
    g = results["gridpoints"]
    r = np.hypot(np.asarray(g["x0"]), np.asarray(g["y0"]))
    t = np.asarray(g["temperature"])
    near = (r >= 5.0) & (r <= 50.0)
    exact = heat.decaying_line_source_temperature(r=r[near], t=100 * YEAR, q=[560.0, 240.0], tau=[30 * YEAR, 300 * YEAR],
                                                  k=3.0, kappa=1.2e-6)
    return float(np.sqrt(np.mean((t[near] - exact) ** 2) / np.mean(exact ** 2)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--vdec", required=True)
    parser.add_argument("--out", required=True, help="JSON file of the measurements")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for scheme, theta, years in RUNS:
            out = Path(folder) / f"{scheme}-{years}"
            command = [args.vdec, "run", str(SCENE), "--out", str(out), "--set", f"heat.theta={theta}"]
            command += ["--set", f"heat.step={years * YEAR!r}"] if years else ["--set", "heat.step=700.0"]
            done = subprocess.run(command, capture_output=True, text=True)
            if done.returncode != 0:
                raise SystemExit(f"{scheme}: vdec exited {done.returncode}: {done.stderr.strip()}")
            results = json.loads((out / "results.json").read_text())
            row = {"scheme": scheme, "theta": theta, "step_seconds": results["heat"]["step"],
                   "steps": results["heat"]["steps"], "wall_seconds": results["run"]["wall_seconds"],
                   "zones": len(results["zones"]["x0"]), "error": error_of(results)}
            rows.append(row)
            print(f"{scheme:15s} step {row['step_seconds']:10.4g} s {row['steps']:9d} steps {row['wall_seconds']:9.4f} s "
                  f"error {row['error']:.3e}", flush=True)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
