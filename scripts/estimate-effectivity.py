#!/usr/bin/python3
"""usage: estimate-effectivity.py NSBRIDGE [SCENES_DIR] [--scenes a,b,...] [--factors 1,10,100]
                                [--reference-cache DIR] [--per-run]

The effectivity of the error estimate (docs/error-estimates.md, "Effectivity on the bridge"):
every shipped bridge scene (SCENES_DIR/bridge-*.toml, or the names given) under Moreau-Jean at
its own step and at 10 and 100 times it; each generalized coordinate's peak, its estimated
error, and its true error against event-driven at solver.tolerance = 1e-10 (the reference of
verification/moreau_order_check.cpp). Prints a Markdown table (one row per peak), then the
share of the peaks whose estimate is at least the true error, the runs at their own step that
warn `accuracy:`, and the median cost ratio (run + companion) / run of the runs of at least
0.1 CPU s. --reference-cache keeps the references' summaries in DIR and reads them from
there when present. --per-run prints one row per run instead of one per peak: the peaks whose
estimate covers the error, the smallest effectivity, the largest estimate / peak. Exit 0."""
import concurrent.futures
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import tomllib

COORDINATE = re.compile(r"(x|y|theta)\d*")


def run(nsbridge, scene, out, method, sets):
    args = [nsbridge, "run", scene, "--quiet", "--out", out, "--method", method]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode not in (0, 1):
        raise RuntimeError(f"{scene} {sets}: exit {done.returncode}: {done.stderr.strip()}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def coordinates(summary):
    return {k: v for k, v in summary["peaks"].items() if COORDINATE.fullmatch(k)}


def main():
    args = [a for a in sys.argv[1:]]
    if not args:
        print(__doc__)
        return 2
    names, factors, cache = None, (1, 10, 100), None
    per_run = "--per-run" in args
    if per_run:
        args.remove("--per-run")
    if "--reference-cache" in args:
        i = args.index("--reference-cache")
        cache = args[i + 1]
        del args[i:i + 2]
    if "--scenes" in args:
        i = args.index("--scenes")
        names = args[i + 1].split(",")
        del args[i:i + 2]
    if "--factors" in args:
        i = args.index("--factors")
        factors = tuple(float(f) for f in args[i + 1].split(","))
        del args[i:i + 2]
    nsbridge = os.path.abspath(args[0])
    scenes = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes")
    files = sorted(f[:-5] for f in os.listdir(scenes)
                   if f.startswith("bridge-") and f.endswith(".toml"))
    if names:
        files = [f for f in files if f in names]
    rows, covered, total, own_warns, ratios, run_rows = [], 0, 0, [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        jobs, hs = {}, {}
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for name in files:
                path = os.path.join(scenes, name + ".toml")
                with open(path, "rb") as f:
                    h = float(tomllib.load(f).get("solver", {}).get("step", 1e-4))
                hs[name] = h
                cached = os.path.join(cache, name + ".json") if cache else None
                if cached and os.path.exists(cached):
                    jobs[(name, "ref")] = pool.submit(lambda p: json.load(open(p)), cached)
                else:
                    jobs[(name, "ref")] = pool.submit(
                        run, nsbridge, path, os.path.join(tmp, name + "-ref"), "event_driven",
                        ["solver.tolerance=1e-10", "solver.error_estimate=false"])
                for k in factors:
                    jobs[(name, k)] = pool.submit(
                        run, nsbridge, path, os.path.join(tmp, f"{name}-{k:g}"), "moreau",
                        [f"solver.step={k * h:g}"])
            results = {key: job.result() for key, job in jobs.items()}
        if cache:
            os.makedirs(cache, exist_ok=True)
            for name in files:
                with open(os.path.join(cache, name + ".json"), "w") as f:
                    json.dump(results[(name, "ref")], f)
        for name in files:
            ref = coordinates(results[(name, "ref")])
            for k in factors:
                s = results[(name, k)]
                warned = any(w.startswith("accuracy:") for w in s["warnings"])
                cost = s["error_estimate"].get("cost") or {}
                if cost.get("run_cpu_seconds", 0.0) >= 0.1:
                    ratios.append(cost["ratio"])
                if k == 1 and warned:
                    own_warns.append(name)
                step = s["accuracy"].get("step", k * hs[name])
                effs, largest = [], (0.0, "-")
                for c, p in coordinates(s).items():
                    true = abs(p["abs_max"] - ref[c]["abs_max"])
                    est = p["error"]
                    est_text = "none" if est is None else f"{est:.2g}"
                    eff = float("inf") if true == 0 else (est if est is not None else 0) / true
                    total += 1
                    covered += eff >= 1
                    effs.append((eff, c))
                    if est is not None and p["abs_max"] > 0:
                        largest = max(largest, (est / p["abs_max"], c))
                    rows.append(f"| {name} | {step:g} | \\|{c}\\| | {p['abs_max']:.4g} "
                                f"| {ref[c]['abs_max']:.4g} | {est_text} "
                                f"| {true:.2g} | {eff:.2f} | {'warns' if warned else 'meets'} "
                                f"| {cost.get('ratio', float('nan')):.2f} |")
                low = min(effs) if effs else (float("nan"), "-")
                good = sum(e >= 1 for e, _ in effs)
                run_rows.append(f"| {name} | {step:g} | {good} of {len(effs)} "
                                f"| {low[0]:.2f} ({low[1]}) | {largest[0]:.3g} ({largest[1]}) "
                                f"| {'warns' if warned else 'meets'} "
                                f"| {cost.get('ratio', float('nan')):.2f} |")
    if per_run:
        print("| scene | h [s] | estimate >= error | smallest effectivity "
              "| largest estimate / peak | verdict | cost ratio |")
        print("|---|---|---|---|---|---|---|")
        print("\n".join(run_rows))
    else:
        print("| scene | h [s] | peak | value | reference | estimate | true error "
              "| effectivity | verdict | cost ratio |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        print("\n".join(rows))
    print(f"\n{covered} of {total} peaks ({100.0 * covered / max(total, 1):.1f} %) have "
          f"estimate >= |true error|")
    print(f"runs at their own step that warn accuracy: {own_warns or 'none'}")
    if ratios:
        print(f"cost ratio of the runs of >= 0.1 CPU s: median {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.2f}-{max(ratios):.2f}, {len(ratios)} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
