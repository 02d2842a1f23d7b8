"""mars_deep_time's model: Mars's orbit from the orbital solution earth_deep_time's orbit keys name (the same
file: it keeps Mars's heliocentric orbit beside the EMB's), and the averaged spin equations on it, the axis
started on the IAU 2015 mean pole at J2000.

The precession constant is the Sun's alone, set by the present precession rate ``mars.precession_rate``
(La2004's -7.597"/yr by default) as the Earth's is by IAU 2006's: alpha cos(eps0) - Omega_g = -rate.  Phobos
and Deimos orbit in Mars's equator, so their own mean torque on the figure vanishes; the Sun's torque on their
orbits, carried to Mars by its bulge, adds m a^2 / 2 to C - A (Laskar 2004, A&A 416, 799): 3.2e-5 of alpha for
Phobos, 2.7e-5 for Deimos.  A measured rate holds that share; it changes only as Phobos spirals in (its a by
~1.8 cm/yr, Jacobson 2010: 2e-6 of alpha over 20 Myr), so it is not evolved.  The Sun's tide (``tides.k2``,
``tides.Q``) slows the rotation and tilts the axis (spinorbit.models.deep_time).

The start: the IAU 2015 pole (Archinal et al. 2018, CMDA 130:22, from Kuchynka et al. 2014) at J2000 with
its long-period pair (the precession written as a slow circle) and without its four rigid-nutation terms
(< 0.00024 deg): the mean pole the averaged equations follow.
"""
import math

import numpy as np

from ..base.constants import ARCSEC, DAY_S, JULIAN_YEAR_D
from .earth_deep_time import SpinModel

BODY = "mars"
# IAU 2015's Mars pole at J2000, deg: the constant and the long-period pair (amplitude, phase) of alpha0, delta0.
POLE_RA_DEG = (317.269202, 0.419057, 79.398797)
POLE_DEC_DEG = (54.432516, 1.591274, 166.325722)


def mean_pole_j2000():
    """The IAU 2015 mean pole of Mars at J2000, a unit vector in ICRF axes."""
    ra = math.radians(POLE_RA_DEG[0] + POLE_RA_DEG[1] * math.sin(math.radians(POLE_RA_DEG[2])))
    dec = math.radians(POLE_DEC_DEG[0] + POLE_DEC_DEG[1] * math.cos(math.radians(POLE_DEC_DEG[2])))
    return np.array([math.cos(dec) * math.cos(ra), math.cos(dec) * math.sin(ra), math.sin(dec)])


def spin_model(p, orbit):
    """The averaged spin equations' parameters on Mars's orbit in ``orbit`` (an OrbitalSolution)."""
    from ..bodies import mars
    from ..bodies.de421_header import header
    from ..bodies.table import gm_km3_d2
    from ..models import deep_time

    path = orbit.of(BODY)
    grid = np.column_stack([path.normal, path.eccentricity_vector])
    j2000 = int(np.searchsorted(orbit.t_d, 0.0))
    normal0, e0 = path.normal[j2000], float(path.eccentricity[j2000])
    spin_axis0 = mean_pole_j2000()
    obliquity0 = math.acos(spin_axis0 @ normal0)
    c_km_d = header()["CLIGHT"] * DAY_S
    a_km = mars.MEAN_SEMI_MAJOR_AXIS_KM
    geodesic = deep_time.geodesic_rate(a_km, c_km_d) / (1 - e0**2)
    per_yr = ARCSEC / JULIAN_YEAR_D
    rate = p.mars.precession_rate * per_yr
    alpha0 = deep_time.constant_from_rate(-rate, obliquity0, geodesic)
    tide = deep_time.solar_tide(p.tides.k2, p.tides.Q, gm_km3_d2(BODY), mars.RADIUS_KM,
                                mars.C_MR2, a_km, mars.ROTATION_RATE_RAD_D)
    params = deep_time.planet_parameters(grid, orbit.t_d[0], p.orbit.output, alpha0, e0, a_km, c_km_d,
                                         mars.ROTATION_RATE_RAD_D, solar_tide_rad_d=tide)
    solar = 1.5 * gm_km3_d2("sun") / a_km**3 / mars.ROTATION_RATE_RAD_D
    myr = 1e6 * JULIAN_YEAR_D
    description = {
        "precession_constant_arcsec_per_yr": alpha0 / per_yr,
        "precession_rate_j2000_arcsec_per_yr": p.mars.precession_rate,
        "dynamical_ellipticity": alpha0 / (solar * (1 - e0**2) ** -1.5),
        "geodesic_arcsec_per_yr": geodesic / per_yr, "obliquity_j2000_deg": math.degrees(obliquity0),
        "pole_j2000": "IAU 2015 (Archinal et al. 2018), mean: without its rigid-nutation terms",
        "k2": p.tides.k2, "Q": p.tides.Q,
        "solar_tide_rotation_change_per_myr": -tide * myr,
        "solar_tide_obliquity_rate_arcsec_per_myr": tide * myr * math.sin(obliquity0)
        * (0.5 * math.cos(obliquity0)) / ARCSEC}
    return SpinModel(deep_time.averaged_spin(params, spin_axis0, planet=BODY), spin_axis0, normal0, description)
