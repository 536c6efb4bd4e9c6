#!/usr/bin/python3
"""The impacts of one scene counted alike by every method (docs/outputs.md, "One event
vocabulary").

usage: events_cross_check.py --nsbridge BIN --scene SCENE --end-time T

Runs SCENE up to T under moreau, event_driven and compliance (without the error estimate) in
a fresh temporary folder, and reads each run's events.csv and summary.json alone:

- per contact, Moreau-Jean and event-driven report the same number of impacts;
- per joint (the contacts of one end, summary.json "contacts": "left +W/2" and "left -W/2"
  are the joint "left"), the three methods report the same number of joint impacts: an
  impact row of a contact at which no other contact of the joint was already in contact
  (closed, between its "close" and "open" rows) or struck at the same time;
- every other impact row is a second-corner impact of the compliance method: its contact
  closed while another corner of the same joint was in contact. A rigid impact takes no
  time, so the deck leaves the face after the first corner's; a compliant contact lasts
  (tens of ms on the benchmark bridge) and penetrates, and the deck turns into the face
  meanwhile, so the joint's other corner, whose gap was W |theta|, closes too;
- summary.json's "events" and "contact_events" impact counts are the rows of events.csv.

Prints the counts; exit 0 when every check holds, 1 otherwise.
"""
import collections
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

METHODS = ("moreau", "event_driven", "compliance")


def joint_of(name):
    """The joint of a contact name: "left +W/2" -> "left", "hinge 1 -W/2" -> "hinge 1"."""
    return name.rsplit(" ", 1)[0] if name.endswith("W/2") else name


def count(run):
    """Per-contact impacts, per-joint impacts and second-corner impacts of the run's files."""
    summary = json.loads((run / "summary.json").read_text())
    joint = {c["contact"]: joint_of(c["name"]) for c in summary["contacts"]}
    with open(run / "events.csv") as f:
        rows = [(float(r["t"]), int(r["contact"]), r["kind"]) for r in csv.DictReader(f)]
    per_contact = collections.Counter()
    per_joint = collections.Counter()
    second = []
    closed = {}  # contact -> time of its open "close" row
    struck = collections.defaultdict(set)  # (joint, t) -> contacts struck at t
    for t, c, kind in rows:
        if kind == "impact":
            per_contact[c] += 1
            j = joint.get(c, str(c))
            others_closed = any(joint.get(o) == j and o != c for o in closed)
            others_struck = any(o != c for o in struck[(j, t)])
            struck[(j, t)].add(c)
            if others_closed or others_struck:
                second.append((t, c))
            else:
                per_joint[j] += 1
        elif kind == "close":
            closed[c] = t
        elif kind == "open":
            closed.pop(c, None)
    ok = summary["events"]["impact"] == sum(per_contact.values())
    for entry in summary["contact_events"]:
        ok = ok and entry["impact"] == per_contact[entry["contact"]]
    return per_contact, per_joint, second, ok


def main(argv):
    args = dict(zip(argv[1::2], argv[2::2]))
    if not {"--nsbridge", "--scene", "--end-time"} <= args.keys():
        print(__doc__, file=sys.stderr)
        return 2
    counts = {}
    with tempfile.TemporaryDirectory() as tmp:
        for method in METHODS:
            out = pathlib.Path(tmp) / method
            cmd = [args["--nsbridge"], "run", args["--scene"], "--method", method, "--out",
                   str(out), "--quiet", "--set", "solver.end_time=" + args["--end-time"],
                   "--set", "solver.error_estimate=false"]
            rc = subprocess.run(cmd, stdout=subprocess.DEVNULL).returncode
            if rc != 0:
                print(f"{method}: nsbridge exited {rc}")
                return 1
            counts[method] = count(out)
    failed = False
    for method, (per_contact, per_joint, second, ok) in counts.items():
        print(f"{method}: impacts per contact {dict(sorted(per_contact.items()))}, "
              f"per joint {dict(sorted(per_joint.items()))}, second-corner "
              f"{[(round(t, 6), c) for t, c in second]}")
        if not ok:
            print(f"{method}: summary.json's impact counts differ from events.csv: FAIL")
            failed = True
    if counts["moreau"][0] != counts["event_driven"][0]:
        print("moreau and event_driven differ in the impacts per contact: FAIL")
        failed = True
    joints = {m: counts[m][1] for m in METHODS}
    if not joints["moreau"] == joints["event_driven"] == joints["compliance"]:
        print("the methods differ in the impacts per joint: FAIL")
        failed = True
    if sum(joints["moreau"].values()) == 0:
        print("no impact before the end time: nothing compared: FAIL")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
