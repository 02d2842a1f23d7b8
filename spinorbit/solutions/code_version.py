"""The code's version a stored solution is keyed by: spinorbit's version and a sha256 of every Python file of the
package, hashed once per install rather than in every process.

The package's files are listed with their stat (relative path, size, mtime_ns, ctime_ns, inode): the sha256 of
that list is a fingerprint, and the content hash made under it is kept in the private cache
(``code-<package>.json`` beside the stored solutions).  A process whose fingerprint matches the record reads the
version from it; any change to a file (its content, size or times: ctime cannot be set back by a user) or to the
list of files changes the fingerprint, and the sources are hashed again and the record rewritten (aside, then
renamed).  The record is JSON, never executed; one that cannot be read is said in one line and made again.
"""
import functools
import hashlib
import json
import os
import shutil
from pathlib import Path

from ..base import private
from ..base.files import open_regular

PACKAGE = Path(__file__).resolve().parents[1]
HEX = frozenset("0123456789abcdef")


def sources(package):
    """[(relative path, stat)] of the package's Python files, sorted by path."""
    found, root = [], str(package)

    def scan(folder, prefix):
        with os.scandir(folder) as entries:
            for entry in entries:
                if entry.is_dir(follow_symlinks=False) and entry.name != "__pycache__":
                    scan(entry.path, f"{prefix}{entry.name}/")
                elif entry.name.endswith(".py"):
                    found.append((prefix + entry.name, entry.stat()))

    scan(root, "")
    return sorted(found)


def fingerprint(files):
    """sha256 of the files' paths and stats (size, mtime_ns, ctime_ns, inode)."""
    listing = [[name, s.st_size, s.st_mtime_ns, s.st_ctime_ns, s.st_ino] for name, s in files]
    return hashlib.sha256(json.dumps(listing).encode()).hexdigest()


def content_hash(package, files):
    """sha256 (16 hex digits) of every file's relative path and bytes."""
    digest = hashlib.sha256()
    for name, _ in files:
        digest.update(name.encode() + b"\0" + (package / name).read_bytes())
    return digest.hexdigest()[:16]


def record_path(directory, package):
    """Where the record of ``package`` is kept in ``directory`` (one per installed copy)."""
    return directory / f"code-{hashlib.sha256(str(package).encode()).hexdigest()[:16]}.json"


def stored(path, stamp):
    """The content hash recorded at ``path`` under fingerprint ``stamp``, or None (no record, another stamp, or
    an unreadable record: said in one line)."""
    try:
        with open_regular(path, "r", follow_links=False) as f:
            record = json.load(f)
        content = record["content"]
        if not (isinstance(content, str) and len(content) == 16 and all(c in HEX for c in content)):
            raise ValueError(f"its content hash is {content!r}, not 16 hex digits")
        return content if record["fingerprint"] == stamp else None
    except FileNotFoundError:
        return None
    except (OSError, ValueError, KeyError, TypeError) as exc:
        private.say(f"the code-version record {path} was refused ({type(exc).__name__}: {exc}); hashing the "
                  "sources again")
        return None


def store(path, stamp, content):
    """Write the record aside and rename it over ``path`` (atomic)."""
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    if path.is_dir() and not path.is_symlink():          # a folder where the record belongs (the cache is ours)
        shutil.rmtree(path, ignore_errors=True)
    try:
        with open(tmp, "w") as f:
            json.dump({"fingerprint": stamp, "content": content}, f)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def content_version(package, directory):
    """The sha256 (16 hex digits) of ``package``'s Python files: read from the record in ``directory`` when the
    files' stats match it, else hashed and recorded."""
    files = sources(package)
    stamp, path = fingerprint(files), record_path(directory, package)
    content = stored(path, stamp)
    if content is None:
        content = content_hash(package, files)
        try:
            store(path, stamp, content)
        except OSError as exc:               # the version stands; only its record is not kept
            private.say(f"the code-version record {path} could not be written ({exc.strerror or exc}); the sources "
                      "are hashed again next time")
    return content


@functools.cache
def package_version(directory):
    """spinorbit's version and the sha256 (16 hex digits) of every Python file of the package, its record kept
    in ``directory`` (the solution store's)."""
    from ..base.version import __version__

    return f"{__version__}+{content_version(PACKAGE, directory)}"
