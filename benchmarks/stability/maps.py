#!/usr/bin/env python3
"""Stability maps of the integrators from the sweeps of benchmarks/stability/*.toml.

    maps.py plot OUT    one map per sweep OUT/<map>/ : OUT/<map>.csv and OUT/<map>.{png,svg}
    maps.py check OUT [--energy-threshold E] [--penetration-threshold P]
                      [--compliance-penetration-threshold C]

Every point of a map is one run of `nsbridge sweep`; its numbers come from the sweep's
results.csv (status, energy_error, max_penetration, lcp_fallbacks) and the run's summary.json
(the gap columns' extremes under "peaks", and "warnings"), the outputs of the one run
pipeline (runs::execute, docs/run-api.md).

A point is untrustworthy when (docs/cli.md, "Warnings"; runs::TrustLimits):
  energy   the energy-balance error exceeds E (default 0.01) or is not finite;
  pen      a rigid-contact method (Moreau-Jean, event-driven) lets a contact penetrate deeper
           than P (default 0.01) of its range of gaps over the run, and deeper than 1e-9 m
           (the round-off of a closed gap); the compliance method's penetration is its Hertz
           deformation, a violation only when it exceeds C (default 0.5) of the contact's gap
           at t0 (history.csv's first row; a contact closed at t0 is not checked);
  failed   the status is not completed or completed_with_fallbacks (diverged, stalled,
           contact_unsolved, rejected).
The criteria are computed here from the run's numbers, independently of runs/trust.cpp; the
check asserts that each point's summary.json carries exactly the warnings the map implies
(energy_balance, penetration) and that a failed point's summary says it did not complete.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

ROUNDOFF_DEPTH = 1e-9  # [m], runs/trust.cpp kRoundoffDepth
SUCCEEDED = ("completed", "completed_with_fallbacks")
X_KEYS = ("solver.step", "solver.tolerance")
Y_KEYS = ("bent stiffness scale", "solver.stiffness_factor")
PANEL_KEY = "pga factor"
TRUST_CODES = ("energy_balance", "penetration", "step_period", "step_record")


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def penetration_share(summary):
    """Largest depth / range of gaps over the contacts (summary.json peaks gN<k>), 0 when none."""
    share = 0.0
    for name, peak in summary.get("peaks", {}).items():
        if not name.startswith("gN"):
            continue
        lo, hi = peak["min"], peak["max"]
        if lo < -ROUNDOFF_DEPTH and hi > lo:
            share = max(share, -lo / (hi - lo))
    return share


def compliance_penetration_share(summary, history_file):
    """Largest depth / gap at t0 over the contacts open at t0, 0 when none or no history."""
    if not os.path.exists(history_file):
        return 0.0
    with open(history_file, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        first = next(reader, [])
    share = 0.0
    for name, value in zip(header, first):
        peak = summary.get("peaks", {}).get(name)
        if not name.startswith("gN") or peak is None:
            continue
        gap = number(value)
        if gap > ROUNDOFF_DEPTH:
            share = max(share, -peak["min"] / gap)
    return share


def load_map(folder, limits):
    """The points of one sweep folder: dicts with the axes, the numbers and the verdicts."""
    with open(os.path.join(folder, "results.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    x_key = next(k for k in X_KEYS if k in rows[0])
    y_key = next(k for k in Y_KEYS if k in rows[0])
    points = []
    for r in rows:
        summary_file = os.path.join(folder, "runs", r["run"], "summary.json")
        summary = {}
        if os.path.exists(summary_file):
            with open(summary_file) as f:
                summary = json.load(f)
        method = summary.get("method", "")
        # The trust checks' codes (runs/trust.hpp); an integrator's own warning is "integrator".
        codes = sorted({w.split(":", 1)[0] if w.split(":", 1)[0] in TRUST_CODES else "integrator"
                        for w in summary.get("warnings", [])})
        energy = number(r["energy_error"])
        share = penetration_share(summary)
        reasons = []
        if r["status"] != "rejected" and not (math.isfinite(energy) and energy <= limits.energy):
            reasons.append("energy")
        if method != "compliance" and share > limits.penetration:
            reasons.append("pen")
        if method == "compliance" and compliance_penetration_share(
                summary, os.path.join(folder, "runs", r["run"], "history.csv")) > \
                limits.compliance_penetration:
            reasons.append("pen")
        if r["status"] not in SUCCEEDED:
            reasons.append("failed")
        points.append({
            "run": r["run"], "x": number(r[x_key]), "y": number(r[y_key]),
            "pga": number(r[PANEL_KEY]), "method": method, "status": r["status"],
            "energy_error": energy, "max_penetration": number(r["max_penetration"]),
            "penetration_share": share, "lcp_fallbacks": r["lcp_fallbacks"],
            "wall_s": number(r["wall_s"]), "warnings": codes, "reasons": reasons,
            "summary_completed": summary.get("completed"),
        })
    return x_key, y_key, points


def map_folders(out):
    return sorted(d for d in os.listdir(out)
                  if os.path.exists(os.path.join(out, d, "results.csv")))


def write_csv(path, points):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "x", "y", "pga_factor", "status", "energy_error", "max_penetration",
                    "penetration_share", "lcp_fallbacks", "warnings", "untrusted", "wall_s"])
        for p in points:
            w.writerow([p["run"], repr(p["x"]), repr(p["y"]), repr(p["pga"]), p["status"],
                        repr(p["energy_error"]), repr(p["max_penetration"]),
                        repr(p["penetration_share"]), p["lcp_fallbacks"],
                        ";".join(p["warnings"]), ";".join(p["reasons"]), repr(p["wall_s"])])


def boundary_segments(points, pga):
    """Edges between neighbouring cells of one panel whose verdicts differ: the trust boundary,
    in log10 coordinates of the axes (the grids are geometric, so cells are equal in log)."""
    cells = {(math.log10(p["x"]), math.log10(p["y"])): bool(p["reasons"])
             for p in points if p["pga"] == pga}
    xs = sorted({k[0] for k in cells})
    ys = sorted({k[1] for k in cells})
    dx = (xs[1] - xs[0]) if len(xs) > 1 else 1.0
    dy = (ys[1] - ys[0]) if len(ys) > 1 else 1.0
    segs = []
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            if i + 1 < len(xs) and cells[(x, y)] != cells[(xs[i + 1], y)]:
                segs.append((x + dx / 2, y - dy / 2, 0.0, dy))
            if j + 1 < len(ys) and cells[(x, y)] != cells[(x, ys[j + 1])]:
                segs.append((x - dx / 2, y + dy / 2, dx, 0.0))
    return segs, dx, dy


def cell_tag(p):
    """The letters drawn in a cell: X failed, P penetration beyond the threshold (rigid
    contacts), F LCP fallbacks, s a coarse-step warning (Moreau-Jean's step_period or
    step_record), . none."""
    tag = ("X" if "failed" in p["reasons"] else "") + ("P" if "pen" in p["reasons"] else "") + \
          ("F" if p["lcp_fallbacks"] not in ("", "0") else "") + \
          ("s" if any(w.startswith("step_") for w in p["warnings"]) else "")
    return tag or "."


def log_or_nan(v, floor):
    return math.log10(max(v, floor)) if math.isfinite(v) else math.nan


def write_panel(path, points, pga):
    """One panel's cells: log10 x, log10 y, log10 energy error, log10 penetration share, tag."""
    with open(path, "w") as f:
        for p in points:
            if p["pga"] == pga:
                f.write(f"{math.log10(p['x'])} {math.log10(p['y'])} "
                        f"{log_or_nan(p['energy_error'], 1e-8)} "
                        f"{log_or_nan(p['penetration_share'], 1e-6)} \"{cell_tag(p)}\"\n")


def gnuplot_script(name, x_key, y_key, points, data_dir):
    """Two rows of panels, one panel per PGA factor: the energy-balance error (top) and the
    deepest penetration as a share of the contact's range of gaps (bottom), each cell a run;
    the thick line is the trust boundary, the edges between trusted and untrusted runs."""
    panels = sorted({p["pga"] for p in points})
    xs = [math.log10(p["x"]) for p in points]
    ys = [math.log10(p["y"]) for p in points]
    lines = [
        "set terminal pngcairo size 1350,820 font ',10' noenhanced", f"set output '{name}.png'",
        f"set multiplot layout 2,{len(panels)} title '{name}: cells are runs; thick line: trust "
        "boundary (energy error > 1 %, penetration > 1 % on rigid contacts, or failed); "
        "X failed, P penetration, F LCP fallbacks, s coarse-step warning'",
        "set palette rgb 33,13,10", "set datafile missing 'nan'",
        f"set xlabel 'log10 {x_key}'", f"set ylabel 'log10 {y_key}'",
    ]
    depth = "penetration / range of gaps"
    if points and points[0]["method"] == "compliance":
        depth = "Hertz deformation / range of gaps (model deformation, not checked)"
    rows = (("energy-balance error", 3, "[-8:0]"), (depth, 4, "[-6:0]"))
    for title, column, cb in rows:
        for k, pga in enumerate(panels):
            segs, dx, dy = boundary_segments(points, pga)
            cell = f"{name}-{k}.dat"
            write_panel(os.path.join(data_dir, cell), points, pga)
            seg = f"{name}-{k}-boundary.dat"
            with open(os.path.join(data_dir, seg), "w") as f:
                f.write("".join(f"{a} {b} {c} {d}\n" for a, b, c, d in segs) or "nan nan nan nan\n")
            lines += [
                f"set title 'log10 {title}, PGA factor {pga:g}'", f"set cbrange {cb}",
                f"set xrange [{min(xs) - dx / 2}:{max(xs) + dx / 2}]",
                f"set yrange [{min(ys) - dy / 2}:{max(ys) + dy / 2}]",
                f"plot '{cell}' using 1:2:{column} with image notitle, "
                f"'' using 1:2:5 with labels font ',9' notitle, "
                f"'{seg}' using 1:2:3:4 with vectors nohead lw 4 lc rgb 'black' notitle",
            ]
    lines.append("unset multiplot")
    return "\n".join(lines) + "\n"


def plot(out):
    for name in map_folders(out):
        x_key, y_key, points = load_map(os.path.join(out, name), LIMITS)
        write_csv(os.path.join(out, name + ".csv"), points)
        script = gnuplot_script(name, x_key, y_key, points, out)
        with open(os.path.join(out, name + ".gp"), "w") as f:
            f.write(script)
        subprocess.run(["gnuplot", name + ".gp"], cwd=out, check=True)
        svg = script.replace("pngcairo size 1350,820", "svg size 1350,820").replace(
            f"{name}.png", f"{name}.svg")
        subprocess.run(["gnuplot"], input=svg.encode(), cwd=out, check=True)
        bad = sum(1 for p in points if p["reasons"])
        print(f"{name}: {len(points)} points, {bad} untrustworthy -> {out}/{name}.png")


def check(out):
    """Every point: the map's verdicts and the run's warnings agree. Returns the mismatches."""
    mismatches = []
    folders = map_folders(out)
    if not folders:
        mismatches.append(f"{out}: no sweep folder with results.csv")
    for name in folders:
        _, _, points = load_map(os.path.join(out, name), LIMITS)
        for p in points:
            where = f"{name} run {p['run']} (x={p['x']:g}, y={p['y']:g}, pga={p['pga']:g})"
            for reason, code in (("energy", "energy_balance"), ("pen", "penetration")):
                if p["status"] == "rejected":
                    continue
                if (reason in p["reasons"]) != (code in p["warnings"]):
                    mismatches.append(f"{where}: map says {reason}={'yes' if reason in p['reasons'] else 'no'}, "
                                      f"summary warnings {p['warnings']}")
            # A failed run's summary says so ("completed": false; `nsbridge run` exits 1); a
            # rejected combination has no summary: `nsbridge run` refuses it (exit 2).
            failed = "failed" in p["reasons"] and p["status"] != "rejected"
            if failed and p["summary_completed"] is not False:
                mismatches.append(f"{where}: status {p['status']} but the summary does not say "
                                  "the run failed")
        print(f"{name}: {len(points)} points checked, "
              f"{sum(1 for p in points if p['reasons'])} untrustworthy")
    for m in mismatches:
        print("mismatch: " + m)
    return mismatches


def main():
    global LIMITS
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("action", choices=["plot", "check"])
    ap.add_argument("out", help="the folder of the sweeps (benchmarks/stability/run.sh OUT)")
    ap.add_argument("--energy-threshold", dest="energy", type=float, default=0.01)
    ap.add_argument("--penetration-threshold", dest="penetration", type=float, default=0.01)
    ap.add_argument("--compliance-penetration-threshold", dest="compliance_penetration",
                    type=float, default=0.5)
    LIMITS = ap.parse_args()
    if LIMITS.action == "plot":
        plot(LIMITS.out)
        return 0
    bad = check(LIMITS.out)
    print(f"{len(bad)} mismatches between the maps and the trust warnings")
    return 1 if bad else 0


LIMITS = None

if __name__ == "__main__":
    sys.exit(main())
