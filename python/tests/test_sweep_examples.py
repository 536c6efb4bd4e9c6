"""nsbridge.sweep against `nsbridge sweep`, and the examples of examples/python/ in small
variants (short runs, matplotlib's Agg backend, PNGs into a temporary folder)."""
import os
import subprocess
import sys

import numpy as np

import nsbridge
from conftest import equal_bits, read_csv_columns

SHORT = ["solver.end_time=1"]


def test_a_sweep_gives_the_command_lines_results(source, nsbridge_exe, tmp_path):
    design = source / "scenes/sweeps/fig6.toml"
    cli = [str(nsbridge_exe), "sweep", str(design), "--out", str(tmp_path / "cli"), "--jobs", "2"]
    for o in SHORT:
        cli += ["--set", o]
    subprocess.run(cli, check=True, capture_output=True)
    r = nsbridge.sweep(design, tmp_path / "py", jobs=2, overrides=SHORT)
    expected = read_csv_columns(tmp_path / "cli" / "results.csv")
    assert list(r) == list(expected)
    assert len(r["run"]) == 36
    for name, fields in expected.items():
        if name == "wall_s":
            continue
        if name in ("run", "status", "message", "pounding"):
            assert r[name] == fields, name
        else:
            assert isinstance(r[name], np.ndarray) and equal_bits(r[name], fields), name
    # A second call finds every run complete and returns the same table.
    again = nsbridge.sweep(design, tmp_path / "py", jobs=2, overrides=SHORT)
    assert np.array_equal(again["wall_s"], r["wall_s"])


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
