"""A System's equations as heyoka expressions: its generated right-hand side run on expressions, not numbers.

One definition of each term, two backends.  The generated source (spinorbit.models.generate) and the kernels it
calls are plain Python that numba compiles; run by Python with the state as heyoka variables and the time as
heyoka's ``time``, the same source builds the expression of every derivative, which heyoka's Taylor integrator
compiles (spinorbit.integrators.taylor).  Inside the source and every kernel it calls, numpy's and math's
``sqrt``, ``sin``, ``cos`` are replaced by functions that build expressions, and arrays hold expressions (dtype
object); heyoka folds the constants (0 x -> 0) and shares repeated subexpressions when it decomposes the system.

A kernel that branches on a value (an ephemeris lookup, an iterative solver) cannot be run on expressions.
The Kepler ellipse's solver has a twin, heyoka's ``kepE`` (the eccentric anomaly as a function of e and the
mean anomaly); any other such kernel stops the trace with :class:`NotTraceable` naming it.
"""
import functools
import math
import types

import numpy as np

from ..orbits.analytic import eccentric_anomaly


class NotTraceable(ValueError):
    """The System's right-hand side calls a kernel that cannot be run on expressions."""


def _expression_type():
    import heyoka

    return heyoka.expression


def _elementwise(symbolic_name, numeric):
    """A function applying heyoka's ``symbolic_name`` to expressions and ``numeric`` to numbers, by element."""
    def apply(x):
        if isinstance(x, np.ndarray):
            return np.array([apply(v) for v in x.ravel()], dtype=object).reshape(x.shape)
        if isinstance(x, _expression_type()):
            import heyoka

            return getattr(heyoka, symbolic_name)(x)
        return numeric(x)
    return apply


def _zeros(shape, dtype=None):
    out = np.empty(shape, dtype=object)
    out.fill(0.0)
    return out


def _array(values, dtype=None):
    return np.array(values, dtype=object)


class _Namespace(types.ModuleType):
    """numpy or math with some functions replaced; the rest read through."""

    def __init__(self, base, replaced):
        super().__init__(base.__name__)
        self._base = base
        self.__dict__.update(replaced)

    def __getattr__(self, name):
        return getattr(self._base, name)


_FUNCTIONS = {name: _elementwise(name, getattr(math, name)) for name in ("sqrt", "sin", "cos")}
NUMPY = _Namespace(np, {**_FUNCTIONS, "zeros": _zeros, "empty": _zeros, "array": _array,
                        "zeros_like": lambda a: _zeros(np.shape(a)), "empty_like": lambda a: _zeros(np.shape(a))})
MATH = _Namespace(math, _FUNCTIONS)


def _kepler(mean_anomaly, e):
    import heyoka

    return heyoka.kepE(e, mean_anomaly)


TWINS = {eccentric_anomaly: _kepler}          # kernel -> the function that builds its expression


@functools.cache
def symbolic(kernel):
    """The kernel's Python function with numpy, math and the kernels it calls replaced by their symbolic versions."""
    if kernel in TWINS:
        return TWINS[kernel]
    function = getattr(kernel, "py_func", kernel)
    scope = dict(function.__globals__)
    for name in _names(function.__code__):
        value = scope.get(name)
        if value is np:
            scope[name] = NUMPY
        elif value is math:
            scope[name] = MATH
        elif hasattr(value, "py_func"):
            scope[name] = symbolic(value)
    return types.FunctionType(function.__code__, scope, function.__name__, function.__defaults__,
                              function.__closure__)


def _names(code):
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _names(const)
    return names


def expressions(system, scales=None, name="rhs"):
    """(variables, derivatives): heyoka variables y0, y1, ... of the System's state and the expression of each
    one's derivative, from its generated source ``name`` run on them (module docstring); with ``scales`` (one per
    component) the variables are the state's components divided by them, and so are the derivatives."""
    import heyoka

    from .generate import rhs_source

    source, code = rhs_source(system)
    if source != system.sources[name]:
        raise AssertionError("the System's rhs source changed since it was built")
    scope = {"np": NUMPY, **{local: _checked(symbolic(kernel), kernel) for local, kernel in code.bindings.items()}}
    exec(compile(source, f"<{system.name} {name}>", "exec"), scope)
    variables = heyoka.make_vars(*(f"y{k}" for k in range(system.layout.size)))
    if system.layout.size == 1:
        variables = [variables]
    scales = np.ones(system.layout.size) if scales is None else np.asarray(scales, dtype=float)
    state = np.array([float(s) * v for s, v in zip(scales, variables)], dtype=object)
    derivatives = scope[name](heyoka.time, state, system.params)
    return list(variables), [(d if isinstance(d, heyoka.expression) else heyoka.expression(float(d))) / float(s)
                             for d, s in zip(derivatives, scales)]


def _checked(function, kernel):
    """``function`` raising NotTraceable (naming the kernel) where it cannot run on expressions."""
    @functools.wraps(function)
    def run(*args):
        try:
            return function(*args)
        except NotTraceable:
            raise
        except TypeError as exc:
            what = getattr(kernel, "py_func", kernel)
            raise NotTraceable(f"{what.__module__}.{what.__name__} cannot be run on expressions ({exc}): it "
                               "branches on a value (an ephemeris lookup or an iterative solver)") from None
    return run
