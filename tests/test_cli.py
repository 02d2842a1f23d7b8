"""The command line and the Python API at their edges: one line for every bad input, no hang, no traceback.

`list` never opens a FIFO; wrong Python types to run_scenario; sweep and bench refusing an --out at a
file or holding files they did not write, an unreachable scheduler, a grid too big to build; a scipy
integration failing before its first output."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from spinorbit import run_scenario, sweep
from spinorbit.cli import main
from spinorbit.errors import IntegrationError, ScenarioError
from spinorbit.integrators import simulate
from spinorbit.layout import Layout
from spinorbit.models.ode import Ode

ROOT = Path(__file__).parents[1]
FREE_BODY = ROOT / "scenarios" / "free_body.toml"


def one_line_error(capsys, key):
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith(f"error: {key}: got "), err
    return err


def test_list_never_opens_a_fifo_or_a_device(tmp_path):
    """Through a fresh process with a timeout: opening the FIFO would block for ever."""
    (tmp_path / "good.toml").write_text(FREE_BODY.read_text())
    os.mkfifo(tmp_path / "pipe.toml")
    os.symlink("/dev/zero", tmp_path / "zero.toml")
    (tmp_path / "huge.toml").write_bytes(b"#" * (2 << 20))
    done = subprocess.run([sys.executable, "-m", "spinorbit.cli", "list", str(tmp_path)], capture_output=True,
                          text=True, timeout=60, env={**os.environ, "PYTHONPATH": str(ROOT)}, check=False)
    lines = done.stdout.splitlines()
    assert done.returncode == 0 and not done.stderr and len(lines) == 4, done.stderr
    assert [line.split()[0] for line in lines] == ["good.toml", "huge.toml", "pipe.toml", "zero.toml"]
    assert "free_body" in lines[0] and "not a regular file" in lines[2] and "not a regular file" in lines[3]
    assert "not a scenario" in lines[1]


@pytest.mark.parametrize("args, key", [
    ((None,), "scenario"), ((42,), "scenario"), ((b"free_body.toml",), "scenario"),
    (([FREE_BODY],), "scenario"),
    ((FREE_BODY, "span.end=5 d"), "--set"), ((FREE_BODY, [1]), "--set"), ((FREE_BODY, None), "--set"),
])
def test_run_scenario_with_wrong_python_types_says_so_in_one_line(args, key):
    with pytest.raises(ScenarioError) as info:
        run_scenario(*args)
    message = str(info.value)
    assert message.startswith(f"{key}: got ") and "\n" not in message


def test_run_scenario_refuses_overrides_it_would_ignore():
    from spinorbit.scenarios import load_scenario

    with pytest.raises(ScenarioError, match="overrides: got .*none with a Scenario"):
        run_scenario(load_scenario(FREE_BODY), ["span.end=5 d"])


@pytest.mark.parametrize("command", ["sweep", "bench"])
def test_out_at_a_file_is_refused_in_one_line(tmp_path, capsys, command):
    (tmp_path / "file").write_text("mine\n")
    extra = ["--vary", "integrator.rtol=1e-8", "--scheduler", "synchronous"] if command == "sweep" else []
    out = str(tmp_path / "file")
    assert main([command, str(FREE_BODY), *extra, "--out", out, "--set", "span.end=5 d"]) == 2
    assert "expected a directory (this is a file)" in one_line_error(capsys, "--out")
    assert (tmp_path / "file").read_text() == "mine\n"


@pytest.mark.parametrize("command, name", [("sweep", "sweep.csv"), ("bench", "work_precision.md")])
def test_files_sweep_and_bench_did_not_write_are_not_overwritten(tmp_path, capsys, command, name):
    out = tmp_path / "out"
    out.mkdir()
    (out / name).write_text("the user's table\n")
    extra = ["--vary", "integrator.rtol=1e-8", "--scheduler", "synchronous"] if command == "sweep" else []
    assert main([command, str(FREE_BODY), *extra, "--out", str(out), "--set", "span.end=5 d"]) == 2
    assert f"{name} (file)" in one_line_error(capsys, "--out")
    assert (out / name).read_text() == "the user's table\n"


def test_a_sweep_replaces_its_own_previous_sweep_and_keeps_the_users_files(tmp_path):
    out = tmp_path / "out"
    grid = {"integrator.rtol": ["1e-8"]}
    sweep.run_sweep(FREE_BODY, grid, out, "synchronous", ["span.end=5 d", "output.plots=false"])
    (out / "notes.txt").write_text("mine\n")
    records = sweep.run_sweep(FREE_BODY, grid, out, "synchronous", ["span.end=6 d", "output.plots=false"],
                              force=True)
    assert records[0]["status"] == "ok" and (out / "notes.txt").read_text() == "mine\n"
    assert sorted(p.name for p in out.iterdir()) == [".spinorbit-manifest.json", "000", "notes.txt",
                                                     "sweep.csv", "sweep.json"]


def test_an_unreachable_scheduler_is_said_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(sweep, "CONNECT_TIMEOUT_S", 2)
    code = main(["sweep", str(FREE_BODY), "--vary", "integrator.rtol=1e-8", "--scheduler",
                 "tcp://127.0.0.1:9", "--out", str(tmp_path / "out"), "--set", "span.end=5 d"])
    assert code == 2 and "a Dask scheduler that answers within 2 s" in one_line_error(capsys, "--scheduler")


def test_a_grid_too_big_is_refused_before_it_is_built(tmp_path, capsys):
    values = ",".join(str(i) for i in range(1000))
    code = main(["sweep", str(FREE_BODY), "--vary", f"body.moments.0={values}", "--vary",
                 f"span.step={values}", "--scheduler", "synchronous", "--out", str(tmp_path / "out")])
    assert code == 2 and "at most 10,000 members (this one has 1,000,000)" in one_line_error(capsys, "--vary")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("budget", ["nan", "inf", "-1", "0"])
def test_a_bench_budget_outside_its_range_is_refused(tmp_path, capsys, budget):
    assert main(["bench", str(FREE_BODY), "--budget", budget, "--out", str(tmp_path / "out")]) == 2
    one_line_error(capsys, "--budget")


@njit(cache=True)
def _not_finite(t, y, p):
    return np.full(7, np.nan)


@njit(cache=True)
def _not_finite_after_start(t, y, p):
    return np.zeros(7) if t == 0.0 else np.full(7, np.nan)


@pytest.mark.parametrize("rhs", [_not_finite, _not_finite_after_start])
def test_scipy_failing_before_its_first_output_is_an_integration_error(rhs):
    """Not finite at the start (scipy's first step would be NaN and loop for ever), or just after it (scipy
    stops with no output, and returns its outputs as empty lists)."""
    layout = Layout([("body.q", 4, "quaternion", ""), ("body.omega", 3, "vector", "rad/d")])
    system = Ode(rhs, (np.ones(3),), 0.0, np.array([1.0, 0, 0, 0, 0, 0, 1.0]), layout)
    with pytest.raises(IntegrationError) as info, np.errstate(divide="ignore", invalid="ignore"):
        simulate(system, np.array([0.0, 1.0, 2.0]), "dop853", estimate_error=False)[0]
    assert info.value.partial.t.size == 0 and info.value.partial.y.shape == (0, 7)
    assert "\n" not in str(info.value)


def test_mercury_on_a_span_too_short_for_its_88_day_term_is_not_compared():
    """20 d cannot separate the 88-d term from the fit's constant (half a cycle, 44 d, is needed): no
    amplitude is reported and the verdict is not-compared, with the span it needs."""
    result = run_scenario(ROOT / "scenarios" / "stress" / "mercury_3_2.toml",
                          ['span.end="20 d"', "output.plots=false", "integrator.estimate_error=false"])
    summary = result.summary
    assert summary["verdict"]["result"] == "not-compared"
    assert summary["comparison"]["libration_88d_measured_arcsec"] is None
    reason = summary["not_measured"]["comparison.libration_88d_measured_arcsec"]
    assert "needs a span of 44 d, the run has 20 d" in reason
