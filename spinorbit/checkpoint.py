"""Long fixed-step runs in chunks that can be checkpointed and resumed, bit for bit.

:func:`fixed_step` is ``integrators.rk8.fixed_step`` run over consecutive pieces of the output
times (``integrators.base.output_chunks``: they depend only on the number of outputs), with a
progress bar.  Each piece starts from the last output exactly as the one-call loop does (it lands
on every output), so the chunked run, and a run resumed at any piece, give the same states bit for
bit.  With a :class:`Checkpoint`, the outputs so far are written atomically (npz: ``outputs``, the
state at the last of them; ``fingerprint``) every ``every_s`` seconds of wall time and when the run
stops on an exception; ``resume=True`` continues from the file if its fingerprint matches, and
refuses one written by a different run (settings, spinorbit's source, equations, start, output
times, step or parameters) with one line saying which differ.

Edge module: the command line makes the Checkpoint (``<out>.checkpoint.npz``, beside the run
directory, removed when the run is committed; ``rundir.RunDirectory.checkpoint``).
"""
import hashlib
import json
import os
import sys
import time
import zipfile
from pathlib import Path

import numpy as np

from .errors import ScenarioError
from .integrators import rk8
from .integrators.base import output_chunks
from .linker import package_fingerprint
from .progress import progress

WHAT_DIFFERS = {"settings": "scenario settings", "source": "spinorbit source code", "rhs": "equations",
                "start": "initial time or state", "output_times": "output times", "step": "step",
                "parameters": "model parameters"}


class Checkpoint:
    """Where a run keeps its checkpoint (``path``, npz), whether it resumes from it, and the run's
    ``settings`` (anything JSON can write; part of the fingerprint)."""

    def __init__(self, path, resume=False, settings=None, every_s=30.0):
        self.path, self.resume, self.settings, self.every_s = Path(path), resume, settings, every_s
        self.resumed_outputs = 0             # outputs a resumed run took from the file

    def part(self, name):
        """The checkpoint of a scene's further run ``name``: ``<out>.checkpoint-<name>.npz``, removed with this one."""
        return Checkpoint(self.path.with_name(f"{self.path.stem}-{name}{self.path.suffix}"), self.resume,
                          self.settings, self.every_s)

    def fingerprint(self, rhs, params, t0, y0, t_out, step):
        """{part: sha256 hex} of the run offered this checkpoint (:func:`run_fingerprint` with its settings)."""
        return run_fingerprint(rhs, params, t0, y0, t_out, step, self)

    def load(self, fingerprint):
        """The outputs (k, dim) a matching checkpoint holds, or None when resume is off or there is none."""
        if not self.resume or not self.path.exists():
            return None
        try:
            with np.load(self.path) as data:
                stored, outputs = json.loads(str(data["fingerprint"])), data["outputs"]
        except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
            raise ScenarioError("--resume", str(self.path), f"a readable checkpoint ({exc}); run without --resume "
                                "to start afresh") from None
        differ = [text for name, text in WHAT_DIFFERS.items() if stored.get(name) != fingerprint[name]]
        if differ:
            raise ScenarioError("--resume", str(self.path), "a checkpoint of this run (it was written by a run that "
                                f"differs in: {', '.join(differ)}); run without --resume to start afresh")
        self.resumed_outputs = len(outputs)
        return outputs

    def save(self, fingerprint, outputs):
        """Write the outputs so far atomically (aside, then renamed over the checkpoint)."""
        tmp = self.path.with_name(f".{self.path.name}.tmp-{os.getpid()}")
        try:
            with open(tmp, "wb") as f:
                np.savez(f, outputs=outputs, fingerprint=json.dumps(fingerprint, sort_keys=True))
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, self.path)
        finally:
            tmp.unlink(missing_ok=True)


def fixed_step(rhs, params, t0, y0, t_out, step, checkpoint=None, label=None):
    """States (len(t_out), dim) of y' = rhs(t, y, params) from (t0, y0) by the compiled RK8 with steps
    <= ``step`` (days), identical to ``rk8.fixed_step``; progress under ``label``, checkpointed and
    resumed with ``checkpoint`` (a Checkpoint or None)."""
    t_out, y0 = np.asarray(t_out, dtype=float), np.asarray(y0, dtype=float)
    states = np.empty((t_out.size, y0.size))
    fingerprint = run_fingerprint(rhs, params, t0, y0, t_out, step, checkpoint)
    done = 0
    if checkpoint is not None and (stored := checkpoint.load(fingerprint)) is not None:
        done = len(stored)
        states[:done] = stored
        print(f"resuming from {checkpoint.path} at output {done} of {t_out.size}", file=sys.stderr)
    saved, last_save = done, time.monotonic()
    with progress(label, float(t_out[done - 1] if done else t0), float(t_out[-1])) as advance_to:   # what is left
        try:
            for part in output_chunks(t_out.size):
                if part.stop <= done:
                    continue
                t, y = (t0, y0) if done == 0 else (t_out[done - 1], states[done - 1])
                states[done:part.stop] = _chunk(rhs, params, t, y, t_out[done:part.stop], step)
                done = part.stop
                advance_to(t_out[done - 1])
                if checkpoint is not None and time.monotonic() - last_save >= checkpoint.every_s:
                    checkpoint.save(fingerprint, states[:done])
                    saved, last_save = done, time.monotonic()
            if checkpoint is not None and done > saved:          # whole: a scene's next run may be interrupted
                checkpoint.save(fingerprint, states[:done])
                saved = done
        except BaseException:
            if checkpoint is not None and done > 0:
                if done > saved:
                    checkpoint.save(fingerprint, states[:done])
                print(f"checkpoint: {done} of {t_out.size} outputs in {checkpoint.path} (continue with --resume)",
                      file=sys.stderr)
            raise
    return states


def _chunk(rhs, params, t0, y0, t_out, step):
    """rk8.fixed_step; an interrupt (Ctrl-C, SIGTERM) that numba wrapped in a SystemError is an interrupt again."""
    try:
        return rk8.fixed_step(rhs, params, t0, y0, t_out, step)
    except SystemError as exc:           # the handler ran in a Python callback of the compiled call
        if isinstance(exc.__cause__, KeyboardInterrupt):
            raise KeyboardInterrupt from None
        raise


def run_fingerprint(rhs, params, t0, y0, t_out, step, checkpoint):
    """{part: sha256 hex} of what decides a run's states (WHAT_DIFFERS names the parts)."""
    settings = None if checkpoint is None else checkpoint.settings
    return {"settings": _sha(json.dumps(settings, sort_keys=True, default=str).encode()),
            "source": package_fingerprint(),
            "rhs": _sha(f"{rhs.py_func.__module__}.{rhs.py_func.__qualname__}".encode()),
            "start": _sha(np.float64(t0).tobytes(), y0.tobytes()),
            "output_times": _sha(t_out.tobytes()),
            "step": _sha(np.float64(step).tobytes()),
            "parameters": _sha(*_leaves(params))}


def _leaves(value):
    """Bytes of every number and array in nested tuples/lists, with the nesting and shapes."""
    if isinstance(value, (tuple, list)):
        yield f"({len(value)}".encode()
        for item in value:
            yield from _leaves(item)
        return
    array = np.asarray(value)
    yield f"{array.dtype.str}{array.shape}".encode()
    yield array.tobytes()


def _sha(*parts):
    digest = hashlib.sha256()
    for part in parts:
        digest.update(part)
    return digest.hexdigest()
