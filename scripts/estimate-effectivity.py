#!/usr/bin/python3
"""usage: estimate-effectivity.py NSBRIDGE [SCENES_DIR] [--scenes a,b,...] [--factors 1,10,100]
                                [--reference-cache DIR] [--per-run]

The effectivity of the error estimate (docs/error-estimates.md, "Effectivity on the bridge"):
every shipped bridge scene (SCENES_DIR/bridge-*.toml, or the names given) under Moreau-Jean at
its own step and at 10 and 100 times it; each generalized coordinate's peak, its estimated
error, and its true error against event-driven at solver.tolerance = 1e-12 (the reference of
docs/benchmarks/work-precision-bridges.md: at the scenes' own steps the errors judged are
1e-7 to 1e-5 of the peaks, and event-driven at 1e-10 is up to 6e-4 of a peak from it). The
reference's own uncertainty is its spread: each peak's difference from event-driven at 1e-13.
Prints a Markdown table (one row per peak), then the share of the peaks whose estimate is at
least the true error: against the reference taken as exact, and within its spread (estimate
>= true error - spread: not refuted by the reference; >= true error + spread: bounded
whatever the reference's own error), the runs at their own step that
warn `accuracy:`, the runs that meet their target while a deck peak is further than the target
from the reference, and the median cost ratio (run + companion) / run of the runs of at least
0.1 CPU s. --reference-cache keeps the references' summaries in DIR (nsb_runs.references) and
reads them from there when present. --per-run prints one row per run instead of one per peak:
the peaks whose estimate covers the error, the smallest effectivity, the largest estimate /
peak, the largest true error / peak. At most two processes run at once. Exit 0."""
import concurrent.futures
import os
import statistics
import sys
import tempfile

import nsb_runs

# The reference's tolerance, and the finer ones whose peaks measure its own uncertainty.
REFERENCE_TOLERANCE = "1e-12"
SPREAD_TOLERANCES = ("1e-13",)


def main():
    args = sys.argv[1:]
    if not args:
        print(__doc__)
        return 2
    per_run = "--per-run" in args
    if per_run:
        args.remove("--per-run")
    cache = nsb_runs.option(args, "--reference-cache")
    names = nsb_runs.option(args, "--scenes")
    names = names.split(",") if names else None
    factors = tuple(float(f) for f in nsb_runs.option(args, "--factors", "1,10,100").split(","))
    nsbridge = os.path.abspath(args[0])
    scenes = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes")
    files = nsb_runs.bridge_scenes(scenes, names)
    paths = {name: os.path.join(scenes, name + ".toml") for name in files}
    hs = {name: float(nsb_runs.solver_table(paths[name]).get("step", 1e-4)) for name in files}
    rows, covered, total, own_warns, ratios, run_rows, false_meets = [], 0, 0, [], [], [], []
    not_refuted, bounded = 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=nsb_runs.MAX_WORKERS) as pool:
            refs = nsb_runs.references(nsbridge, paths.values(), tmp, cache, pool,
                                       sets=(f"solver.tolerance={REFERENCE_TOLERANCE}",))
            finer = [nsb_runs.references(nsbridge, paths.values(), tmp, cache, pool,
                                         sets=(f"solver.tolerance={t}",))
                     for t in SPREAD_TOLERANCES]
            jobs = {}
            for name in files:
                for k in factors:
                    jobs[(name, k)] = pool.submit(
                        nsb_runs.run, nsbridge, paths[name],
                        os.path.join(tmp, f"{name}-{k:g}"), "moreau",
                        [f"solver.step={k * hs[name]:g}"])
            results = {key: job.result() for key, job in jobs.items()}
            references = {name: refs[paths[name]].result() for name in files}
            spreads = {name: [nsb_runs.coordinates(f[paths[name]].result()) for f in finer]
                       for name in files}
        for name in files:
            ref = nsb_runs.coordinates(references[name])
            for k in factors:
                s = results[(name, k)]
                warned = nsb_runs.warns_accuracy(s)
                cost = s["error_estimate"].get("cost") or {}
                if cost.get("run_cpu_seconds", 0.0) >= 0.1:
                    ratios.append(cost["ratio"])
                if k == 1 and warned:
                    own_warns.append(name)
                step = s["accuracy"].get("step", k * hs[name])
                target = s["accuracy"]["target"]
                effs, largest, worst_true = [], (0.0, "-"), (0.0, "-")
                for c, p in nsb_runs.coordinates(s).items():
                    true = abs(p["abs_max"] - ref[c]["abs_max"])
                    spread = max(abs(f[c]["abs_max"] - ref[c]["abs_max"]) for f in spreads[name])
                    est = p["error"]
                    est_text = "none" if est is None else f"{est:.2g}"
                    eff = float("inf") if true == 0 else (est if est is not None else 0) / true
                    total += 1
                    covered += eff >= 1
                    not_refuted += (est or 0) >= true - spread
                    bounded += (est or 0) >= true + spread
                    effs.append((eff, c))
                    if est is not None and p["abs_max"] > 0:
                        largest = max(largest, (est / p["abs_max"], c))
                    if ref[c]["abs_max"] > 0:
                        worst_true = max(worst_true, (true / ref[c]["abs_max"], c))
                    rows.append(f"| {name} | {step:g} | \\|{c}\\| | {p['abs_max']:.4g} "
                                f"| {ref[c]['abs_max']:.4g} | {spread:.2g} | {est_text} "
                                f"| {true:.2g} | {eff:.2f} | {'warns' if warned else 'meets'} "
                                f"| {cost.get('ratio', float('nan')):.2f} |")
                if not warned and worst_true[0] > target:
                    false_meets.append(f"{name} at {step:g} s ({worst_true[1]} "
                                       f"{100 * worst_true[0]:.2g} % off)")
                low = min(effs) if effs else (float("nan"), "-")
                good = sum(e >= 1 for e, _ in effs)
                run_rows.append(f"| {name} | {step:g} | {good} of {len(effs)} "
                                f"| {low[0]:.2f} ({low[1]}) | {largest[0]:.3g} ({largest[1]}) "
                                f"| {worst_true[0]:.3g} ({worst_true[1]}) "
                                f"| {'warns' if warned else 'meets'} "
                                f"| {cost.get('ratio', float('nan')):.2f} |")
    if per_run:
        print("| scene | h [s] | estimate >= error | smallest effectivity "
              "| largest estimate / peak | largest true error / peak | verdict | cost ratio |")
        print("|---|---|---|---|---|---|---|---|")
        print("\n".join(run_rows))
    else:
        print("| scene | h [s] | peak | value | reference | reference spread | estimate "
              "| true error | effectivity | verdict | cost ratio |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(rows))
    print(f"\n{covered} of {total} peaks ({100.0 * covered / max(total, 1):.1f} %) have "
          f"estimate >= |true error|")
    print(f"within the reference's spread: {not_refuted} "
          f"({100.0 * not_refuted / max(total, 1):.1f} %) have estimate >= |true error| - spread, "
          f"{bounded} ({100.0 * bounded / max(total, 1):.1f} %) estimate >= |true error| + spread")
    print(f"runs at their own step that warn accuracy: {own_warns or 'none'}")
    print(f"runs that meet their target while further from the reference: "
          f"{'; '.join(false_meets) or 'none'}")
    if ratios:
        print(f"cost ratio of the runs of >= 0.1 CPU s: median {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.2f}-{max(ratios):.2f}, {len(ratios)} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
