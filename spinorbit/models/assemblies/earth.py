"""The rigid Earth under the Moon's and the Sun's torques: precession and nutation (Euler ch. 16 P91, P96).

An oblate (optionally triaxial) rigid Earth with IAU 2006's dynamical ellipticity H_d = (C - A)/C, its
anisotropy changing with the secular J2 rate, driven by point masses (the orbit source's bodies relative to the
geocentre, GCRS) through the P91 gravity-gradient torque (§815), optionally on its J4 (EGM2008).  Two rotators:

* ``gyroscopic`` (the default) -- the spin angular momentum alone (spinorbit.models.rotators.Gyroscopic), the
  torque on the figure axis recovered from it by the Oppolzer terms; the step follows the month;
* ``full`` -- Euler's equations with the daily spin resolved (Rigid: q body -> GCRS, w body axes).

Euler's equations hold in the dynamically non-rotating frame, which turns against the GCRS at the geodesic
precession (prograde about the ecliptic pole, de Sitter; spinorbit.models.interactions.geodesic), so the observed
precession in longitude is 1.919883"/cy less than the dynamical one.  Moments G-scaled: C = C/(M a^2) GM a^2.
"""
import math

import numpy as np

from ...base.constants import ARCSEC, JULIAN_CENTURY_D
from ...base.errors import PhysicsError
from ...bodies import earth
from ...bodies.table import gm_km3_d2
from ..figure import Body, Field, Figure
from ..interactions import GeodesicRate, Harmonics, PointMass
from ..motion import Centred
from ..rotators import Gyroscopic, Rigid
from ..system import System

# The Earth's heliocentric orbit: eccentricity and the Sun's mean anomaly l' = l'_0 + n' t (rad, rad/d),
# Simon et al. 1994 as in the IERS Conventions 2010 (eq. 5.43, linear part).
ORBIT_ECCENTRICITY = 0.0167086
SUN_MEAN_ANOMALY_RAD = (math.radians(357.52910918), math.radians(129596581.0481 / 3600.0) / JULIAN_CENTURY_D)
MODELS = ("gyroscopic", "full")


def figure(gm, h_d=earth.H_D, b_minus_a_over_c=0.0, j2_rate=True, j4=False):
    """The Earth's figure, G-scaled: (C - (A + B)/2)/C = h_d, (B - A)/C as given, C = C/(M a^2) GM a^2; the
    anisotropy's secular rate from IAU 2006's dJ2/dt (if ``j2_rate``); EGM2008's J4 at a (if ``j4``)."""
    c = earth.C_MR2 * gm * earth.EQUATORIAL_RADIUS_KM ** 2
    moments = c * np.array([1.0 - h_d - b_minus_a_over_c / 2, 1.0 - h_d + b_minus_a_over_c / 2, 1.0])
    field = None
    if j4:
        c_nm = np.zeros((5, 5))
        c_nm[4, 0] = -earth.J4
        field = Field(earth.EQUATORIAL_RADIUS_KM, c_nm, np.zeros((5, 5)), n_min=4)
    rate = earth.J2_RATE_PER_CY / earth.J2 / JULIAN_CENTURY_D if j2_rate else 0.0
    return Figure(moments, field, rate)


def geodesic_precession(ecliptic_pole, annual=False):
    """The geodesic precession about ``ecliptic_pole`` (GCRS unit vector) at the IERS rate, with its annual
    term (the geodesic nutation) if ``annual``."""
    rate = earth.GEODESIC_PRECESSION_ARCSEC_CY * ARCSEC / JULIAN_CENTURY_D
    pole = np.asarray(ecliptic_pole, dtype=float)
    modulation = 3.0 * ORBIT_ECCENTRICITY if annual else 0.0
    return GeodesicRate("earth", rate * pole / np.linalg.norm(pole), np.array([modulation, *SUN_MEAN_ANOMALY_RAD]))


def rigid_earth(orbits, model="gyroscopic", h_d=earth.H_D, b_minus_a_over_c=0.0, j2_rate=True, j4=False,
                ecliptic_pole=None, geodesic_nutation=False, t0=0.0, start=None):
    """The rigid Earth at the origin, driven by ``orbits`` (bodies relative to the geocentre): ``model`` one of
    MODELS; the geodesic precession about ``ecliptic_pole`` (None: none)."""
    if model == "gyroscopic" and b_minus_a_over_c:
        raise PhysicsError(f"the gyroscopic model needs an axisymmetric Earth (A = B), got (B - A)/C = "
                           f"{b_minus_a_over_c}; use the full model for a triaxial Earth")
    gm = gm_km3_d2("earth")
    body = Body("earth", gm, figure(gm, h_d, b_minus_a_over_c, j2_rate, j4),
                Gyroscopic() if model == "gyroscopic" else Rigid())
    names = tuple(orbits.names)
    interactions = [PointMass("earth", names)] + ([Harmonics("earth", names)] if j4 else [])
    if ecliptic_pole is not None:
        interactions.append(geodesic_precession(ecliptic_pole, geodesic_nutation))
    return System(f"earth ({model})", [body], Centred("earth", orbits), interactions, t0, start, {"model": model})
