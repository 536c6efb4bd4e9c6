#!/usr/bin/python3
"""Every output group of every shipped scene under every method (docs/outputs.md, "Optional
groups").

usage: outputs_groups.py --nsbridge BIN --scenes DIR [--end-time T]

Runs every scene of DIR (*.toml) under moreau, event_driven and compliance with
`[output] groups` = every group, up to min(T, the scene's end_time) (T default 4.5 s: the
benchmark excitations' first impacts come at 3.8-4.2 s), without the error estimate, in a
fresh temporary folder, and checks each run's files alone:

- energy: the six energy_* columns; forces: fN<k>, fT<k> per contact, fsmooth_<q> and
  fcontact_<q> per coordinate, and summary.json's mass (n x n);
- for a scene of kind "bridge", "rigid_deck" or "deck_chain" (an assembly of bodies):
  relative (x<b>_rel, y<b>_rel and 8 corner columns per body, every body of the coordinates),
  ground (6 columns) and bents (4 columns per bent; a scene may have none);
  for the test systems (ball, oscillator, block) none of these three;
- impulses: events.csv's header ends with impulse_N,impulse_T, and every impact row carries a
  finite impulse_N;
- every group column of every row is a finite number;
- the group columns are the same for the three methods of a scene.

Prints one line per scene-method (the groups found and the counts) and every problem; exit 0
when there is none, 1 otherwise.
"""
import csv
import json
import math
import pathlib
import re
import subprocess
import sys
import tempfile
import tomllib

METHODS = ("moreau", "event_driven", "compliance")
GROUPS = "bents,relative,ground,energy,forces,impulses"
ENERGY = ["energy_kinetic", "energy_elastic", "energy_hysteretic", "energy_damping",
          "energy_contact", "energy_input"]
GROUND = ["ground_ux", "ground_uy", "ground_vx", "ground_vy", "ground_ax", "ground_ay"]
ASSEMBLIES = {"bridge", "rigid_deck", "deck_chain"}


def check_run(run, kind):
    """(group columns, description, problems) of the run in folder `run`."""
    problems = []
    summary = json.loads((run / "summary.json").read_text())
    with open(run / "history.csv") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    gap_columns = [h for h in header if re.fullmatch(r"gN\d+", h)]
    m = len(gap_columns)
    first_group = header.index("energy_error") + 1
    group_columns = header[first_group:]
    coordinates = header[1:1 + (header.index(gap_columns[0]) - 1 if m else
                                first_group - 2) // 2]
    n = len(coordinates)
    found = []

    def need(group, names):
        missing = [c for c in names if c not in group_columns]
        if missing:
            problems.append(f"group {group}: missing {missing[:4]}{'...' if len(missing) > 4 else ''}")
        else:
            found.append(group)

    need("energy", ENERGY)
    need("forces", [f"f{a}{k}" for k in range(1, m + 1) for a in "NT"] +
         [f"fsmooth_{q}" for q in coordinates] + [f"fcontact_{q}" for q in coordinates])
    mass = summary.get("mass")
    if not (isinstance(mass, list) and len(mass) == n and all(len(r) == n for r in mass)):
        problems.append("group forces: summary.json has no n x n mass")
    bodies = n // 3
    bents = sum(1 for c in group_columns if re.fullmatch(r"bent\d+_ux", c))
    system_groups = [c for c in group_columns if c.startswith(("bent", "ground_")) or
                     c.endswith("_rel")]
    if kind in ASSEMBLIES:
        need("relative", [f"{a}{b}_rel" for b in range(1, bodies + 1) for a in "xy"] +
             [f"corner{b}_{k}_{a}_rel" for b in range(1, bodies + 1) for k in range(1, 5)
              for a in "xy"])
        need("ground", GROUND)
        need("bents", [f"bent{i}_{s}" for i in range(1, bents + 1)
                       for s in ("ux", "uy", "fx", "fy")])
    elif system_groups:
        problems.append(f"a test system with bridge columns {system_groups[:3]}")
    for r, row in enumerate(rows):
        bad = [group_columns[j] for j, v in enumerate(row[first_group:])
               if v == "" or not math.isfinite(float(v))]
        if bad:
            problems.append(f"row {r + 1}: non-finite {bad[:3]}")
            break
    with open(run / "events.csv") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames[-2:] != ["impulse_N", "impulse_T"]:
            problems.append("group impulses: events.csv has no impulse_N,impulse_T")
            events = []
        else:
            events = list(reader)
            found.append("impulses")
    impacts = [e for e in events if e["kind"] == "impact"]
    unset = [e["t"] for e in impacts
             if e["impulse_N"] == "" or not math.isfinite(float(e["impulse_N"]))]
    if unset:
        problems.append(f"group impulses: impact rows without impulse_N at t = {unset[:3]}")
    text = (f"{','.join(found)}; {bodies if kind in ASSEMBLIES else 0} bodies, {bents} bents, "
            f"{m} contacts, {len(rows)} rows, {len(impacts)} impacts with impulses")
    return group_columns, text, problems


def main(argv):
    args = dict(zip(argv[1::2], argv[2::2]))
    if not {"--nsbridge", "--scenes"} <= args.keys():
        print(__doc__, file=sys.stderr)
        return 2
    end_cap = float(args.get("--end-time", "4.5"))
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for scene in sorted(pathlib.Path(args["--scenes"]).glob("*.toml")):
            data = tomllib.loads(scene.read_text())
            kind = data["model"]["kind"]
            end = min(end_cap, float(data.get("solver", {}).get("end_time", end_cap)))
            columns = {}
            for method in METHODS:
                out = pathlib.Path(tmp) / scene.stem / method
                cmd = [args["--nsbridge"], "run", str(scene), "--method", method, "--out",
                       str(out), "--quiet", "--set", f"output.groups={GROUPS}", "--set",
                       f"solver.end_time={end:g}", "--set", "solver.error_estimate=false"]
                rc = subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode
                if rc not in (0, 1) or not (out / "summary.json").exists():
                    print(f"{scene.stem} {method}: nsbridge exited {rc}, no files: FAIL")
                    failed += 1
                    continue
                cols, text, problems = check_run(out, kind)
                columns[method] = cols
                status = json.loads((out / "summary.json").read_text())["status"]
                print(f"{scene.stem} {method} ({status}, to {end:g} s): {text}")
                for p in problems:
                    print(f"  {p}: FAIL")
                failed += len(problems)
            if len({tuple(c) for c in columns.values()}) > 1:
                print(f"{scene.stem}: the group columns differ between methods: FAIL")
                failed += 1
    print(f"{failed} problems")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
