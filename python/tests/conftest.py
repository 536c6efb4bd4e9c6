"""Where the tests find the source tree (scenes, data) and the nsbridge executable, and how
they run it."""
import csv
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("NSB_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("NSB_BUILD_DIR", SOURCE / "build"))


@pytest.fixture
def source():
    return SOURCE


@pytest.fixture
def nsbridge_exe():
    exe = BUILD / "app" / "nsbridge"
    if not exe.exists():
        # Under CTest (NSB_BUILD_DIR set) the executable belongs to the build: its absence is
        # a failure; a bare `pytest` without a build skips the comparisons with it.
        if "NSB_BUILD_DIR" in os.environ:
            pytest.fail(f"{exe} not built (cmake --build build --target nsbridge)")
        pytest.skip(f"{exe} not built")
    return exe


@pytest.fixture
def run_cli(nsbridge_exe, source):
    """`nsbridge run SCENE --out OUT --quiet [--method M] [--set ...]`; returns OUT."""
    def run(scene, out, method=None, overrides=()):
        args = [str(nsbridge_exe), "run", str(source / scene), "--out", str(out), "--quiet"]
        if method:
            args += ["--method", method]
        for o in overrides:
            args += ["--set", o]
        subprocess.run(args, check=False, capture_output=True, cwd=source)
        assert (out / "summary.json").exists(), " ".join(args)
        return out
    return run


def read_csv_columns(path):
    """A CSV file's columns: name -> list of fields (text), in file order."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [row[i] for row in body] for i, name in enumerate(header)}


def csv_floats(fields):
    """Fields written by io::csv_number as float64: shortest round-trip text, read back
    exactly; an empty field was a value that was not finite (NaN here)."""
    return np.array([float(f) if f != "" else math.nan for f in fields], dtype=np.float64)


def equal_bits(array, fields):
    """True when every finite value has the bits of its field (shortest round-trip text read
    back: -0 and 0 differ) and every non-finite value is an empty field."""
    expected = csv_floats(fields)
    finite = np.isfinite(array)
    return (array.shape == expected.shape and
            np.array_equal(np.isnan(expected), ~finite) and
            np.array_equal(array[finite].view(np.uint64), expected[finite].view(np.uint64)))
