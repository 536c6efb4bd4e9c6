"""Checks a sweep's DIR/sweep.h5 against the sweep's CSV files, with h5py and numpy.

  store_check.py equal DIR     every run's group and /results hold the numbers of DIR's CSV
                               files bit for bit (each CSV field read back with float(), which
                               rounds correctly, from io::csv_number's shortest round-trip
                               text), the texts character for character
  store_check.py partial DIR   the file opens; every group marked done equals its run's files;
                               /results may be absent (a sweep stopped part way)
  store_check.py same A B      A/sweep.h5 and B/sweep.h5 hold the same runs and numbers, but
                               for the wall and CPU times (summary.json's wall_time and
                               error_estimate.cost, results' wall_s)
Exit status 0 when it holds; otherwise 1 and what differs on stderr."""
import csv
import io
import json
import math
import pathlib
import sys

import h5py
import numpy as np

VOLATILE = {"wall_time", "cost"}  # summary.json keys that time the run
failures = []


def fail(what):
    failures.append(what)


def csv_table(text):
    rows = list(csv.reader(io.StringIO(text, newline="")))
    return rows[0], rows[1:]


def floats(fields):
    return np.array([float(f) if f != "" else math.nan for f in fields], dtype=np.float64)


def same_bits(array, fields):
    """Every finite value has its field's bits (-0 and 0 differ); NaN where a field is empty."""
    expected = floats(fields)
    array = np.asarray(array, dtype=np.float64)
    finite = np.isfinite(array)
    return (array.shape == expected.shape and np.array_equal(np.isnan(expected), ~finite) and
            np.array_equal(array[finite].view(np.uint64), expected[finite].view(np.uint64)))


def texts(dataset):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in dataset[()]]


def check_column(where, dataset, fields):
    if dataset.dtype.kind == "f":
        if not same_bits(dataset[()], fields):
            fail(f"{where}: float64 values differ from the CSV's")
    elif dataset.dtype.kind == "i":
        if [int(v) for v in dataset[()]] != [int(f) for f in fields]:
            fail(f"{where}: integers differ from the CSV's")
    elif texts(dataset) != fields:
        fail(f"{where}: texts differ from the CSV's")


def check_run(run_dir, group, history_columns):
    rid = run_dir.name
    header, body = csv_table((run_dir / "row.csv").read_text())
    row_header, row_body = csv_table(group.attrs["row"])
    results_header, results_body = RESULTS
    line = [r for r in results_body if r[0] == rid] if results_body is not None else None
    if row_body[0][0] != rid:
        fail(f"{rid}: row attribute of run {row_body[0][0]}")
    if line is not None:
        for name, field in zip(row_header, row_body[0]):
            if line[0][results_header.index(name)] != field:
                fail(f"{rid}: row's {name} = {field!r}, results.csv has "
                     f"{line[0][results_header.index(name)]!r}")
    history = run_dir / "history.csv"
    if history.exists() and history_columns != "none":
        h_header, h_body = csv_table(history.read_text())
        d = group["history"]
        names = list(d.attrs["columns"])
        wanted = h_header if history_columns == "all" else history_columns.split(",")
        if names != wanted:
            fail(f"{rid}: history columns {names}, expected {wanted}")
        for j, name in enumerate(names):
            k = h_header.index(name)
            if not same_bits(d[:, j], [r[k] for r in h_body]):
                fail(f"{rid}: history column {name} differs from history.csv")
    elif "history" in group:
        fail(f"{rid}: a history the design does not keep")
    events = run_dir / "events.csv"
    if events.exists():
        e_header, e_body = csv_table(events.read_text())
        e = group["events"]
        if list(e.attrs["columns"]) != e_header:
            fail(f"{rid}: events columns {list(e.attrs['columns'])}, events.csv has {e_header}")
        for k, name in enumerate(e_header):
            check_column(f"{rid}: events {name}", e[name], [r[k] for r in e_body])
    summary = run_dir / "summary.json"
    if summary.exists() and group["summary"].asstr()[()] != summary.read_text():
        fail(f"{rid}: summary differs from summary.json")


def check_dir(folder, complete):
    global RESULTS
    folder = pathlib.Path(folder)
    with h5py.File(folder / "sweep.h5", "r") as f:
        results = folder / "results.csv"
        RESULTS = csv_table(results.read_text()) if complete else (None, None)
        history_columns = f.attrs["hdf5_history"]
        # A group a killed process left half written may not open (None): it is not done.
        done = {name for name, g in f["runs"].items()
                if g is not None and g.attrs.get("done", 0) == 1}
        finished = {p.parent.name for p in (folder / "runs").glob("*/row.csv")}
        if complete and done != finished:
            fail(f"groups done {sorted(done)} != runs finished {sorted(finished)}")
        if not done <= finished:
            fail(f"groups done without their run's files: {sorted(done - finished)}")
        for rid in sorted(done):
            check_run(folder / "runs" / rid, f["runs"][rid], history_columns)
        if complete:
            header, body = RESULTS
            g = f["results"]
            if list(g.attrs["columns"]) != header:
                fail(f"/results columns {list(g.attrs['columns'])} != results.csv's {header}")
            for k, name in enumerate(header):
                check_column(f"/results {name}", g[name], [r[k] for r in body])
        return len(done)


def drop_volatile(value):
    if isinstance(value, dict):
        return {k: drop_volatile(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [drop_volatile(v) for v in value]
    return value


def same_dataset(where, a, b):
    va, vb = a[()], b[()]
    if a.dtype.kind == "f":
        equal = va.shape == vb.shape and np.array_equal(
            np.nan_to_num(va).view(np.uint64), np.nan_to_num(vb).view(np.uint64)) and \
            np.array_equal(np.isnan(va), np.isnan(vb))
    else:
        equal = va.shape == vb.shape and list(va) == list(vb)
    if not equal:
        fail(f"{where}: differs")


def check_same(dir_a, dir_b):
    with h5py.File(pathlib.Path(dir_a) / "sweep.h5", "r") as a, \
            h5py.File(pathlib.Path(dir_b) / "sweep.h5", "r") as b:
        if sorted(a["runs"]) != sorted(b["runs"]):
            fail(f"runs {sorted(a['runs'])} != {sorted(b['runs'])}")
            return
        for rid in a["runs"]:
            ga, gb = a["runs"][rid], b["runs"][rid]
            for key in ("done", "index"):
                if ga.attrs[key] != gb.attrs[key]:
                    fail(f"{rid}: attribute {key} differs")
            row_a, row_b = csv_table(ga.attrs["row"]), csv_table(gb.attrs["row"])
            wall = row_a[0].index("wall_s")
            if row_a[0] != row_b[0] or [v for i, v in enumerate(row_a[1][0]) if i != wall] != \
                    [v for i, v in enumerate(row_b[1][0]) if i != wall]:
                fail(f"{rid}: rows differ")
            if "history" in ga:
                same_dataset(f"{rid}/history", ga["history"], gb["history"])
            if "events" in ga:
                for name in ga["events"].attrs["columns"]:
                    same_dataset(f"{rid}/events/{name}", ga["events"][name], gb["events"][name])
            if "summary" in ga and drop_volatile(json.loads(ga["summary"].asstr()[()])) != \
                    drop_volatile(json.loads(gb["summary"].asstr()[()])):
                fail(f"{rid}: summaries differ beyond their timing")
        for name in a["results"].attrs["columns"]:
            if name != "wall_s":
                same_dataset(f"/results/{name}", a["results"][name], b["results"][name])
        return len(a["runs"])


RESULTS = (None, None)
if __name__ == "__main__":
    mode = sys.argv[1]
    if mode == "equal":
        n = check_dir(sys.argv[2], complete=True)
    elif mode == "partial":
        n = check_dir(sys.argv[2], complete=False)
    else:
        n = check_same(sys.argv[2], sys.argv[3])
    for f in failures:
        print("FAILED:", f, file=sys.stderr)
    if not failures:
        print(f"store_check {mode}: ok ({n} runs)")
    sys.exit(1 if failures else 0)
