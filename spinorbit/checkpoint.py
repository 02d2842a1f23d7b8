"""A run's checkpoint: the outputs so far, kept so that an interrupted run can continue, bit for bit.

The integrator that can resume (the RK8 driver, spinorbit.integrators.rk8) offers a :class:`Checkpoint` its
outputs between compiled chunks (which end on outputs and depend only on their number, so a resumed run gives
the same states as one never interrupted): they are written atomically (npz: ``outputs``, ``fingerprint``,
``sha256`` of both) every ``every_s`` seconds of wall time, at the end, and when the run stops on an
exception; a save that fails (a full disk, a name too long) is said in one line and the run goes on.
``resume=True`` continues from the file if it is one spinorbit wrote for this run (validated like an input:
owner, layout, hash, shape, finite values) and refuses anything else, or one written by a different run
(settings, spinorbit's source, equations, start, output times, step or parameters), in one line.

Edge module: the command line makes the Checkpoint (``<out>.checkpoint.npz``, beside the run
directory, removed when the run is committed; ``rundir.RunDirectory.checkpoint``).
"""
import hashlib
import json
import os
import stat
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from .errors import ScenarioError
from .files import open_regular
from .linker import fingerprint, python_function

WHAT_DIFFERS = {"settings": "scenario settings", "source": "spinorbit source code", "rhs": "equations",
                "start": "initial time or state", "output_times": "output times", "step": "step",
                "parameters": "model parameters"}


class Checkpoint:
    """Where a run keeps its checkpoint (``path``, npz), whether it resumes from it, and the run's
    ``settings`` (anything JSON can write; part of the fingerprint).

    A checkpoint is validated as input is: a regular file of this user, an npz spinorbit wrote
    (``outputs``, ``fingerprint``, and ``sha256`` of the two), the fingerprint of this run, outputs of
    float64 in the run's shape and finite.  Anything else is refused in one line, never resumed.
    """

    def __init__(self, path, resume=False, settings=None, every_s=30.0):
        self.path, self.resume, self.settings, self.every_s = Path(path), resume, settings, every_s
        self.resumed_outputs = 0             # outputs a resumed run took from the file
        self.written = {self.path}           # files it and its parts may leave: discard() removes them

    def part(self, name):
        """The checkpoint of a scene's further run ``name``: ``<out>.checkpoint-<name>.npz``, discarded with
        this one."""
        part = Checkpoint(self.path.with_name(f"{self.path.stem}-{name}{self.path.suffix}"), self.resume,
                          self.settings, self.every_s)
        part.written = self.written
        self.written.add(part.path)
        return part

    def load(self, fingerprint):
        """The outputs (k, dim) a matching checkpoint holds, or None when resume is off or there is none."""
        if not self.resume or not os.path.lexists(self.path):
            return None
        stored, outputs = self._read()
        differ = [text for name, text in WHAT_DIFFERS.items() if stored.get(name) != fingerprint[name]]
        if differ:
            self._refuse(f"a checkpoint of this run (it was written by a run that differs in: "
                         f"{', '.join(differ)})")
        rows, dim = fingerprint.get("outputs", (None, outputs.shape[1]))
        if outputs.shape[1] != dim or (rows is not None and outputs.shape[0] > rows):
            self._refuse(f"outputs of at most {rows} rows of {dim} states (it holds {outputs.shape})")
        self.resumed_outputs = len(outputs)
        return outputs

    def save(self, fingerprint, outputs):
        """Write the outputs so far atomically (aside, synced, then renamed over the checkpoint)."""
        outputs = np.ascontiguousarray(outputs, dtype=np.float64)
        text = json.dumps(fingerprint, sort_keys=True)
        handle, tmp = tempfile.mkstemp(prefix=f".{self.path.name}.tmp-", dir=self.path.parent)   # a new file
        try:
            with os.fdopen(handle, "wb") as f:
                np.savez(f, outputs=outputs, fingerprint=text, sha256=_content_hash(text, outputs))
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, self.path)
            self.written.add(self.path)
        finally:
            if os.path.lexists(tmp):
                os.unlink(tmp)

    def fingerprint(self, rhs, params, t0, y0, t_out, step):
        """What decides a run's states (run_fingerprint), with this checkpoint's settings."""
        return run_fingerprint(rhs, params, t0, y0, t_out, step, self)

    def keep(self, fingerprint, outputs):
        """:meth:`save`; a failure is said in one line and the run goes on.  True when saved."""
        try:
            self.save(fingerprint, outputs)
            return True
        except OSError as exc:
            print(f"checkpoint: could not save {self.path} ({exc.strerror or exc}); the run goes on without it",
                  file=sys.stderr)
            return False

    def discard(self):
        """Remove the checkpoint files of this run (its own and its parts'): the run is whole."""
        for path in self.written:
            if os.path.isfile(path) and not os.path.islink(path):
                path.unlink()

    def _read(self):
        """(fingerprint dict, outputs) of a checkpoint spinorbit wrote, or a one-line refusal."""
        info = os.lstat(self.path)
        if not stat.S_ISREG(info.st_mode):
            self._refuse("a regular file (this is not one)")
        if info.st_uid != os.geteuid():
            self._refuse(f"a checkpoint of your own (it belongs to uid {info.st_uid})")
        keys = ["fingerprint", "outputs", "sha256"]
        try:
            with open_regular(self.path) as f, np.load(f, allow_pickle=False) as data:
                files = sorted(data.files)
                content = [data[key] for key in keys] if files == keys else None
        except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
            reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            self._refuse(f"a readable checkpoint ({reason})")
        if content is None:
            self._refuse(f"a checkpoint spinorbit wrote (it holds {files})")
        text, outputs, digest = str(content[0]), content[1], str(content[2])
        if outputs.dtype != np.float64 or outputs.ndim != 2 or not outputs.shape[0]:
            self._refuse(f"outputs of float64 states, one row per output (it holds {outputs.dtype} "
                         f"{outputs.shape})")
        if digest != _content_hash(text, outputs):
            self._refuse("a checkpoint as spinorbit wrote it (its content does not match its sha256: edited "
                         "or damaged)")
        if not np.isfinite(outputs).all():
            self._refuse("finite states (it holds NaN or inf)")
        try:
            stored = json.loads(text)
        except ValueError:
            stored = None
        if not (isinstance(stored, dict) and all(isinstance(stored.get(name), str) for name in WHAT_DIFFERS)):
            self._refuse("a checkpoint whose fingerprint names every part of the run")
        return stored, outputs

    def _refuse(self, accepted):
        raise ScenarioError("--resume", str(self.path), f"{accepted}; run without --resume to start afresh")


def _content_hash(fingerprint_text, outputs):
    """sha256 of a checkpoint's content: its fingerprint and its outputs (shape and bytes)."""
    return _sha(fingerprint_text.encode(), str(outputs.shape).encode(),
                np.ascontiguousarray(outputs).tobytes())


def run_fingerprint(rhs, params, t0, y0, t_out, step, checkpoint):
    """{part: sha256 hex} of what decides a run's states (WHAT_DIFFERS names the parts)."""
    settings = None if checkpoint is None else checkpoint.settings
    return {"settings": _sha(json.dumps(settings, sort_keys=True, default=str).encode()),
            "source": fingerprint(rhs),
            "rhs": _sha(f"{python_function(rhs).__module__}.{python_function(rhs).__qualname__}".encode()),
            "start": _sha(np.float64(t0).tobytes(), y0.tobytes()),
            "output_times": _sha(t_out.tobytes()),
            "step": _sha(np.float64(step).tobytes()),
            "parameters": _sha(*_leaves(params)),
            "outputs": [int(t_out.size), int(y0.size)]}


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
