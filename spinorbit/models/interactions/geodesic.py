"""Geodesic precession: the frame in which a body's spin equations hold turns against the inertial (GCRS) axes.

De Sitter's precession of a body moving at w relative to the Sun at x (the Sun's field, PPN gamma = 1):
Omega = (3/2) GM_sun / (c^2 |x|^3) x x w (Soffel et al. 2003, IAU 2000 resolutions; IERS Conventions 2010
§5.6.4: 1.919883"/cy prograde about the ecliptic pole for the Earth).  :class:`Geodesic` takes it from the
System's own state; :class:`GeodesicRate` as the IERS constant rate about a fixed pole, with its annual
term (size h/r^3 over the orbit, (1 + e cos f)^3 ~ 1 + 3 e cos l'), which integrates to the geodesic
nutation, 3 e Omega / n' = 0.153 mas in psi (Fukushima 1991).
"""
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ...base.linker import cached
from ...base.rotations import cross3, dot3
from .base import Interaction


@cached(nogil=True)
def de_sitter(x, w, gm_sun, c):
    """Omega (rad/d, inertial) of a body at x (km) moving at w (km/d) relative to the Sun."""
    return 1.5 * gm_sun / (c * c * dot3(x, x) ** 1.5) * cross3(x, w)


@njit(cache=True, nogil=True)
def constant_rate(rate, annual, t):
    """rate (3,) rad/d times (1 + annual[0] cos(annual[1] + annual[2] t)), t TDB days."""
    return rate * (1.0 + annual[0] * math.cos(annual[1] + annual[2] * t))


@dataclass(frozen=True)
class Geodesic(Interaction):
    """De Sitter's precession of ``body``'s spin frame from its motion about ``sun`` in the System."""

    body: str
    sun: str
    c_km_d: float
    citation = "Soffel et al. 2003; IERS Conventions 2010, §5.6.4"

    def bodies(self):
        return (self.body, self.sun)

    def frames(self):
        return (self.body,)

    def tidal_attractors(self, name):
        """None: it turns the frame, with no torque."""
        return ()

    def emit(self, code):
        x = code.relative(self.sun, self.body)
        w = code.relative_velocity(self.sun, self.body)
        gm = code.param("gm_sun", code.system.motion.gm(self.sun))
        code.add_frame_rate(self.body, f"{code.bind(de_sitter)}({x}, {w}, {gm}, {code.param('c_km_d', self.c_km_d)})")


@dataclass(frozen=True)
class GeodesicRate(Interaction):
    """The geodesic precession of ``body``'s spin frame as a rate ``rate_rad_d`` (3,) about a fixed pole, times
    1 + annual[0] cos(annual[1] + annual[2] t) (annual[0] = 3 e, or 0 for the mean rate alone)."""

    body: str
    rate_rad_d: np.ndarray
    annual: np.ndarray
    citation = "IERS Conventions 2010, §5.6.4; Fukushima 1991"

    reads_places = False

    def bodies(self):
        return (self.body,)

    def frames(self):
        return (self.body,)

    def tidal_attractors(self, name):
        """None: it turns the frame, with no torque."""
        return ()

    def emit(self, code):
        code.add_frame_rate(self.body, f"{code.bind(constant_rate)}({code.param('geodesic_rate', self.rate_rad_d)}, "
                                       f"{code.param('geodesic_annual', self.annual)}, t)")
