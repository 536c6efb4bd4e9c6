"""nsbridge.sweep against `nsbridge sweep`, and the examples of examples/python/ in small
variants (short runs, matplotlib's Agg backend, PNGs into a temporary folder)."""
import os
import subprocess
import sys

import numpy as np
import pandas as pd

import nsbridge
from conftest import equal_bits, read_csv_columns

SHORT = ["solver.end_time=1"]


def check_columns(columns, expected, kinds):
    """Each column equals results.csv's field by field, with the type its kind has: float64
    bits (an empty field NaN), int64 and bool values (an empty field absent), str."""
    assert list(columns) == list(expected)
    for name, fields in expected.items():
        values, kind = columns[name], kinds(name)
        if kind == "real":
            assert values.dtype == np.float64, name
            if name != "wall_s":
                assert equal_bits(np.asarray(values, dtype=np.float64), fields), name
        elif kind == "integer":
            assert [None if v is None else int(v) for v in values] == \
                [int(f) if f != "" else None for f in fields], name
        elif kind == "boolean":
            assert [None if v is None else bool(v) for v in values] == \
                [{"1": True, "0": False, "true": True, "false": False}.get(f) for f in fields], name
        else:
            assert [str(v) for v in values] == fields, name


def pandas_kind(frame):
    dtypes = {"float64": "real", "Int64": "integer", "boolean": "boolean", "string": "text"}
    return lambda name: dtypes[str(frame[name].dtype)]


def numpy_kind(columns):
    dtypes = {"f": "real", "i": "integer", "b": "boolean", "U": "text"}
    return lambda name: dtypes[columns[name].dtype.kind]


def as_values(frame):
    """A DataFrame's columns as lists with None where a value is absent (pd.NA)."""
    return {name: [None if v is pd.NA else v for v in frame[name]] if str(frame[name].dtype)
            in ("Int64", "boolean") else frame[name].to_numpy() for name in frame.columns}


def as_numpy_values(columns):
    """numpy columns as lists with None where a masked array masks a value."""
    return {name: [None if m else v for v, m in zip(c.data, np.ma.getmaskarray(c))]
            if isinstance(c, np.ma.MaskedArray) else c for name, c in columns.items()}


def test_a_sweep_gives_the_command_lines_results(source, nsbridge_exe, tmp_path):
    design = source / "scenes/sweeps/fig6.toml"
    cli = [str(nsbridge_exe), "sweep", str(design), "--out", str(tmp_path / "cli"), "--jobs", "2"]
    for o in SHORT:
        cli += ["--set", o]
    subprocess.run(cli, check=True, capture_output=True)
    r = nsbridge.sweep(design, tmp_path / "py", jobs=2, overrides=SHORT)
    expected = read_csv_columns(tmp_path / "cli" / "results.csv")
    assert isinstance(r, pd.DataFrame) and len(r) == 36
    check_columns(as_values(r), expected, pandas_kind(r))
    # The types come from the rows, whatever the values: the factor of named levels "0.17",
    # ... is real, "pounding" ("yes", "no") text, the counts integers.
    kinds = pandas_kind(r)
    assert kinds("model.excitation.target_pga") == "real"
    assert kinds("pounding") == "text" and kinds("status") == "text" and kinds("run") == "text"
    assert kinds("impacts") == "integer" and kinds("steps") == "integer"
    # A second call finds every run complete and returns the same table (resumed rows).
    again = nsbridge.sweep(design, tmp_path / "py", jobs=2, overrides=SHORT)
    assert again.equals(r)


def test_without_pandas_a_sweep_gives_numpy_columns(source, tmp_path, monkeypatch):
    """Limit states (seat lengths, bent drift) and a rejected run (a step longer than the run)
    give bool and int64 columns, masked where a value is absent, beside float64 and str."""
    monkeypatch.setattr(nsbridge, "_pandas", None)
    design = tmp_path / "limits.toml"
    design.write_text(
        f'scene = "{source / "scenes/bridge-two-frame.toml"}"\n'
        'set = ["model.abutments.seat_length=0.037", "model.limit_states.drift_ratio=0.01"]\n'
        '[[factor]]\nkey = "solver.end_time"\nvalues = [0.2, 0.002]\n'
        '[[factor]]\nkey = "solver.step"\nvalues = [1e-4, 0.005]\n')
    out = tmp_path / "np"
    r = nsbridge.sweep(design, out, jobs=2)
    assert isinstance(r, dict) and all(isinstance(c, np.ndarray) for c in r.values())
    assert "rejected" in list(r["status"])
    kinds = numpy_kind(r)
    assert kinds("unseating_left_exceeded") == "boolean"
    assert kinds("impacts") == "integer" and kinds("solver.end_time") == "real"
    assert isinstance(r["impacts"], np.ma.MaskedArray)  # the rejected run has no count
    check_columns(as_numpy_values(r), read_csv_columns(out / "results.csv"), kinds)


def run_example(source, name, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, str(source / "examples/python" / name),
                          "--out", str(tmp_path), "--end-time", "1"],
                         capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    return out.stdout


def is_png(path):
    return path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_fig6_example_draws_a_png(source, tmp_path):
    assert "36 runs, 0 failed" in run_example(source, "fig6.py", tmp_path)
    assert is_png(tmp_path / "fig6.png")


def test_the_methods_example_draws_a_png(source, tmp_path):
    printed = run_example(source, "methods.py", tmp_path)
    for method in ("moreau completed", "event_driven completed", "compliance completed"):
        assert method in printed
    assert is_png(tmp_path / "methods.png")
