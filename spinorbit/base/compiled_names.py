"""Names of compiled code that no other process gives: numba's function numbers started at random per process.

numba names a compiled function's machine code and its environment (the list of Python constants its wrapper
reads, e.g. the dtype of an array it returns) by its qualified name, its argument types and a number counted
from 1 in every process (``FunctionIdentity._unique_ids``), and keeps one environment per name in a process.
Compiled code from numba's disk caches carries the names of the process that compiled it.  So when a process
loads a cached library (a kernel with a callee linked in) and then compiles that callee afresh (another cache
folder, a new signature) under a number the loaded library already used, both share one environment: the fresh
compile appends its dtype after the unpickled one, and saves code that reads the second entry.  A later process
that loads the first library before it gives that code the one-entry environment, and the call returns
``RuntimeError: In 'NRT_adapt_ndarray_to_python', 'descr' is NULL``.

Starting the count at a random 48-bit number in each process (and again in a forked child) makes a name
compiled in one process one that no other process compiles: code and environment under one name always come
from one compilation.  :func:`install` does it when numba is imported (it is called by ``import spinorbit``,
which does not import numba itself).
"""
import importlib.abc
import importlib.machinery
import itertools
import os
import secrets
import sys

COUNTER_MODULE = "numba.core.bytecode"


def install():
    """Start numba's function count at random now if numba is loaded, else as soon as it is."""
    module = sys.modules.get(COUNTER_MODULE)
    if module is not None:
        _start_at_random(module)
    elif not any(isinstance(finder, _AfterImport) for finder in sys.meta_path):
        sys.meta_path.insert(0, _AfterImport())


def _start_at_random(module):
    identity = module.FunctionIdentity
    identity._unique_ids = itertools.count(secrets.randbits(48))
    if not getattr(identity, "_spinorbit_fork_hook", False):
        identity._spinorbit_fork_hook = True
        os.register_at_fork(after_in_child=lambda: _start_at_random(module))


class _AfterImport(importlib.abc.MetaPathFinder):
    """Finds numba's counter module as the path finder does, and starts its count once it has run."""

    def find_spec(self, name, path, target=None):
        if name != COUNTER_MODULE:
            return None
        sys.meta_path.remove(self)
        spec = importlib.machinery.PathFinder.find_spec(name, path, target)
        if spec is not None and spec.loader is not None:
            run = spec.loader.exec_module

            def exec_module(module):
                run(module)
                _start_at_random(module)

            spec.loader.exec_module = exec_module
        return spec
