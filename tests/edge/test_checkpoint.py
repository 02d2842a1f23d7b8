"""Checkpointed fixed-step runs: a run interrupted and resumed gives the states, and the run directory,
of one that was not, bit for bit; a checkpoint of another run is refused."""
import dataclasses
import errno
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from spinorbit.base import verified
from spinorbit.base.errors import ScenarioError
from spinorbit.bodies import earth
from spinorbit.edge import checkpoint as checkpoints
from spinorbit.edge.checkpoint import Checkpoint, run_fingerprint
from spinorbit.edge.cli import main
from spinorbit.integrators import rk8, simulate
from spinorbit.models.assemblies.earth_moon import FIGURES, closed
from spinorbit.models.figure import Figure
from spinorbit.models.rotators import Rigid
from spinorbit.models.system import System
from tests.second_user import OTHER, chown_other, needs_root

T_OUT = np.arange(0.0, 31.0)         # 31 outputs, one per chunk (integrators.base.output_chunks)
STEP = 0.5
SCENE = Path(__file__).parents[2] / "scenarios" / "stress" / "coupled_conservation.toml"
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
    assert verified.read(tmp_path / "run.npz").arrays["outputs"].shape == (k, system.y0.size)
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
    with pytest.raises(ScenarioError, match="--resume: .*an intact checkpoint spinorbit wrote"):
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
    """A real checkpoint of the first 3 outputs: (record, outputs) as stored."""
    run(system, Checkpoint(path, every_s=0.0), T_OUT[:3])
    entry = verified.read(path)
    return entry.record, entry.arrays["outputs"]


def rewrite(path, **arrays):
    with open(path, "wb") as f:
        np.savez(f, **arrays)


def rewrite_hashed(path, outputs, record_text):
    """The room's layout with a hash that matches, around a record of any text."""
    held = {"outputs": outputs, "record": np.array(record_text), "meta": np.array("{}"),
            "room_format": np.array(verified.FORMAT)}
    rewrite(path, sha256=np.array(verified.arrays_hash(held)), **held)


def damage(kind, path, record, outputs):
    if kind == "zero bytes":
        path.write_bytes(b"")
    elif kind == "truncated":
        path.write_bytes(path.read_bytes()[:200])
    elif kind == "integers":
        verified.write(path, {"outputs": outputs.astype(np.int64)}, record)
    elif kind == "wrong shape":
        verified.write(path, {"outputs": np.hstack([outputs, outputs])}, record)
    elif kind == "edited states":
        edited = outputs.copy()
        edited[1, 8] += 1.0                      # the Moon's position, 1 km: a valid npz, hash unchanged
        with np.load(path) as data:
            held = {name: data[name] for name in data.files}
        rewrite(path, **{**held, "outputs": edited})
    elif kind == "NaN rows":
        nan = outputs.copy()
        nan[1:] = np.nan
        verified.write(path, {"outputs": nan}, record)
    elif kind == "malformed record":
        rewrite_hashed(path, outputs, "[1, 2")
    elif kind == "record not an object":
        rewrite_hashed(path, outputs, "[1, 2]")
    elif kind == "record missing a part":
        verified.write(path, {"outputs": outputs}, {k: v for k, v in record.items() if k != "rhs"})
    elif kind == "another array":
        verified.write(path, {"outputs": outputs, "extra": outputs}, record)
    elif kind == "written without a hash":
        rewrite(path, outputs=outputs, record=json.dumps(record))
    elif kind == "a link":
        target = path.with_name("elsewhere.npz")
        path.rename(target)
        path.symlink_to(target)


@pytest.mark.parametrize("kind, says", [
    ("zero bytes", "an intact checkpoint"), ("truncated", "an intact checkpoint"),
    ("integers", "float64"), ("wrong shape", "of 20 states (it holds (3, 40))"),
    ("edited states", "do not match their hash"),
    ("NaN rows", "finite states"), ("malformed record", "record is not JSON"),
    ("record not an object", "not a JSON object"), ("record missing a part", "every part of the run"),
    ("another array", "the outputs alone"), ("written without a hash", "not a file spinorbit wrote"),
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
    assert os.path.lexists(path)                 # refused, not remade: the user named it


def test_every_byte_damaged_is_refused_in_one_line_or_resumes_the_outputs_written(system, tmp_path):
    """Each byte of a real checkpoint flipped in turn (zip and npy headers, record, hash, states): a resume refuses
    it in one line naming the file, or (a byte nothing reads, e.g. a zip timestamp) takes the very outputs written.
    Reference: the outputs written, byte for byte."""
    path = tmp_path / "run.npz"
    record, outputs = saved_checkpoint(system, path)
    good = path.read_bytes()
    with open(path, "r+b") as f:                 # each byte flipped in place and put back (no truncation)
        for i in range(len(good)):
            os.pwrite(f.fileno(), bytes([good[i] ^ 0xFF]), i)
            try:
                resumed = Checkpoint(path, resume=True).load(record)
            except ScenarioError as exc:
                message = str(exc)
                assert message.startswith(f"--resume: got '{path}'") and "\n" not in message, (i, message)
            else:
                assert resumed.tobytes() == outputs.tobytes(), i
            os.pwrite(f.fileno(), good[i:i + 1], i)


def test_a_checkpoint_of_other_code_is_refused_in_one_line(system, tmp_path, monkeypatch):
    """Written by another spinorbit (another release, or edited sources): its states came from other code, so it
    is not resumed.  Reference: this code's version (solutions.code_version)."""
    from spinorbit.solutions.store import code_version

    path = tmp_path / "run.npz"
    with monkeypatch.context() as patch:
        patch.setattr(checkpoints, "code_version", lambda: "0.0.9+0123456789abcdef")
        run(system, Checkpoint(path, every_s=0.0), T_OUT[:3])
    with pytest.raises(ScenarioError) as info:
        run(system, Checkpoint(path, resume=True), T_OUT[:3])
    message = str(info.value)
    assert message.startswith(f"--resume: got '{path}'") and "\n" not in message
    assert message.endswith(f"expected a checkpoint of this code, spinorbit {code_version()} (it was written by "
                            "spinorbit 0.0.9+0123456789abcdef); run without --resume to start afresh")


KILLED_SAVE = """
import json, os, signal, sys
import numpy as np
from spinorbit.edge.checkpoint import Checkpoint

def killed(f, **arrays):
    f.write(b"PK\\x03\\x04" + bytes(64))
    f.flush()
    os.kill(os.getpid(), signal.SIGKILL)

np.savez = killed
Checkpoint(sys.argv[1]).save(json.loads(sys.argv[2]), np.zeros((6, 20)))
"""


def test_a_save_interrupted_half_way_leaves_the_last_checkpoint(system, tmp_path, monkeypatch):
    """A save stopped inside its write (Ctrl-C; the process killed) leaves the last checkpoint whole, and it
    resumes; the next save removes what the killed one left.  Reference: the outputs of the last save."""
    path = tmp_path / "run.npz"
    record, outputs = saved_checkpoint(system, path)

    def half(f, **arrays):
        f.write(b"PK\x03\x04" + bytes(64))
        raise KeyboardInterrupt
    with monkeypatch.context() as patch:
        patch.setattr(np, "savez", half)
        with pytest.raises(KeyboardInterrupt):
            Checkpoint(path).save(record, np.vstack([outputs, outputs]))
    assert sorted(os.listdir(tmp_path)) == ["run.npz"]
    killed = subprocess.run([sys.executable, "-c", KILLED_SAVE, str(path), json.dumps(record)], timeout=120,
                            env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])})
    assert killed.returncode == -signal.SIGKILL
    (left,) = set(os.listdir(tmp_path)) - {"run.npz"}
    assert left.startswith(".run.npz.tmp-")              # the killed save's half
    assert Checkpoint(path, resume=True).load(record).tobytes() == outputs.tobytes()
    Checkpoint(path).save(record, np.vstack([outputs, outputs]))
    assert sorted(os.listdir(tmp_path)) == ["run.npz"]


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
    entry = verified.read(path)
    outputs = entry.arrays["outputs"].copy()
    outputs[-1] = np.nan
    verified.write(path, {"outputs": outputs}, entry.record)
    capsys.readouterr()
    assert main(["--quiet", "run", str(SCENE), *SHORT, "--out", str(out), "--resume"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --resume: got ") and "finite states" in err[0]
    assert not out.exists() and path.exists()
