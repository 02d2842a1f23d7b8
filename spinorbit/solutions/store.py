"""The solution store: every solution computed, kept in spinorbit's private cache and extended on demand.

Where: ``<the kernel cache's private directory>/solutions`` (spinorbit.linker.cache: 0700, refused when
another user could change it).  A solution is keyed by what decides its numbers: the scene, every key of the
scenario but its comparisons, outputs and span (kept for a scene whose start is fitted over its span: the
Earth's), the integrator's options, and the code's version (solutions.code_version: spinorbit's version and a
sha256 of the package's source: a changed integration never reuses an old file).  Each file is an npz read with
``allow_pickle=False`` (nothing in it can run code) holding the series, the layout, the provenance, the states
where the integration stopped, the record it was keyed by and a sha256 over every array; one that is not
intact (truncated, tampered with, another model's) is refused in one line and computed again.  Files are
written aside and renamed (atomic); a lock beside each makes one process at a time extend it, the others
waiting and then reading what it wrote.

A query outside the stored span extends the solution from its nearer end (forward from its end, backward
from its start), the same System started at the state where the last run stopped.
"""
import contextlib
import fcntl
import hashlib
import json
import os
import shutil
import stat
import sys
import time
import zipfile

import numpy as np

from ..files import open_lock, open_regular
from ..layout import Layout
from ..linker import cache
from ..orbits.solution import arrays_hash
from .chebyshev import Segments
from .code_version import package_version
from .solution import Solution

LAYER_KEYS = ("span.", "model.start", "scene.", "compare.", "comparison.", "report.", "output.", "limits.",
              "earth.nonrigid", "earth.transfer_function", "integrator.estimate_error")


PLACE = {"directory": None}          # another directory (tests); None: the private cache's


def directory():
    """``<private cache>/solutions`` (created 0700)."""
    path = PLACE["directory"] or cache.kernels_dir().parent / "solutions"
    if not path.is_dir():
        path.mkdir(mode=0o700, exist_ok=True)
    return path


def code_version():
    """spinorbit's version and the sha256 of its sources (solutions.code_version, recorded in the store)."""
    return package_version(directory())


def record(scenario):
    """What decides a solution's numbers: the scene kind, its model keys, the code's version (and the span, for a
    scene whose start depends on it: the Earth's is fitted over its span's outputs)."""
    from .models import KINDS

    anchored = scenario.kind in KINDS and KINDS[scenario.kind].anchor is not None
    ignored = LAYER_KEYS if anchored else tuple(k for k in LAYER_KEYS if k not in ("span.", "model.start"))
    keys = {k: v.tolist() if hasattr(v, "tolist") else v for k, v in sorted(scenario.values.items())
            if not k.startswith(ignored)}
    keys["integrator"] = scenario.integrator_options()
    return {"scene": scenario.kind, "keys": json.loads(json.dumps(keys, default=str)), "code": code_version()}


def path_of(rec):
    key = hashlib.sha256(json.dumps(rec, sort_keys=True).encode()).hexdigest()[:20]
    return directory() / f"{rec['scene']}-{key}.npz"


ARRAYS = ("coefficients", "grid", "layout", "provenance", "record", "end_start_t", "end_start_state",
          "end_end_t", "end_end_state")


def _arrays(solution, rec):
    s = solution.segments
    layout = [[p.name, p.stop - p.start, p.kind, p.unit] for p in solution.layout.slices]
    grid = np.array([s.origin_d, s.length_d, s.first, len(s.coefficients)], dtype=float)
    return {"coefficients": s.coefficients, "grid": grid,
            "layout": np.array(json.dumps(layout)), "provenance": np.array(json.dumps(solution.provenance)),
            "record": np.array(json.dumps(rec, sort_keys=True)),
            **{f"end_{name}_{part}": np.asarray(value, dtype=float) for name, (t, y) in solution.ends.items()
               for part, value in (("t", t), ("state", y))}}


def content_hash(arrays):
    """sha256 of the stored arrays (each name, dtype, shape and bytes), as the orbital solutions are hashed."""
    return arrays_hash({name: arrays[name] for name in ARRAYS})


def save(solution, rec, path):
    """Write atomically: aside in the same directory, fsync, rename over ``path``."""
    arrays = _arrays(solution, rec)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with open(tmp, "wb") as f:
            np.savez(f, sha256=np.array(content_hash(arrays)), **arrays)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


class Refused(Exception):
    """A store file that is not an intact solution of the record asked for."""


def load(path, rec):
    """The Solution in ``path``; Refused (saying why) unless it is intact and made with ``rec``."""
    try:
        with open_regular(path) as f, np.load(f, allow_pickle=False) as data:
            arrays = {name: data[name] for name in ARRAYS}
            stored_hash = str(data["sha256"])
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:
        raise Refused(f"not a readable solution file: {type(exc).__name__}: {exc}") from None
    if content_hash(arrays) != stored_hash:
        raise Refused("its arrays do not match their sha256")
    if json.loads(str(arrays["record"])) != json.loads(json.dumps(rec, sort_keys=True)):
        raise Refused("it was made with another model, keys or code version")
    origin, length, first, count = arrays["grid"]
    if count != len(arrays["coefficients"]):
        raise Refused("its grid does not match its series")
    segments = Segments(float(origin), float(length), int(first), arrays["coefficients"])
    layout = Layout([tuple(p) for p in json.loads(str(arrays["layout"]))])
    ends = {name: (float(arrays[f"end_{name}_t"]), arrays[f"end_{name}_state"]) for name in ("start", "end")}
    return Solution(segments, layout, json.loads(str(arrays["provenance"])), ends)


VERIFIED = {}          # path -> ((device, inode, size, mtime), Solution, record): files this process has checked


def stamp_of(info):
    return info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns


def read(path, rec):
    """The stored Solution, or None when there is none or it is refused (said in one line, then deleted).  A
    file this process has already read and checked, unchanged since (same inode, size and time), is not read
    again."""
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return None
    known = VERIFIED.get(str(path))
    if known is not None and known[0] == stamp_of(info) and known[2] == json.dumps(rec, sort_keys=True):
        return known[1]
    try:
        solution = load(path, rec)
        VERIFIED[str(path)] = (stamp_of(info), solution, json.dumps(rec, sort_keys=True))
        return solution
    except Refused as exc:
        cache.say(f"the stored solution {path} was refused ({exc}); computing it again")
        if stat.S_ISDIR(info.st_mode):          # a folder in the private store, where a file belongs
            shutil.rmtree(path, ignore_errors=True)
        else:
            path.unlink(missing_ok=True)
        return None


def solve(rec, t_start, t_end, extend):
    """The stored solution keyed by ``rec`` (``record``) covering [t_start, t_end] TDB days; where the store
    lacks part of it, ``extend(solution or None, t_start, t_end)`` computes the stretches (solutions.solve);
    one process at a time extends a file (a lock), the others wait and read what it wrote."""
    path = path_of(rec)
    solution = read(path, rec)
    if solution is not None and solution.covers(t_start, t_end):
        solution.path = path
        return solution
    with locked(path):
        solution = read(path, rec)
        if solution is None or not solution.covers(t_start, t_end):
            started = time.perf_counter()
            solution = extend(solution, t_start, t_end)
            solution.provenance["last_extension_wall_s"] = time.perf_counter() - started
            save(solution, rec, path)
    solution.path = path
    return solution


def offer(solution, rec):
    """Keep ``solution`` under ``rec`` unless the store already holds a span it does not cover (under the
    file's lock); returns the file's path."""
    path = path_of(rec)
    with locked(path):
        stored = read(path, rec)
        if stored is None or solution.covers(*stored.span):
            save(solution, rec, path)
    solution.path = path
    return path


@contextlib.contextmanager
def locked(path):
    """The exclusive lock of the stored file ``path``: one process at a time writes it, the others wait."""
    with open_lock(path.with_name(path.name + ".lock")) as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            print(f"spinorbit: waiting for another process writing {path}", file=sys.stderr)
            fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def entry_span(path):
    """(start, end) TDB days of the solution stored at ``path``, read from its grid alone (not checked), or
    None."""
    try:
        with open_regular(path) as f, np.load(f, allow_pickle=False) as data:
            origin, length, first, count = data["grid"]
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None
    return float(origin + first * length), float(origin + (first + count) * length)


def entries():
    """[(path, scene, (start, end) TDB days, bytes)] of the stored solutions: a file of another code version
    says so after its scene (no run of this code reads it; `spinorbit cache clear` removes it), an unreadable
    one has span None."""
    out = []
    for path in sorted(directory().glob("*.npz")):
        scene, span = "unreadable", None
        try:
            with open_regular(path) as f, np.load(f, allow_pickle=False) as data:
                rec = json.loads(str(data["record"]))
                scene = rec["scene"] if rec.get("code") == code_version() else \
                    f"{rec['scene']} (code {rec.get('code')}, not this one's)"
                origin, length, first, count = data["grid"]
            span = (origin + first * length, origin + (first + count) * length)
        except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
            pass
        out.append((path, scene, span, path.stat().st_size))
    return out


def clear():
    """Delete every stored solution (and its lock) and the code-version records; return the number of files
    removed."""
    removed = 0
    for path in directory().iterdir():
        if path.is_file() and not path.is_symlink() and (path.suffix in (".npz", ".lock", ".json")
                                                          or ".tmp-" in path.name):
            path.unlink()
            removed += 1
    return removed

