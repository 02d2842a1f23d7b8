"""``@cached``: numba's ``njit(cache=True)`` for a function that calls functions, or reads constants, of other
files.

numba keys a cached function's compiled code by its own bytecode and stamps its index with its own file's time
and size, so an edit to a callee's file alone leaves the caller running the old callee (a limitation numba's
documentation states, "Cache invalidation fails to recognize changes in symbols defined in a different file";
numba issue #1833).  :class:`ReachCache` adds to the key the :func:`spinorbit.base.linker.fingerprint` of what the
function reaches in its package (the sources of the modules whose functions and constants it uses, followed
through compiled callees, and numba's version), as the linker names its generated kernels: after such an edit
the key is new and the function compiles afresh; with none, a later process loads the cache as before.  The
fingerprint is taken at the first compilation (every module the function names is imported by then), once per
process.  Entries of older keys stay in the index until the function's own file changes (numba then starts
it anew) or the cache is cleared.
"""
import sys
from pathlib import Path

from numba import njit
from numba.core.caching import FunctionCache


def cached(function=None, **options):
    """``@cached`` or ``@cached(nogil=True, ...)``: ``numba.njit(**options)`` with its compiled code cached on
    disk by :class:`ReachCache` (where numba caches any ``cache=True`` function)."""

    def compile_cached(fn):
        dispatcher = njit(**options)(fn)
        if hasattr(dispatcher, "py_func"):        # not under NUMBA_DISABLE_JIT (the plain function)
            dispatcher._cache = ReachCache(dispatcher.py_func)
        return dispatcher

    return compile_cached if function is None else compile_cached(function)


class ReachCache(FunctionCache):
    """numba's FunctionCache, its index key extended by the fingerprint of what the function reaches."""

    def __init__(self, py_func):
        super().__init__(py_func)
        self._reach = None

    def _index_key(self, sig, codegen):
        if self._reach is None:
            from . import fingerprint

            self._reach = fingerprint(self._py_func, package_root(self._py_func.__module__))
        return (*super()._index_key(sig, codegen), self._reach)


def package_root(module_name):
    """The folder of the top-level package holding ``module_name`` (the reach a fingerprint follows)."""
    top = sys.modules[module_name.partition(".")[0]]
    return Path(top.__file__).resolve().parent
