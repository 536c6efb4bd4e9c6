"""Runs of the nsbridge binary for the measuring scripts (estimate-effectivity.py,
accuracy-coarse-check.py, adapt-check.py): one run and its summary.json, the generalized coordinates' peaks,
the shipped bridge scenes, and the converged references, kept across invocations in a folder.

Every helper runs at most MAX_WORKERS processes at once (the machines these run on are small
and shared)."""
import concurrent.futures
import hashlib
import json
import os
import re
import subprocess
import tomllib

MAX_WORKERS = 2

# The columns of the generalized coordinates (x, y, theta of each deck body): the ones that
# solver.accuracy judges.
COORDINATE = re.compile(r"(x|y|theta)\d*")

# The converged reference of a bridge scene: event-driven at solver.tolerance = 1e-10 (the
# reference of verification/moreau_order_check.cpp), without an estimate.
REFERENCE_METHOD = "event_driven"
REFERENCE_SETS = ("solver.tolerance=1e-10", "solver.error_estimate=false")


def attempt(nsbridge, scene, out, method=None, sets=()):
    """Runs `nsbridge run scene --quiet --out out [--method method] --set s ...` and returns
    (exit code, its summary.json or None when it wrote none, the end of its message)."""
    args = [nsbridge, "run", scene, "--quiet", "--out", out]
    if method:
        args += ["--method", method]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True)
    path = os.path.join(out, "summary.json")
    summary = None
    if os.path.exists(path):
        with open(path) as f:
            summary = json.load(f)
    return done.returncode, summary, (done.stderr or done.stdout).strip()[-300:]


def run(nsbridge, scene, out, method=None, sets=()):
    """attempt()'s summary.json. Exit 0 and 1 (a numerical failure, or a warning under
    --strict) are results; others raise."""
    code, summary, message = attempt(nsbridge, scene, out, method, sets)
    if code not in (0, 1) or summary is None:
        raise RuntimeError(f"{scene} {list(sets)}: exit {code}: {message}")
    return summary


def option(args, name, default=None):
    """Removes `name VALUE` from the argument list args and returns VALUE (default when absent)."""
    if name not in args:
        return default
    i = args.index(name)
    value = args[i + 1]
    del args[i:i + 2]
    return value


def coordinates(summary):
    """The peaks entries of the generalized coordinates, by column name."""
    return {k: v for k, v in summary["peaks"].items() if COORDINATE.fullmatch(k)}


def warns_accuracy(summary):
    return any(w.startswith("accuracy:") for w in summary["warnings"])


def bridge_scenes(scenes_dir, names=None):
    """The shipped bridge scenes (bridge-*.toml) of scenes_dir by name, sorted; only `names`
    when given."""
    found = sorted(f[:-5] for f in os.listdir(scenes_dir)
                   if f.startswith("bridge-") and f.endswith(".toml"))
    return [f for f in found if names is None or f in names]


def solver_table(path):
    with open(path, "rb") as f:
        return tomllib.load(f).get("solver", {})


def _cache_file(cache, path, method, sets):
    # Keyed by the scene file's content, the method and the overrides: a changed scene is run
    # again. A changed binary is not detected; a new model or integrator needs a fresh folder.
    with open(path, "rb") as f:
        digest = hashlib.sha256(f.read() + "\n".join(sets).encode()).hexdigest()[:12]
    name = os.path.basename(path)[:-5]
    return os.path.join(cache, f"{name}-{method}-{digest}.json")


def references(nsbridge, paths, tmp, cache=None, pool=None, method=REFERENCE_METHOD, sets=()):
    """The reference summary of each scene path (`method` with REFERENCE_SETS: the tolerance
    1e-10; event-driven unless given; then the overrides `sets`, e.g. a shorter end_time or
    a finer tolerance),
    read from the folder `cache` when it holds one for the scene's content and overrides and
    written there otherwise. Returns {path: future}; pool: the executor to run on
    (MAX_WORKERS)."""
    own = pool is None
    if own:
        pool = concurrent.futures.ThreadPoolExecutor(max_workers=MAX_WORKERS)
    if cache:
        os.makedirs(cache, exist_ok=True)

    def one(path):
        cached = _cache_file(cache, path, method, list(sets)) if cache else None
        if cached and os.path.exists(cached):
            with open(cached) as f:
                return json.load(f)
        out = os.path.join(tmp, os.path.basename(path)[:-5] + "-reference-" + method +
                           "".join("-" + x.replace("=", "-") for x in sets))
        summary = run(nsbridge, path, out, method, list(REFERENCE_SETS) + list(sets))
        if cached:
            with open(cached + ".part", "w") as f:
                json.dump(summary, f)
            os.replace(cached + ".part", cached)
        return summary

    jobs = {p: pool.submit(one, p) for p in paths}
    if own:
        pool.shutdown(wait=True)
    return jobs
