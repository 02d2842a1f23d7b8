"""Bad scenario input -> one clear error line naming the key, what was given, what is accepted."""
import os
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
        (lambda s: s.replace('end = "1073.15 d"', 'end = "1999-01-01T00:00:00"'), "span.end",
         "a time after span.start"),
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
    [("[0.4, 0.5, 1.0]", "triangle inequality"), ("[-0.8, 0.9, 1.0]", "positive"),
     ("[0.9, 0.8, 1.0]", "ordered")],
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
    proc = subprocess.run([sys.executable, "-m", "spinorbit.cli", "run", str(path)], capture_output=True,
                          text=True, check=False)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines() == [proc.stderr.strip()]


def test_list_shows_every_scene(capsys):
    assert main(["list", str(FREE_BODY.parent)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == len(list(FREE_BODY.parent.rglob("*.toml")))
    assert any(line.startswith("free_body.toml") and "free_body" in line for line in out)


# --- issue 27: the up-front estimate, honest in time and memory ---------------------------------

MOON = Path(__file__).parents[1] / "scenarios" / "moon_libration.toml"
COUPLED = Path(__file__).parents[1] / "scenarios" / "stress" / "coupled_conservation.toml"
# The peak resident memory of this process's image (VmHWM; ru_maxrss would keep the forking parent's peak).
PEAK = """
import sys
from spinorbit.cli import main
assert main(sys.argv[1:]) == 0
print(next(int(line.split()[1]) * 1024 for line in open("/proc/self/status") if line.startswith("VmHWM")))
"""


def peak_bytes(tmp_path, scenario, sets):
    argv = ["--quiet", "run", str(scenario), "--out", str(tmp_path / "out"), "--force"]
    for assignment in ["output.plots=false", "integrator.estimate_error=false", *sets]:
        argv += ["--set", assignment]
    done = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True, check=False,
                          env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])})
    assert done.returncode == 0, done.stderr
    return int(done.stdout.split()[-1])


@pytest.mark.parametrize("scenario, common, sizes", [
    (MOON, ['span.start="2000-01-01T12:00:00"', "span.end=2000 d", "span.step=20 d"],
     ["orbit.step=0.1 d", "orbit.step=0.01 d"]),                           # 20,001 and 200,001 orbit samples
    (P93, ["span.end=2000 d"], ["span.step=0.1 d", "span.step=0.01 d"]),    # 20,001 and 200,001 output rows
])
def test_the_memory_estimate_holds_the_measured_peak(tmp_path, scenario, common, sizes):
    """The estimate of the larger run is above its measured peak, and what the estimate adds for the extra
    samples (rows) is at least what they add to the measured peak and at most three times it."""
    from spinorbit.scenarios import load_scenario

    peaks = [peak_bytes(tmp_path, scenario, [*common, size]) for size in sizes]
    estimates = [load_scenario(scenario, [*common, size]).estimate()["memory_bytes"] for size in sizes]
    assert estimates[1] > peaks[1]
    assert peaks[1] - peaks[0] <= estimates[1] - estimates[0] <= 3 * (peaks[1] - peaks[0])


def refused(capsys, scenario, *sets):
    argv = ["run", str(scenario), "--out", "unused"]
    for assignment in sets:
        argv += ["--set", assignment]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_a_run_longer_than_the_time_limit_is_refused_with_its_estimate(capsys):
    """A 0.0004-d step on the closed Earth-Moon system over its 10 yr: ~9 million steps, hours."""
    err = refused(capsys, COUPLED, "integrator.step=0.0004 d", "span.end=100 yr")
    assert err.startswith("error: integrator.step: got '0.0004 d'; expected a run the estimate finishes "
                          "within limits.time = 1 h: 91,312,501 integrator steps at ~")
    assert "raise limits.time" in err
    from spinorbit.scenarios import load_scenario

    allowed = load_scenario(COUPLED, ["integrator.step=0.0004 d", "span.end=100 yr", 'limits.time="100 d"'])
    assert allowed.estimate()["time_s"] > 3600


def test_a_run_over_the_memory_limit_is_refused_with_its_estimate(capsys):
    err = refused(capsys, MOON, 'span.start="2000-01-01T12:00:00"', "span.end=10 yr", "orbit.step=0.0005 d",
                  'limits.memory="2 GB"')
    assert "limits.memory = 2 GB: 7,305,001 orbit samples at ~" in err and "raise limits.memory" in err


def test_more_samples_than_the_limit_quote_their_true_memory(capsys):
    """Over 10 million orbit samples: refused, quoting the memory at no less than the measured cost per sample
    (278 B, benchmarks/results_costs.md) and at most ten times it."""
    err = refused(capsys, MOON, "orbit.step=0.0015 d")
    assert "at most 10,000,000 orbit samples" in err
    gigabytes = float(err.split("~")[1].split(" GB")[0])
    assert 36_522_001 * 278e-9 < gigabytes < 36_522_001 * 2780e-9


def test_a_free_body_whose_euler_rates_would_never_end_is_refused(capsys):
    """moments [1, 1, 1e30]: the body-frame rates reach |omega| (C - A)/B = 1e30 |omega|."""
    err = refused(capsys, FREE_BODY, "body.moments=[1, 1, 1e30]")
    assert err.startswith("error: body.moments: got [1, 1, 1e+30]; expected ") and "cycles" in err
