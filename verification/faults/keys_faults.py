#!/usr/bin/python3
"""Fault injection on every numeric key of the scene schema.

usage: keys_faults.py NSBRIDGE SCENE_DOCS SCENES_DIR

The keys come from the schema itself (`scene_docs --keys`), never from a list written here:
a key added to the schema is tested without touching this file. Each number, integer or
three-vector key is set (as an override) to each of nan, inf, 0, -0, the subnormal 4.9e-324,
1e308 and -1, on a small shipped scene of its model family, with a short end_time, and each
case must end in one of two ways (docs/cli.md, "What each fault gets"):
  - exit 0, with finite outputs (no nan or inf in summary.json, history.csv, events.csv or
    on the terminal);
  - exit 2, with a message that names the key's path, prints no nan or inf, is no
    "internal error", and nothing written (neither --out nor a staging folder).
Every case must take less than 2 s. A table the schema declares but no entry of SCENES maps
to a scene fails the test, so that a new table is not silently left out.
"""
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

NSBRIDGE, SCENE_DOCS, SCENES = (os.path.abspath(a) for a in sys.argv[1:4])

# The scene of each schema table, the override prefix of its keys there, and extra options.
# (The schema's tables are those of docs/scenes.md; a deck chain's [[model.decks]] and
# [[model.joints]] hold the keys of model.segments and model.hinges.)
SCENES_OF = {
    "solver": [("bouncing-ball.toml", "solver.", [])],
    "solver.moreau": [("bouncing-ball.toml", "solver.", ["--method", "moreau"])],
    "solver.event_driven": [("bouncing-ball.toml", "solver.", ["--method", "event_driven"])],
    "solver.compliance": [("bouncing-ball.toml", "solver.", ["--method", "compliance"])],
    "output": [("bouncing-ball.toml", "output.", [])],
    "model.bouncing_ball": [("bouncing-ball.toml", "model.", [])],
    "model.impact_oscillator": [("impact-oscillator.toml", "model.", [])],
    "model.sliding_block": [("sliding-block.toml", "model.", [])],
    "model.rigid_deck": [("rigid-deck-straight.toml", "model.", [])],
    "model.deck": [("bridge-exc7.toml", "model.deck.", [])],
    "model.gaps": [("bridge-exc7.toml", "model.gaps.", [])],
    "model.damping": [("bridge-exc7.toml", "model.damping.", [])],
    "model.bents": [("bridge-exc7.toml", "model.bents.0.", [])],
    "model.seats": [("bridge-exc7.toml", "model.seats.", [])],
    "model.excitation": [("bridge-exc7.toml", "model.excitation.", [])],
    "model.excitation.sequence": [("bridge-aftershock.toml", "model.excitation.sequence.1.", [])],
    "model.shear_keys": [("bridge-shear-keys.toml", "model.shear_keys.", [])],
    "model.layout": [("bridge-two-frame.toml", "model.", [])],
    "model.segments": [("bridge-two-frame.toml", "model.segments.0.", []),
                       ("deck-chain-two.toml", "model.decks.0.", [])],
    "model.hinges": [("bridge-two-frame-restrainers.toml", "model.hinges.0.", []),
                     ("deck-chain-two.toml", "model.joints.0.", [])],
    "model.restrainer": [("bridge-two-frame-restrainers.toml", "model.hinges.0.restrainer.", [])],
    "model.abutments": [("bridge-backfill.toml", "model.abutments.", [])],
    "model.bearings": [("bridge-bearings.toml", "model.bearings.0.", [])],
    "model.limit_states": [("bridge-unseating.toml", "model.limit_states.", [])],
}
# Keys of a table that a scene of another kind does not have (a deck chain's joints hold no
# seat_length).
NOT_IN = {("deck-chain-two.toml", "seat_length")}

VALUES = ["nan", "inf", "0", "-0.0", "4.9e-324", "1e308", "-1"]
END_TIME = "0.2"  # [s]: every case under 2 s
NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|-?inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def schema_keys():
    out = subprocess.run([SCENE_DOCS, "--keys"], capture_output=True, text=True, check=True)
    keys = []
    for line in out.stdout.splitlines():
        table, key, kind = line.split()
        if kind in ("number", "integer", "vector3"):
            keys.append((table, key, kind))
    return keys


def cases():
    out, unmapped = [], set()
    for table, key, kind in schema_keys():
        if table not in SCENES_OF:
            unmapped.add(table)
            continue
        for scene, prefix, options in SCENES_OF[table]:
            if (scene, key) in NOT_IN:
                continue
            for value in VALUES:
                text = f"[{value}, 0, 0]" if kind == "vector3" else value
                out.append((scene, prefix + key, text, options))
    return out, unmapped


def message_path(override):
    """The key as messages print it: model.bents.0.height -> model.bents[0].height."""
    return re.sub(r"\.(\d+)(?=\.|$)", r"[\1]", override)


def run_case(case, root):
    scene, key, value, options = case
    work = tempfile.mkdtemp(dir=root)
    out = os.path.join(work, "out")
    args = [NSBRIDGE, "run", os.path.join(SCENES, scene), "--out", out, "--quiet",
            "--set", f"{key}={value}"] + options
    if key != "solver.end_time":
        args += ["--set", f"solver.end_time={END_TIME}"]
    start = time.monotonic()
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=20, cwd=work)
    except subprocess.TimeoutExpired:
        return f"{scene} {key}={value}: still running after 20 s"
    took = time.monotonic() - start
    problems = []
    if took > 2.0:
        problems.append(f"took {took:.1f} s (> 2 s)")
    said = p.stdout + p.stderr
    if "internal error" in said:
        problems.append("internal error")
    if p.returncode == 0:
        texts = [said]
        for name in ("summary.json", "history.csv", "events.csv"):
            path = os.path.join(out, name)
            if os.path.exists(path):
                with open(path) as f:
                    texts.append(f.read())
        if any(NON_FINITE.search(t) for t in texts):
            problems.append("exit 0 with a non-finite number in its outputs")
    elif p.returncode == 2:
        path = message_path(key)
        if path not in p.stderr:
            problems.append(f"exit 2 without naming {path}")
        if NON_FINITE.search(p.stderr.replace(path, "")):
            problems.append("a non-finite number in the message")
        if p.stdout:
            problems.append("exit 2 with standard output")
        left = [f for f in os.listdir(work)]
        if left:
            problems.append(f"exit 2 left {left} behind")
    else:
        problems.append(f"exit {p.returncode}")
    shutil.rmtree(work, ignore_errors=True)
    if not problems:
        return None
    first = p.stderr.strip().splitlines()[:1]
    return f"{scene} {key}={value}: {'; '.join(problems)} [{first[0] if first else ''}]"


def main():
    all_cases, unmapped = cases()
    failures = [f"table {t}: no scene in SCENES_OF" for t in sorted(unmapped)]
    root = tempfile.mkdtemp(prefix="keys-faults-")
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for r in pool.map(lambda c: run_case(c, root), all_cases):
                if r:
                    failures.append(r)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    for f in failures:
        print("FAIL", f)
    print(f"{len(all_cases)} cases, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
