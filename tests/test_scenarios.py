"""Bad scenario input -> one clear error line naming the key, what was given, what is accepted."""
import subprocess
import sys
from pathlib import Path

import pytest

from spinorbit.cli import main

FREE_BODY = Path(__file__).parents[1] / "scenarios" / "free_body.toml"
P93 = Path(__file__).parents[1] / "scenarios" / "p93_bounded.toml"


def write_scene(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return path


def base_text():
    return FREE_BODY.read_text()


@pytest.mark.parametrize(
    "edit, key, accepted",
    [
        (lambda s: s + '\n[body.extra]\nfoo = 1\n', "body.extra.foo", "one of the keys"),
        (lambda s: s.replace('step = "0.5 d"', 'stepp = "0.5 d"'), "span.stepp", "one of the keys"),
        (lambda s: s.replace("[body]", "[bodyy]"), "bodyy", "one of the tables"),
        (lambda s: s.replace('end = "1073.15 d"', 'end = "1999-01-01T00:00:00"'), "span.end", "a time after span.start"),
        (lambda s: s.replace('step = "0.5 d"', 'step = "0.5 km"'), "span.step", "units convertible to 'd'"),
        (lambda s: s.replace('step = "0.5 d"', "step = 0.5"), "span.step", "a quantity with a unit"),
        (lambda s: s.replace('method = "dop853"', 'method = "euler"'), "integrator.method", "one of ["),
        (lambda s: s.replace("rtol = 1e-13", "rtoll = 1e-13"), "integrator.rtoll", "one of the keys ["),
        (lambda s: s.replace('kind = "free_body"', 'kind = "free_bdy"'), "scene.kind", "one of ["),
        (lambda s: s.replace("moments = [0.6666666666666666, 1.0, 2.0]", "moments = [1.0, 2.0]"),
         "body.moments", "a list of 3 numbers"),
    ],
)
def test_bad_input_gives_one_line_naming_the_key(tmp_path, capsys, edit, key, accepted):
    path = write_scene(tmp_path, edit(base_text()))
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--set", "span.end=5 d"]
                if key != "span.end" else ["run", str(path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f"error: {key}: got ")
    assert accepted in err


@pytest.mark.parametrize(
    "moments, accepted",
    [("[0.4, 0.5, 1.0]", "triangle inequality"), ("[-0.8, 0.9, 1.0]", "positive"), ("[0.9, 0.8, 1.0]", "ordered")],
)
def test_non_physical_inertia_is_named(tmp_path, capsys, moments, accepted):
    path = write_scene(tmp_path, P93.read_text().replace("moments = [0.8, 0.9, 1.0]", f"moments = {moments}"))
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--set", "span.end=1 d"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1, err
    assert err.startswith("error: body.moments: got ") and accepted in err


def test_missing_table_is_named(tmp_path, capsys):
    text = base_text().split("[body]")[0]
    code = main(["run", str(write_scene(tmp_path, text))])
    err = capsys.readouterr().err
    assert code == 2 and "error: body.moments: got '(missing table)'" in err


def test_set_overrides_by_dotted_path(tmp_path, capsys):
    code = main(["run", str(FREE_BODY), "--out", str(tmp_path), "--set", "span.end=not-a-time"])
    err = capsys.readouterr().err
    assert code == 2 and "span.end: got 'not-a-time'" in err


def test_no_traceback_from_the_command_line(tmp_path):
    path = write_scene(tmp_path, base_text().replace('step = "0.5 d"', 'step = "0.5 km"'))
    proc = subprocess.run([sys.executable, "-m", "spinorbit.cli", "run", str(path)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines() == [proc.stderr.strip()]


def test_list_shows_every_scene(capsys):
    assert main(["list", str(FREE_BODY.parent)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == len(list(FREE_BODY.parent.rglob("*.toml")))
    assert any(line.startswith("free_body.toml") and "free_body" in line for line in out)
