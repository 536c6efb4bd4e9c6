"""A scene as a value from Python: Scene.from_dict builds the scene a TOML file with the same
keys builds, and runs bit for bit as it; typed overrides give the scene of their text form;
to_toml reads back to the same scene; a Scene runs without reading its file again."""
import math
import pathlib
import tomllib

import numpy as np
import pytest

import nsbridge

RECORD = "ground-motions/RSN988_NORTHR_CCN360.AT2"


def without_wall_time(summary):
    """The summary without its timings: wall_time and the error estimate's CPU seconds."""
    out = {k: v for k, v in summary.items() if k != "wall_time"}
    if "error_estimate" in out:
        out["error_estimate"] = {k: v for k, v in out["error_estimate"].items() if k != "cost"}
    return out


def assert_same_run(a, b):
    """Every history column equal with == and in its bits (so -0 and 0 differ, NaN is NaN),
    the events equal, the summary equal except its wall time."""
    assert list(a.history) == list(b.history)
    for name in a.history:
        x, y = a.history[name], b.history[name]
        assert x.shape == y.shape, name
        finite = np.isfinite(x)
        assert np.array_equal(finite, np.isfinite(y)), name
        assert np.all(x[finite] == y[finite]), name
        assert np.array_equal(x.view(np.uint64), y.view(np.uint64)), name
    assert np.array_equal(a.events["t"].view(np.uint64), b.events["t"].view(np.uint64))
    assert a.events["contact"].tolist() == b.events["contact"].tolist()
    assert (a.events["kind"], a.events["note"]) == (b.events["kind"], b.events["note"])
    assert without_wall_time(a.summary) == without_wall_time(b.summary)


def bridge_dict(record):
    """A three-bent bridge under one record, 0.5 s of it: a dict made by hand."""
    return {
        "description": "three bents, one record",
        "model": {
            "kind": "bridge",
            "bents": [
                {"position": -8.34, "height": 1.83, "columns": 2},
                {"position": 0.0, "height": 2.44, "columns": 2},
                {"position": 8.34, "height": 1.52, "columns": 2},
            ],
            "gaps": {"left": 0.0127, "right": 0.0127},
            "seats": {"friction": 0.5, "transverse": False},
            "excitation": {"time_scale": 0.5, "transverse_record": record, "target_pga": 0.5},
        },
        "solver": {"end_time": 0.5, "step": 1e-4},
        "output": {"sample_dt": 0.0},
    }


# The same bridge as a scene file: what the dict says, written by hand in TOML.
BRIDGE_TOML = """description = "three bents, one record"
[model]
kind = "bridge"
[[model.bents]]
position = -8.34
height = 1.83
columns = 2
[[model.bents]]
position = 0.0
height = 2.44
columns = 2
[[model.bents]]
position = 8.34
height = 1.52
columns = 2
[model.gaps]
left = 0.0127
right = 0.0127
[model.seats]
friction = 0.5
transverse = false
[model.excitation]
time_scale = 0.5
transverse_record = "{record}"
target_pga = 0.5
[solver]
end_time = 0.5
step = 1e-4
[output]
sample_dt = 0.0
"""


def test_a_bridge_from_a_dict_runs_bit_for_bit_as_its_file(source, tmp_path):
    record = str(source / "data" / RECORD)
    file = tmp_path / "three-bents.toml"
    file.write_text(BRIDGE_TOML.format(record=record))
    from_file = nsbridge.load_scene(file)
    from_dict = nsbridge.Scene.from_dict(bridge_dict(record), name="three-bents")
    assert from_dict.path is None and from_file.path == file
    assert (from_dict.name, from_dict.kind, from_dict.method, from_dict.end_time) == \
           ("three-bents", "bridge", "moreau", 0.5)
    assert from_dict.warnings == from_file.warnings
    for method in ("moreau", "event_driven", "compliance"):
        a = nsbridge.run(from_file, method=method)
        b = nsbridge.run(from_dict, method=method)
        # 0.5 s at 1e-4 s, every step sampled: 5000 steps and the initial row.
        assert len(a.history["t"]) == 5001 if method == "moreau" else len(a.history["t"]) > 1
        assert_same_run(a, b)
    # The record named relative to the dict's folder, as a file's beside it.
    relative = nsbridge.Scene.from_dict(bridge_dict(RECORD), name="three-bents",
                                        folder=source / "data")
    assert_same_run(nsbridge.run(from_file), nsbridge.run(relative))


@pytest.mark.parametrize("scene,end_time", [("bridge-exc5.toml", 2), ("bridge-bearings.toml", 2),
                                            ("bridge-two-frame-restrainers.toml", 2),
                                            ("deck-chain-two.toml", None),
                                            ("rigid-deck-skew.toml", None),
                                            ("bouncing-ball.toml", None)])
def test_a_shipped_scene_read_by_tomllib_runs_as_its_file(source, scene, end_time):
    file = source / "scenes" / scene
    d = tomllib.loads(file.read_text())
    excitation = d["model"].get("excitation", {})
    for key in ("transverse_record", "longitudinal_record", "vertical_record"):
        if key in excitation:
            excitation[key] = str(source / "data" / excitation[key])
    overrides = []
    if end_time is not None:
        d["solver"]["end_time"] = end_time
        overrides = [f"solver.end_time={end_time}"]
    a = nsbridge.run(nsbridge.load_scene(file, overrides))
    b = nsbridge.run(nsbridge.Scene.from_dict(d, name=file.stem))
    assert_same_run(a, b)


def test_from_dict_checks_every_key_as_a_file_does(tmp_path):
    ball = {"model": {"kind": "bouncing_ball", "mas": 1.0, "height": 1.0}}
    file = tmp_path / "ball.toml"
    file.write_text('[model]\nkind = "bouncing_ball"\nmas = 1.0\nheight = 1.0\n')
    with pytest.raises(nsbridge.InputError) as from_file:
        nsbridge.load_scene(file)
    with pytest.raises(nsbridge.InputError) as from_dict:
        nsbridge.Scene.from_dict(ball, name="ball")
    # The file's message "<file>:3:7: model.mas: unknown key; ..." (at the value); the dict's names the key
    # with no line.
    why = str(from_file.value).split(": model.mas: ")[1]
    assert str(from_file.value).startswith(f"{file}:3:7: model.mas: unknown key")
    assert str(from_dict.value) == "ball: model.mas: " + why

    def error(d):
        with pytest.raises(nsbridge.InputError) as e:
            nsbridge.Scene.from_dict(d)
        return str(e.value)

    assert error({"model": {"kind": "bouncing_ball", "mass": "heavy", "height": 1.0}}) == \
        "scene: model.mass: expected a number, got a string"
    assert error({"model": {"kind": "bouncing_ball", "mass": -1.0, "height": 1.0}}).startswith(
        "scene: model.mass: ")
    assert error({"model": {"kind": "bouncing_ball", "mass": None}}) == \
        "scene: model.mass: expected a dict, a list, a bool, an int, a float or a str, got NoneType"
    bents = [{"position": 0.0, "height": 1.0}, {"position": 1.0, "height": object()}]
    assert error({"model": {"kind": "bridge", "bents": bents}}).startswith(
        "scene: model.bents[1].height: expected a dict, ")
    assert error({"model": {"kind": "bouncing_ball"}, 3: 1}) == \
        "scene: expected str keys, got the int 3"
    assert error({"solver": {"step": 1e-3}}).startswith("scene: ")
    assert error({"solver": {"step": 1e-3}}).endswith("missing table [model]")
    assert error({"model": {"kind": "bouncing_ball", "mass": 2**64}}) == \
        f"scene: model.mass: the integer {2**64} does not fit in 64 bits"
    assert issubclass(nsbridge.InputError, ValueError)


def test_typed_overrides_equal_their_text_form_bit_for_bit(source):
    file = source / "scenes" / "bridge-exc7.toml"
    text = ["solver.end_time=1.5", "solver.step=2e-4", "model.gaps.left=0.05",
            "model.bents.0.height=2.0", "model.damping.mode_j=2", "solver.method=event_driven",
            "model.seats.transverse=true"]
    typed = {"solver.end_time": 1.5, "solver.step": 2e-4, "model.gaps.left": 0.05,
             "model.bents.0.height": 2.0, "model.damping.mode_j": 2,
             "solver.method": "event_driven", "model.seats.transverse": True}
    strings = {k: v.split("=", 1)[1] for k, v in zip(typed, text)}  # a dict of text values
    a = nsbridge.load_scene(file, text)
    b = nsbridge.load_scene(file, typed)
    c = nsbridge.load_scene(file, strings)
    d = nsbridge.load_scene(file).with_overrides(typed)
    assert a.to_toml() == b.to_toml() == c.to_toml() == d.to_toml()
    assert "left = 0.05" in b.to_toml() and b.method == "event_driven" and b.end_time == 1.5
    # Scene.overrides: the text form of each, the value as TOML; read back, the same scene.
    assert b.overrides[0] == "solver.end_time=1.5" and b.overrides[3:] == [
        "model.bents.0.height=2.0", "model.damping.mode_j=2", "solver.method='event_driven'",
        "model.seats.transverse=true"]
    assert nsbridge.load_scene(file, b.overrides).to_toml() == b.to_toml()
    ra = nsbridge.run(a)
    assert_same_run(ra, nsbridge.run(b))
    assert_same_run(ra, nsbridge.run(d))
    assert_same_run(ra, nsbridge.run(file, overrides=typed))
    # A vector key takes a list of numbers; a numpy float is a float.
    e = nsbridge.load_scene(source / "scenes" / "rigid-deck-skew.toml",
                            {"solver.end_time": np.float64(0.5)})
    assert e.end_time == 0.5
    # A typed value the key does not take is reported as its text form is.
    with pytest.raises(nsbridge.InputError) as typed_error:
        nsbridge.load_scene(file, {"solver.step": -1.0})
    with pytest.raises(nsbridge.InputError) as text_error:
        nsbridge.load_scene(file, ["solver.step=-1.0"])
    assert str(typed_error.value) == str(text_error.value)
    assert f"{file}: solver.step (override): " in str(typed_error.value)
    with pytest.raises(nsbridge.InputError, match='override "solver.step": expected a bool'):
        nsbridge.load_scene(file, {"solver.step": None})
    with pytest.raises(nsbridge.InputError, match="typed values go in a dict"):
        nsbridge.load_scene(file, [("solver.step", 1e-4)])


def test_a_bare_string_is_one_override(source):
    file = source / "scenes" / "bouncing-ball.toml"
    one = nsbridge.load_scene(file, "solver.end_time=0.5")
    assert one.overrides == ["solver.end_time=0.5"] and one.end_time == 0.5
    assert one.to_toml() == nsbridge.load_scene(file, ["solver.end_time=0.5"]).to_toml()
    assert one.with_overrides("solver.end_time=0.25").end_time == 0.25
    assert nsbridge.run(file, overrides="solver.end_time=0.25").summary["end_time"] == 0.25
    # A string without "=" is one malformed override, not a list of characters.
    with pytest.raises(nsbridge.InputError,
                       match='override "solver.end_time": expected section.key=value'):
        nsbridge.load_scene(file, "solver.end_time")


def test_to_toml_reads_back_to_the_same_scene(source):
    file = source / "scenes" / "bridge-exc5.toml"
    s = nsbridge.load_scene(file, {"solver.end_time": 1, "model.gaps.right": 0.02})
    text = s.to_toml()
    # The file's keys with the overrides applied: what tomllib reads of each text.
    expected = tomllib.loads(file.read_text())
    expected["solver"]["end_time"] = 1
    expected["model"]["gaps"]["right"] = 0.02
    assert tomllib.loads(text) == expected
    back = nsbridge.Scene.from_dict(tomllib.loads(text), name="bridge-exc5",
                                    folder=source / "scenes")
    assert back.to_toml() == text
    assert_same_run(nsbridge.run(s), nsbridge.run(back))


def test_a_scene_runs_without_reading_its_file_again(source, tmp_path):
    file = tmp_path / "ball.toml"
    file.write_text((source / "scenes" / "bouncing-ball.toml").read_text())
    s = nsbridge.load_scene(file, {"solver.end_time": 0.5})
    first = nsbridge.run(s)
    file.write_text("this is not TOML")  # a run would fail if it read the file
    assert_same_run(first, nsbridge.run(s))
    file.unlink()
    again = s.with_overrides({"solver.end_time": 0.25})
    assert again.path == file and again.end_time == 0.25
    assert nsbridge.run(again, method="event_driven").status == "completed"
    assert math.isclose(nsbridge.run(again).summary["end_time"], 0.25)
    assert isinstance(again.path, pathlib.Path)


def test_the_examples_of_docs_python_md_run(source, monkeypatch, capsys):
    text = (source / "docs" / "python.md").read_text()
    section = text.split("## Scenes as values")[1].split("\n## ")[0]
    blocks = [b.split("```")[0] for b in section.split("```python\n")[1:]]
    assert len(blocks) == 2
    monkeypatch.chdir(source)  # the examples name scenes/ relative to the source tree
    names = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), names)
    # The ball from 1 m and from 0.5 m with less restitution bounces; the dict's integers and
    # floats reach the file as they were.
    assert all(len(r.events["t"]) > 0 for r in names["runs"])
    assert "height = 0.5" in capsys.readouterr().out
    assert names["r"].status == "completed" and names["r"].name == "exc5-gap"
