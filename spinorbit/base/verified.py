"""The verified-cache room: files spinorbit computed once and reads back only when they are intact.

Every cache of numbers spinorbit keeps on disk goes through these few calls, so that each keeps the same rules:

- ``folder(name)``: ``<spinorbit's private cache>/<name>`` (spinorbit.base.linker.cache: ``$SPINORBIT_CACHE_DIR``,
  else ``~/.cache/spinorbit``), created 0700; ``private(path)`` checks a folder named elsewhere (a test's).  A
  folder another user owns or can write is refused in one line (an InputError naming SPINORBIT_CACHE_DIR):
  nothing planted there is read.
- ``write(path, arrays, record, meta=None)``: one npz holding ``arrays`` (name -> numpy array), ``record`` (a
  JSON dict: everything that decides the arrays, *the code's version among them*: the caller's own, e.g.
  solutions.code_version's hash of the package, or the orbits' integration digest and REBOUND's version),
  ``meta`` (a JSON dict: provenance, not compared) and a ``sha256`` over all of them (each name, dtype, shape
  and bytes: :func:`arrays_hash`).  Written aside (``.<name>.tmp-<pid>-*`` in the same folder), synced, then
  renamed over ``path``: a reader sees the old file or the new one, never a part; a write that fails (a full
  disk: ENOSPC, EFBIG) removes what it wrote and raises its OSError; one that succeeds removes what writes of
  ``path`` killed before their rename left (``remove_leftovers``).
- ``read(path, record=None)``: :class:`Entry` (arrays, record, meta), or None when there is no file.
  :class:`Damaged` (its one-line reason) when the file itself is bad: not a regular file, not an npz this room
  wrote (read with ``allow_pickle=False``: nothing in it runs; a zip member compressed, encrypted or of a
  later zip version is refused too), an array missing or added, its content not its sha256, a record that is not
  a JSON object, or another ``record`` than the one asked for (the differing keys named).  The caller deletes it
  (:func:`discard`) and makes it again.  An OSError that says nothing about the file (EIO, EMFILE, EACCES) is
  raised as it is: the caller answers without the cache, and never deletes the file for it.
  ``read_file(f, record=None)`` checks a file its caller opened (a file the user named, whose owner the caller
  checks first: spinorbit.edge.checkpoint) by the same rules.
- ``peek(path, names)``: some arrays read without the hash checked (a listing; a span compared), None if
  unreadable.
- ``lock(path, wait_s=None, repair=True)``: the exclusive lock of ``path`` (``<name>.lock`` beside it, a regular
  file) held for the ``with`` block; waits at most ``wait_s`` seconds (None: as long as it takes, saying once
  that it waits; 0: not at all) and then raises :class:`Busy`.  Something else at the lock's place (a FIFO, a
  folder, a link to a device) is made again, said in one line (``repair=False``, for a file the user named:
  refused, NotRegular).  ``locked_elsewhere(path)``: whether another process
  holds it now.
- ``clear(folder, pattern)``: deletes the files matching ``pattern`` and the leftovers of their killed writes,
  except those another live process holds the lock of (kept, and said; lock files stay); ``remove_leftovers(path)``
  deletes the temporary files of writes whose process is gone.
- ``prune(folder, pattern, max_bytes, keep)``: deletes the least recently written files (their locks free, not
  ``keep``) until those matching ``pattern`` take at most ``max_bytes``.
"""
import contextlib
import fcntl
import hashlib
import json
import os
import re
import stat
import sys
import time
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .files import NotRegular, open_lock, open_regular, process_alive, write_atomically
from .private import check_private, private_folder

FORMAT = 1                  # the room's file layout: "record", "meta", "sha256" beside the caller's arrays
RESERVED = ("record", "meta", "sha256", "room_format")
ENVIRONMENT = "SPINORBIT_CACHE_DIR"
POLL_S = 0.05


class Damaged(Exception):
    """A cache file that is not an intact one of the record asked for: its one-line reason."""


class Busy(Exception):
    """A lock another process holds beyond the time allowed."""


@dataclass
class Entry:
    """What a verified file holds: ``arrays`` (name -> array), ``record`` and ``meta`` (dicts)."""

    arrays: dict
    record: dict
    meta: dict


def folder(name):
    """``<spinorbit's private cache>/<name>``, created 0700, refused in one line when not private."""
    return private_folder(name)


def private(path):
    """``path`` (created 0700 if missing) when it is a directory of this user's that others cannot write;
    InputError on SPINORBIT_CACHE_DIR otherwise."""
    path = Path(path)
    if not os.path.lexists(path):
        os.mkdir(path, 0o700)
    check_private(path, path, ENVIRONMENT, "spinorbit's caches")
    return path


def arrays_hash(arrays):
    """sha256 of named arrays: each name, dtype, shape and bytes, in the order of the names."""
    digest = hashlib.sha256()
    for name in sorted(arrays):
        array = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}:{array.dtype.str}{array.shape}:".encode())
        digest.update(array.data)          # the buffer itself, no copy
    return digest.hexdigest()


def _held(arrays, record, meta):
    """Everything a file holds but its hash."""
    clash = set(arrays) & set(RESERVED)
    if clash:
        raise ValueError(f"array names {sorted(clash)} are the room's own")
    return {**{name: np.asarray(value) for name, value in arrays.items()},
            "record": np.array(json.dumps(record, sort_keys=True)), "meta": np.array(json.dumps(meta or {})),
            "room_format": np.array(FORMAT)}


def write(path, arrays, record, meta=None):
    """Write ``arrays``, ``record`` and ``meta`` to ``path`` with their sha256, aside then renamed (atomic);
    on an OSError nothing is left of the write and the error is raised."""
    path = Path(path)
    held = _held(arrays, record, meta)
    write_atomically(path, lambda f: np.savez(f, sha256=np.array(arrays_hash(held)), **held),
                     prefix=f".{path.name}.tmp-{os.getpid()}-")
    remove_leftovers(path)


# what a reader raises for a file that is not an npz (zipfile, zlib; a member compressed in a way it lacks, or of a
# later zip version: NotImplementedError; flagged encrypted: RuntimeError) or not one of ours (numpy: ValueError)
_BAD_FORMAT = (ValueError, KeyError, EOFError, zipfile.BadZipFile, zlib.error, NotImplementedError, RuntimeError,
               NotRegular, IsADirectoryError)


def read(path, record=None):
    """The :class:`Entry` at ``path``, None when there is none; Damaged (one line) when the file is bad or was made
    with another ``record`` (when one is given); any other OSError raised as it is."""
    try:
        f = open_regular(path)
    except FileNotFoundError:
        return None
    except _BAD_FORMAT as exc:
        raise _not_ours(exc) from None
    with f:
        return read_file(f, record)


def _not_ours(exc):
    return Damaged(f"not a file spinorbit wrote ({type(exc).__name__}: {_first_line(exc)})")


def read_file(f, record=None):
    """The :class:`Entry` an open binary file holds, checked as :func:`read` checks a path's (for a file its caller
    opened itself: one the user named, its owner checked)."""
    try:
        with np.load(f, allow_pickle=False) as data:
            held = {name: data[name] for name in data.files}
    except _BAD_FORMAT as exc:
        raise _not_ours(exc) from None
    stored_hash = held.pop("sha256", None)
    if stored_hash is None or not set(RESERVED[:2]) <= set(held) or held.get("room_format") != FORMAT:
        raise Damaged(f"not a file spinorbit wrote (it holds {sorted(held)})")
    if arrays_hash(held) != str(stored_hash):
        raise Damaged("its arrays do not match their hash (sha256: damaged or edited)")
    try:
        stored, meta = json.loads(str(held.pop("record"))), json.loads(str(held.pop("meta")))
    except ValueError as exc:
        raise Damaged(f"its record is not JSON ({exc})") from None
    if not (isinstance(stored, dict) and isinstance(meta, dict)):
        raise Damaged("its record or meta is not a JSON object")
    held.pop("room_format")
    if record is not None:
        expected = json.loads(json.dumps(record, sort_keys=True))
        differ = sorted(k for k in set(stored) | set(expected) if stored.get(k) != expected.get(k))
        if differ:
            raise Damaged(f"it was made with another {', '.join(differ)}")
    return Entry(held, stored, meta)


def peek(path, names):
    """{name: array} of some arrays of the file at ``path``, read without checking its hash (what a listing shows,
    or a span compared before the file is read whole with :func:`read`); None when the file cannot be read or
    lacks one of them."""
    try:
        with open_regular(path) as f, np.load(f, allow_pickle=False) as data:
            return {name: data[name] for name in names}
    except (OSError, *_BAD_FORMAT):
        return None


def _first_line(exc):
    text = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
    return text.splitlines()[0] if text else type(exc).__name__


def discard(path):
    """Delete a damaged cache file (a folder in its place too: the room is spinorbit's alone)."""
    import shutil

    path = Path(path)
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


def lock_path(path):
    path = Path(path)
    return path.with_name(path.name + ".lock")


def _open_lock(path, repair):
    """The lock file of ``path`` opened; with ``repair`` (a folder of the room's own) something other than a
    regular file there (a FIFO, a folder, a link to a device) is removed, said in one line, and the lock made."""
    try:
        return open_lock(lock_path(path))
    except OSError as exc:
        if not repair or os.path.isfile(lock_path(path)) and not os.path.islink(lock_path(path)):
            raise
        print(f"spinorbit: the lock {lock_path(path)} was not a regular file ({exc.strerror or exc}); made again",
              file=sys.stderr)
        discard(lock_path(path))
        return open_lock(lock_path(path))


@contextlib.contextmanager
def lock(path, wait_s=None, repair=True):
    """Hold the exclusive lock of ``path`` for the block: at once if free, else waiting at most ``wait_s`` seconds
    (None: without limit, said once on stderr; 0: not at all), then Busy.  ``repair``: the folder is the room's
    (``folder``, ``private``): a lock that is not a regular file is made again (said); without it, refused
    (NotRegular, an OSError)."""
    with _open_lock(path, repair) as handle:
        started, said = time.monotonic(), False
        while True:
            try:
                fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                waited = time.monotonic() - started
                if wait_s is not None and waited >= wait_s:
                    raise Busy(f"{path} is being written by another process (waited {waited:.3g} s)") from None
                if not said and wait_s is None:
                    print(f"spinorbit: waiting for another process writing {path}", file=sys.stderr)
                    said = True
                time.sleep(POLL_S)
        yield


def locked_elsewhere(path):
    """Whether another process holds the lock of ``path`` now."""
    if not os.path.lexists(lock_path(path)):
        return False
    try:
        with lock(path, wait_s=0):
            return False
    except Busy:
        return True


def _leftover_pattern(path):
    return re.compile(rf"\.{re.escape(Path(path).name)}\.tmp-(\d+)(-.*)?")


def remove_leftovers(path):
    """Delete the ``.<name>.tmp-<pid>*`` files that writes killed before their rename left beside ``path`` (their
    process is gone); return how many."""
    path, pattern, removed = Path(path), _leftover_pattern(path), 0
    for entry in os.scandir(path.parent):
        match = pattern.fullmatch(entry.name)
        if match and entry.is_file(follow_symlinks=False) and not process_alive(int(match.group(1))):
            os.unlink(entry.path)
            removed += 1
    return removed


def clear(directory, pattern="*.npz"):
    """Delete the files matching ``pattern`` in ``directory`` and the leftovers of their killed writes, except
    those whose lock another process holds (kept with their temporary files, and said on stdout); return the
    number of files removed.  The lock files stay: removing one that another process has opened and waits on
    would let a third take a new one and two write at once."""
    removed = 0
    for path in sorted(Path(directory).glob(pattern)):
        if path.is_symlink() or not path.is_file():
            continue
        try:
            with lock(path, wait_s=0):
                removed += remove_leftovers(path)
                path.unlink()
                removed += 1
        except Busy:
            print(f"kept {path}: another process is writing it")
    return removed


def usage(directory, pattern="*.npz"):
    """[(path, bytes, mtime_ns)] of the files matching ``pattern``, least recently written first."""
    found = []
    for path in Path(directory).glob(pattern):
        try:
            info = os.lstat(path)
        except FileNotFoundError:
            continue
        if stat.S_ISREG(info.st_mode):
            found.append((path, info.st_size, info.st_mtime_ns))
    return sorted(found, key=lambda item: item[2])


def prune(directory, pattern, max_bytes, keep=()):
    """Delete the least recently written files matching ``pattern`` (not ``keep``, their lock free) until the
    rest take at most ``max_bytes``; return the paths removed."""
    files = usage(directory, pattern)
    total, removed, kept = sum(size for _, size, _ in files), [], {Path(p) for p in keep}
    for path, size, _ in files:
        if total <= max_bytes:
            break
        if path in kept:
            continue
        try:
            with lock(path, wait_s=0):
                path.unlink(missing_ok=True)
        except Busy:
            continue
        total -= size
        removed.append(path)
    return removed
