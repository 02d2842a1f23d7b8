"""Checkpointed fixed-step runs: a run interrupted and resumed gives the states, and the run directory,
of one that was not, bit for bit; a checkpoint of another run is refused."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from spinorbit.bodies import earth
from spinorbit.checkpoint import Checkpoint
from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.integrators import rk8
from spinorbit.models.assemblies.earth_moon import FIGURES, closed
from spinorbit.models.figure import Figure
from spinorbit.models.rotators import Rigid
from spinorbit.models.system import System
from spinorbit.simulate import simulate

T_OUT = np.arange(0.0, 31.0)         # 31 outputs, one per chunk (integrators.base.output_chunks)
STEP = 0.5
SCENE = Path(__file__).parents[1] / "scenarios" / "stress" / "coupled_conservation.toml"
SHORT = ["--set", "span.end=60 d", "--set", "span.step=1 d", "--set", "integrator.step=0.5 d"]


def circular(figures=tuple(FIGURES), moon_moments_factor=1.0):
    """The closed Earth-Moon system on a circular orbit, the Moon synchronous, the Earth rigid; the Moon's
    moments scaled by ``moon_moments_factor`` (the same equations with other parameters)."""
    system = closed(figures, earth_rotator=Rigid(), moon_core=False)
    if moon_moments_factor != 1.0:
        moon = system.bodies["moon"]
        figure = Figure(moon.figure.moments * moon_moments_factor, moon.figure.field)
        moon = dataclasses.replace(moon, figure=figure)
        system = System(system.name, [moon, system.bodies["earth"]], system.motion, system.interactions)
    gm, r = system.bodies["earth"].gm + system.bodies["moon"].gm, 384400.0
    n = np.sqrt(gm / r**3)
    return system.with_start(0.0, system.layout.pack({
        "moon.r": [r, 0, 0], "moon.v": [0, n * r, 0], "moon.q": [1.0, 0, 0, 0], "moon.omega": [0, 0, n],
        "earth.q": [1.0, 0, 0, 0], "earth.omega": [0, 0, earth.ERA_RATE_RAD_D]}))


@pytest.fixture(scope="module")
def system():
    return circular()


def run(system, checkpoint=None, t_out=T_OUT, step=STEP):
    """The states of simulate()'s rk8 run (no error estimate), offered ``checkpoint``."""
    return simulate(system, t_out, "rk8", {"step": step}, estimate_error=False, checkpoint=checkpoint)[0].y


@pytest.fixture(scope="module")
def reference(system):
    """The one-call compiled loop over all outputs (integrators.rk8.fixed_step), quaternions made unit as a
    Solution's are."""
    states = rk8.fixed_step(system.rhs, system.params, 0.0, system.y0, T_OUT, STEP)
    return system.layout.normalise(states)


def interrupt_after(monkeypatch, calls, error=RuntimeError):
    """Make the RK8 driver raise ``error`` before its compiled chunk number ``calls`` + 1 (None: never);
    returns the number of outputs each chunk made."""
    made, chunk = [], rk8._uninterrupted

    def counted(advance):
        if len(made) == calls:
            raise error("injected")
        before = advance.__self__.done
        chunk(advance)
        made.append(advance.__self__.done - before)

    monkeypatch.setattr(rk8, "_uninterrupted", counted)
    return made


def test_chunked_run_equals_the_one_call_loop(system, reference, tmp_path):
    with pytest.MonkeyPatch.context() as patch:
        made = interrupt_after(patch, None)
        states = run(system, Checkpoint(tmp_path / "run.npz"))
    assert made == [1] * T_OUT.size                      # one chunk per output, each a compiled call
    assert np.array_equal(states, reference)


@pytest.mark.parametrize("every_s", [0.0, 3600.0])      # saved after each chunk / only when the run stops
def test_interrupted_run_resumes_bit_identical(system, reference, tmp_path, monkeypatch, every_s):
    k = 12
    with monkeypatch.context() as patch:
        interrupt_after(patch, k)
        with pytest.raises(RuntimeError, match="injected"):
            run(system, Checkpoint(tmp_path / "run.npz", every_s=every_s))
    with np.load(tmp_path / "run.npz") as saved:
        assert saved["outputs"].shape == (k, system.y0.size)
    made = interrupt_after(monkeypatch, None)
    states = run(system, Checkpoint(tmp_path / "run.npz", resume=True))
    assert sum(made) == T_OUT.size - k                   # only the outputs the checkpoint lacked
    assert np.array_equal(states, reference)


@pytest.mark.parametrize("change, named", [("step", "step"), ("start", "initial time or state"),
                                           ("settings", "scenario settings"), ("params", "model parameters"),
                                           ("figures", "equations, model parameters")])
def test_checkpoint_of_another_run_is_refused(system, tmp_path, change, named):
    path = tmp_path / "run.npz"
    run(system, Checkpoint(path, every_s=0.0, settings={"a": 1}), T_OUT[:3])
    step, settings = (0.25 if change == "step" else STEP), ({"a": 2} if change == "settings" else {"a": 1})
    other = {"params": lambda: circular(moon_moments_factor=1.001),
             "figures": lambda: circular(tuple(FIGURES)[1:]),
             "start": lambda: system.with_start(0.0, system.y0 + 1e-9)}.get(change, lambda: system)()
    with pytest.raises(ScenarioError, match=f"--resume: .*differs in: {named}\\)"):
        run(other, Checkpoint(path, resume=True, settings=settings), T_OUT[:3], step)


def test_unreadable_checkpoint_is_refused(system, tmp_path):
    (tmp_path / "run.npz").write_bytes(b"not a checkpoint")
    with pytest.raises(ScenarioError, match="--resume: .*a readable checkpoint"):
        run(system, Checkpoint(tmp_path / "run.npz", True), T_OUT[:3])


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """An uninterrupted 60-d coupled_conservation run (--resume with no checkpoint: starts afresh)."""
    out = tmp_path_factory.mktemp("cli") / "whole"
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out), "--resume"]) == 0
    return out


def test_resumed_cli_run_writes_the_uninterrupted_run(uninterrupted, tmp_path, monkeypatch, capsys):
    out = tmp_path / "run"
    checkpoint = tmp_path / "run.checkpoint.npz"
    with monkeypatch.context() as patch:
        interrupt_after(patch, 18, KeyboardInterrupt)    # after 18 chunks
        assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out)]) == 130
    assert checkpoint.is_file() and not out.exists()
    assert "continue with --resume" in capsys.readouterr().err
    made = interrupt_after(monkeypatch, None)
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out), "--resume"]) == 0
    assert "resuming from" in capsys.readouterr().err
    assert sum(made) == 61 - 18                          # the outputs after the checkpoint
    assert not checkpoint.exists()                       # a committed run leaves nothing to resume
    assert (out / "timeseries.ecsv").read_bytes() == (uninterrupted / "timeseries.ecsv").read_bytes()
    assert json.loads((out / "summary.json").read_text())["run"]["resumed_after_outputs"] == 18


def test_resume_with_no_checkpoint_says_so(tmp_path, capsys):
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--set", "span.end=2 d", "--out", str(tmp_path / "r"),
                 "--resume"]) == 0
    assert f"no checkpoint at {tmp_path / 'r.checkpoint.npz'}: starting from the beginning" in capsys.readouterr().err
