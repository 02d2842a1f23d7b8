"""The command line and the Python API at their edges: one line for every bad input, no hang, no traceback.

`list` never opens a FIFO; wrong Python types to run_scenario; sweep and bench refusing an --out at a
file or holding files they did not write, an unreachable scheduler, a grid too big to build; a scipy
integration failing before its first output."""
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from spinorbit import run_scenario
from spinorbit.base.errors import IntegrationError, ScenarioError
from spinorbit.base.layout import Layout
from spinorbit.edge import sweep
from spinorbit.edge.cli import main
from spinorbit.edge.scenarios import load_scenario
from spinorbit.integrators import simulate
from spinorbit.models.ode import Ode

ROOT = Path(__file__).parents[2]
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
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "list", str(tmp_path)], capture_output=True,
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


# Signals stop a run as the user means them to: Ctrl-C after REBOUND has run (it installs its own SIGINT
# handler) still interrupts, and SIGTERM keeps a sweep's or a bench's finished members as Ctrl-C does.
# Each case is a fresh process, signalled once it has reached the stage named.


ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def answer_ctrl_c():
    """In the child: SIGINT at its default, as in a terminal (a suite run in the background ignores it, and
    Python then never installs its handler)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def wait_for(condition, process, timeout=240.0):
    start = time.monotonic()
    while not condition():
        assert process.poll() is None, process.communicate()
        assert time.monotonic() - start < timeout, "the process never reached the stage"
        time.sleep(0.05)


AFTER_REBOUND = """
import sys, time
from spinorbit.orbits import nbody, solution
{call}
try:
    print("ready", flush=True)
    time.sleep(60)
except KeyboardInterrupt:
    sys.exit(130)
sys.exit(0)
"""


def interrupted_after(call):
    """Exit code of a process sent SIGINT once ``call`` (a REBOUND run) has returned: 130 when Python's
    handler raised KeyboardInterrupt, a timeout when the signal went to REBOUND's."""
    process = subprocess.Popen([sys.executable, "-c", AFTER_REBOUND.format(call=call)], stdout=subprocess.PIPE,
                               text=True, env=ENV, preexec_fn=answer_ctrl_c)
    assert process.stdout.readline().strip() == "ready"
    process.send_signal(signal.SIGINT)
    try:
        return process.wait(timeout=20)
    finally:
        process.kill()


def test_ctrl_c_interrupts_after_an_nbody_orbit():
    assert interrupted_after("nbody.ReboundOrbits('earth', ('moon',), 0.0, 2.0, step=1.0, epoch=-20.0)") == 130


def test_ctrl_c_interrupts_after_an_orbital_solution(tmp_path):
    call = f"solution.solve(solution.Settings(output_d=3650.0), -3650.0, 0.0, path={str(tmp_path / 'a.npz')!r})"
    assert interrupted_after(call) == 130


def staged_member(out):
    """A finished member in the sweep's or bench's hidden staging directory beside ``out``."""
    return any((p / "000" / "summary.json").exists() or list(p.glob("*.csv"))
               for p in out.parent.glob(f".{out.name}.new-*"))


def test_sigterm_keeps_a_sweeps_finished_members(tmp_path):
    out = tmp_path / "sweep"
    process = subprocess.Popen([sys.executable, "-m", "spinorbit.edge.cli", "--quiet", "sweep",
                                "scenarios/free_body.toml", "--vary",
                                "integrator.rtol=1e-8,1e-9,1e-10,1e-11,1e-12,1e-13",
                                "--set", "span.end=100 d", "--set", "output.plots=false", "--scheduler",
                                "synchronous", "--out", str(out)], cwd=ROOT, env=ENV, stderr=subprocess.PIPE,
                               text=True)
    wait_for(lambda: staged_member(out), process)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    kept = out if (out / "000").exists() else Path(f"{out}.failed")
    assert (kept / "000" / "summary.json").exists(), err
    assert not list(tmp_path.glob(".sweep.new-*"))


def test_sigterm_stops_a_bench_as_ctrl_c_does(tmp_path):
    out = tmp_path / "bench"
    process = subprocess.Popen([sys.executable, "-m", "spinorbit.edge.cli", "--quiet", "bench",
                                "scenarios/free_body.toml", "--methods", "rk4,dop853", "--budget", "5",
                                "--out", str(out)], cwd=ROOT, env=ENV, stderr=subprocess.PIPE, text=True)
    wait_for(lambda: (tmp_path / ".bench.lock").exists(), process)      # the command has started
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert not list(tmp_path.glob(".bench.new-*"))


def test_an_interrupted_bench_keeps_the_methods_that_finished(tmp_path, monkeypatch):
    from spinorbit.edge import bench

    run_method, calls = bench.run_method, []

    def second_interrupted(name, *args, **kwargs):
        calls.append(name)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return run_method(name, *args, **kwargs)

    monkeypatch.setattr(bench, "run_method", second_interrupted)
    try:
        bench.bench_scenario(ROOT / "scenarios/free_body.toml", ["rk4", "dop853"], tmp_path / "bench", 0.5,
                             ["span.end=50 d"])
    except KeyboardInterrupt:
        pass
    else:
        raise AssertionError("the bench was not interrupted")
    kept = tmp_path / "bench"
    table = (kept / "work_precision.csv").read_text().splitlines()
    assert table[0].startswith("method") and len(table) > 1
    assert {line.split(",")[0] for line in table[1:]} == {"rk4"}


REPEATED_STOP = """
import os, signal, sys, threading, time
from spinorbit.edge import cli

def stops():
    time.sleep({delay})
    for _ in range(100):                    # a stop, again and again while the command exits
        os.kill(os.getpid(), signal.{name})
        time.sleep(0.002)

def slow_run(args):
    threading.Thread(target=stops, daemon=True).start()
    time.sleep({run_s})
    return 0

cli._run = slow_run
cli.gc.freeze = lambda: time.sleep(0.3)      # the command's way out, long enough for the stops to reach it
sys.argv = ["spinorbit", "run", "free_body"]
sys.exit(cli.console())
"""


def test_a_stop_delivered_again_while_the_command_exits_still_ends_as_130():
    for name in ("SIGINT", "SIGTERM"):
        done = subprocess.run([sys.executable, "-c", REPEATED_STOP.format(name=name, delay=0.5, run_s=30)],
                              capture_output=True, text=True, env=ENV, timeout=60, preexec_fn=answer_ctrl_c)
        assert done.returncode == 130 and done.stderr == "interrupted\n", (name, done.returncode, done.stderr)


def test_a_stop_after_the_work_is_done_leaves_the_commands_exit_code():
    """The run finished and was written: a Ctrl-C or SIGTERM while the process exits changes nothing."""
    for name in ("SIGINT", "SIGTERM"):
        done = subprocess.run([sys.executable, "-c", REPEATED_STOP.format(name=name, delay=0.15, run_s=0.0)],
                              capture_output=True, text=True, env=ENV, timeout=60, preexec_fn=answer_ctrl_c)
        assert done.returncode == 0 and done.stderr == "", (name, done.returncode, done.stderr)


SWALLOWED_STOP = """
import ctypes, os, signal, sys, time
from spinorbit.edge import cli

def inside_a_callback():                      # as llvmlite's object-cache callback while numba compiles
    os.kill(os.getpid(), signal.{name})
    for _ in range(100000):
        pass                                  # the handler's KeyboardInterrupt is raised here, and dropped

callback = ctypes.CFUNCTYPE(None)(inside_a_callback)

def run(args):
    callback()
    time.sleep(20)
    return 0

cli._run = run
sys.argv = ["spinorbit", "run", "free_body"]
sys.exit(cli.console())
"""


def test_a_stop_dropped_inside_a_ctypes_callback_is_heard_again():
    for name in ("SIGINT", "SIGTERM"):
        done = subprocess.run([sys.executable, "-c", SWALLOWED_STOP.format(name=name)], capture_output=True,
                              text=True, env=ENV, timeout=60, preexec_fn=answer_ctrl_c)
        assert done.returncode == 130 and done.stderr.splitlines()[-1] == "interrupted", (name, done.stderr)


STOP_DURING_CLEANUP = """
import os, signal, sys, time
from pathlib import Path
from spinorbit.edge import cli

def run(args):
    try:
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(20)
    except BaseException:
        for _ in range(30):                      # a 1.5-s save of what the run has, as a checkpoint is saved
            time.sleep(0.05)
        Path(os.environ["SAVED"]).write_text("saved")
        raise
    return 0

cli._run = run
sys.argv = ["spinorbit", "run", "free_body"]
sys.exit(cli.console())
"""


def test_the_stops_sent_again_never_interrupt_the_saving_of_a_stopped_run(tmp_path):
    saved = tmp_path / "saved"
    done = subprocess.run([sys.executable, "-c", STOP_DURING_CLEANUP], capture_output=True, text=True,
                          env={**ENV, "SAVED": str(saved)}, timeout=60, preexec_fn=answer_ctrl_c)
    assert done.returncode == 130 and done.stderr == "interrupted\n", done.stderr
    assert saved.read_text() == "saved"


# What a user types at the command line works or is answered in words that say what is accepted: a value with a
# space left unquoted, and `list` printing every word at any terminal width (a method switched with --set over a
# file written for another: tests/edge/test_method_switch.py; dates and durations: tests/scene/test_schema.py; `show`:
# tests/edge/test_key_table.py).


def test_a_value_with_a_space_left_unquoted_gets_a_hint_to_quote_it(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["run", "free_body", "--set", "span.step=2", "km"])
    assert stop.value.code == 2
    assert 'unrecognized arguments: km (a value with spaces needs quotes: --set "span.step=2 km")' in \
        capsys.readouterr().err


def words(text):
    return " ".join(text.split())


def test_list_prints_every_title_whole_at_any_width(monkeypatch, capsys):
    import tomllib

    from spinorbit.edge import catalogue

    titles = [tomllib.loads(path.read_text())["scene"]["title"] for path in catalogue.folder().rglob("*.toml")]
    for columns in ("60", "200"):
        monkeypatch.setenv("COLUMNS", columns)
        assert main(["list"]) == 0
        out = capsys.readouterr().out
        assert all(words(title) in words(out) for title in titles)


# A failing integration writes its partial output through the command line.


def test_failed_run_writes_partial_output(tmp_path, capsys):
    """rk8 stopped by max_steps: exit 3, summary.json with status 'failed', the outputs computed so far kept."""
    text = FREE_BODY.read_text()
    text = re.sub(r'method = "dop853"\nrtol = .*\natol = .*\n', 'method = "rk8"\nstep = "0.1 d"\nmax_steps = 100\n',
                  text)
    scenario = tmp_path / "stopped.toml"
    scenario.write_text(text)
    out = tmp_path / "run"
    assert main(["run", str(scenario), "--out", str(out)]) == 3
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed" and "max_steps" in summary["error"]
    assert summary["run"]["failed_at_tdb_d"] == pytest.approx(100 * 0.1)      # max_steps steps of 0.1 d
    assert summary["run"]["outputs_written"] == 21                   # t = 0, 0.5, ..., 10 d
    rows = [line for line in (out / "timeseries.ecsv").read_text().splitlines() if not line.startswith("#")]
    assert len(rows) == 1 + 21
    assert "partial output written" in capsys.readouterr().err
