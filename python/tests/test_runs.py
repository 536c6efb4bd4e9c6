"""nsbridge.run against `nsbridge run`: the same scene gives the same numbers, bit for bit, in
the arrays as in history.csv and events.csv, and the same summary.json; Scene and Result."""
import json
import pathlib

import numpy as np
import pytest

import nsbridge
from conftest import equal_bits, read_csv_columns

# (scene, method, overrides): every method on the bridge (shortened), the other model kinds
# with their own method, and a run that stalls (a status, the files still written).
CASES = [
    ("scenes/bridge-exc5.toml", "moreau", ["solver.end_time=10"]),
    ("scenes/bridge-exc5.toml", "event_driven", ["solver.end_time=10"]),
    ("scenes/bridge-exc5.toml", "compliance", ["solver.end_time=10"]),
    ("scenes/bouncing-ball.toml", None, []),
    ("scenes/impact-oscillator.toml", None, []),
    ("scenes/sliding-block.toml", None, []),
    ("scenes/rigid-deck-skew.toml", None, []),
    ("scenes/bouncing-ball.toml", "compliance", ["solver.max_steps=10"]),
]


def without_wall_time(summary):
    """The summary without its timings: wall_time and the error estimate's CPU seconds."""
    out = {k: v for k, v in summary.items() if k != "wall_time"}
    if "error_estimate" in out:
        out["error_estimate"] = {k: v for k, v in out["error_estimate"].items() if k != "cost"}
    return out


@pytest.mark.parametrize("scene,method,overrides", CASES)
def test_a_run_equals_the_command_lines_files_bit_for_bit(source, run_cli, tmp_path,
                                                          scene, method, overrides):
    out = run_cli(scene, tmp_path / "cli", method, overrides)
    r = nsbridge.run(source / scene, method=method, overrides=overrides)

    history = read_csv_columns(out / "history.csv")
    assert list(r.history) == list(history)
    for name, fields in history.items():
        column = r.history[name]
        assert column.dtype == np.float64 and column.flags.c_contiguous, name
        assert equal_bits(column, fields), name

    events = read_csv_columns(out / "events.csv")
    assert list(r.events) == ["t", "contact", "kind", "note"]
    assert equal_bits(r.events["t"], events["t"])
    assert r.events["contact"].tolist() == [int(c) for c in events["contact"]]
    assert r.events["kind"] == events["kind"]
    assert r.events["note"] == events["note"]

    expected = json.loads((out / "summary.json").read_text())
    assert without_wall_time(r.summary) == without_wall_time(expected)
    assert r.status == expected["status"]
    assert r.summary["wall_time"] >= 0


def test_result_write_gives_the_command_lines_files(source, run_cli, tmp_path):
    out = run_cli("scenes/bridge-exc5.toml", tmp_path / "cli", "event_driven", ["solver.end_time=5"])
    r = nsbridge.run(str(source / "scenes/bridge-exc5.toml"), method="event_driven",
                     overrides=["solver.end_time=5"])
    r.write(tmp_path / "py")
    for name in ("history.csv", "events.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (out / name).read_bytes(), name
    written = json.loads((tmp_path / "py" / "summary.json").read_text())
    assert written == r.summary  # the dict is the file, wall_time included
    assert without_wall_time(written) == without_wall_time(json.loads((out / "summary.json").read_text()))


def test_a_numerical_failure_is_a_status_not_an_exception(source):
    r = nsbridge.run(source / "scenes/bouncing-ball.toml", method="compliance",
                     overrides=["solver.max_steps=10"])
    assert r.status == "stalled"
    assert r.summary["failure_time"] > 0
    assert len(r.history["t"]) >= 1


def test_scene_loads_and_runs_with_its_overrides(source):
    s = nsbridge.load_scene(source / "scenes/bridge-exc5.toml", ["solver.end_time=2"])
    assert (s.name, s.kind, s.method, s.end_time) == ("bridge-exc5", "bridge", "moreau", 2.0)
    assert isinstance(s.path, pathlib.Path) and s.overrides == ["solver.end_time=2"]
    t = s.with_overrides(["solver.end_time=1", "solver.method=event_driven"])
    assert (t.method, t.end_time, s.end_time) == ("event_driven", 1.0, 2.0)
    r = nsbridge.run(t)
    assert (r.method, r.summary["end_time"], r.status) == ("event_driven", 1.0, "completed")
    # run's own method and overrides come after the scene's
    r = nsbridge.run(s, method="compliance", overrides=["solver.end_time=0.5"])
    assert (r.method, r.summary["end_time"]) == ("compliance", 0.5)


def test_progress_reports_the_simulated_time(source, capsys):
    times = []
    nsbridge.run(source / "scenes/bouncing-ball.toml", progress=times.append)
    assert times and times[-1] == pytest.approx(4.0) and times == sorted(times)
    nsbridge.run(source / "scenes/bouncing-ball.toml", progress=True)
    assert "t = 4 / 4 s" in capsys.readouterr().err

    def fails(t):
        raise KeyError("from the callback")
    with pytest.raises(KeyError, match="from the callback"):
        nsbridge.run(source / "scenes/bouncing-ball.toml", progress=fails)


def test_version_and_build_info():
    info = nsbridge.build_info()
    assert nsbridge.__version__ == info["version"]
    assert info["revision"] and info["compiler"].split()[0] in ("gcc", "clang")
    assert set(info["libraries"]) >= {"Eigen", "Boost", "GSL", "toml++", "pybind11", "Python"}


def test_peaks_carry_their_error_estimate_and_the_accuracy_verdict(source):
    # Moreau–Jean at 2e-3 s on the ball: the companion at 4e-3 s; each peak's error is the
    # factor 1 / (2^0.5 - 1) times the difference of the two runs' peaks (docs/error-estimates.md).
    r = nsbridge.run(source / "scenes/bouncing-ball.toml", overrides=["solver.step=2e-3"])
    e = r.error_estimate
    assert e["enabled"] and e["computed"]
    assert e["companion"] == {"setting": "step", "value": 4e-3, "status": "completed"}
    assert e["factor"] == pytest.approx(1.0 / (2.0 ** 0.5 - 1.0))
    assert r.peaks["y"]["error"] >= 0
    assert e["cost"]["companion_cpu_seconds"] > 0
    # One contact: no second corner whose order against the impact could be in question.
    assert "impact_order" in e and e["impact_order"] is None
    assert r.accuracy["target"] == 0.01 and r.accuracy["step"] == 2e-3
    assert r.accuracy["met"] in (True, False)
    off = nsbridge.run(source / "scenes/bouncing-ball.toml", overrides=["solver.error_estimate=false"])
    assert off.peaks["y"]["error"] is None
    assert off.error_estimate["enabled"] is False and off.accuracy["met"] is None


def test_cross_check_compares_a_second_method_and_warns_where_they_disagree(source):
    # Excitation 7's first 4.5 s (five poundings from 3.96 s): Moreau-Jean against
    # event-driven at the scene's settings agree within the estimates and the 1 % floor
    # (measured differences 1.4e-4 to 6.0e-4 of the peaks) ...
    scene = source / "scenes/bridge-exc7.toml"
    r = nsbridge.run(scene, overrides=["solver.end_time=4.5"], cross_check="event_driven")
    x = r.cross_check
    assert x["method"] == "event_driven" and x["compared"] is True
    assert set(x["peaks"]) == {"x", "y", "theta"}
    for name, p in x["peaks"].items():
        assert p["agrees"] is True
        assert abs(p["difference"]) <= 3e-3 * r.peaks[name]["abs_max"]
    assert not [w for w in r.summary["warnings"] if w.startswith("cross_check:")]
    # ... while the compliance method at 1e-4 of its contact stiffness reaches 27 % more
    # rotation, and the warning names both numbers.
    soft = nsbridge.run(scene, method="compliance", cross_check="moreau",
                        overrides=["solver.end_time=4.5", "solver.stiffness_factor=1e-4"])
    assert soft.cross_check["peaks"]["theta"]["agrees"] is False
    theta = [w for w in soft.summary["warnings"] if w.startswith("cross_check: the peak |theta|")]
    assert len(theta) == 1
    assert " under compliance and " in theta[0] and " under moreau" in theta[0]
    # Without the argument there is no cross-check.
    assert nsbridge.run(source / "scenes/bouncing-ball.toml").cross_check is None
    with pytest.raises(nsbridge.InputError, match="cross_check: unknown method"):
        nsbridge.run(scene, cross_check="runge_kutta")
