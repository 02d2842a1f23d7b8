"""A run's checkpoint: the outputs so far, kept so that an interrupted run can continue, bit for bit.

The integrator that can resume (the RK8 driver, spinorbit.integrators.rk8) offers a :class:`Checkpoint` its
outputs between compiled chunks (which end on outputs and depend only on their number, so a resumed run gives
the same states as one never interrupted): they are saved every ``every_s`` seconds of wall time, at the end, and
when the run stops on an exception; a save that fails (a full disk, a name too long) is said in one line and the
run goes on.

A checkpoint is a file of the verified room (spinorbit.base.verified.write): the ``outputs`` beside the run's record
(:func:`run_fingerprint`: the code's version, solutions.code_version, and what decides the states) and a sha256
over all of them, written aside and renamed, so that a save interrupted half-way, even killed, leaves the last
checkpoint whole (the next save removes what a killed one left).  ``resume=True`` continues from the file if it
is one spinorbit wrote for this run: a regular file of this user (not a link), intact (verified.read_file), of
this code's version and this run's record, its outputs float64 of the run's width and finite.  Anything else is
refused in one line naming the file and what is accepted (a ScenarioError on ``--resume``), and left as it is:
the room's caches delete a damaged file and make it again, but a checkpoint is input the user named
(``<out>.checkpoint.npz`` beside ``--out``), so the user decides (a run without ``--resume`` starts afresh).

No lock of its own: only a run that holds its run directory's lock (rundir: ``.<out>.lock``, taken without
waiting, a second run on the same ``--out`` refused in one line) writes ``<out>.checkpoint*.npz``; and two writers
could only rename whole files over each other, each a checkpoint its record describes.

Edge module: the command line makes the Checkpoint (``rundir.RunDirectory.checkpoint``) and removes its files
when the run is committed.
"""
import hashlib
import json
import os
import sys
from pathlib import Path

import numpy as np

from ..base import verified
from ..base.errors import ScenarioError
from ..base.files import open_regular
from ..base.linker import fingerprint, python_function
from ..solutions.store import code_version

WHAT_DIFFERS = {"settings": "scenario settings", "source": "spinorbit source code", "rhs": "equations",
                "start": "initial time or state", "output_times": "output times", "step": "step",
                "parameters": "model parameters"}
class Checkpoint:
    """Where a run keeps its checkpoint (``path``, npz), whether it resumes from it, and the run's
    ``settings`` (anything JSON can write; part of the fingerprint).  A checkpoint is validated as input is
    (the module's docstring) and anything else refused in one line, never resumed nor deleted."""

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
        if stored["code"] != fingerprint["code"]:
            self._refuse(f"a checkpoint of this code, spinorbit {fingerprint['code']} (it was written by spinorbit "
                         f"{stored['code'][:40]})")
        differ = [text for name, text in WHAT_DIFFERS.items() if stored[name] != fingerprint[name]]
        if differ:
            self._refuse(f"a checkpoint of this run (it was written by a run that differs in: "
                         f"{', '.join(differ)})")
        rows, dim = fingerprint.get("outputs", (None, outputs.shape[1]))
        if outputs.shape[1] != dim or (rows is not None and outputs.shape[0] > rows):
            self._refuse(f"outputs of at most {rows} rows of {dim} states (it holds {outputs.shape})")
        self.resumed_outputs = len(outputs)
        return outputs

    def save(self, fingerprint, outputs):
        """Write the outputs so far with ``fingerprint`` as their record (spinorbit.base.verified.write: aside, synced,
        renamed over the checkpoint)."""
        verified.write(self.path, {"outputs": np.ascontiguousarray(outputs, dtype=np.float64)}, fingerprint)
        self.written.add(self.path)

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
        """(record, outputs) of a checkpoint spinorbit wrote, or a one-line refusal."""
        try:
            f = open_regular(self.path, follow_links=False)
        except OSError as exc:
            what = "a symbolic link" if self.path.is_symlink() else exc.strerror
            self._refuse(f"a regular file you can read ({what})")
        with f:
            owner = os.fstat(f.fileno()).st_uid
            if owner != os.geteuid():
                self._refuse(f"a checkpoint of your own (it belongs to uid {owner})")
            try:
                entry = verified.read_file(f)
            except (verified.Damaged, OSError) as exc:
                self._refuse(f"an intact checkpoint spinorbit wrote ({exc})")
        outputs, record = entry.arrays.get("outputs"), entry.record
        if set(entry.arrays) != {"outputs"}:
            self._refuse(f"a checkpoint holding the outputs alone (it holds {sorted(entry.arrays)})")
        if outputs.dtype != np.float64 or outputs.ndim != 2 or not outputs.shape[0]:
            self._refuse(f"outputs of float64 states, one row per output (it holds {outputs.dtype} "
                         f"{outputs.shape})")
        if not np.isfinite(outputs).all():
            self._refuse("finite states (it holds NaN or inf)")
        if not all(isinstance(record.get(name), str) for name in ("code", *WHAT_DIFFERS)):
            self._refuse("a checkpoint whose record names the code's version and every part of the run")
        return record, outputs

    def _refuse(self, accepted):
        raise ScenarioError("--resume", str(self.path), f"{accepted}; run without --resume to start afresh")


def run_fingerprint(rhs, params, t0, y0, t_out, step, checkpoint):
    """{part: sha256 hex} of what decides a run's states (WHAT_DIFFERS names the parts), the code's version
    (``code``) and the outputs' shape."""
    settings = None if checkpoint is None else checkpoint.settings
    return {"code": code_version(),
            "settings": _sha(json.dumps(settings, sort_keys=True, default=str).encode()),
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
