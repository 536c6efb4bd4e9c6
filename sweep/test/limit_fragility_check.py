"""Recounts the stripes of a limit-state fragility from the runs' own summary.json files.

    python3 limit_fragility_check.py DESIGN.toml OUT

OUT is the folder of `nsbridge sweep DESIGN.toml --out OUT`. For every run folder
OUT/runs/<id>/ the IM is summary.json's achieved Sa of the transverse record
(input.transverse.sa_g), the outcome its status, limit_states and peaks: the files each run
writes, not results.csv or the sweep's counting (sweep/fragility_sweep.cpp), which are under
test. Each [[fragility.limit_state]] of the design is counted by the rules of docs/fragility.md:

  - a run counts when its status is completed, completed_with_fallbacks or unseated;
  - an unseated run reaches the limit state unless it says unseated = "response";
  - limit_state = X: reached when summary.json limit_states[X].exceeded;
  - response = peak_<q>, threshold: reached when peaks[q].abs_max >= threshold.

and the counts (n, exceeded, unseated per IM) must equal fragility.json's stripes. Also:
results.csv's <X>_exceeded cells equal summary.json's verdicts, every unseated run lost exactly
one seat, and the study has an unseated run and a stripe that is neither all nor nothing for
the unseating limit states (so that the example exercises what it is there to show).
Exit 0 when everything holds, 1 with one line per discrepancy otherwise.
"""
import csv
import json
import pathlib
import sys
import tomllib

RESULTS = {"completed", "completed_with_fallbacks", "unseated"}


def reached(summary, ls):
    if summary["status"] == "unseated" and ls.get("unseated", "exceeded") == "exceeded":
        return True
    if "limit_state" in ls:
        return bool(summary["limit_states"][ls["limit_state"]]["exceeded"])
    q = ls["response"].removeprefix("peak_")
    return summary["peaks"][q]["abs_max"] >= ls["threshold"]


def main(design_file, out):
    design = tomllib.loads(pathlib.Path(design_file).read_text())
    limit_states = design["fragility"]["limit_state"]
    runs = sorted(pathlib.Path(out, "runs").iterdir())
    summaries = {r.name: json.loads((r / "summary.json").read_text()) for r in runs}
    fragility = json.loads(pathlib.Path(out, "fragility.json").read_text())["limit_states"]
    errors = []

    for ls in limit_states:
        name = ls.get("name", ls.get("limit_state"))
        expected = {}
        for s in summaries.values():
            im = round(s["input"]["transverse"]["sa_g"], 9)
            n, k, u = expected.get(im, (0, 0, 0))
            if s["status"] in RESULTS:
                expected[im] = (n + 1, k + reached(s, ls), u + (s["status"] == "unseated"))
        got = {round(st["im"], 9): (st["n"], st["exceeded"], st.get("unseated", 0))
               for st in fragility[name]["stripes"]}
        if got != expected:
            errors.append(f"{name}: stripes (n, exceeded, unseated) {got}, recounted {expected}")

    with open(pathlib.Path(out, "results.csv"), newline="") as f:
        for row in csv.DictReader(f):
            s = summaries[row["run"]]
            for x, v in s["limit_states"].items():
                if row[x + "_exceeded"] != ("1" if v["exceeded"] else "0"):
                    errors.append(f"run {row['run']}: {x}_exceeded {row[x + '_exceeded']}, "
                                  f"summary.json {v['exceeded']}")
    unseated = [i for i, s in summaries.items() if s["status"] == "unseated"]
    for i in unseated:
        lost = [x for x, v in summaries[i]["limit_states"].items()
                if x.startswith("unseating_") and v["exceeded"]]
        if len(lost) != 1:
            errors.append(f"run {i}: unseated with the seats {lost} lost (one expected)")
    if not unseated:
        errors.append("no run lost a seat: the example shows no unseating")
    mixed = [st for st in fragility["unseating"]["stripes"] if 0 < st["exceeded"] < st["n"]]
    if not mixed:
        errors.append("unseating: no stripe with some runs unseated and some not")
    for e in errors:
        print("FAILED:", e)
    print(f"{len(summaries)} runs, {len(unseated)} unseated, {len(limit_states)} limit states "
          f"recounted: {'ok' if not errors else str(len(errors)) + ' discrepancies'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
