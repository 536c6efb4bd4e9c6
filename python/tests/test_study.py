"""nsbridge.open_study against the CSV files of the sweep that wrote the study's sweep.h5
(`nsbridge sweep --hdf5`): the same results table, histories, events and summaries."""
import json
import subprocess

import pandas as pd
import pytest

import nsbridge
from conftest import equal_bits, read_csv_columns


@pytest.fixture
def study_dir(nsbridge_exe, source, tmp_path):
    """Two runs of the bouncing ball, 0.5 s each."""
    design = tmp_path / "d.toml"
    design.write_text(f'scene = "{source}/scenes/bouncing-ball.toml"\n'
                      'set = ["solver.end_time=0.5"]\n'
                      '[[factor]]\nkey = "model.restitution"\nvalues = [0.5, 0.9]\n')
    out = tmp_path / "out"
    done = subprocess.run([str(nsbridge_exe), "sweep", str(design), "--out", str(out), "--hdf5",
                           "--jobs", "1"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return out


def test_open_study_reads_what_the_csv_files_hold(study_dir):
    expected = read_csv_columns(study_dir / "results.csv")
    with nsbridge.open_study(study_dir / "sweep.h5") as study:
        table = study.results
        assert list(table.columns) == list(expected)
        assert list(table["run"]) == expected["run"] == study.runs
        assert list(table["status"]) == expected["status"]
        assert equal_bits(table["peak_y"].to_numpy(dtype=float), expected["peak_y"])
        assert str(table["impacts"].dtype) == "Int64"
        for run in expected["run"]:
            folder = study_dir / "runs" / run
            history = study.history(run)
            columns = read_csv_columns(folder / "history.csv")
            assert list(history.columns) == list(columns)
            for name, fields in columns.items():
                assert equal_bits(history[name].to_numpy(), fields), (run, name)
            events = study.events(run)
            columns = read_csv_columns(folder / "events.csv")
            assert list(events.columns) == list(columns)
            assert [str(k) for k in events["kind"]] == columns["kind"]
            assert equal_bits(events["t"].to_numpy(), columns["t"])
            assert study.summary(run) == json.loads((folder / "summary.json").read_text())
        with pytest.raises(KeyError, match="no complete run"):
            study.history("9999")


def test_a_stopped_study_gives_the_rows_of_its_runs(study_dir):
    """Without /results (a sweep stopped part way) the table is made from the runs' rows."""
    import h5py
    with h5py.File(study_dir / "sweep.h5", "a") as f:
        del f["results"]
    expected = read_csv_columns(study_dir / "results.csv")
    with nsbridge.open_study(study_dir / "sweep.h5") as study:
        assert isinstance(study.results, pd.DataFrame)
        assert list(study.results["run"]) == expected["run"]
        assert equal_bits(study.results["peak_y"].to_numpy(dtype=float), expected["peak_y"])
