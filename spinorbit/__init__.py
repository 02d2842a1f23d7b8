"""spinorbit: orbit-spin coupling after Euler, *Theoria motus corporum solidorum* ch. 15-16.

The angles at your dates (spinorbit.edge.api), astropy Time in, QTable out::

    import spinorbit
    from astropy.time import Time
    t = Time(["2027-03-01", "2027-06-01"])
    spinorbit.moon_librations(t), spinorbit.earth_pole(t), spinorbit.earth_moon(t), spinorbit.orientation("mars", t)

A scene, built in (``spinorbit list``) or a scenario file, its typed parameters changed by
``dataclasses.replace`` (times in TDB days from J2000.0, values in their keys' units)::

    scenario = spinorbit.load_scenario("free_body")
    p = scenario.params
    result = spinorbit.run_scenario(scenario.with_params(p.with_span(end=p.span.start + 100.0)))
    result.table, result.summary

or as the command line's text: ``spinorbit.run_scenario("free_body", ["span.end=100 d"])``.

Internal units: TDB days from J2000.0, km, rad (see spinorbit.base.constants).
"""
import os as _os
import sys as _sys

from .base.compiled_names import install as _install_compiled_names
from .base.private import NUMBA as _NUMBA
from .base.private import numba_cache_refusal as _numba_cache_refusal
from .base.version import __version__  # noqa: F401

if _numba_cache_refusal() is not None:           # others could plant pickles there: numba never reads it
    _os.environ[_NUMBA] = ""                     # (the first kernel asked for refuses it in one line)
    if "numba.core.config" in _sys.modules:
        _sys.modules["numba.core.config"].CACHE_DIR = ""
_install_compiled_names()                        # names no other process compiles (spinorbit.base.compiled_names)


def load_scenario(path, overrides=()):
    """Read and validate a scenario TOML file (see spinorbit.edge.scenarios)."""
    from .edge.scenarios import load_scenario as _load

    return _load(path, overrides)


def run_scenario(scenario, overrides=()):
    """Run a scenario (path or Scenario) and return a RunResult with .table and .summary."""
    from .edge.runner import run_scenario as _run

    return _run(scenario, overrides)


_API = ("moon_librations", "earth_pole", "earth_moon", "orientation")


def __getattr__(name):
    """The API's functions (spinorbit.edge.api), imported when first asked for: ``import spinorbit`` stays light,
    and ``help(spinorbit.moon_librations)`` shows the function itself, its signature and its docstring."""
    if name in _API:
        from .edge import api

        return getattr(api, name)
    raise AttributeError(f"module 'spinorbit' has no attribute {name!r}")


def __dir__():
    return sorted([*globals(), *_API])
