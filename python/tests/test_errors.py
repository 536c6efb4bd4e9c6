"""Bad input raises nsbridge.InputError (a ValueError) with the command line's message:
file:line:col: key: what is allowed."""
import subprocess

import pytest

import nsbridge

BAD_KEY = 'description = "bad"\n[model]\nkind = "bouncing_ball"\nmas = 1.0\n'


def cli_message(exe, *args):
    """What `nsbridge run ...` says on standard error for bad input (exit code 2)."""
    cli = subprocess.run([str(exe), "run", *map(str, args), "--quiet"], capture_output=True, text=True)
    assert cli.returncode == 2, cli.stderr
    assert cli.stderr.startswith("nsbridge: ")
    return cli.stderr[len("nsbridge: "):].rstrip("\n")


def test_a_bad_key_names_file_line_column_and_key(nsbridge_exe, tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text(BAD_KEY)
    expected = cli_message(nsbridge_exe, scene, "--out", tmp_path / "out")
    assert expected.startswith(f"{scene}:4:") and "model.mas: unknown key" in expected
    for call in (lambda: nsbridge.load_scene(scene), lambda: nsbridge.run(scene)):
        with pytest.raises(nsbridge.InputError) as e:
            call()
        assert str(e.value) == expected
    assert not (tmp_path / "out").exists()


def test_an_override_of_an_unknown_key(nsbridge_exe, source, tmp_path):
    scene = source / "scenes/bouncing-ball.toml"
    expected = cli_message(nsbridge_exe, scene, "--set", "model.foo=1", "--out", tmp_path / "o")
    assert "model.foo (override): unknown key" in expected
    with pytest.raises(nsbridge.InputError) as e:
        nsbridge.run(scene, overrides=["model.foo=1"])
    assert str(e.value) == expected
    with pytest.raises(nsbridge.InputError) as e:
        nsbridge.load_scene(scene).with_overrides(["model.foo=1"])
    assert str(e.value) == expected
    with pytest.raises(nsbridge.InputError, match="solver.method"):
        nsbridge.run(scene, method="runge_kutta")


def test_a_missing_file(tmp_path):
    missing = tmp_path / "missing.toml"
    with pytest.raises(nsbridge.InputError, match=f"^{missing}: cannot open scene file"):
        nsbridge.run(missing)
    with pytest.raises(nsbridge.InputError, match=f"^{missing}: cannot open"):
        nsbridge.load_scene(str(missing))
    with pytest.raises(nsbridge.InputError, match="missing.toml"):
        nsbridge.sweep(missing, tmp_path / "sweep")


def test_other_bad_calls(source, tmp_path):
    r = nsbridge.run(source / "scenes/bouncing-ball.toml", overrides=["solver.end_time=0.1"])
    (tmp_path / "file").write_text("")
    with pytest.raises(nsbridge.InputError, match="Result.write: "):
        r.write(tmp_path / "file" / "out")  # a folder inside a file
    with pytest.raises(TypeError):
        nsbridge.run(42)
    with pytest.raises(nsbridge.InputError, match="progress"):
        nsbridge.run(source / "scenes/bouncing-ball.toml", progress="yes")
    assert issubclass(nsbridge.InputError, ValueError)
