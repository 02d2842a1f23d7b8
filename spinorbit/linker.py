"""Compiled kernels bound to the functions they call, compiled once and cached on disk.

numba caches a function only when everything it calls is a module-level name:
a function passed as an argument, or captured by a closure, is a "dynamic
global" and defeats ``cache=True`` (every process would compile again).  A
*template* is a plain Python function that calls some functions by free names
(``rhs``, ``torque``, ``positions``) or reads compile-time constants
(``N_MAX``); :func:`link` writes a small module that imports those names,
appends the template's source under ``@njit(cache=True, nogil=True)`` and
imports it (without the GIL, two runs can share a machine's cores from threads).
The module's file name carries a hash of its source and of the package's
sources, so a change anywhere in spinorbit compiles afresh, and the same
binding in a later process loads numba's cache instead of compiling.

    >>> @template("rhs")
    ... def euler_step(t, y, p, h):
    ...     return y + h * rhs(t, y, p)
    >>> step = link(euler_step, rhs=my_compiled_rhs)      # doctest: +SKIP

Generated modules live in ``$SPINORBIT_CACHE_DIR`` (default
``~/.cache/spinorbit``, or a temporary directory when that is not writable).
"""
import functools
import hashlib
import importlib
import inspect
import os
import sys
import tempfile
import textwrap
import threading
import types
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent


def template(*free_names):
    """Mark a function as a template whose ``free_names`` are bound by :func:`link`."""

    def mark(fn):
        fn.free_names = free_names
        return fn

    return mark


@functools.cache
def cache_dir():
    """Directory of the generated modules, on ``sys.path`` so that they import each other."""
    home = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache"))
    for candidate in (os.environ.get("SPINORBIT_CACHE_DIR"), home / "spinorbit",
                      Path(tempfile.gettempdir()) / f"spinorbit-{os.getuid()}"):
        if candidate is None:
            continue
        path = Path(candidate) / "kernels"
        try:
            path.mkdir(parents=True, exist_ok=True)
            probe = path / f".probe-{os.getpid()}"
            probe.write_text("")
            probe.unlink()
        except OSError:
            continue
        sys.path.insert(0, str(path))
        return path
    raise OSError("no writable cache directory for compiled kernels; set SPINORBIT_CACHE_DIR")


@functools.cache
def package_fingerprint():
    """Hash of every source file of the package and of numba's version."""
    import numba

    digest = hashlib.sha256(numba.__version__.encode())
    for path in sorted(PACKAGE_DIR.rglob("*.py")):
        digest.update(path.relative_to(PACKAGE_DIR).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def link_source(name, source, **bindings):
    """Compile generated source defining function ``name`` (a template written by code, e.g. a sum
    of terms) with its free names bound as in :func:`link`; cached on disk like any template."""
    with _LOCK:
        return _link_generated(name, source, tuple(sorted(bindings.items(), key=lambda kv: kv[0])))


def link(fn, **bindings):
    """The compiled, disk-cached version of template ``fn`` with its free names bound.

    A binding is a compiled function defined at module level (or returned by
    ``link``) or a compile-time constant (bool, int, float).
    """
    missing = sorted(set(fn.free_names) - set(bindings))
    extra = sorted(set(bindings) - set(fn.free_names))
    if missing or extra:
        raise TypeError(f"link({fn.__name__}): bind exactly {list(fn.free_names)}; "
                        f"missing {missing}, unexpected {extra}")
    with _LOCK:                                  # threads of one process link one at a time
        return _link(fn, tuple(sorted(bindings.items(), key=lambda kv: kv[0])))


_LOCK = threading.RLock()


@functools.cache
def _link(fn, bindings):
    return _load(fn.__name__, _module_source(fn, dict(bindings)), bindings)


@functools.cache
def _link_generated(name, source, bindings):
    fn = types.SimpleNamespace(__name__=name, __module__=__name__, source=source)
    return _load(name, _module_source(fn, dict(bindings)), bindings)


def _load(fn_name, source, bindings):
    outside = [_file_hash(value) for _, value in bindings if hasattr(value, "py_func")]
    key = hashlib.sha256("".join([package_fingerprint(), *outside, source]).encode()).hexdigest()[:20]
    name = f"spinorbit_{fn_name.strip('_')}_{key}"
    path = cache_dir() / f"{name}.py"
    if not path.exists():                        # other processes may write it at the same time
        handle, tmp = tempfile.mkstemp(suffix=".tmp", dir=path.parent)
        with os.fdopen(handle, "w") as file:
            file.write(source)
        os.replace(tmp, path)
    return getattr(importlib.import_module(name), fn_name)


def _file_hash(function):
    """Hash of the file defining a bound function outside the package (numba would not see it change)."""
    path = Path(inspect.getsourcefile(function.py_func)).resolve()
    if PACKAGE_DIR in path.parents or path.parent == cache_dir().resolve():
        return ""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _module_source(fn, bindings):
    lines = [f"# Generated by spinorbit.linker from {fn.__module__}.{fn.__name__}; do not edit.",
             "from numba import njit", "import numpy as np"]
    generated = getattr(fn, "source", None)
    if generated is None:
        for name in sorted(_global_names(fn.__code__) - set(bindings) - {"np"}):
            if name in fn.__globals__:
                lines.append(_import_line(fn.__globals__[name], name, fn.__module__))
    for name, value in bindings.items():
        if isinstance(value, (bool, int, float)):
            lines.append(f"{name} = {value!r}")
        else:
            lines.append(_function_import(value, name))
    body = generated or textwrap.dedent(inspect.getsource(fn))
    body = body[body.index("def "):]                      # drop the decorators
    return "\n".join(lines) + "\n\n\n@njit(cache=True, nogil=True)\n" + body


def _global_names(code):
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _global_names(const)
    return names


def _import_line(value, name, home):
    if isinstance(value, types.ModuleType):
        return f"import {value.__name__} as {name}"
    return f"from {home} import {name}"


def _function_import(value, name):
    py_func = getattr(value, "py_func", None)
    if py_func is None:
        raise TypeError(f"link: {name} must be a compiled (numba) function or a constant, got {value!r}")
    module, attr = py_func.__module__, py_func.__name__
    if getattr(sys.modules.get(module), attr, None) is not value:
        raise TypeError(f"link: {name} = {module}.{attr} is not a module-level function "
                        "(closures defeat numba's cache; write it as a template and link it)")
    return f"from {module} import {attr} as {name}"
