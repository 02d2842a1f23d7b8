"""The kernel cache: a private directory that holds only spinorbit's own generated code and numba's
compiled copies of it, each checked before it is run.

Where: ``$SPINORBIT_CACHE_DIR``, else ``$XDG_CACHE_HOME/spinorbit`` (``~/.cache/spinorbit``); the
generated modules in ``kernels/``, numba's files for them in ``kernels/numba/``.  The directories
are created private (0700) and refused, in one line naming SPINORBIT_CACHE_DIR, when one of them is
another user's or writable by others, or a folder above them can be renamed by another user
(writable by others without the sticky bit, or another user's).  There is no fallback into a shared
temporary directory.

A generated module is named after the sha256 of its text.  It is written atomically (a temporary
file in the same directory, fsync, rename, ``importlib.invalidate_caches``) and run only when the
file's bytes are the text expected (so its hash matches its name): the verified bytes are compiled
and executed as the module, registered in ``sys.modules`` (where numba's cache index and other
generated modules find it), never imported through ``sys.path``.  A file that differs (truncated,
damaged, edited) is rewritten, and said in one line; one that cannot be written (a full disk) is run from the
verified bytes in memory, said in one line.

numba's cache files are pickles, so they are trusted only as far as they are checked: a generated kernel's
index and data files live in the private ``kernels/numba/`` whatever NUMBA_CACHE_DIR says, each a file of the
verified room (spinorbit.base.verified: the pickle's bytes hashed, numba's version as its record, written aside and
renamed) that is checked before it is unpickled; a damaged one is deleted, the kernel compiled again, and said
in one line.  The generated modules stay plain ``.py`` files, checked by their name (the sha256 of their text),
because numba and tracebacks read a function's source from its file.  Functions of the package itself,
``@njit(cache=True)``, are cached by numba beside them (the same trust as the package's own files and their
``.pyc``) or in NUMBA_CACHE_DIR, which must meet the same rule: ``import spinorbit`` hides a NUMBA_CACHE_DIR
that breaks it from numba, and the first kernel asked for refuses it in one line (spinorbit.base.private).
"""
import errno
import hashlib
import importlib
import importlib.abc
import importlib.util
import os
import pickle
import stat
import sys
from pathlib import Path

import numpy as np
from numba import njit
from numba.core.caching import CompileResultCacheImpl, FunctionCache, IndexDataCacheFile, _CacheLocator

from .. import verified
from ..files import write_atomically
from ..private import ENVIRONMENT, kernels_dir, private_folder, root, say  # noqa: F401  (cache.root, ...)

LOADED = {}                          # generated module name -> sha256 of its text, for this process


def load_module(name, text):
    """The generated module ``name`` (its text ``text``), written to the cache if it is missing or differs."""
    path = kernels_dir() / f"{name}.py"
    expected = text.encode()
    found = _read_own(path)
    if found != expected:
        if found is not None:
            say(f"the compiled-kernel cache entry {path} was damaged (its content does not match its name); "
                "rebuilt")
            remove_compiled(name)
        try:
            _write_atomically(path, expected)
        except OSError as exc:              # a full disk: the module runs from the bytes in memory, not cached
            say(f"the compiled-kernel cache entry {path} could not be written ({exc.strerror or exc}); compiled "
                "for this process only")
    spec = importlib.util.spec_from_file_location(name, path, loader=_VerifiedSource(path, expected))
    module = importlib.util.module_from_spec(spec)
    LOADED[name] = hashlib.sha256(expected).hexdigest()
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module


class _VerifiedSource(importlib.abc.SourceLoader):
    """Loads a generated module from the bytes already checked (never from the file again, nor a .pyc)."""

    def __init__(self, path, data):
        self.path, self.data = str(path), data

    def get_filename(self, fullname):
        return self.path

    def get_data(self, path):
        return self.data


def _read_own(path):
    """The bytes of a regular file of this user at ``path`` (None if there is none or it is not one)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_uid != os.geteuid():
            return None
        return f.read()


def _write_atomically(path, data):
    write_atomically(path, lambda f: f.write(data))
    importlib.invalidate_caches()


def remove_compiled(module_name):
    """Delete numba's cache files of a generated module's functions."""
    folder = kernels_dir() / "numba"
    for entry in os.scandir(folder):
        if entry.name.startswith(module_name + ".") and not entry.is_dir(follow_symlinks=False):
            os.unlink(entry.path)


def kernel(function):
    """``@kernel`` in a generated module: ``njit(nogil=True)`` with its compiled code cached, checked,
    in the private cache (numba's ``Dispatcher.enable_caching`` with :class:`CheckedCache`)."""
    dispatcher = njit(nogil=True)(function)
    if not hasattr(dispatcher, "py_func"):          # NUMBA_DISABLE_JIT: the plain function, nothing to cache
        return dispatcher
    dispatcher._cache = CheckedCache(dispatcher.py_func)
    return dispatcher


def clear():
    """Delete every generated module and compiled copy (the kernels folder is spinorbit's alone); return
    the number of files removed."""
    folder = kernels_dir()
    removed = 0
    for path, dirs, files in os.walk(folder, topdown=False):
        for name in files:
            os.unlink(Path(path) / name)
            removed += 1
        for name in dirs:
            if Path(path) / name != folder / "numba":
                os.rmdir(Path(path) / name)
    return removed


class _Locator(_CacheLocator):
    """numba's files for a generated module: in the private ``kernels/numba``, stamped with the
    module's verified hash (not re-read from its path)."""

    def __init__(self, py_func):
        self._py_file = py_func.__code__.co_filename
        self._lineno = py_func.__code__.co_firstlineno
        self._stamp = LOADED[py_func.__module__]

    def ensure_cache_path(self):
        kernels_dir()

    def get_cache_path(self):
        return str(kernels_dir() / "numba")

    def get_source_stamp(self):
        return self._stamp

    def get_disambiguator(self):
        return str(self._lineno)


class _Impl(CompileResultCacheImpl):
    def __init__(self, py_func):                     # CacheImpl's, with the one locator and no lookup
        self._lineno = py_func.__code__.co_firstlineno
        self._locator = _Locator(py_func)
        self._filename_base = self.get_filename_base(f"{py_func.__module__}.{py_func.__qualname__}",
                                                     getattr(sys, "abiflags", ""))


class _CheckedFile(IndexDataCacheFile):
    """numba's index and data files, each a verified file (the pickle's bytes, numba's version as the record);
    unpickled only when intact."""

    def _load_index(self):
        try:
            payload = self._read_checked(self._index_path)
        except FileNotFoundError:
            return {}
        if payload is None:
            return {}                                 # another numba version's index
        stamp, overloads = pickle.loads(payload)
        return overloads if stamp == self._source_stamp else {}

    def _save_index(self, overloads):
        self._write_checked(self._index_path, self._dump((self._source_stamp, overloads)))

    def _load_data(self, name):
        payload = self._read_checked(self._data_path(name))
        if payload is None:
            raise verified.Damaged(f"{name} was written by another numba version")
        return pickle.loads(payload)

    def _save_data(self, name, data):
        self._write_checked(self._data_path(name), self._dump(data))

    def _read_checked(self, path):
        """The pickle's bytes at ``path``; None when another numba version wrote them; FileNotFoundError when there
        is no file, verified.Damaged (the file named) when it is not intact."""
        try:
            entry = verified.read(path)
        except verified.Damaged as exc:
            raise verified.Damaged(f"{os.path.basename(path)}: {exc}") from None
        if entry is None:
            raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), path)
        return entry.arrays["pickle"].tobytes() if entry.record == {"numba": self._version} else None

    def _write_checked(self, path, payload):
        verified.write(path, {"pickle": np.frombuffer(payload, np.uint8)}, {"numba": self._version})

    def remove(self):
        """Delete this function's index and data files."""
        base = os.path.basename(self._index_path)[:-len(".nbi")]
        for entry in os.scandir(self._cache_path):
            if entry.name.startswith(base + ".") and not entry.is_dir(follow_symlinks=False):
                os.unlink(entry.path)


UNREADABLE = (verified.Damaged, pickle.UnpicklingError, EOFError, ValueError, TypeError, AttributeError, ImportError,
              IndexError, KeyError)


class CheckedCache(FunctionCache):
    """numba's FunctionCache for a generated kernel: files in the private cache, hash-checked; a damaged
    entry is deleted, compiled again and said in one line."""

    _impl_class = _Impl

    def __init__(self, py_func):
        super().__init__(py_func)
        self._cache_file = _CheckedFile(self._cache_path, self._impl.filename_base,
                                        self._impl.locator.get_source_stamp())

    def load_overload(self, sig, target_context):
        try:
            return super().load_overload(sig, target_context)
        except UNREADABLE as exc:
            self._repair(exc)
        except OSError:                               # e.g. the cache cleared meanwhile: compile
            pass
        return None

    def save_overload(self, sig, data):
        try:
            try:
                super().save_overload(sig, data)
            except UNREADABLE as exc:                 # the index it adds to was damaged
                self._repair(exc)
                super().save_overload(sig, data)
        except OSError as exc:
            say(f"could not save the compiled {self._py_func.__qualname__} in {self._cache_path} "
                f"({exc.strerror or exc}); it compiles again in the next run")

    def _repair(self, exc):
        say(f"numba's cache entry of {self._py_func.__qualname__} in {self._cache_path} was damaged ({exc}); "
            "compiled again")
        self._cache_file.remove()
