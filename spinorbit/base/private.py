"""The rule a folder must meet before spinorbit runs or unpickles anything kept in it (the kernel cache, numba's
cache, heyoka's, the orbital solutions): a directory of yours, writable by you only, inside folders only you (or
root) can rename.  A folder that breaks it is refused in one line naming the environment variable that chose it.
Checked before ``numba`` is imported: ``NUMBA_CACHE_DIR`` is read once, when numba loads.  The cache directory
itself (``root``, ``kernels_dir``, ``private_folder``) is found here, without numba, so that reading a stored
answer never imports it."""
import functools
import os
import stat
import sys
from pathlib import Path

from .errors import InputError

NUMBA = "NUMBA_CACHE_DIR"
ENVIRONMENT = "SPINORBIT_CACHE_DIR"


def check_private(folder, named, variable, purpose="compiled kernels"):
    """Refuse ``folder`` (InputError on ``variable``, which named it as ``named``) unless it is a directory of
    this user's that others cannot write."""
    info = os.lstat(folder)
    mode = stat.S_IMODE(info.st_mode)
    why = ("it is not a directory" if not stat.S_ISDIR(info.st_mode)
           else f"{folder} belongs to uid {info.st_uid}" if info.st_uid != os.geteuid()
           else f"{folder} is writable by others (mode {mode:o})" if mode & 0o022 else None)
    if why:
        raise InputError(variable, str(named), f"a private directory for {purpose}, yours and writable by you "
                                               f"only ({why}); set {variable} to one")


def check_above(folder, named, variable, purpose="compiled kernels"):
    """Refuse a ``folder`` above a cache that another user could rename things in (writable by others without
    the sticky bit, or another user's)."""
    info = os.stat(folder)
    others_write = info.st_mode & 0o022 and not info.st_mode & stat.S_ISVTX
    if others_write or info.st_uid not in (0, os.geteuid()):
        what = "writable by others" if others_write else "another user's"
        raise InputError(variable, str(named), f"a private directory for {purpose} in folders only you (or root) "
                                               f"can change ({folder} is {what}); set {variable} to one")


@functools.cache
def numba_cache_refusal():
    """The InputError for a ``NUMBA_CACHE_DIR`` that breaks the rule (numba unpickles its index files: a
    planted one would run), or None when it is unset or private; judged once per process, when spinorbit is
    imported (which then hides a refused folder from numba).  A folder not made yet is judged by the
    folders above it (numba makes it without write access for others)."""
    named = os.environ.get(NUMBA)
    if not named:
        return None
    path = Path(named).expanduser().absolute()
    purpose = "numba's cache of spinorbit's compiled functions"
    try:
        if os.path.lexists(path):
            check_private(path, named, NUMBA, purpose)
            path = path.resolve()
        for folder in path.parents:
            if os.path.lexists(folder):
                check_above(folder, named, NUMBA, purpose)
    except InputError as refusal:
        return refusal
    except OSError as exc:
        return InputError(NUMBA, named, f"a directory numba can use ({exc.strerror}); unset {NUMBA} or set it "
                                        "to one")
    return None


def root():
    """The cache directory named by the environment (not created)."""
    named = os.environ.get(ENVIRONMENT)
    if named:
        return Path(named).expanduser().absolute()
    home = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(home).expanduser().absolute() / "spinorbit"


@functools.cache
def kernels_dir():
    """The private directory of the generated modules (created 0700; refused if not private, and refused when
    NUMBA_CACHE_DIR is not: spinorbit.base.private)."""
    refusal = numba_cache_refusal()
    if refusal is not None:
        raise refusal
    base = root()
    try:
        base.parent.mkdir(parents=True, exist_ok=True)
        for folder in (base, base / "kernels", base / "kernels" / "numba"):
            if not os.path.lexists(folder):
                os.mkdir(folder, 0o700)
        resolved = base.resolve()
    except OSError as exc:
        raise InputError(ENVIRONMENT, str(base), f"a directory spinorbit can create for its compiled kernels "
                                                 f"({exc.strerror}); set {ENVIRONMENT} to one") from None
    for folder in (resolved, resolved / "kernels", resolved / "kernels" / "numba"):
        check_private(folder, base, ENVIRONMENT)
    for folder in resolved.parents:
        check_above(folder, base, ENVIRONMENT)
    return resolved / "kernels"


def private_folder(name):
    """``<the cache directory>/<name>``, created private (0700) beside the kernels and refused, under the same
    rule, when it is not (another user's, writable by others, or not a directory)."""
    folder = kernels_dir().parent / name
    try:
        if not os.path.lexists(folder):
            os.mkdir(folder, 0o700)
    except OSError as exc:
        raise InputError(ENVIRONMENT, str(root()), f"a directory spinorbit can create for its caches ({folder}: "
                                                   f"{exc.strerror}); set {ENVIRONMENT} to one") from None
    check_private(folder, root(), ENVIRONMENT, "spinorbit's caches")
    return folder


def say(message):
    print(f"spinorbit: {message}", file=sys.stderr)
