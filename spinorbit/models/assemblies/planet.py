"""A rigid planet at the origin under the point masses of an orbit source: precession and nutation (Euler ch. 16
P91, P96), written from a body's constants alone (its GM, J2, C22, C/(M R^2), rotation rate).

Two rotators, as the Earth's (spinorbit.models.assemblies.earth): ``gyroscopic`` (the spin angular momentum,
an axisymmetric figure with the mean equatorial moment (A + B)/2: the sectoral C22 acts on a daily period the
gyroscopic model averages away) and ``full`` (Euler's equations with the spin resolved, the triaxial figure).
Optional: satellites as rings held to the equator (interactions.rings), and the geodesic precession as a
rate about the orbit's pole (de Sitter: (3/2) GM_sun n / (c^2 a), prograde; interactions.geodesic).
Moments G-scaled: C = C/(M R^2) GM R^2.
"""
from dataclasses import dataclass

import numpy as np

from ..figure import Body, Figure
from ..interactions import GeodesicRate, PointMass, Rings
from ..interactions.rings import ring_inertia
from ..motion import Centred
from ..rotators import Gyroscopic, Rigid
from ..system import System

MODELS = ("gyroscopic", "full")


@dataclass(frozen=True)
class Planet:
    """A planet's constants the spin needs: GM (km^3/d^2), R (km) with J2 and C22 (unnormalised) at it, C/(M R^2),
    and its satellites ((name, GM km^3/d^2, a km), ...) held to its equator."""

    name: str
    gm_km3_d2: float
    radius_km: float
    j2: float
    c22: float
    c_mr2: float
    satellites: tuple = ()

    def moments(self, model):
        """(A, B, C), G-scaled; A = B = their mean for the gyroscopic model."""
        half_width = 0.0 if model == "gyroscopic" else 2.0 * self.c22
        unit = self.gm_km3_d2 * self.radius_km ** 2
        return unit * np.array([self.c_mr2 - self.j2 - half_width, self.c_mr2 - self.j2 + half_width, self.c_mr2])


def geodesic_rate(gm_sun_km3_d2, c_km_d, semi_major_axis_km, orbit_pole, eccentricity=0.0, mean_anomaly=(0.0, 0.0)):
    """De Sitter's precession of a planet on a mean orbit (a, e; mean anomaly M0 + n t, rad, rad/d) as a
    GeodesicRate's (rate vector rad/d about ``orbit_pole``, annual modulation 3 e cos M)."""
    n = np.sqrt(gm_sun_km3_d2 / semi_major_axis_km ** 3)
    rate = 1.5 * gm_sun_km3_d2 / (c_km_d ** 2 * semi_major_axis_km) * n
    pole = np.asarray(orbit_pole, dtype=float)
    return rate * pole / np.linalg.norm(pole), np.array([3.0 * eccentricity, *mean_anomaly])


def rigid_planet(planet, orbits, model="gyroscopic", rings=True, geodesic=None, t0=0.0, start=None):
    """``planet`` (a Planet) at the origin, driven by ``orbits`` (bodies relative to it): ``model`` one of MODELS;
    its satellites as rings if ``rings``; ``geodesic`` = (rate vector, annual) from :func:`geodesic_rate`, or
    None."""
    name, names = planet.name, tuple(orbits.names)
    body = Body(name, planet.gm_km3_d2, Figure(planet.moments(model)),
                Gyroscopic() if model == "gyroscopic" else Rigid())
    interactions = [PointMass(name, names)]
    if rings and planet.satellites:
        interactions.append(Rings(name, names, ring_inertia(planet.satellites)))
    if geodesic is not None:
        interactions.append(GeodesicRate(name, *geodesic))
    return System(f"{name} ({model})", [body], Centred(name, orbits), interactions, t0, start, {"model": model})
