"""Stress: Hyperion's chaotic tumbling, its maximal Lyapunov exponent measured, not assumed.

Planar spin-orbit on a Kepler ellipse (e = 0.1, (B - A)/C = 0.26; Wisdom, Peale
& Mignard 1984) and the full 3-D rigid body (Euler ch. 15 §808 + ch. 16 P91).

Method: analysis.lyapunov (Benettin et al. 1980), a reference and a neighbour d0 apart in the scaled phase
space (theta, theta'/n) -- in 3-D (2 q, omega/n) -- renormalised every orbital period T; lambda in 1/T.

The scene checks (a) a regular orbit (small (B - A)/C, synchronous start) whose lambda falls like
ln t/t (halves from T to 2T) below ``lyapunov.regular_max``; (b) the nominal Hyperion start: lambda
clearly positive and the same over two integration lengths (rk8) and with scipy's DOP853; (c) the 3-D
exponent of the same start.  It maps lambda over a grid of initial (theta - f, theta'/n) at periapsis
(PNG) with the chaotic fraction, and checks the planar model against the 3-D body in the plane once.

A finite-time exponent of a chaotic orbit is a random variable: rounding (another machine, library or
integrator) changes the trajectory after a few Lyapunov times, and the estimate with it.  So (b) takes
an ensemble of ``lyapunov.ensemble`` starts 1e-3 rad apart around the nominal one (decorrelated within
~50 periods) and compares ensemble means within ``lyapunov.max_sigma`` of their own standard errors.
"""

import numpy as np

from ..comparisons import hyperion_lyapunov as vs
from ..scene.declaration import Model, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from . import common


def verdict(p, comparison):
    """The exponents' agreement between integrators and run lengths, the regular orbit, and all criteria."""
    return Verdict("Benettin exponents, rk8 and dop853", (
        Check("regular exponent", vs.LYAPUNOV_REGULAR_PER_T, p.lyapunov.regular_max, "/T",
              "a regular orbit's exponent falls like ln t/t (lyapunov.regular_max)"),
        *(Check(f"ensemble means, {pair.replace('_vs_', ' vs ').replace('_', ' ')}",
                vs.nominal_sigmas(pair), p.lyapunov.max_sigma, " sigma",
                "two integrators and two run lengths must give one mean exponent, within the ensemble's own "
                "standard errors (lyapunov.max_sigma)") for pair in vs.ENSEMBLE_PAIRS),
        Check("all criteria", vs.PASSED, source="module docstring: (a)-(d)")))


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A < B < C (3-D runs); (B - A)/C for planar")


@table
class LyapunovTable:
    start: np.ndarray = key(unit="", size=2, help="nominal start at periapsis: theta - f (rad), theta'/n")
    orbits: int = key(type=int, default=1000, help="length of the shorter nominal run, orbital periods")
    regular_orbits: int = key(type=int, default=2000,
                              help="length of the regular check run, orbital periods")
    orbits_3d: int = key(type=int, default=300, help="length of the 3-D run, orbital periods")
    steps_per_orbit: int = key(type=int, default=128, help="rk8 steps per orbital period")
    d0: float = key(unit="", default=1e-8, help="separation after each renormalisation")
    ensemble: int = key(type=int, default=16,
                        help="starts around the nominal one (1e-3 rad apart in theta)")
    max_sigma: float = key(unit="", default=4.0,
                           help="pass: ensemble means agree within this many standard errors")
    regular_gamma: float = key(unit="", default=0.01, help="(B - A)/C of the regular check orbit")
    regular_max: float = key(unit="", default=0.01,
                             help="pass: regular exponent after regular_orbits below this, 1/T")
    chaotic_min: float = key(unit="", default=0.2,
                             help="chaotic above this, 1/T (map; nominal must exceed it)")


@table
class MapTable:
    grid: np.ndarray = key(unit="", size=2, default=np.array([36.0, 36.0]), help="points in theta - f and theta'/n")
    rate_range: np.ndarray = key(unit="", size=2, default=np.array([0.0, 3.0]), help="theta'/n range")
    orbits: int = key(type=int, default=200, help="length of each map run, orbital periods")


@table
class StressHyperionParams(Params):
    body: BodyTable
    orbit: common.KeplerOrbitTable
    lyapunov: LyapunovTable
    map: MapTable


def build(p, times):
    """No main run: the Lyapunov pairs, ensembles and map are integrations of their own (compare)."""
    return Model(None)


SCENE = Scene(StressHyperionParams, build, vs.compare_run, verdict, time_scales=common.rigid_body_time_scales)
