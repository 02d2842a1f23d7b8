"""Compiled kernels bound to the functions they call, compiled once and cached on disk.

numba caches a function only when everything it calls is a module-level name:
a function passed as an argument, or captured by a closure, is a "dynamic
global" and defeats ``cache=True`` (every process would compile again).  A
*template* is a plain Python function that calls some functions by free names
(``rhs``, ``torque``, ``positions``) or reads compile-time constants
(``N_MAX``), declared in its module with :func:`free` so that readers and
linters can follow them.  :func:`link` writes a small module that imports those
names, appends the template's source under ``@kernel`` (``njit(nogil=True)``
with its compiled code cached: :mod:`spinorbit.base.linker.cache`) and loads it
(without the GIL, two runs can share a machine's cores from threads).

    >>> rhs = free("rhs")                                  # bound by link()
    >>> @template("rhs")
    ... def euler_step(t, y, p, h):
    ...     return y + h * rhs(t, y, p)
    >>> step = link(euler_step, rhs=my_compiled_rhs)      # doctest: +SKIP

The generated module is named after the sha256 of its text, and the text carries
the :func:`fingerprint` of what the template and its bound functions reach: the
source files of the modules whose functions and constants they use, followed
through compiled callees, and numba's version.  So editing a module no kernel
reaches leaves every kernel warm, editing one a kernel reaches compiles that
kernel afresh, and the same binding in a later process loads numba's cache.
Generated modules live in a private directory (``$SPINORBIT_CACHE_DIR``,
default ``~/.cache/spinorbit``) and are run only when their content matches
their name (:mod:`spinorbit.base.linker.cache`).

A plain compiled function that calls functions of other files by their module-level names needs no template:
``@linker.cached`` (:mod:`spinorbit.base.linker.stamped`) is ``njit`` whose disk cache is keyed by the same
fingerprint, so editing a callee's file compiles it afresh (numba's own ``cache=True`` sees its own file only).
"""
import functools
import hashlib
import inspect
import marshal
import sys
import textwrap
import threading
import types
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parents[2]
NAMES = "names unique per process"   # spinorbit.base.compiled_names: caches written before it are not read
FILES = "verified numba files"      # linker.cache's files in the verified room: caches written before are not read


class Free:
    """A template's free name, declared at module level (``rhs = free("rhs")``); :func:`link` binds it."""

    def __init__(self, name):
        self.name = name

    def __repr__(self):
        return f"free({self.name!r})"

    def __call__(self, *args):
        raise TypeError(f"{self.name} is a free name of a template: compile the template with "
                        f"linker.link(template, {self.name}=...) and call what it returns")


def free(*names):
    """Placeholders for a module's templates' free names: ``rhs = free("rhs")``,
    ``positions, terms = free("positions", "terms")``."""
    return Free(names[0]) if len(names) == 1 else tuple(Free(name) for name in names)


def template(*free_names):
    """Mark a function as a template whose ``free_names`` are bound by :func:`link` (by default, the
    names it uses that its module declares with :func:`free`)."""

    def mark(fn):
        fn.free_names = free_names or tuple(sorted(name for name in _global_names(fn.__code__)
                                                   if isinstance(fn.__globals__.get(name), Free)))
        return fn

    return mark


def cached(function=None, **options):
    """``@linker.cached``: :func:`spinorbit.base.linker.stamped.cached` (numba imported when a module applies it)."""
    from .stamped import cached as stamped

    return stamped(function, **options)


class OnDemand:
    """A module's plain-numba functions compiled (``njit(**options)``) when one is first asked for, so that
    importing the module imports no numba: decorate each with the instance, then end the module with
    ``__getattr__ = on_demand.hide(globals())``.  The first name asked for (``from module import dot3``, or
    ``module.dot3``) compiles them all into the module's globals, where they find each other as numba needs;
    ``source(name)`` is the Python function itself, for callers on whole arrays."""

    def __init__(self, **options):
        self.options, self.sources, self.namespace = options, {}, None

    def __call__(self, function):
        self.sources[function.__name__] = function
        return function

    def source(self, name):
        return self.sources[name]

    def hide(self, namespace):
        for name in self.sources:
            del namespace[name]
        self.namespace = namespace
        return self.attribute

    def attribute(self, name):
        if name not in self.sources:
            raise AttributeError(f"module {self.namespace['__name__']!r} has no attribute {name!r}")
        with _LOCK:
            if name not in self.namespace:
                from numba import njit

                for key, function in self.sources.items():
                    self.namespace[key] = njit(**self.options)(function)
        return self.namespace[name]


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


def fingerprint(function, root=PACKAGE_DIR):
    """sha256 (hex) of what ``function`` (a template, a compiled or a plain function) reaches in the package at
    ``root`` (:func:`reached`) and of numba's version."""
    import numba

    sources = reached(function, root)
    digest = hashlib.sha256(f"numba {numba.__version__}, {NAMES}, {FILES}".encode())
    for module in sorted(sources):
        digest.update(f"\0{module}\0".encode())
        digest.update(sources[module])
    return digest.hexdigest()


def reached(function, root=PACKAGE_DIR):
    """{module name: its source bytes} of the modules whose functions and constants ``function`` uses,
    followed through compiled callees, and of the package's (under ``root``, spinorbit's by default) through
    plain ones; a generated module stands by the hash of its text (which holds its own reach), a module without
    a file by the function's code."""
    sources = {}
    _reach(getattr(function, "py_func", function), sources, set(), _Package(root))
    return sources


def python_function(kernel):
    """The Python function a compiled kernel runs (the function itself under NUMBA_DISABLE_JIT), or None
    when ``kernel`` is not one."""
    if hasattr(kernel, "py_func"):
        return kernel.py_func
    import numba

    return kernel if numba.config.DISABLE_JIT and isinstance(kernel, types.FunctionType) else None


_LOCK = threading.RLock()


@functools.cache
def _link(fn, bindings):
    reach = [fingerprint(fn)] + [fingerprint(value) for _, value in bindings if python_function(value)]
    return _load(fn.__name__, _module_source(fn, dict(bindings), reach))


@functools.cache
def _link_generated(name, source, bindings):
    fn = types.SimpleNamespace(__name__=name, __module__=__name__, source=source)
    reach = [fingerprint(value) for _, value in bindings if python_function(value)]
    return _load(name, _module_source(fn, dict(bindings), reach))


def _load(fn_name, text):
    from . import cache

    name = f"spinorbit_{fn_name.strip('_')}_{hashlib.sha256(text.encode()).hexdigest()[:20]}"
    module = sys.modules.get(name) if name in cache.LOADED else None
    return getattr(module or cache.load_module(name, text), fn_name)


def _reach(function, sources, seen, package):
    from . import cache

    if function in seen:
        return
    seen.add(function)
    module = sys.modules.get(function.__module__)
    sources.setdefault(function.__module__, _source_of(module, function))
    if function.__module__ in cache.LOADED:
        return                                   # a generated module's text holds its reach
    names = _global_names(function.__code__)
    for name in names:
        value = function.__globals__.get(name)
        if isinstance(value, types.ModuleType):
            if value in package:                 # mod.attr: its file, and the functions named
                sources.setdefault(value.__name__, _source_of(value, None))
                for attr in names:
                    _follow(getattr(value, attr, None), sources, seen, package)
        elif not _follow(value, sources, seen, package) and not isinstance(value, Free):
            for home in _homes(name, value, package):   # a constant numba freezes: the modules holding it
                sources.setdefault(home.__name__, _source_of(home, None))


def _follow(value, sources, seen, package):
    """Reach a compiled function anywhere, a plain function of the package; True if ``value`` is one."""
    if hasattr(value, "py_func"):
        _reach(value.py_func, sources, seen, package)
        return True
    if isinstance(value, types.FunctionType):
        if sys.modules.get(value.__module__) in package:
            _reach(value, sources, seen, package)
        return True
    return False


def _homes(name, value, package):
    """The package's modules holding ``value`` under ``name`` (where a constant imported by name is from)."""
    return [] if value is None else [module for module in package.modules if getattr(module, name, None) is value]


class _Package:
    """The package a reach follows: the modules with a file whose top-level package is in the folder ``root``
    (``module in package``), and those imported (listed once per reach)."""

    def __init__(self, root):
        self.root, self._modules = root, None

    def __contains__(self, module):
        name = getattr(module, "__name__", None)
        return (isinstance(name, str) and _top_in(name.partition(".")[0], self.root)
                and getattr(module, "__file__", None) is not None)

    @property
    def modules(self):
        if self._modules is None:
            self._modules = [module for name, module in list(sys.modules.items())    # by name: no getattr
                             if _top_in(name.partition(".")[0], self.root) and module in self]
        return self._modules


@functools.cache
def _top_in(top, root):
    """Is top-level package ``top`` (or module) in the folder ``root``?  Resolved once per package."""
    file = getattr(sys.modules.get(top), "__file__", None)
    return file is not None and Path(file).resolve().parent == root


def _source_of(module, function):
    """Bytes standing for a module's source: a generated module's hash, a file's bytes, else the code."""
    from . import cache

    name = getattr(module, "__name__", None)
    if name in cache.LOADED:
        return cache.LOADED[name].encode()
    file = getattr(module, "__file__", None)
    if file is not None:
        try:
            return _file_bytes(file)
        except OSError:
            pass
    return marshal.dumps(function.__code__) if function is not None else b""


@functools.cache
def _file_bytes(path):
    return Path(path).read_bytes()


def _module_source(fn, bindings, reach):
    reached = hashlib.sha256("".join(reach).encode()).hexdigest()
    lines = [f"# Generated by spinorbit.base.linker from {fn.__module__}.{fn.__name__}; do not edit.",
             f"# Reaches {reached} (sha256 of the sources it and its bindings use, numba's version)",
             "import numpy as np", "from spinorbit.base.linker.cache import kernel as spinorbit_kernel"]
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
    return "\n".join(lines) + "\n\n\n@spinorbit_kernel\n" + body


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
    py_func = python_function(value)
    if py_func is None:
        raise TypeError(f"link: {name} must be a compiled (numba) function or a constant, got {value!r}")
    module, attr = py_func.__module__, py_func.__name__
    if getattr(sys.modules.get(module), attr, None) is not value:
        raise TypeError(f"link: {name} = {module}.{attr} is not a module-level function "
                        "(closures defeat numba's cache; write it as a template and link it)")
    return f"from {module} import {attr} as {name}"
