"""Stress: Mercury in the 3:2 spin-orbit resonance, the 88-day forced libration in longitude.

The full 3-D rigid body on a fixed Kepler ellipse (e = 0.2056) of the Sun
(Euler ch. 16 P91 torque, §825; P94's forced libration with an eccentric orbit)
starts in the 3:2 state, theta = (3/2) M + gamma with gamma on its linear
forced solution.  gamma = theta - (3/2) M obeys, to first order in gamma,

    gamma'' + w0^2 gamma = -(3/2) n^2 ((B - A)/C) sum_k S_k sin kM,  w0^2 = 3 n^2 ((B - A)/C) H,

so the 88-day (k = 1) term is (3/2) ((B - A)/C) S_1/(1 - w0^2/n^2) sin M.
Margot et al. (2007) (after Peale 1972) write (3/2) ((B - A)/C) (1 - 11 e^2 +
959 e^4/48): S_1 truncated at e^4 and w0 << n.  The scene fits sin/cos kM
(k <= 6), the free libration at w0 and a constant to the integrated gamma and
compares the sin M amplitude with both.  The linear start leaves a free
libration of ~0.2" (w0 << n turns the O(gamma^2) terms it omits in gamma'(0)
into an amplitude ~ delta gamma'/w0); it is fitted separately.

The radar amplitude is NOT an independent check: Margot's 35.8 +- 2" is the observation the scenario's
(B - A)/C (their mantle (B - A)/C_m = 2.03e-4) was inferred from, so agreeing with it is circular.  The
scene reports it, and its verdict says so; it passes or fails on the integration against the theory.
"""

import numpy as np

from ..comparisons.mercury_libration import (
    LIBRATION_88D_REL_ERROR_VS_LINEAR,
    LIBRATION_88D_REL_ERROR_VS_SERIES,
    compare_run,
)
from ..scene.declaration import Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
from . import common

RADAR_NOT_INDEPENDENT = ("Margot et al. (2007)'s 35.8\" radar amplitude is not compared: the (B - A)/C used "
                         "here was inferred from it, so agreement would be circular")


def verdict(p, comparison):
    """The 88-d libration against linear theory and Margot et al. (2007)'s series."""
    return Verdict("linear forced libration; Margot et al. (2007)", (
        Check("88-d vs linear", LIBRATION_88D_REL_ERROR_VS_LINEAR, p.stress.linear_rel_tol, "",
              "linear in the libration (35.8\" = 1.7e-4 rad): the nonlinear remainder is far below 1e-3"),
        Check("88-d vs series", LIBRATION_88D_REL_ERROR_VS_SERIES, p.stress.series_rel_tol, "",
              "the e^6 remainder of (1 - 11e^2 + 959e^4/48) at e = 0.2056 (~1e-3)")),
        RADAR_NOT_INDEPENDENT)


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A < B < C; (B - A)/C sets the libration")


@table
class StressTable:
    linear_rel_tol: float = key(unit="", default=1e-3, help="pass: |measured/linear theory - 1|")
    series_rel_tol: float = key(unit="", default=1e-2, help="pass: |measured/Margot series - 1|")


@table
class StressMercuryParams(Params):
    body: BodyTable
    orbit: common.KeplerOrbitTable
    stress: StressTable


def build(p, times):
    """The body in the 3:2 state on its linear forced solution (gamma(0) = 0 at periapsis)."""
    return start.mercury_3_2(p)


SCENE = Scene(StressMercuryParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales)

