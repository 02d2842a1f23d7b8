"""Signals stop a run as the user means them to: Ctrl-C after REBOUND has run (it installs its own SIGINT
handler) still interrupts, and SIGTERM keeps a sweep's or a bench's finished members as Ctrl-C does.
Each case is a fresh process, signalled once it has reached the stage named."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).parents[1]
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
    process = subprocess.Popen([sys.executable, "-m", "spinorbit.cli", "--quiet", "sweep",
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
    process = subprocess.Popen([sys.executable, "-m", "spinorbit.cli", "--quiet", "bench",
                                "scenarios/free_body.toml", "--methods", "rk4,dop853", "--budget", "5",
                                "--out", str(out)], cwd=ROOT, env=ENV, stderr=subprocess.PIPE, text=True)
    wait_for(lambda: (tmp_path / ".bench.lock").exists(), process)      # the command has started
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert not list(tmp_path.glob(".bench.new-*"))


def test_an_interrupted_bench_keeps_the_methods_that_finished(tmp_path, monkeypatch):
    from spinorbit import bench

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
from spinorbit import cli

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
from spinorbit import cli

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
from spinorbit import cli

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
