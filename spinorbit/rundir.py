"""A run directory as a unit: written aside, swapped in whole, locked, never clobbering foreign files.

A run writes into a fresh sibling ``.<name>.new-<pid>`` and, once every file is
there, records them in a manifest (``MANIFEST``: name -> sha256) and swaps the
directory in (``out`` -> ``.<name>.old-<pid>``, new -> ``out``, old removed).
So ``out`` always holds one whole run, the old or the new one: a crash between
the two renames leaves a complete new directory (it has its manifest) that the
next run moves into place.  A failed run leaves a good previous run alone and
puts its partial output beside it in ``<out>.failed``.  A long run's checkpoint
(spinorbit.checkpoint) lives beside it in ``<out>.checkpoint.npz``: a failed or
interrupted run leaves it, a committed run removes it.  A lock refuses a
second run into the same ``out`` while the first is alive.  The lock is an
flock on ``.<name>.lock`` in the parent, which the kernel drops when its holder
exits, even on kill -9; the file itself stays.  Files in ``out``
that spinorbit did not write (not in the manifest, or changed since) are never
overwritten or removed: the run is refused unless ``force``, and then the ones
the new run does not replace are carried over into it.

Edge module.
"""
import fcntl
import hashlib
import json
import os
import shutil
from pathlib import Path

from .errors import ScenarioError

MANIFEST = ".spinorbit-manifest.json"


class RunDirectory:
    """``with RunDirectory(out) as run: run.commit(write)``; ``write(path)`` fills a directory."""

    def __init__(self, out, force=False):
        try:
            str(out).encode("utf-8")
        except UnicodeEncodeError as exc:          # undecodable bytes from the command line
            raise ScenarioError("--out", str(out), f"a UTF-8 path (a byte that is not UTF-8 at offset {exc.start})") from None
        self.out = Path(out).resolve()
        self.force = force
        parent, name = self.out.parent, self.out.name
        self.lock = parent / f".{name}.lock"
        self.new = parent / f".{name}.new-{os.getpid()}"
        self.old = parent / f".{name}.old-{os.getpid()}"
        self.failed = parent / f"{name}.failed"
        self.checkpoint = parent / f"{name}.checkpoint.npz"
        self.foreign = []
        self._lock_fd = None

    def __enter__(self):
        self.out.parent.mkdir(parents=True, exist_ok=True)
        self._acquire()
        try:
            self._repair()
            self.foreign = foreign_files(self.out)
            if self.foreign and not self.force:
                raise ScenarioError("--out", str(self.out),
                                    f"a new directory or one holding a spinorbit run; it holds {len(self.foreign)} "
                                    f"file(s) spinorbit did not write ({', '.join(self.foreign[:3])}"
                                    f"{', ...' if len(self.foreign) > 3 else ''}): choose another --out, "
                                    "or pass --force to overwrite them")
        except BaseException:
            self._release()
            raise
        return self

    def __exit__(self, *exc):
        try:
            _remove(self.new)
        finally:
            self._release()

    # --- writing ----------------------------------------------------------
    def commit(self, write):
        """Write a whole run aside with ``write(path)`` and swap it in as ``out``; return ``out``."""
        self._write_aside(write, "ok", carry_foreign=True)
        self._swap(self.out)
        for done in (self.checkpoint, *self.checkpoint.parent.glob(f"{self.checkpoint.stem}-*.npz")):
            _remove(done)                              # the run is whole: nothing left to resume
        return self.out

    def fail(self, write):
        """Write a failed run's partial output: into ``out`` if it holds no good run, else beside it
        (``<out>.failed``, or ``<out>.failed-<pid>`` if that holds files spinorbit did not write)."""
        target = self.out
        if read_manifest(self.out).get("status") == "ok":
            target = self.failed if not foreign_files(self.failed) else self.failed.with_name(
                f"{self.failed.name}-{os.getpid()}")
        self._write_aside(write, "failed", carry_foreign=target == self.out)
        self._swap(target)
        return target

    def _swap(self, target):
        if target.exists():
            os.replace(target, self.old)
        os.replace(self.new, target)
        _remove(self.old)

    def _write_aside(self, write, status, carry_foreign):
        _remove(self.new)
        self.new.mkdir()
        write(self.new)
        manifest = {"status": status, "files": {rel: _sha256(self.new / rel) for rel in _files(self.new)}}
        for rel in self.foreign if carry_foreign else ():   # --force: keep what the new run does not replace
            if not (self.new / rel).exists():
                (self.new / rel).parent.mkdir(parents=True, exist_ok=True)
                os.replace(self.out / rel, self.new / rel)
        tmp = self.new / f"{MANIFEST}.tmp"
        tmp.write_text(json.dumps(manifest, indent=1) + "\n")
        os.replace(tmp, self.new / MANIFEST)          # written last: marks the directory complete

    # --- lock and repair --------------------------------------------------
    def _acquire(self):
        """Take the lock (flock: the kernel drops it when the holder exits, even on kill -9)."""
        fd = os.open(self.lock, os.O_CREAT | os.O_RDWR, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(fd, 32).decode(errors="replace").strip() or "?"
            os.close(fd)
            raise ScenarioError("--out", str(self.out),
                                f"a directory no other run is writing (process {holder} holds {self.lock.name}): "
                                "wait for it, or choose another --out") from None
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        self._lock_fd = fd

    def _release(self):
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None

    def _repair(self):
        """Finish or undo what a killed run left (we hold the lock, so its writer is gone)."""
        parent, name = self.out.parent, self.out.name
        news = sorted(parent.glob(f".{name}.new-*"))
        olds = sorted(parent.glob(f".{name}.old-*"))
        if not self.out.exists():
            complete = [d for d in news if read_manifest(d).get("status") == "ok"]
            if complete:                               # killed between the two renames of a swap
                os.replace(complete[-1], self.out)
            elif olds:
                os.replace(olds[-1], self.out)
        for stale in (*news, *olds, *parent.glob(f".{self.checkpoint.name}.tmp-*")):
            _remove(stale)


def read_manifest(directory):
    """The manifest of a run directory ({} if there is none or it is unreadable)."""
    try:
        manifest = json.loads((Path(directory) / MANIFEST).read_text())
    except (OSError, ValueError):
        return {}
    return manifest if isinstance(manifest, dict) and isinstance(manifest.get("files"), dict) else {}


def foreign_files(directory):
    """Files in ``directory`` that spinorbit did not write, or that changed since (relative paths)."""
    directory = Path(directory)
    if not directory.exists():
        return []
    if not directory.is_dir():
        raise ScenarioError("--out", str(directory), "a directory (this is a file)")
    ours = read_manifest(directory).get("files", {})
    return [rel for rel in _files(directory) if rel != MANIFEST and ours.get(rel) != _sha256(directory / rel)]


def _files(directory):
    return sorted(str(p.relative_to(directory)) for p in Path(directory).rglob("*") if not p.is_dir())


def _sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _remove(path):
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    elif path.exists() or path.is_symlink():
        path.unlink()
