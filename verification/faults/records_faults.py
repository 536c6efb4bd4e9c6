#!/usr/bin/python3
"""Fault injection into ground-motion record files (docs/ground-motions.md).

Every record format the scenes read (PEER .AT2 in the NGA and the older header form, CSV with
and without a header, two-column text, a single column of values with record_dt) meets every
defect (empty, truncated, non-numeric cell, NaN, binary bytes, wrong sample count, non-increasing
time, unknown unit, conflicting unit). Each case runs `nsbridge run` on a bridge scene that
reads the broken record and asserts exit code 2, a message naming the record file (and its
line where one exists) or the scene key, and that no output folder was left behind.

Where a format cannot carry a defect (a file without a header names no unit, a file without
a time column has no time to decrease), the case puts the defect where that format keeps the
information: in the scene keys (record_unit, record_dt). docs/cli.md, "What each fault gets".

Usage: records_faults.py <nsbridge binary>
"""
import os
import subprocess
import sys
import tempfile

HEAD = ("PEER STRONG MOTION DATABASE RECORD\nSYNTHETIC 1/1/2000, STATION, 090\n"
        "ACCELERATION TIME SERIES IN UNITS OF G\n")
VALUES = ["0.1", "-0.2", "0.3", "-0.4", "0.5", "-0.6"]
TIMES = ["0", "0.01", "0.02", "0.03", "0.04", "0.05"]


def at2(line4, values=VALUES, head=HEAD):
    return head + line4 + " " + " ".join(values[:3]) + "\n " + " ".join(values[3:]) + "\n"


def rows(sep, values=VALUES, times=TIMES):
    return "".join(t + sep + v + "\n" for t, v in zip(times, values))


def replaced(seq, i, v):
    out = list(seq)
    out[i] = v
    return out


NGA = "NPTS=      6, DT=   .0100 SEC\n"
OLD = "    6    .0100    NPTS, DT\n"

# format -> the record's file name
FORMATS = {
    "at2": "rec.AT2",
    "at2_old": "old.AT2",
    "csv_header": "head.csv",
    "csv_plain": "plain.csv",
    "two_column": "two.txt",
    "single_column": "single.txt",
}


def case(fmt, defect):
    """(record text, extra scene lines, fragments the message must hold, line of record_unit
    or record_dt in the scene when the fragment is a scene key)."""
    name = FORMATS[fmt]
    extra = "record_dt = 0.01\n" if fmt == "single_column" else ""

    def build(values=VALUES, times=TIMES, npts=6, dt=".0100", unit="G", header="t [s],a [g]\n"):
        if fmt in ("at2", "at2_old"):
            head = HEAD.replace("UNITS OF G", "UNITS OF " + unit)
            line4 = (f"NPTS=      {npts}, DT=   {dt} SEC\n" if fmt == "at2"
                     else f"    {npts}    {dt}    NPTS, DT\n")
            return at2(line4, values, head)
        if fmt == "csv_header":
            return header + rows(",", values, times)
        if fmt == "csv_plain":
            return rows(",", values, times)
        if fmt == "two_column":
            return rows(" ", values, times)
        return "".join(v + "\n" for v in values)

    at2_like = fmt in ("at2", "at2_old")
    if defect == "empty":
        return "", extra, [name, "empty record file"]
    if defect == "truncated":
        # The file ends in the middle of its last line.
        text = build().rstrip("\n")
        if at2_like:
            return text[: text.rfind(" ")], extra, [name + ":6:", "NPTS = 6 (line 4) but 5 values"]
        if fmt == "single_column":
            return text.rsplit("\n", 1)[0] + "\n-", extra, [name + ":6:", "non-numeric"]
        head, last = text.rsplit("\n", 1)
        sep = "," if "csv" in fmt else " "
        return head + "\n" + last[: last.find(sep)], extra, [name + ":", "found 1"]
    if defect == "non_numeric":
        return build(values=replaced(VALUES, 1, "abc")), extra, [name + ":", "non-numeric", "abc"]
    if defect == "nan":
        return build(values=replaced(VALUES, 1, "nan")), extra, [name + ":", "not finite"]
    if defect == "binary":
        return (build(values=replaced(VALUES, 1, "0.3\x00\x01\xfe")), extra,
                [name + ":", "\\x00\\x01\\xfe"])
    if defect == "wrong_count":
        if at2_like:
            return build(npts=7), extra, [name + ":", "NPTS = 7 (line 4) but 6 values"]
        if fmt == "single_column":
            return "0.1\n-0.2\n", extra, [name, "at least 3 samples, found 2"]
        sep = "," if "csv" in fmt else " "
        text = build().splitlines(True)
        text[-2] = text[-2].rstrip("\n") + sep + "9\n"
        return "".join(text), extra, [name + ":", "found 3"]
    if defect == "non_increasing":
        if at2_like:
            return build(dt="-.0100"), extra, [name + ":4:", "DT must be > 0"]
        if fmt == "single_column":
            return build(), "record_dt = 0.0\n", ["model.excitation.record_dt", "> 0"]
        return build(times=replaced(TIMES, 3, "0.02")), extra, [name + ":", "not greater"]
    if defect == "unknown_unit":
        if at2_like:
            return build(unit="FURLONG/S/S"), extra, [name + ":3:", "FURLONG/S/S"]
        if fmt == "csv_header":
            return build(header="t [s],a [furlong/s^2]\n"), extra, [name + ":1:", "[furlong/s^2]"]
        if fmt == "single_column":
            return ("a [furlong/s^2]\n" + build(), extra,
                    [name + ":1:", "[furlong/s^2]"])
        return build(), 'record_unit = "g"\n', ["model.excitation.record_unit", "number"]
    if defect == "conflicting_unit":
        if at2_like or fmt == "csv_header":
            return (build(), extra + "record_unit = 1.0\n",
                    [name + ":", "conflicts with model.excitation.record_unit = 1"])
        if fmt == "single_column":
            return ("a [g]\n" + build(), extra + "record_unit = 1.0\n",
                    [name + ":1:", "conflicts with model.excitation.record_unit = 1"])
        if fmt == "csv_plain":
            return build(), "record_dt = 0.02\n", [name + ":", "differs from model.excitation.record_dt"]
        return build(), "record_dt = 0.01\n", [name + ":1:", "remove model.excitation.record_dt"]
    raise ValueError(defect)


DEFECTS = ["empty", "truncated", "non_numeric", "nan", "binary", "wrong_count",
           "non_increasing", "unknown_unit", "conflicting_unit"]

SCENE = """[model]
kind = "bridge"
[[model.bents]]
position = -8.34
height = 1.83
[[model.bents]]
position = 0.0
height = 2.44
[[model.bents]]
position = 8.34
height = 1.52
[model.excitation]
transverse_record = "{record}"
{extra}
[solver]
method = "moreau"
end_time = 0.05
step = 1e-3
"""


def main():
    binary = os.path.abspath(sys.argv[1])
    failures = []
    count = 0
    for fmt in FORMATS:
        for defect in DEFECTS:
            count += 1
            text, extra, fragments = case(fmt, defect)
            # single-column files are plain text, except the unit cases, which need a header.
            name = FORMATS[fmt]
            if fmt == "single_column" and defect in ("unknown_unit", "conflicting_unit"):
                name = "single.csv"
                fragments = [f.replace("single.txt", "single.csv") for f in fragments]
            with tempfile.TemporaryDirectory() as tmp:
                with open(os.path.join(tmp, name), "wb") as f:
                    f.write(text.encode("latin-1"))
                scene = os.path.join(tmp, "scene.toml")
                with open(scene, "w") as f:
                    f.write(SCENE.format(record=name, extra=extra))
                before = set(os.listdir(tmp))
                out = os.path.join(tmp, "out")
                p = subprocess.run([binary, "run", scene, "--out", out], cwd=tmp,
                                   capture_output=True, timeout=60)
                err = p.stderr.decode("utf-8", "replace")
                label = f"{fmt} x {defect}"
                problems = []
                if p.returncode != 2:
                    problems.append(f"exit {p.returncode}, expected 2")
                for frag in fragments:
                    if frag not in err:
                        problems.append(f"message lacks {frag!r}")
                if b"\x00" in p.stderr or b"\xfe" in p.stderr:
                    problems.append("message echoes raw bytes")
                if "scene.toml:" not in err:
                    problems.append("message does not name the scene file")
                left = set(os.listdir(tmp)) - before
                if left:
                    problems.append(f"left behind: {sorted(left)}")
                if problems:
                    failures.append(f"{label}: {'; '.join(problems)}\n    stderr: {err.strip()}")
    for f in failures:
        print("FAIL", f)
    print(f"{count - len(failures)} of {count} record faults answered as documented")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
