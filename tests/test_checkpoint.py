"""Checkpointed fixed-step runs: a run interrupted and resumed gives the states, and the run directory,
of one that was not, bit for bit; a checkpoint of another run is refused."""
import dataclasses
import errno
import json
from pathlib import Path

import numpy as np
import pytest

from spinorbit.bodies import earth
from spinorbit.checkpoint import Checkpoint, _content_hash, run_fingerprint
from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.integrators import rk8, simulate
from spinorbit.models.assemblies.earth_moon import FIGURES, closed
from spinorbit.models.figure import Figure
from spinorbit.models.rotators import Rigid
from spinorbit.models.system import System
from tests.second_user import OTHER, chown_other, needs_root

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
                                           ("figures", "spinorbit source code, equations, model parameters")])
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
    said = f"no checkpoint at {tmp_path / 'r.checkpoint.npz'}: starting from the beginning"
    assert said in capsys.readouterr().err


# --- issue 27: a checkpoint is validated like input, and a failing save never loses a finished run ---

def saved_checkpoint(system, path):
    """A real checkpoint of the first 3 outputs: (fingerprint, outputs) as stored."""
    run(system, Checkpoint(path, every_s=0.0), T_OUT[:3])
    with np.load(path) as data:
        return str(data["fingerprint"]), data["outputs"], str(data["sha256"])


def rewrite(path, **arrays):
    with open(path, "wb") as f:
        np.savez(f, **arrays)


def damage(kind, path, fingerprint, outputs, digest):
    if kind == "zero bytes":
        path.write_bytes(b"")
    elif kind == "truncated":
        path.write_bytes(path.read_bytes()[:200])
    elif kind == "integers":
        ints = outputs.astype(np.int64)
        rewrite(path, outputs=ints, fingerprint=fingerprint, sha256=_content_hash(fingerprint, ints))
    elif kind == "wrong shape":
        wide = np.hstack([outputs, outputs])
        rewrite(path, outputs=wide, fingerprint=fingerprint, sha256=_content_hash(fingerprint, wide))
    elif kind == "edited states":
        edited = outputs.copy()
        edited[1, 8] += 1.0                      # the Moon's position, 1 km: a valid npz, hash unchanged
        rewrite(path, outputs=edited, fingerprint=fingerprint, sha256=digest)
    elif kind == "NaN rows":
        nan = outputs.copy()
        nan[1:] = np.nan
        rewrite(path, outputs=nan, fingerprint=fingerprint, sha256=_content_hash(fingerprint, nan))
    elif kind == "malformed fingerprint":
        rewrite(path, outputs=outputs, fingerprint="[1, 2", sha256=_content_hash("[1, 2", outputs))
    elif kind == "fingerprint missing a part":
        partial = json.dumps({k: v for k, v in json.loads(fingerprint).items() if k != "rhs"})
        rewrite(path, outputs=outputs, fingerprint=partial, sha256=_content_hash(partial, outputs))
    elif kind == "written without a hash":
        rewrite(path, outputs=outputs, fingerprint=fingerprint)
    elif kind == "a link":
        target = path.with_name("elsewhere.npz")
        path.rename(target)
        path.symlink_to(target)


@pytest.mark.parametrize("kind, says", [
    ("zero bytes", "a readable checkpoint"), ("truncated", "a readable checkpoint"),
    ("integers", "float64"), ("wrong shape", "of 20 states (it holds (3, 40))"),
    ("edited states", "does not match its sha256"),
    ("NaN rows", "finite states"), ("malformed fingerprint", "fingerprint"),
    ("fingerprint missing a part", "fingerprint"), ("written without a hash", "a checkpoint spinorbit wrote"),
    ("a link", "a regular file"),
])
def test_a_bad_checkpoint_is_refused_in_one_line_and_never_resumed(system, tmp_path, kind, says):
    path = tmp_path / "run.npz"
    damage(kind, path, *saved_checkpoint(system, path))
    with pytest.raises(ScenarioError) as info:
        run(system, Checkpoint(path, resume=True), T_OUT[:3])
    message = str(info.value)
    assert message.startswith(f"--resume: got '{path}'") and says in message and "\n" not in message, message
    assert message.endswith("run without --resume to start afresh")


@needs_root
def test_a_checkpoint_of_another_user_is_refused(system, tmp_path):
    path = tmp_path / "run.npz"
    saved_checkpoint(system, path)
    chown_other(path)
    with pytest.raises(ScenarioError, match=f"a checkpoint of your own \\(it belongs to uid {OTHER}\\)"):
        run(system, Checkpoint(path, resume=True), T_OUT[:6])


def test_more_outputs_than_the_run_has_are_refused(system, tmp_path):
    path = tmp_path / "run.npz"
    run(system, Checkpoint(path, every_s=0.0), T_OUT[:6])
    fingerprint = run_fingerprint(system.rhs, system.params, 0.0, system.y0, T_OUT[:6], STEP, None)
    fingerprint["outputs"] = [3, system.y0.size]                # the same run asked for 3 outputs
    with pytest.raises(ScenarioError, match="at most 3 rows"):
        Checkpoint(path, resume=True).load(fingerprint)


def test_a_failing_save_at_the_end_keeps_the_finished_run(system, reference, tmp_path, monkeypatch, capsys):
    """Disk full (or a name too long) when the finished run saves its checkpoint: the states are returned."""
    def full(self, fingerprint, outputs):
        raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr(Checkpoint, "save", full)
    states = run(system, Checkpoint(tmp_path / ("x" * 300 + ".npz")))
    assert np.array_equal(states, reference)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "could not save" in err[0] and "No space left on device" in err[0]


def test_discard_removes_only_this_runs_files(system, tmp_path):
    """The checkpoint of run[1] and its parts: removed when the run is whole; run1's is not touched."""
    (tmp_path / "run1.checkpoint.npz").write_bytes(b"run1's")
    (tmp_path / "run1.checkpoint-tides_off.npz").write_bytes(b"run1's part")
    main_checkpoint = Checkpoint(tmp_path / "run[1].checkpoint.npz", every_s=0.0)
    for checkpoint in (main_checkpoint, main_checkpoint.part("tides_off")):
        run(system, checkpoint, T_OUT[:3])
    main_checkpoint.discard()
    left = sorted(q.name for q in tmp_path.iterdir())
    assert left == ["run1.checkpoint-tides_off.npz", "run1.checkpoint.npz"]


def test_an_edited_checkpoint_through_the_command_line(tmp_path, capsys, monkeypatch):
    """Interrupted, then hand-edited (NaN rows, its hash recomputed or not): --resume refuses, exit 2."""
    out = tmp_path / "run"
    with monkeypatch.context() as patch:
        interrupt_after(patch, 6, KeyboardInterrupt)
        assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out)]) == 130
    path = tmp_path / "run.checkpoint.npz"
    with np.load(path) as data:
        fingerprint, outputs = str(data["fingerprint"]), data["outputs"].copy()
    outputs[-1] = np.nan
    rewrite(path, outputs=outputs, fingerprint=fingerprint, sha256=_content_hash(fingerprint, outputs))
    capsys.readouterr()
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out), "--resume"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --resume: got ") and "finite states" in err[0]
    assert not out.exists() and path.exists()
