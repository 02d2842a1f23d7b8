"""Checkpointed fixed-step runs: a run interrupted and resumed gives the states, and the run directory,
of one that was not, bit for bit; a checkpoint of another run is refused."""
import json
from pathlib import Path

import numpy as np
import pytest

from spinorbit import coupled
from spinorbit.bodies import earth
from spinorbit.checkpoint import Checkpoint, fixed_step
from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.integrators import rk8

T_OUT = np.arange(0.0, 31.0)         # 31 outputs, one per chunk (integrators.base.output_chunks)
STEP = 0.5
SCENE = Path(__file__).parents[1] / "scenarios" / "stress" / "coupled_conservation.toml"
SHORT = ["--set", "span.end=60 d", "--set", "span.step=1 d", "--set", "integrator.step=0.5 d"]


@pytest.fixture(scope="module")
def system():
    """The closed Earth-Moon system on a circular orbit, the Moon synchronous: (params, y0)."""
    p = coupled.parameters()
    gm, r = float(p[0].sum()), 384400.0
    n = np.sqrt(gm / r**3)
    y0 = coupled.state([r, 0, 0], [0, n * r, 0], [1.0, 0, 0, 0], [0, 0, n],
                       [1.0, 0, 0, 0], [0, 0, earth.ERA_RATE_RAD_D])
    return p, y0


@pytest.fixture(scope="module")
def reference(system):
    """The one-call compiled loop over all outputs."""
    return rk8.fixed_step(coupled.rhs, *system[:1], 0.0, system[1], T_OUT, STEP)


def interrupt_after(monkeypatch, calls, error=RuntimeError):
    """Make rk8.fixed_step raise ``error`` after ``calls`` calls (None: never); returns the outputs of each call."""
    made, chunk = [], rk8.fixed_step

    def counted(*args):
        if len(made) == calls:
            raise error("injected")
        made.append(args[4].size)
        return chunk(*args)

    monkeypatch.setattr(rk8, "fixed_step", counted)
    return made


def test_chunked_run_equals_the_one_call_loop(system, reference, tmp_path):
    p, y0 = system
    states = fixed_step(coupled.rhs, p, 0.0, y0, T_OUT, STEP, Checkpoint(tmp_path / "run.npz"))
    assert np.array_equal(states, reference)


@pytest.mark.parametrize("every_s", [0.0, 3600.0])      # saved after each chunk / only when the run stops
def test_interrupted_run_resumes_bit_identical(system, reference, tmp_path, monkeypatch, every_s):
    p, y0, k = *system, 12
    with monkeypatch.context() as patch:
        interrupt_after(patch, k)
        with pytest.raises(RuntimeError, match="injected"):
            fixed_step(coupled.rhs, p, 0.0, y0, T_OUT, STEP, Checkpoint(tmp_path / "run.npz", every_s=every_s))
    with np.load(tmp_path / "run.npz") as saved:
        assert saved["outputs"].shape == (k, y0.size)
    made = interrupt_after(monkeypatch, None)
    states = fixed_step(coupled.rhs, p, 0.0, y0, T_OUT, STEP, Checkpoint(tmp_path / "run.npz", resume=True))
    assert sum(made) == T_OUT.size - k                   # only the outputs the checkpoint lacked were integrated
    assert np.array_equal(states, reference)


@pytest.mark.parametrize("change, named", [("step", "step"), ("start", "initial time or state"),
                                           ("settings", "scenario settings"), ("params", "model parameters")])
def test_checkpoint_of_another_run_is_refused(system, tmp_path, change, named):
    p, y0 = system
    path = tmp_path / "run.npz"
    fixed_step(coupled.rhs, p, 0.0, y0, T_OUT[:3], STEP, Checkpoint(path, every_s=0.0, settings={"a": 1}))
    step, settings = (0.25 if change == "step" else STEP), ({"a": 2} if change == "settings" else {"a": 1})
    y1 = y0 + (change == "start") * 1e-9
    p1 = coupled.parameters(coupled.FIGURES[1:]) if change == "params" else p
    with pytest.raises(ScenarioError, match=f"--resume: .*differs in: {named}\\)"):
        fixed_step(coupled.rhs, p1, 0.0, y1, T_OUT[:3], step, Checkpoint(path, resume=True, settings=settings))


def test_unreadable_checkpoint_is_refused(system, tmp_path):
    (tmp_path / "run.npz").write_bytes(b"not a checkpoint")
    with pytest.raises(ScenarioError, match="--resume: .*a readable checkpoint"):
        fixed_step(coupled.rhs, *system[:1], 0.0, system[1], T_OUT[:3], STEP, Checkpoint(tmp_path / "run.npz", True))


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
        interrupt_after(patch, 20, KeyboardInterrupt)    # after the scene's warm-up (2 calls) and 18 chunks
        assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out)]) == 130
    assert checkpoint.is_file() and not out.exists()
    assert "continue with --resume" in capsys.readouterr().err
    made = interrupt_after(monkeypatch, None)
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out), "--resume"]) == 0
    assert "resuming from" in capsys.readouterr().err
    assert sum(made) == 2 + 61 - 18                      # warm-up, then the outputs after the checkpoint
    assert not checkpoint.exists()                       # a committed run leaves nothing to resume
    assert (out / "timeseries.ecsv").read_bytes() == (uninterrupted / "timeseries.ecsv").read_bytes()
    assert json.loads((out / "summary.json").read_text())["run"]["resumed_after_outputs"] == 18


def test_resume_with_no_checkpoint_says_so(tmp_path, capsys):
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--set", "span.end=2 d", "--out", str(tmp_path / "r"),
                 "--resume"]) == 0
    assert f"no checkpoint at {tmp_path / 'r.checkpoint.npz'}: starting from the beginning" in capsys.readouterr().err
