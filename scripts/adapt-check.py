#!/usr/bin/python3
"""Does `solver.adapt = true` reach its accuracy on the bridges? (docs/error-estimates.md,
"Choosing the step", "Measured on every bridge").

For every shipped bridge scene (scenes/bridge-*.toml, over its own end time) and the four
work-precision bridges over [0, 8] s (docs/benchmarks/work-precision-bridges.md), and for
every method, one run with `--set solver.adapt=true --set solver.accuracy=A` (A = 1e-2 by
default) from the scene's own settings. Every deck peak (summary.json `peaks` of the
generalized coordinates x, y, theta of each body) is compared with a converged reference:
event-driven at tolerance 1e-10 for the rigid methods (Moreau–Jean, event-driven), the
compliance method at a tight tolerance (1e-9) for compliance, whose contact law is another
model; where that reference does not reach a result (event-driven at 1e-10 stalls on an event
storm of the unequal-skew bridge) the next tighter tolerance is taken. Prints one row per scene and method: the worst relative error and its coordinate,
whether the run claimed to meet its target (summary.json `accuracy.met`), its attempts and
final setting, its CPU seconds (`accuracy.total_cpu_seconds`, every attempt and companion).

References are cached in CACHE (one JSON per scene, window, method and tolerance), so a second
call runs only the adapt runs; `--reuse` keeps the adapt runs already in OUT as well.
At most 2 runs at once (`--jobs`, 1 or 2); the runs themselves are nsb_runs.py's.

Usage: adapt-check.py NSBRIDGE [--scenes DIR] [--cache DIR] [--out DIR] [--accuracy A]
                      [--methods m1,m2] [--only NAME,...] [--jobs N] [--reuse]
                      [--set KEY=VALUE ...]
Exits 1 when a row misses the accuracy or a run failed, 2 on bad arguments.
"""
import argparse
import concurrent.futures
import json
import os
import shutil
import sys

import nsb_runs

METHODS = ("moreau", "event_driven", "compliance")
# The work-precision bridges and their window (benchmarks/work_precision_bridges.py).
WORK_PRECISION = ("bridge-exc7", "bridge-skew-three-span", "bridge-two-frame",
                  "bridge-shear-keys")
WORK_PRECISION_END = 8.0
# The references: (method, tolerances tried in turn) per method checked.
RIGID_REFERENCE = ("event_driven", (1e-10, 1e-11, 1e-12))
COMPLIANCE_REFERENCE = ("compliance", (1e-9, 1e-10))


def reference_of(method):
    return COMPLIANCE_REFERENCE if method == "compliance" else RIGID_REFERENCE


def deck_peaks(summary):
    """The peaks |q| of the generalized coordinates of every body (x, y, theta or x1, ...)."""
    return {k: v["abs_max"] for k, v in nsb_runs.coordinates(summary).items()}


def run(nsbridge, scene_path, method, sets, out):
    """One `nsbridge run` into a fresh out; returns (exit code, summary or None, message)."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    return nsb_runs.attempt(nsbridge, scene_path, out, method, [f"{k}={v}" for k, v in sets])


class Case:
    """A scene over a window (None: its own end time)."""

    def __init__(self, scene_path, end_time):
        self.path = scene_path
        self.scene = os.path.basename(scene_path)[:-len(".toml")]
        self.end_time = end_time

    def label(self):
        return self.scene if self.end_time is None else f"{self.scene} [0, {self.end_time:g}] s"

    def key(self):
        return self.scene if self.end_time is None else f"{self.scene}-{self.end_time:g}s"

    def window(self):
        return [] if self.end_time is None else [("solver.end_time", repr(self.end_time))]


def reference(case, method, nsbridge, cache):
    """The reference peaks of case for method: the first of its tolerances that reaches a
    result."""
    ref_method, tolerances = reference_of(method)
    for tol in tolerances:
        entry = reference_at(case, ref_method, tol, nsbridge, cache)
        if entry["rc"] == 0:
            break
    return entry


def reference_at(case, ref_method, tol, nsbridge, cache):
    """The cached reference peaks of case under ref_method at tol (computed on a miss; a
    failed run is cached too, so that it is not run again)."""
    path = os.path.join(cache, f"{case.key()}-{ref_method}-{tol:g}.json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    out = os.path.join(cache, "tmp", f"{case.key()}-{ref_method}-{tol:g}")
    rc, summary, msg = run(nsbridge, case.path, ref_method,
                           case.window() + [("solver.tolerance", repr(tol)),
                                            ("solver.error_estimate", "false")], out)
    entry = {"method": ref_method, "tolerance": tol, "rc": rc, "message": msg,
             "status": summary["status"] if summary else "",
             "peaks": deck_peaks(summary) if summary else {}}
    shutil.rmtree(out, ignore_errors=True)
    with open(path, "w") as f:
        json.dump(entry, f, indent=1)
    return entry


def adapt(case, method, nsbridge, out_dir, accuracy, extra, reuse):
    """The adapt run of case under method; its summary (None when it failed) and message."""
    out = os.path.join(out_dir, f"{case.key()}-{method}")
    path = os.path.join(out, "summary.json")
    if reuse and os.path.exists(path):
        with open(path) as f:
            return 0, json.load(f), "reused"
    sets = case.window() + [("solver.adapt", "true"), ("solver.accuracy", repr(accuracy))]
    sets += extra
    return run(nsbridge, case.path, method, sets, out)


def check(case, method, args, extra):
    ref = reference(case, method, args.nsbridge, args.cache)
    rc, summary, msg = adapt(case, method, args.nsbridge, args.out, args.accuracy, extra,
                             args.reuse)
    row = {"case": case.label(), "method": method, "rc": rc, "message": msg,
           "reference": f"{ref['method']} {ref['tolerance']:g}",
           "tighter": ref["tolerance"] != reference_of(method)[1][0]}
    if ref["rc"] != 0 or not ref["peaks"]:
        row["message"] = "reference failed: " + ref["message"]
        return row
    if summary is None:
        return row
    peaks = deck_peaks(summary)
    worst, name = -1.0, ""
    for k, r in ref["peaks"].items():
        e = abs(peaks[k] - r) / abs(r) if r != 0.0 else abs(peaks[k])
        if e > worst:
            worst, name = e, k
    acc = summary.get("accuracy", {})
    attempts = acc.get("attempts", [])
    row.update(worst=worst, coordinate=name, claimed=acc.get("met"),
               attempts=len(attempts),
               setting=acc.get("local_tolerance", acc.get("tolerance", float("nan"))),
               cpu=acc.get("total_cpu_seconds", float("nan")),
               status=summary.get("status", ""))
    return row


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("nsbridge")
    ap.add_argument("--scenes", default=os.path.join(here, "..", "scenes"))
    ap.add_argument("--cache", default="out/adapt-check/references")
    ap.add_argument("--out", default="out/adapt-check/runs")
    ap.add_argument("--accuracy", type=float, default=1e-2)
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--only", default="", help="scene names (without .toml), comma-separated")
    ap.add_argument("--jobs", type=int, default=nsb_runs.MAX_WORKERS)
    ap.add_argument("--reuse", action="store_true", help="keep adapt runs already in --out")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="an override for the adapt runs, e.g. solver.min_step=1e-5")
    args = ap.parse_args()
    methods = [m for m in args.methods.split(",") if m]
    if any(m not in METHODS for m in methods) or args.jobs not in (1, 2) or \
            not 0.0 < args.accuracy < 1.0 or any("=" not in s for s in args.set) or \
            not os.path.isdir(args.scenes):
        ap.print_usage(sys.stderr)
        return 2
    extra = [tuple(s.split("=", 1)) for s in args.set]
    os.makedirs(args.cache, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    only = set(s for s in args.only.split(",") if s)
    cases = [Case(os.path.join(args.scenes, name + ".toml"), None)
             for name in nsb_runs.bridge_scenes(args.scenes)]
    cases += [Case(os.path.join(args.scenes, s + ".toml"), WORK_PRECISION_END)
              for s in WORK_PRECISION]
    if only:
        cases = [c for c in cases if c.scene in only]
    work = [(c, m) for c in cases for m in methods]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        rows = list(pool.map(lambda cm: check(cm[0], cm[1], args, extra), work))

    print(f"solver.adapt = true, solver.accuracy = {args.accuracy:g}; references: "
          f"{RIGID_REFERENCE[0]} at {RIGID_REFERENCE[1][0]:g} (moreau, event_driven), "
          f"{COMPLIANCE_REFERENCE[0]} at {COMPLIANCE_REFERENCE[1][0]:g} (compliance), "
          "tighter where marked")
    if extra:
        print("overrides: " + " ".join(f"{k}={v}" for k, v in extra))
    print("\n| scene | method | worst relative error | claimed met | attempts | setting | CPU s |")
    print("|---|---|---|---|---|---|---|")
    failed = 0
    for r in rows:
        if "worst" not in r:
            failed += 1
            print(f"| {r['case']} | {r['method']} | failed (exit {r['rc']}): "
                  f"{r['message'].replace('|', '/')} | | | | |")
            continue
        miss = r["worst"] > args.accuracy
        failed += miss
        tighter = f" (against {r['reference']})" if r["tighter"] else ""
        print(f"| {r['case']} | {r['method']} | {100 * r['worst']:.3f} % ({r['coordinate']})"
              f"{' **misses**' if miss else ''}{tighter} | {str(r['claimed']).lower()} | "
              f"{r['attempts']} | {r['setting']:g} | {r['cpu']:.3g} |")
    print(f"\n{len(rows) - failed} of {len(rows)} within {100 * args.accuracy:g} %")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
