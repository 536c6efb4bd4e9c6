"""Checks `nsbridge export pelicun` output against pelicun's documented formats and against
the sweep's own results.csv and fragility.json.

Formats (pelicun v3 documentation, "Response Data File", and pelicun/base.py):
  - demand sample CSV: the first column is the index; every other header reads
    <event_id>-<demand type>-<location>-<direction>; the second row is the units row (index
    label "Units"); the types are pelicun's EDP types (EDP_to_demand_type's values: PID, PRD,
    DWD, RDR, PMD, RID, EDR, PFA, PFV, PFD, LR, LBR, PWS, PIH, PGA, PGV, SA, SV, SD, PGD);
  - fragility CSV: columns ID, Incomplete, Demand-Type, Demand-Unit, Demand-Offset,
    Demand-Directional, LS<k>-Family, LS<k>-Theta_0, LS<k>-Theta_1; Demand-Type is the EDP's
    full name (EDP_to_demand_type's keys).
Usage: pelicun_export_check.py PREFIX SWEEP_DIR [H1,H2,...]  (bent heights: check the drifts)
"""
import json
import math
import os
import re
import sys

import pandas as pd

EDP_TYPES = {
    "Story Drift Ratio": "PID", "Peak Interstory Drift Ratio": "PID", "Roof Drift Ratio": "PRD",
    "Peak Roof Drift Ratio": "PRD", "Damageable Wall Drift": "DWD", "Racking Drift Ratio": "RDR",
    "Mega Drift Ratio": "PMD", "Residual Drift Ratio": "RID",
    "Residual Interstory Drift Ratio": "RID", "Peak Effective Drift Ratio": "EDR",
    "Peak Floor Acceleration": "PFA", "Peak Floor Velocity": "PFV",
    "Peak Floor Displacement": "PFD", "Peak Link Rotation Angle": "LR",
    "Peak Link Beam Chord Rotation": "LBR", "Peak Gust Wind Speed": "PWS",
    "Peak Inundation Height": "PIH", "Peak Ground Acceleration": "PGA",
    "Peak Ground Velocity": "PGV", "Spectral Acceleration": "SA", "Spectral Velocity": "SV",
    "Spectral Displacement": "SD", "Permanent Ground Deformation": "PGD",
}
UNITS = {"m", "rad", "g"}  # names in pelicun's default_units.json (length, angle, acceleration)

prefix, sweep_dir = sys.argv[1], sys.argv[2]
heights = [float(h) for h in sys.argv[3].split(",")] if len(sys.argv) > 3 else []
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


demands = pd.read_csv(prefix + "_demands.csv", index_col=0, dtype=str)  # text: parsed below
check(demands.index[0] == "Units", "row 2 is not the units row: %r" % demands.index[0])
units = demands.loc["Units"]
samples = demands.drop(index="Units").applymap(float)  # Python float(): round-trip exact
for col in demands.columns:
    m = re.fullmatch(r"(\d+)-([A-Z]+)-(\d+)-(\d+)", col)
    check(m is not None, "header %r is not <event>-<TYPE>-<loc>-<dir>" % col)
    if m:
        check(m.group(2) in EDP_TYPES.values(), "type %s is not a pelicun EDP type" % m.group(2))
    check(units[col] in UNITS, "unit %r of %s is not a pelicun unit" % (units[col], col))

results = pd.read_csv(os.path.join(sweep_dir, "results.csv"), dtype={"run": str},
                      float_precision="round_trip")
done = results[results["status"].isin(["completed", "completed_with_fallbacks", "unseated"])]
check(len(samples) == len(done), "%d samples, %d completed runs" % (len(samples), len(done)))
by_run = done.set_index(done["run"].astype(int))
expected = {"1-PFD-1-1": ("peak_x", False), "1-PFD-1-2": ("peak_y", False),
            "1-LR-1-0": ("peak_theta", False), "1-RID-1-0": ("residual_theta", True),
            "1-PGA-0-2": ("model.excitation.target_pga", False)}
for col, (source, absolute) in expected.items():
    if source not in results.columns:
        continue
    check(col in samples.columns, "%s missing (results.csv has %s)" % (col, source))
    for run, value in samples[col].items():
        want = by_run.loc[int(run), source]
        want = abs(want) if absolute else want
        check(value == want, "%s of run %s: %r, results.csv %r" % (col, run, value, want))
for i, h in enumerate(heights, start=1):
    for axis, d in (("x", 1), ("y", 2)):
        col, source = "1-PID-%d-%d" % (i, d), "peak_bent%d_u%s" % (i, axis)
        check(col in samples.columns, "%s missing" % col)
        check(units.get(col) == "rad", "%s unit %r" % (col, units.get(col)))
        for run, value in samples.get(col, pd.Series(dtype=float)).items():
            want = abs(by_run.loc[int(run), source]) / h
            check(math.isclose(value, want, rel_tol=1e-15), "%s of run %s: %r, %r" % (col, run, value, want))

frag_json = os.path.join(sweep_dir, "fragility.json")
if os.path.exists(frag_json) and os.path.exists(prefix + "_fragility.csv"):
    frag = pd.read_csv(prefix + "_fragility.csv", index_col=0, float_precision="round_trip")
    check(frag.index.name == "ID", "first column %r, expected ID" % frag.index.name)
    check(list(frag.columns) == ["Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset",
                                 "Demand-Directional", "LS1-Family", "LS1-Theta_0",
                                 "LS1-Theta_1"], "fragility columns %r" % list(frag.columns))
    fits = json.load(open(frag_json))["limit_states"]
    check(len(frag) == len(fits), "%d fragility rows, %d limit states" % (len(frag), len(fits)))
    for name, fit in fits.items():
        row = frag.loc["nsbridge." + name]
        check(row["Demand-Type"] in EDP_TYPES, "demand type %r" % row["Demand-Type"])
        check(row["Demand-Unit"] in UNITS, "demand unit %r" % row["Demand-Unit"])
        check(row["LS1-Family"] == "lognormal", "family %r" % row["LS1-Family"])
        if fit["theta"] is None:
            check(row["Incomplete"] == 1 and math.isnan(row["LS1-Theta_0"]), "%s: no estimate" % name)
        else:
            check(row["Incomplete"] == 0, "%s: Incomplete %r" % (name, row["Incomplete"]))
            check(row["LS1-Theta_0"] == fit["theta"], "%s theta %r vs %r" % (name, row["LS1-Theta_0"], fit["theta"]))
            check(row["LS1-Theta_1"] == fit["beta"], "%s beta %r vs %r" % (name, row["LS1-Theta_1"], fit["beta"]))
elif os.path.exists(frag_json):
    failures.append("no fragility CSV beside a fragility.json")

if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("pelicun format checks passed: %d demand columns, %d samples" % (len(demands.columns), len(samples)))
