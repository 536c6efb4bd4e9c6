#!/usr/bin/python3
"""usage: accuracy-coarse-check.py NSBRIDGE [SCENES_DIR] [--method event_driven|compliance]

Every shipped bridge scene (SCENES_DIR/bridge-*.toml) at 10 and 100 times its own step
(Moreau-Jean, the scenes' method), or with --method at 100 and 10^4 times that method's
solver.tolerance (default 1e-8), either warns `accuracy:` or meets its solver.accuracy
(docs/error-estimates.md, "Coarse steps warn"). Prints a Markdown table: the scene, the step,
the deck's largest relative error estimate, the verdict, and the deck's largest true
deviation from the run at the scene's own step (for reading, not judged). Exit 1 when a run
neither warns nor meets its target, or does not run."""
import json
import os
import re
import subprocess
import sys
import tempfile
import tomllib


def run(nsbridge, scene, out, sets, method=None):
    args = [nsbridge, "run", scene, "--quiet", "--out", out]
    if method:
        args += ["--method", method]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode not in (0, 1):
        raise RuntimeError(f"{scene} {sets}: exit {done.returncode}: {done.stderr.strip()}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def deck(summary):
    """The generalized coordinates' peaks: the columns whose error the accuracy judges."""
    return {k: v["abs_max"] for k, v in summary["peaks"].items()
            if re.fullmatch(r"(x|y|theta)\d*", k)}


def main():
    args = sys.argv[1:]
    method = None
    if "--method" in args:
        i = args.index("--method")
        method = args[i + 1]
        del args[i:i + 2]
    if not args:
        print(__doc__)
        return 2
    nsbridge = os.path.abspath(args[0])
    scenes = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__),
                                                                  "..", "scenes")
    files = sorted(f for f in os.listdir(scenes) if f.startswith("bridge-") and f.endswith(".toml"))
    bad = 0
    knob = "tolerance" if method else "step"
    print(f"| scene | {knob} | largest estimate / peak | accuracy | verdict "
          "| largest deviation from own step |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in files:
            path = os.path.join(scenes, name)
            with open(path, "rb") as f:
                solver = tomllib.load(f).get("solver", {})
            h = float(solver.get("step", 1e-4)) if not method else 1e-8
            own = deck(run(nsbridge, path, os.path.join(tmp, "own"), [], method))
            for factor in ((10, 100) if not method else (100, 10000)):
                step = factor * h
                s = run(nsbridge, path, os.path.join(tmp, f"x{factor}"),
                        [f"solver.{knob}={step:g}"], method)
                acc = s["accuracy"]
                warned = any(w.startswith("accuracy:") for w in s["warnings"])
                met = acc["met"] is True
                verdict = "warns" if warned else ("meets" if met else "NEITHER")
                bad += verdict == "NEITHER"
                peaks = deck(s)
                dev = max(abs(peaks[k] - own[k]) / own[k] for k in own if own[k] > 0)
                worst = acc["worst_relative_error"]
                worst_text = "none" if worst is None else f"{worst:.3g}"
                target = acc["target"]
                print(f"| {name[:-5]} | {step:g} | {worst_text} ({acc['worst'] or '-'}) "
                      f"| {target:g} | {verdict} | {dev:.3g} |")
    print(f"\n{bad} runs neither warn nor meet their target")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
