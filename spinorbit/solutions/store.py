"""The solution store: every solution computed, kept in spinorbit's private cache and extended on demand.

Where: ``<spinorbit's private cache>/solutions`` (spinorbit.base.verified: 0700, refused in one line when another
user owns it or can write it).  A solution is keyed by what decides its numbers: the scene, every key of the
scenario but its comparisons, outputs and span (kept for a scene whose start is fitted over its span: the
Earth's), the integrator's options, the ephemeris *file* the orbit source names (its sha256 and size: another
file under the same name, or a file replaced at its path, is another solution), and the code's version
(solutions.code_version: spinorbit's version and a sha256 of the package's source: a changed integration never
reuses an old file).  Each file is a verified npz (spinorbit.base.verified: every array hashed, written aside and
renamed) holding the series, the layout, the provenance, the states where the integration stopped and the record
it was keyed by; one that is not intact (truncated, tampered with, another model's) is refused in one line,
deleted and computed again.  A read that fails for a reason that is not the file's (EIO, EMFILE) is said and the
answer computed without the store; a write that fails (a full disk) is warned of, the answer kept.

A lock beside each file makes one process at a time extend it, the others waiting and then reading what it wrote;
a finished run offers its solution without waiting (``offer``: at most OFFER_WAIT_S).  The store keeps within
``LIMIT["bytes"]`` (default 2 GB): after each write the least recently written files go first (`spinorbit
cache` states the bound).  Lock files stay (`spinorbit cache clear` too): one removed while another process waits on
it would let a third write at once.

A query outside the stored span extends the solution from its nearer end (forward from its end, backward
from its start), the same System started at the state where the last run stopped.
"""
import contextlib
import hashlib
import json
import os
import time
import warnings

import numpy as np

from ..base import private, verified
from ..base.layout import Layout
from ..orbits.sources import OrbitSource
from .chebyshev import Segments
from .code_version import package_version
from .solution import Solution

LAYER_KEYS = ("span.", "model.start", "scene.", "compare.", "comparison.", "report.", "output.", "limits.",
              "earth.nonrigid", "earth.transfer_function", "integrator.estimate_error")

PLACE = {"directory": None}          # another directory (tests); None: the private cache's
LIMIT = {"bytes": 2_000_000_000}     # the store's size bound: least recently written files removed beyond it
OFFER_WAIT_S = 2.0                   # how long a finished run waits for the store's lock before it says it was not
# stored


def directory():
    """``<private cache>/solutions`` (created 0700; refused in one line when not private)."""
    if PLACE["directory"] is not None:
        return verified.private(PLACE["directory"])
    return verified.folder("solutions")


def code_version():
    """spinorbit's version and the sha256 of its sources (solutions.code_version, recorded in the store)."""
    return package_version(directory())


def record(scenario):
    """What decides a solution's numbers: the scene kind, its model keys, the ephemeris file's identity, the code's
    version (and the span, for a scene whose start depends on it: the Earth's is fitted over its span's
    outputs)."""
    from ..scene.params import values_of

    anchored = scenario.scene.stored is not None and scenario.scene.stored.anchor is not None
    ignored = LAYER_KEYS if anchored else tuple(k for k in LAYER_KEYS if k not in ("span.", "model.start"))
    values = values_of(scenario.params)
    keys = {k: recorded(v) for k, v in sorted(values.items()) if not k.startswith(ignored)}
    keys["integrator"] = scenario.params.integrator.options()
    source = values.get("orbit.source")
    return {"scene": scenario.kind, "keys": json.loads(json.dumps(keys, default=str)), "code": code_version(),
            "ephemeris_file": source.file_identity() if isinstance(source, OrbitSource) else None}


def recorded(value):
    """A key's value as the record holds it (JSON): an orbit source by its name, an array as a list."""
    if isinstance(value, OrbitSource):
        return value.name
    return value.tolist() if hasattr(value, "tolist") else value



def path_of(rec):
    key = hashlib.sha256(json.dumps(rec, sort_keys=True).encode()).hexdigest()[:20]
    return directory() / f"{rec['scene']}-{key}.npz"


def _arrays(solution):
    s = solution.segments
    layout = [[p.name, p.stop - p.start, p.kind, p.unit] for p in solution.layout.slices]
    grid = np.array([s.origin_d, s.length_d, s.first, len(s.coefficients)], dtype=float)
    return {"coefficients": s.coefficients, "grid": grid, "layout": np.array(json.dumps(layout)),
            **{f"end_{name}_{part}": np.asarray(value, dtype=float) for name, (t, y) in solution.ends.items()
               for part, value in (("t", t), ("state", y))}}


def save(solution, rec, path):
    """Write atomically (spinorbit.base.verified.write), then keep the store within LIMIT."""
    verified.write(path, _arrays(solution), rec, solution.provenance)
    verified.prune(path.parent, "*.npz", LIMIT["bytes"], keep=[path])


Refused = verified.Damaged


def load(path, rec):
    """The Solution in ``path``; Refused (saying why) unless it is intact and made with ``rec``; None when there is
    no file; an OSError that is not the file's raised."""
    entry = verified.read(path, rec)
    if entry is None:
        return None
    try:
        arrays = entry.arrays
        origin, length, first, count = arrays["grid"]
        if count != len(arrays["coefficients"]):
            raise Refused("its grid does not match its series")
        segments = Segments(float(origin), float(length), int(first), arrays["coefficients"])
        layout = Layout([tuple(p) for p in json.loads(str(arrays["layout"]))])
        ends = {name: (float(arrays[f"end_{name}_t"]), arrays[f"end_{name}_state"]) for name in ("start", "end")}
    except (KeyError, ValueError, TypeError) as exc:
        raise Refused(f"not a stored solution ({type(exc).__name__}: {exc})") from None
    return Solution(segments, layout, entry.meta, ends)


VERIFIED = {}          # path -> ((device, inode, size, mtime), Solution, record): files this process has checked


def stamp_of(info):
    return info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns


def read(path, rec):
    """The stored Solution, or None when there is none, it is refused (said in one line, then deleted), or it
    cannot be read for a reason that is not the file's (said in one line, the file kept).  A file this process
    has already read and checked, unchanged since (same inode, size and time), is not read again."""
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return None
    known = VERIFIED.get(str(path))
    if known is not None and known[0] == stamp_of(info) and known[2] == json.dumps(rec, sort_keys=True):
        return known[1]
    try:
        solution = load(path, rec)
    except Refused as exc:
        private.say(f"the stored solution {path} was refused ({exc}); computing it again")
        verified.discard(path)
        return None
    except OSError as exc:
        _warn(f"the stored solution {path} could not be read ({exc.strerror or exc}); answering without the store")
        raise Unreadable from None
    if solution is not None:
        VERIFIED[str(path)] = (stamp_of(info), solution, json.dumps(rec, sort_keys=True))
    return solution


class Unreadable(Exception):
    """A store file that could not be read for a reason that is not its own (said already)."""


def _warn(message):
    warnings.warn(f"spinorbit: {message}", UserWarning, stacklevel=4)


def _save_or_warn(solution, rec, path):
    """Save; a write that fails (a full disk) is warned of and said in the provenance.  True when stored."""
    try:
        save(solution, rec, path)
        return True
    except OSError as exc:
        why = f"{type(exc).__name__}: {exc.strerror or exc}"
        solution.provenance["not_stored_because"] = why
        _warn(f"the solution was not stored ({why}); answering from this computation")
        return False


def solve(rec, t_start, t_end, extend):
    """The stored solution keyed by ``rec`` (``record``) covering [t_start, t_end] TDB days; where the store
    lacks part of it, ``extend(solution or None, t_start, t_end)`` computes the stretches (solutions.for_scenario);
    one process at a time extends a file (a lock), the others wait and read what it wrote.  A store that cannot
    be read or written is said, and the answer is computed without it."""
    path = path_of(rec)
    try:
        solution = read(path, rec)
    except Unreadable:
        return _timed(extend, None, t_start, t_end)
    if solution is not None and solution.covers(t_start, t_end):
        solution.path = path
        return solution
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(verified.lock(path))
        except OSError as exc:
            _warn(f"the store's lock of {path} cannot be taken ({exc.strerror or exc}); answering without the store")
            return _timed(extend, solution, t_start, t_end)
        try:
            solution = read(path, rec)
        except Unreadable:
            return _timed(extend, None, t_start, t_end)
        if solution is None or not solution.covers(t_start, t_end):
            solution = _timed(extend, solution, t_start, t_end)
            if not _save_or_warn(solution, rec, path):
                return solution
    solution.path = path
    return solution


def _timed(extend, solution, t_start, t_end):
    started = time.perf_counter()
    solution = extend(solution, t_start, t_end)
    solution.provenance["last_extension_wall_s"] = time.perf_counter() - started
    return solution


def offer(solution, rec):
    """Keep ``solution`` under ``rec`` unless the store already holds a span it does not cover, waiting at most
    OFFER_WAIT_S for the file's lock; returns the file's path.  verified.Busy when another process holds the lock
    longer; OSError when the store cannot be read or written."""
    path = path_of(rec)
    with verified.lock(path, wait_s=OFFER_WAIT_S):
        try:
            stored = read(path, rec)
        except Unreadable:
            raise OSError(f"{path} could not be read") from None
        if stored is None or solution.covers(*stored.span):
            save(solution, rec, path)
    solution.path = path
    return path


def entry_span(path):
    """(start, end) TDB days of the solution stored at ``path``, read from its grid alone (not checked), or
    None."""
    held = verified.peek(path, ["grid"])
    if held is None or held["grid"].shape != (4,):
        return None
    origin, length, first, count = held["grid"]
    return float(origin + first * length), float(origin + (first + count) * length)


def entries():
    """[(path, scene, (start, end) TDB days, bytes)] of the stored solutions, read without their hash checked
    (a listing): a file of another code version says so after its scene (no run of this code reads it;
    `spinorbit cache clear` removes it), an unreadable one has span None."""
    out = []
    for path in sorted(directory().glob("*.npz")):
        scene, span = "unreadable", None
        held = verified.peek(path, ["record", "grid"])
        try:
            rec = json.loads(str(held["record"]))
            scene = rec["scene"] if rec.get("code") == code_version() else \
                f"{rec['scene']} (code {rec.get('code')}, not this one's)"
            span = entry_span(path)
        except (TypeError, KeyError, ValueError):
            pass
        out.append((path, scene, span, path.stat().st_size))
    return out


def clear():
    """Delete every stored solution no process holds (and the leftovers of killed writes) and the code-version
    records; a solution another live process holds the lock of is kept, with its lock and temporary files, and
    said (spinorbit.base.verified.clear).  Returns the number of files removed."""
    folder = directory()
    removed = verified.clear(folder, "*.npz")
    for path in folder.glob("*.json"):
        if path.is_file() and not path.is_symlink():
            path.unlink()
            removed += 1
    return removed
