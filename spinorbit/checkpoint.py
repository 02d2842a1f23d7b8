"""A run's checkpoint: the outputs so far, kept so that an interrupted run can continue, bit for bit.

The integrator that can resume (the RK8 driver, spinorbit.integrators.rk8) offers a :class:`Checkpoint` its
outputs between compiled chunks (which end on outputs and depend only on their number, so a resumed run
gives the same states as one never interrupted): they are written atomically (npz: ``outputs``;
``fingerprint``) every ``every_s`` seconds of wall time, at the end, and when the run stops on an exception;
``resume=True`` continues from the file if its fingerprint matches, and refuses one written by a different
run (settings, spinorbit's source, equations, start, output times, step or parameters) with one line saying
which differ.

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
from .linker import package_fingerprint

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

    def fingerprint(self, rhs, params, t0, y0, t_out, step):
        """What decides a run's states (run_fingerprint), with this checkpoint's settings."""
        return run_fingerprint(rhs, params, t0, y0, t_out, step, self)

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
