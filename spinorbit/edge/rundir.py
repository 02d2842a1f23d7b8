"""The output directory as a transaction that owns only what it wrote.

A run writes aside into a fresh sibling ``.<name>.new-<pid>-<random>``, records what it wrote in a
manifest (``.spinorbit-manifest.json``: relative path -> size and sha256) and swaps it in: ``out`` ->
``.<name>.old-<pid>-<random>``, the new one -> ``out``.  So ``out`` always holds one whole run, the old one
or the new one; a run killed between the two renames leaves a complete new directory (it has its
manifest) that the next run moves into place.  The old directory is then retired: whatever in it
spinorbit did not write (files, folders, links, sockets, FIFOs the user put there, before or during
the run) is moved into the new ``out``, and only the old run's own files, as its manifest lists
them and unchanged, are deleted; anything that can be neither moved nor deleted is left in a
visible ``<out>.leftover-<pid>-<random>`` and said.  The new directory takes the old one's mode (and owner,
where the system allows; a directory of another user is refused up front).

Foreign entries are recognised from metadata only (``lstat``; a file is spinorbit's when the
manifest lists it with its size and its sha256 still matches, and only such files are opened):
nothing foreign is read, followed or hashed.  A run refuses an ``out`` holding foreign entries
unless ``force``, which keeps them and replaces only the files the new run writes itself.  Entries
that appear while the run computes are kept; if they take a name the run writes, the run goes to
``<out>.new-<pid>-<random>`` instead and the refusal says so.

A failed run leaves a good previous run alone and puts its partial output beside it in
``<out>.failed`` (``<out>.failed-<pid>-<random>`` when that is not a directory of this user's
holding only spinorbit's files).  Output
staged by a writer that then fails (an exception, a full disk) is kept the same way.  ``sweep``
and ``bench`` fill a staging directory progressively (:meth:`RunDirectory.stage`) and commit it.

A lock refuses a second run into the same ``out`` while the first is alive: an flock on
``.<name>.lock`` in the parent, which the kernel drops when its holder exits, even on kill -9.  The
lock file is opened without following links and written only if it is a regular file of this user
with one link, so a link planted in a shared directory cannot make the run truncate its target.
No name given by the user is used as a pattern.

Edge module.
"""
import fcntl
import hashlib
import json
import os
import re
import secrets
import shutil
import stat
import sys
from pathlib import Path

from ..base.errors import ScenarioError
from ..base.files import open_regular

MANIFEST = ".spinorbit-manifest.json"
MAX_MANIFEST_BYTES = 64 << 20
BESIDE_CHARS = 72              # the longest sibling's additions (.<name>.checkpoint-<part>.npz.tmp-<pid>-<8>)
KINDS = {stat.S_IFREG: "file", stat.S_IFDIR: "folder", stat.S_IFLNK: "symbolic link", stat.S_IFIFO: "FIFO",
         stat.S_IFSOCK: "socket", stat.S_IFCHR: "device", stat.S_IFBLK: "device"}


class RunDirectory:
    """``with RunDirectory(out) as run: run.commit(write)``; ``write(path)`` fills a directory."""

    def __init__(self, out, force=False, key="--out"):
        try:
            str(out).encode("utf-8")
        except UnicodeEncodeError as exc:          # undecodable bytes from the command line
            accepted = f"a UTF-8 path (a byte that is not UTF-8 at offset {exc.start})"
            raise ScenarioError(key, str(out), accepted) from None
        self.key = key
        self.out = Path(os.path.abspath(out))
        if os.path.isdir(self.out):
            self.out = self.out.resolve()          # a link to a directory: the run goes into its target
        self.force = force
        parent, name = self.out.parent, self.out.name
        token = f"{os.getpid()}-{secrets.token_hex(4)}"      # not predictable: nobody can plant these first
        self.lock = parent / f".{name}.lock"
        self.staging = parent / f".{name}.new-{token}"
        self.old = parent / f".{name}.old-{token}"
        self.failed = parent / f"{name}.failed"
        self.checkpoint = parent / f"{name}.checkpoint.npz"
        self.foreign = []                          # (relative path, kind) found when the run started
        self._token = token
        self._lock_fd = None
        self._keep_staging = False

    def __enter__(self):
        self._acquire()
        try:
            self._repair()
            self._check_owner()
            self.foreign = foreign_entries(self.out, self.key)
            if self.foreign and not self.force:
                count = f"{len(self.foreign)} entr{'y' if len(self.foreign) == 1 else 'ies'}"
                raise ScenarioError(self.key, str(self.out), f"a new directory or one holding a "
                                    f"spinorbit run; it holds {count} spinorbit did not write "
                                    f"({describe(self.foreign)}): choose another {self.key}, or pass --force "
                                    "to keep them and overwrite only the files the run writes")
        except BaseException:
            self._release()
            raise
        return self

    def __exit__(self, exc_type, exc, tb):
        try:
            if exc_type is not None and _has_content(self.staging):
                self._keep_staged()
            if not self._keep_staging:
                _remove_tree(self.staging)
        finally:
            self._release()

    # --- writing ----------------------------------------------------------
    def stage(self):
        """The staging directory (created on first call, never an entry that was there), for writers that
        fill it as they go."""
        if not os.path.lexists(self.staging):
            self._io(os.mkdir, self.staging)
        return self.staging

    def staged(self):
        """Does the staging directory hold anything (what a failed commit keeps)?"""
        return _has_content(self.staging)

    def commit(self, write=None):
        """Write a whole run aside with ``write(path)`` (or take what was staged) and swap it in as
        ``out``; return ``out``."""
        if write is not None:
            self._io(write, self.stage())
        self._install("ok", self.out)
        return self.out

    def fail(self, write=None):
        """Write a failed run's partial output (``write(path)``, or what was staged): into ``out`` if it
        holds no good run, else beside it; return where it went."""
        if write is not None:
            self._io(write, self.stage())
        target = self.out if read_manifest(self.out).get("status") != "ok" else self._failed_target()
        self._install("failed", target)
        return target

    def _failed_target(self):
        """``<out>.failed``, unless it is something else than a directory of this user's holding only
        spinorbit's files; then ``<out>.failed-<token>``."""
        try:
            info = os.lstat(self.failed)
            usable = (stat.S_ISDIR(info.st_mode) and info.st_uid == os.geteuid()
                      and not foreign_entries(self.failed))
        except FileNotFoundError:
            usable = True
        return self.failed if usable else self.failed.with_name(f"{self.failed.name}-{self._token}")

    def _keep_staged(self):
        """Keep what a failed writer staged (``<out>.failed`` or ``out``); say where in one line."""
        try:
            where = self.fail()
        except (ScenarioError, OSError) as error:
            print(f"could not keep the partial output staged in {self.staging} ({error}); it is left there",
                  file=sys.stderr)
            self._keep_staging = True
            return
        print(f"the output written before the run stopped is in {where}/", file=sys.stderr)

    def _install(self, status, target):
        """Manifest the staging directory and swap it in at ``target``; retire what was there."""
        staged = self.stage()
        manifest = {"status": status, "files": {rel: record(staged / rel) for rel in _own_files(staged)}}
        self._io(_write_manifest, staged, manifest)
        arrived = [entry for entry in foreign_entries(target, self.key) if entry not in self.foreign]
        clash = [rel for rel, _ in arrived if _overlaps(rel, manifest["files"])]
        if clash:
            elsewhere = target.with_name(f"{target.name}.new-{self._token}")
            self._io(os.replace, staged, elsewhere)
            raise ScenarioError(self.key, str(target), f"a directory nothing else writes into during the "
                                f"run: {describe(arrived)} appeared in it meanwhile, under names the run "
                                f"writes; this run was written to {elsewhere}/")
        if os.path.lexists(target):
            _copy_mode(target, staged)
            self._io(os.replace, target, self.old)
        self._io(os.replace, staged, target)
        if os.path.lexists(self.old):
            self._retire(self.old, target)

    def _retire(self, old, into):
        """Move what ``old`` holds that spinorbit did not write into ``into``; delete old's own files."""
        overwritten = {rel for rel, _ in self.foreign} if self.force else set()
        for rel, _ in foreign_entries(old, self.key):
            destination = into / rel
            if not os.path.lexists(destination):
                try:
                    destination.parent.mkdir(parents=True, exist_ok=True)
                    os.replace(old / rel, destination)
                except OSError:
                    pass                             # left in the leftover folder below, and said
            elif rel in overwritten:
                _remove_tree(old / rel)              # --force: the new run's file replaces it
        for rel in sorted(_own_files(old), reverse=True):
            try:
                os.unlink(old / rel)
            except OSError:
                pass
        _prune(old)
        if os.path.lexists(old):
            leftover = into.with_name(f"{into.name}.leftover-{self._token}")
            os.replace(old, leftover)
            print(f"kept in {leftover}/ what could be neither moved into {into}/ nor deleted "
                  f"({describe(foreign_entries(leftover))})", file=sys.stderr)

    def _io(self, action, *args):
        """``action(*args)``; an OSError is a one-line refusal on the output directory."""
        try:
            return action(*args)
        except OSError as exc:
            where = f" ({exc.filename})" if exc.filename else ""
            raise ScenarioError(self.key, str(self.out), f"a directory spinorbit can write: "
                                f"{exc.strerror or exc}{where}") from None

    # --- lock, owner and repair --------------------------------------------
    def _acquire(self):
        """Take the lock: flock on ``.<name>.lock`` opened without following links; its content (the
        holder's pid) is written only in a regular file of this user with one link."""
        def refuse(why):
            raise ScenarioError(self.key, str(self.out), f"a directory whose lock file {self.lock} is "
                                f"spinorbit's own ({why}): remove it, or choose another {self.key}")
        self._make_parent()
        try:
            fd = os.open(self.lock, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC,
                         0o644)
        except OSError as exc:
            refuse("it is a symbolic link" if os.path.islink(self.lock) else exc.strerror)
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_uid != os.geteuid() or info.st_nlink != 1:
            os.close(fd)
            refuse(f"it is a {KINDS.get(stat.S_IFMT(info.st_mode), 'special file')}"
                   if not stat.S_ISREG(info.st_mode) else f"it belongs to uid {info.st_uid}"
                   if info.st_uid != os.geteuid() else f"it has {info.st_nlink} hard links")
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 32, 0).decode(errors="replace").strip() or "?"
            os.close(fd)
            raise ScenarioError(self.key, str(self.out), f"a directory no other run is writing (process "
                                f"{holder} holds {self.lock.name}): wait for it, or choose another {self.key}"
                                ) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
        self._lock_fd = fd

    def _make_parent(self):
        """Create ``out``'s parent; refuse a path under a file, or a name too long for its siblings."""
        above = next((p for p in self.out.parents if os.path.lexists(p) and not os.path.isdir(p)), None)
        if above is not None:
            raise ScenarioError(self.key, str(self.out), f"a path through folders ({above} is not a folder)")
        self._io(self.out.parent.mkdir, 0o777, True, True)
        try:
            longest = os.pathconf(self.out.parent, "PC_NAME_MAX") - BESIDE_CHARS
        except (OSError, ValueError):
            longest = 255 - BESIDE_CHARS
        if len(self.out.name.encode()) > longest:
            raise ScenarioError(self.key, str(self.out), f"a name of at most {longest} bytes (spinorbit "
                                "writes siblings such as .<name>.new-<pid>-<random> beside it)")

    def _release(self):
        if self._lock_fd is not None:
            fcntl.flock(self._lock_fd, fcntl.LOCK_UN)
            os.close(self._lock_fd)
            self._lock_fd = None

    def _check_owner(self):
        """Refuse an ``out`` that is not a directory, or another user's (the swap would change its owner)."""
        try:
            info = os.lstat(self.out)
        except FileNotFoundError:
            return
        if not stat.S_ISDIR(info.st_mode):
            raise ScenarioError(self.key, str(self.out), "a directory (this is a "
                                f"{KINDS.get(stat.S_IFMT(info.st_mode), 'special file')})")
        if info.st_uid != os.geteuid() and os.geteuid() != 0:
            raise ScenarioError(self.key, str(self.out), f"a directory of your own (it belongs to uid "
                                f"{info.st_uid}, and a run replaces the directory whole): choose another "
                                f"{self.key}")

    def _repair(self):
        """Finish or undo what a killed run left (we hold the lock, so its writer is gone)."""
        parent, name = self.out.parent, self.out.name
        pattern = re.compile(rf"\.{re.escape(name)}\.(new|old)-\d+(-[0-9a-f]{{8}})?")
        tmp = re.compile(rf"\.{re.escape(self.checkpoint.stem)}(-\w+)?\.npz\.tmp-\d+-\w+")   # verified.write's
        left = {"new": [], "old": []}
        with os.scandir(parent) as entries:
            for entry in entries:
                if (match := pattern.fullmatch(entry.name)) and entry.is_dir(follow_symlinks=False):
                    left[match[1]].append(parent / entry.name)
                elif tmp.fullmatch(entry.name) and entry.is_file(follow_symlinks=False):
                    os.unlink(entry.path)
        complete = [d for d in sorted(left["new"]) if read_manifest(d).get("status") == "ok"]
        if not os.path.lexists(self.out) and (complete or left["old"]):
            os.replace((complete or sorted(left["old"]))[-1], self.out)    # killed between the two renames
        for stale in left["old"]:
            if os.path.lexists(stale):
                self._retire(stale, self.out)            # killed before its foreign entries were moved
        for stale in left["new"]:
            _remove_tree(stale)


def read_manifest(directory):
    """The manifest of a run directory ({} if there is none, or not a regular file spinorbit can read)."""
    try:
        with open_regular(Path(directory) / MANIFEST, follow_links=False) as f:
            manifest = json.loads(f.read(MAX_MANIFEST_BYTES))
    except (OSError, ValueError):
        return {}
    return manifest if isinstance(manifest, dict) and isinstance(manifest.get("files"), dict) else {}


def record(path):
    """A manifest entry: size and sha256 of a file spinorbit wrote."""
    with open_regular(path, follow_links=False) as f:
        return {"size": os.fstat(f.fileno()).st_size, "sha256": _sha256(f)}


def foreign_entries(directory, key="--out"):
    """[(relative path, kind)] of what ``directory`` holds that spinorbit did not write or that changed
    since, top-most only (a folder holding nothing of spinorbit's is one entry), from metadata only."""
    directory = Path(directory)
    try:
        info = os.lstat(directory)
    except FileNotFoundError:
        return []
    if not stat.S_ISDIR(info.st_mode):
        raise ScenarioError(key, str(directory), f"a directory (this is a "
                            f"{KINDS.get(stat.S_IFMT(info.st_mode), 'special file')})")
    found = []
    if _walk(directory, "", read_manifest(directory).get("files", {}), found) is None:
        return [(".", "unreadable folder")]
    return found


def describe(entries, limit=3):
    """'a.txt (file), data (folder), ...' for a refusal."""
    text = ", ".join(f"{rel} ({kind})" for rel, kind in entries[:limit])
    return text + (f", and {len(entries) - limit} more" if len(entries) > limit else "")


def write_whole(path, write):
    """``write(directory)`` into a fresh sibling of ``path``, renamed to ``path`` when done (so that a reader
    sees all of it or nothing); replaces a directory spinorbit wrote there before."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    _remove_tree(tmp)
    tmp.mkdir(parents=True)
    try:
        write(tmp)
        _remove_tree(path)
        os.replace(tmp, path)
    finally:
        _remove_tree(tmp)
    return path


def _walk(root, rel, ours, found):
    """Append to ``found`` the foreign entries under ``root/rel``; True if any entry under it is spinorbit's,
    False if none is, None if the folder cannot be listed."""
    try:
        with os.scandir(root / rel if rel else root) as listing:
            entries = sorted(listing, key=lambda e: e.name)
    except OSError:
        return None
    any_ours, foreign = False, []
    for entry in entries:
        path = f"{rel}/{entry.name}" if rel else entry.name
        try:
            info = entry.stat(follow_symlinks=False)
        except OSError:
            foreign.append((path, "unreadable entry"))
            continue
        kind = KINDS.get(stat.S_IFMT(info.st_mode), "special file")
        if path == MANIFEST and kind == "file":
            continue
        if kind == "folder":
            inside = []
            holds = _walk(root, path, ours, inside)
            if holds:
                any_ours = True
                foreign += inside
            else:
                foreign.append((path, "folder" if holds is False else "unreadable folder"))
        elif kind == "file" and _unchanged(root / path, info, ours.get(path)):
            any_ours = True
        else:
            foreign.append((path, kind))
    found += foreign
    return any_ours


def _unchanged(path, info, recorded):
    """Is the regular file ``path`` (lstat ``info``) the one the manifest records?  Only then is it opened."""
    if isinstance(recorded, dict):
        if recorded.get("size") != info.st_size:
            return False
        recorded = recorded.get("sha256")
    if not isinstance(recorded, str):
        return False
    try:
        with open_regular(path, follow_links=False) as f:
            return _sha256(f) == recorded
    except OSError:
        return False                                  # unreadable: not provably ours


def _sha256(f):
    digest = hashlib.sha256()
    for block in iter(lambda: f.read(1 << 20), b""):
        digest.update(block)
    return digest.hexdigest()


def _own_files(directory):
    """Relative paths of the regular files in ``directory`` (a staging folder, or an old run's own files)."""
    manifest = read_manifest(directory).get("files", {})
    out = []
    for folder, dirs, files in os.walk(directory):
        for name in files:
            path = Path(folder) / name
            rel = path.relative_to(directory).as_posix()
            if rel == MANIFEST or not stat.S_ISREG(os.lstat(path).st_mode):
                continue
            if not manifest or _unchanged(path, os.lstat(path), manifest.get(rel)):
                out.append(rel)
    if manifest:
        out.append(MANIFEST)
    return sorted(out)


def _overlaps(rel, written):
    """Does the foreign entry ``rel`` take a name the run writes (the same path, or a folder above one)?"""
    return any(name == rel or name.startswith(rel + "/") or rel.startswith(name + "/") for name in written)


def _write_manifest(directory, manifest):
    tmp = directory / f"{MANIFEST}.tmp"
    tmp.write_text(json.dumps(manifest, indent=1) + "\n")
    os.replace(tmp, directory / MANIFEST)             # written last: marks the directory complete


def _copy_mode(source, target):
    """Give ``target`` the mode (and, where allowed, owner and group) of ``source``."""
    info = os.stat(source)
    os.chmod(target, stat.S_IMODE(info.st_mode))
    try:
        os.chown(target, info.st_uid, info.st_gid)
    except OSError:
        pass                                          # another group: the owner was checked up front


def _has_content(directory):
    try:
        with os.scandir(directory) as entries:
            return any(True for _ in entries)
    except OSError:
        return False


def _prune(directory):
    """Remove the empty folders under ``directory``, and it too if it ends empty."""
    for folder, _, _ in sorted(os.walk(directory), key=lambda w: -len(w[0])):
        try:
            os.rmdir(folder)
        except OSError:
            pass


def _remove_tree(path):
    """Remove a file, link or folder spinorbit made (staging and temporary folders), as far as it can;
    never follows a link."""
    try:
        if not stat.S_ISDIR(os.lstat(path).st_mode):
            os.unlink(path)
            return
    except OSError:
        return

    def writable_and_retry(function, name, _):
        try:
            os.chmod(os.path.dirname(name), 0o700)    # a read-only folder of ours
            function(name)
        except OSError:
            pass

    shutil.rmtree(path, **{"onexc" if sys.version_info >= (3, 12) else "onerror": writable_and_retry})
