#!/usr/bin/python3
"""Equilibrium of a run from its files alone (docs/outputs.md, "The equilibrium check").

usage: outputs_equilibrium.py RUN_DIR [--tolerance TOL]
       outputs_equilibrium.py --nsbridge BIN (--scene SCENE | --scenes DIR) --end-time T
                              --tolerance moreau=TOL,event_driven=TOL,compliance=TOL

The second form runs SCENE (or every scene of DIR, each of which has contacts) up to T, or
to the scene's own end_time when that comes first, under each method named, with the groups
and sampling the check needs, in a fresh temporary folder, and checks each run against its
tolerance.

RUN_DIR holds history.csv, events.csv and summary.json of a run made with
[output] groups including "forces" and sample_dt = 0 (a row per accepted step). Between two
consecutive rows k, k+1 the equation of motion M du/dt = f_S + f_C (eq. 2 of Shi &
Dimitrakopoulos 2017, smooth part) gives, with du/dt the differentiated velocities,

    r = M (u_k+1 - u_k) / (t_k+1 - t_k) - (f_S,k + f_S,k+1) / 2 - f_C

where f_S is fsmooth_<coordinate> (bents, bearings, restrainers, backfills and damping) and
f_C is fcontact_<coordinate> (W_N fN + W_T fT): for Moreau-Jean the step's contact force
f_C,k+1 (its impulse over the step, at the step's end), for the other methods the
trapezoidal mean (f_C,k + f_C,k+1) / 2 of the instantaneous forces. An interval that holds an
event (impact, close, open, stick, slip: where a force or a velocity jumps) is left out.
Each coordinate's residual is divided by its force scale, the largest
|M du/dt| + |f_S| + |f_C| of that coordinate over the kept intervals, and at least its
largest momentum |M u| over the run's duration (the scale of a free deck's coordinate, which
no force moves between impacts).

Prints one line: method, kept and left-out intervals, the largest scaled residual and the
coordinate and time where it occurs. Exit 0 when it is at most TOL (default: no check), 1
otherwise, 2 for unusable files.
"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile
import tomllib

import numpy as np


def check(run):
    """The largest scaled residual of the run in folder `run`, printed; None for bad files."""
    summary = json.loads((run / "summary.json").read_text())
    if "mass" not in summary:
        print(f"{run}: summary.json has no mass (run without the output group forces)",
              file=sys.stderr)
        return None
    mass = np.array(summary["mass"], dtype=float)
    method = summary["method"]
    with open(run / "history.csv") as f:
        header = f.readline().strip().split(",")
    data = np.genfromtxt(run / "history.csv", delimiter=",", skip_header=1, ndmin=2)
    col = {name: i for i, name in enumerate(header)}
    coords = [n[len("fsmooth_"):] for n in header if n.startswith("fsmooth_")]
    ndof = len(coords)
    if ndof != mass.shape[0]:
        print(f"{run}: {ndof} coordinates against a {mass.shape[0]}-square mass", file=sys.stderr)
        return None
    # The velocities follow the coordinates: column 1 + ndof + j.
    vel = [1 + ndof + col[c] - 1 for c in coords]
    t = data[:, 0]
    u = data[:, vel]
    fs = data[:, [col["fsmooth_" + c] for c in coords]]
    fc = data[:, [col["fcontact_" + c] for c in coords]]

    jumps = []
    with open(run / "events.csv") as f:
        for row in csv.DictReader(f):
            if row["kind"] != "warning":
                jumps.append(float(row["t"]))
    jumps = np.sort(np.array(jumps))

    dt = np.diff(t)
    ok = dt > 0.0
    # An interval [t_k, t_k+1] holding an event (at either end included) is left out.
    lo = np.searchsorted(jumps, t[:-1], side="left")
    hi = np.searchsorted(jumps, t[1:], side="right")
    ok &= hi == lo
    ma = (np.diff(u, axis=0) / np.where(ok, dt, 1.0)[:, None]) @ mass.T
    fs_mean = 0.5 * (fs[:-1] + fs[1:])
    fc_mean = fc[1:] if method == "moreau" else 0.5 * (fc[:-1] + fc[1:])
    r = ma - fs_mean - fc_mean
    kept = np.flatnonzero(ok)
    if kept.size == 0:
        print(f"{method}: no interval without an event")
        return float("inf")
    scale = np.max(np.abs(ma[kept]) + np.abs(fs_mean[kept]) + np.abs(fc_mean[kept]), axis=0)
    # A coordinate that no force moves between events (a free deck, whose every force is an
    # impact's percussion) would have a scale of round-off alone: its floor is the force that
    # changes the coordinate's largest momentum over the run, max |M u| / duration.
    duration = t[-1] - t[0]
    if duration > 0.0:
        scale = np.maximum(scale, np.max(np.abs(u @ mass.T), axis=0) / duration)
    scale = np.where(scale > 0.0, scale, 1.0)
    scaled = np.abs(r[kept]) / scale
    k, j = np.unravel_index(np.argmax(scaled), scaled.shape)
    worst = scaled[k, j]
    print(f"{method}: intervals kept {kept.size}, left out {dt.size - kept.size}; "
          f"largest scaled residual {worst:.3e} ({coords[j]}, t = {t[kept[k] + 1]:.6g} s)")
    return worst


def run_scene(argv):
    args = dict(zip(argv[1::2], argv[2::2]))
    tolerances = dict(item.split("=") for item in args["--tolerance"].split(","))
    if "--scenes" in args:
        scenes = sorted(pathlib.Path(args["--scenes"]).glob("*.toml"))
    else:
        scenes = [pathlib.Path(args["--scene"])]
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            solver = tomllib.loads(scene.read_text()).get("solver", {})
            end_time = min(float(args["--end-time"]),
                           float(solver.get("end_time", args["--end-time"])))
            for method, tol in tolerances.items():
                out = pathlib.Path(tmp) / scene.stem / method
                cmd = [args["--nsbridge"], "run", str(scene), "--method", method, "--out",
                       str(out), "--quiet", "--set", "output.sample_dt=0", "--set",
                       "output.groups=forces", "--set",
                       f"solver.end_time={end_time:g}", "--set",
                       "solver.error_estimate=false"]
                rc = subprocess.run(cmd).returncode
                print(f"{scene.stem} ", end="")
                if rc != 0:
                    print(f"{method}: nsbridge exited {rc}")
                    failed = True
                    continue
                worst = check(out)
                if worst is None or not worst <= float(tol):
                    print(f"{scene.stem} {method}: residual above the tolerance "
                          f"{float(tol):.3e}: FAIL")
                    failed = True
    return 1 if failed else 0


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    if argv[1] == "--nsbridge":
        return run_scene(argv)
    tolerance = None
    if len(argv) >= 4 and argv[2] == "--tolerance":
        tolerance = float(argv[3])
    worst = check(pathlib.Path(argv[1]))
    if worst is None:
        return 2
    if tolerance is not None and not worst <= tolerance:
        print(f"equilibrium residual {worst:.3e} above the tolerance {tolerance:.3e}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
