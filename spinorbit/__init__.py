"""spinorbit: orbit-spin coupling after Euler, *Theoria motus corporum solidorum* ch. 15-16.

The angles at your dates (spinorbit.api), astropy Time in, QTable out::

    import spinorbit
    from astropy.time import Time
    t = Time(["2027-03-01", "2027-06-01"])
    spinorbit.moon_librations(t), spinorbit.earth_pole(t), spinorbit.earth_moon(t)

A scene, built in (``spinorbit list``) or a scenario file::

    result = spinorbit.run_scenario("free_body", ["span.end=100 d"])
    result.table, result.summary

Internal units: TDB days from J2000.0, km, rad (see spinorbit.constants).
"""
import os as _os
import sys as _sys

from .private import NUMBA as _NUMBA
from .private import numba_cache_refusal as _numba_cache_refusal
from .version import __version__  # noqa: F401

if _numba_cache_refusal() is not None:           # others could plant pickles there: numba never reads it
    _os.environ[_NUMBA] = ""                     # (the first kernel asked for refuses it in one line)
    if "numba.core.config" in _sys.modules:
        _sys.modules["numba.core.config"].CACHE_DIR = ""


def load_scenario(path, overrides=()):
    """Read and validate a scenario TOML file (see spinorbit.scenarios)."""
    from .scenarios import load_scenario as _load

    return _load(path, overrides)


def run_scenario(scenario, overrides=()):
    """Run a scenario (path or Scenario) and return a RunResult with .table and .summary."""
    from .runner import run_scenario as _run

    return _run(scenario, overrides)


def moon_librations(times, **options):
    """The Moon's orientation and physical librations at ``times`` (spinorbit.api.moon_librations)."""
    from .api import moon_librations as _moon

    return _moon(times, **options)


def earth_pole(times, **options):
    """The Earth's CIP X, Y, precession and nutation at ``times`` (spinorbit.api.earth_pole)."""
    from .api import earth_pole as _pole

    return _pole(times, **options)


def earth_moon(times, **options):
    """The coupled Earth-Moon system's state at ``times`` (spinorbit.api.earth_moon)."""
    from .api import earth_moon as _earth_moon

    return _earth_moon(times, **options)
