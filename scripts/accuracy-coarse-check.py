#!/usr/bin/python3
"""usage: accuracy-coarse-check.py NSBRIDGE [SCENES_DIR] [--method event_driven|compliance]
                                 [--scenes a,b,...] [--reference-cache DIR] [--set KEY=VALUE]

Every shipped bridge scene (SCENES_DIR/bridge-*.toml, or the names given) at 10 and 100 times
its own step (Moreau-Jean, the scenes' method), or with --method at 100 and 10^4 times that
method's solver.tolerance (default 1e-8), either warns `accuracy:` or meets its
solver.accuracy (docs/error-estimates.md, "Coarse steps warn"). Prints a Markdown table: the
scene, the step or tolerance, the deck's largest relative error estimate, the verdict, the
deck's largest true error against the converged reference (the same method at tolerance
1e-10 for --method, event-driven at 1e-10 for Moreau-Jean; nsb_runs.references, kept in
--reference-cache DIR), and the deck's largest deviation from the run at the scene's own
settings. Then the runs that meet their target while a deck peak is further than the target
from the reference. --set (repeatable) overrides a key in every run and reference, e.g.
solver.end_time=10 for a shorter window. At most two processes run at once. Exit 1 when a run
neither warns nor meets its target, or does not run."""
import concurrent.futures
import os
import sys
import tempfile

import nsb_runs


def deck(summary):
    """The generalized coordinates' peaks: the columns whose error the accuracy judges."""
    return {k: v["abs_max"] for k, v in nsb_runs.coordinates(summary).items()}


def largest_relative(peaks, reference):
    return max((abs(peaks[k] - reference[k]) / reference[k], k)
               for k in reference if reference[k] > 0)


def main():
    args = sys.argv[1:]
    method = nsb_runs.option(args, "--method")
    cache = nsb_runs.option(args, "--reference-cache")
    names = nsb_runs.option(args, "--scenes")
    names = names.split(",") if names else None
    extra = []
    while "--set" in args:
        extra.append(nsb_runs.option(args, "--set"))
    if not args:
        print(__doc__)
        return 2
    nsbridge = os.path.abspath(args[0])
    scenes = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes")
    files = nsb_runs.bridge_scenes(scenes, names)
    paths = {name: os.path.join(scenes, name + ".toml") for name in files}
    knob = "tolerance" if method else "step"
    factors = (100, 10000) if method else (10, 100)
    bad, false_meets = 0, []
    print(f"| scene | {knob} | largest estimate / peak | accuracy | verdict "
          "| largest true error / peak | largest deviation from own settings |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=nsb_runs.MAX_WORKERS) as pool:
            refs = nsb_runs.references(nsbridge, paths.values(), tmp, cache, pool,
                                       method or nsb_runs.REFERENCE_METHOD, extra)
            jobs = {}
            for name in files:
                own = 1e-8 if method else float(
                    nsb_runs.solver_table(paths[name]).get("step", 1e-4))
                jobs[(name, 1)] = pool.submit(nsb_runs.run, nsbridge, paths[name],
                                              os.path.join(tmp, f"{name}-own"), method, extra)
                for factor in factors:
                    value = factor * own
                    jobs[(name, factor)] = (value, pool.submit(
                        nsb_runs.run, nsbridge, paths[name],
                        os.path.join(tmp, f"{name}-x{factor}"), method,
                        extra + [f"solver.{knob}={value:g}"]))
            for name in files:
                own = deck(jobs[(name, 1)].result())
                reference = deck(refs[paths[name]].result())
                for factor in factors:
                    value, job = jobs[(name, factor)]
                    s = job.result()
                    acc = s["accuracy"]
                    warned = nsb_runs.warns_accuracy(s)
                    met = acc["met"] is True
                    verdict = "warns" if warned else ("meets" if met else "NEITHER")
                    bad += verdict == "NEITHER"
                    peaks = deck(s)
                    dev = largest_relative(peaks, own)
                    true = largest_relative(peaks, reference)
                    worst = acc["worst_relative_error"]
                    worst_text = "none" if worst is None else f"{worst:.3g}"
                    target = acc["target"]
                    if verdict == "meets" and true[0] > target:
                        false_meets.append(f"{name} at {value:g} ({true[1]} "
                                           f"{100 * true[0]:.2g} % off)")
                    print(f"| {name} | {value:g} | {worst_text} ({acc['worst'] or '-'}) "
                          f"| {target:g} | {verdict} | {true[0]:.3g} ({true[1]}) "
                          f"| {dev[0]:.3g} |")
    print(f"\n{bad} runs neither warn nor meet their target")
    print(f"runs that meet their target while further from the reference: "
          f"{'; '.join(false_meets) or 'none'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
