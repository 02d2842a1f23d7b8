"""A second user for attacker tests: ``as_user(fn, *args)`` runs ``fn`` in a forked child as uid/gid
``OTHER`` (65534, "nobody"), which needs root; ``shared_dir()`` is a sticky world-writable folder both
can use."""
import os
import pickle
import tempfile
from pathlib import Path

import pytest

OTHER = 65534
IS_ROOT = os.geteuid() == 0
needs_root = pytest.mark.skipif(not IS_ROOT, reason="a second user needs root (setuid / chown to uid 65534)")


def as_user(fn, *args, uid=OTHER):
    """``fn(*args)`` run as ``uid`` in a forked child; its return value, or its exception raised here as
    a RuntimeError naming it."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:                                     # the child: drop to the other user, run, report
        os.close(read)
        try:
            os.setgroups([])
            os.setgid(uid)
            os.setuid(uid)
            outcome = ("ok", fn(*args))
        except BaseException as exc:  # noqa: BLE001 (the forked child reports anything to the parent)
            outcome = ("raised", f"{type(exc).__name__}: {exc}")
        with os.fdopen(write, "wb") as pipe:
            pipe.write(pickle.dumps(outcome))
        os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        data = pipe.read()
    os.waitpid(pid, 0)
    kind, value = pickle.loads(data)
    if kind == "raised":
        raise RuntimeError(value)
    return value


def chown_other(*paths):
    for path in paths:
        os.lchown(path, OTHER, OTHER)


def shared_dir():
    """A fresh sticky, world-writable folder in the temporary directory (as /tmp is)."""
    path = Path(tempfile.mkdtemp(prefix="spinorbit-shared-"))
    os.chmod(path, 0o1777)
    return path
