"""Planar libration on a circular orbit (Euler ch. 16 P93, §825-831) against its closed form.

The full 3-D rigid body turns about its axis C, normal to the orbit of the
centre of forces F (a uniform circle in the body's equatorial plane, the
inertial x-y plane).  zeta = AF = (longitude of F) - (longitude of A) obeys
zeta'' + n sin 2 zeta = 0 with n = (3/2) GM (B - A)/(C s^3); the scenario picks
Euler's energy constant C as a multiple of n (-1, 0, 1, > 1: §826's cases).
"""

import numpy as np

from ..comparisons import planar_libration_euler as vs
from ..scene.declaration import Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A < B <= C, any unit")


@table
class LibrationTable:
    energy_over_n: float = key(unit="", min=-1.0, max=1e6,
                               help="Euler's constant C in units of n: -1, 0, 1 or > 1")


@table
class P93PlanarLibrationParams(Params):
    body: BodyTable
    orbit: common.CircularCentreTable
    libration: LibrationTable


_ZETA = "dop853 at rtol 1e-12 over 200 d: ~1e-4\" (tests/test_scenes.py)"


def verdict(p, comparison):
    """zeta against Euler's closed form; on the separatrix only while zeta < 80 deg (it is unstable)."""
    metric = vs.ZETA_ERROR_MAX_ARCSEC_BELOW_80DEG if p.libration.energy_over_n == 1 else vs.ZETA_ERROR_MAX_ARCSEC
    return Verdict("Euler's closed form (§826-831)", (Check("zeta", metric, 1e-3, "″", _ZETA),))


def build(p, times):
    """The body on Euler's circle with zeta = 0 and zeta' from the energy constant; the closed form."""
    return start.planar_libration(p)


SCENE = Scene(P93PlanarLibrationParams, build, vs.compare_run, verdict, time_scales=common.rigid_body_time_scales,
              taylor=True)
