"""Orbit sources: where the attracting masses are, relative to the spinning body.

One protocol for the orbits a source gives (:class:`Orbits`), several sources
(spinorbit.orbits.sources: each an ``OrbitSource``), each reader in its own module
and importing only its own library:

* ``analytic``  — uniform circle (Euler's hypothesis, ch. 16 P93/P96) and Kepler ellipse;
* ``kernel``    — JPL SPK kernels through jplephem (DE421 from skyfield-data by default);
* ``nbody``     — REBOUND N-body runs (+ REBOUNDx gr_full and Earth J2);
* ``interpolant`` — the dense quintic-Hermite interpolant built once per run.

Positions are km in inertial axes (ICRF for real ephemerides), relative to the
spinning body's centre, at TDB days from J2000.0.
"""
from typing import Protocol

import numpy as np


class Orbits(Protocol):
    """What the torque models need from the orbits an orbit source gives.

    ``names``      — the attracting bodies, in order;
    ``gm``         — their GM, km^3/day^2, shape (n,);
    ``span``       — (start, end) TDB days covered; outside it EphemerisRangeError;
    ``kernel``     — numba function (t, data) -> (n, 3) positions, km, inertial axes;
    ``data``       — the tuple of arrays ``kernel`` reads;
    ``positions(t)`` — the same for an array of times, from Python: (len(t), n, 3).
    """

    names: tuple
    gm: np.ndarray
    span: tuple
    data: tuple

    def kernel(self, t, data): ...

    def positions(self, t) -> np.ndarray: ...
