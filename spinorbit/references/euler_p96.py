"""Euler's precession of the equinoxes (Theoria motus ch. 16, P96, §846) on his hypothesis: the Moon and the
Sun on uniform circles, the rate N cos n of each added (theory.SymmetricPrecession), and a run's mean
precession set beside it."""
import math

import numpy as np

from ..base.constants import ARCSEC
from ..bodies.table import gm_km3_d2

# Euler's circles: mean distance (km) and sidereal period (d) of the Moon and the Sun.
CIRCLES = {"moon": (384400.0, 27.321661), "sun": (149597870.7, 365.256363)}
# The metric compare computes (the summary's comparison key, read by the Earth's verdict)
MODEL_MINUS_P96_ARCSEC_CY = "model_minus_p96_arcsec_cy"


def circles():
    """(orbit source, tilt): Euler's circles of the Moon and the Sun in the J2000 ecliptic (his hypothesis, §844),
    tilted by the IAU 2006 obliquity at J2000 from the GCRS equator."""
    from ..orbits.analytic import CircularOrbits
    from .erfa_pole import EPS0_ARCSEC

    tilt = EPS0_ARCSEC * ARCSEC
    names = tuple(CIRCLES)
    return CircularOrbits(names, [gm_km3_d2(b) for b in names], [CIRCLES[b][0] for b in names],
                          [2 * math.pi / CIRCLES[b][1] for b in names], None, [tilt, tilt]), tilt


def precession_rate(moments, spin_rad_d, tilt_rad):
    """Euler's P96 rate (rad/d) of a body of principal ``moments`` spinning at ``spin_rad_d``, its equator
    at ``tilt_rad`` to the circles' plane: the sum over Moon and Sun of N cos n (theory.precession_constant
    N, times the gyroscopic ratio A/C: the figure axis follows the angular momentum)."""
    from ..analysis.theory import SymmetricPrecession, precession_constant

    rate = 0.0
    for name, (radius, period) in CIRCLES.items():
        big_n = precession_constant(gm_km3_d2(name), radius, spin_rad_d, moments[2], moments[0])
        big_n *= moments[0] / moments[2]
        rate += SymmetricPrecession(spin_rad_d, 2 * math.pi / period, big_n, tilt_rad).precession_rate
    return rate


def compare(t_tdb_d, poles, ecliptic_pole, moments, spin_rad_d, circles, geodesic_arcsec_cy=0.0):
    """Euler's P96 rate (on the circles, tilted as the first pole) beside the model's mean node rate on the
    fixed ecliptic, arcsec/cy: (comparison, not_measured).  ``circles``: the run was driven by them (the
    node rate is fitted with their 2-phi terms, and the P96 rate adds the model's ``geodesic_arcsec_cy``);
    else it ran on DE421, where the node rate needs analysis.precession.RATE_MIN_SPAN_D."""
    from ..analysis.precession import node_rate, rate_refusal
    from ..base.constants import ARCSEC, JULIAN_CENTURY_D

    t = np.asarray(t_tdb_d, dtype=float)
    tilt = math.acos(float(poles[0] @ ecliptic_pole))
    p96 = precession_rate(moments, spin_rad_d, tilt) * JULIAN_CENTURY_D / ARCSEC
    periodic = {b: (4 * math.pi * t / period, 4 * math.pi / period) for b, (_, period) in CIRCLES.items()}
    model = node_rate(t, poles, ecliptic_pole, periodic if circles else None) / ARCSEC
    if not circles:
        why = rate_refusal(float(np.ptp(t)))          # the nutation aliases into a short span's rate
        return ({"p96_circles_precession_rate_arcsec_cy": p96, "fixed_ecliptic_precession_rate_arcsec_cy":
                 None if why else model}, {"comparison.fixed_ecliptic_precession_rate_arcsec_cy": why} if why else {})
    p96 -= geodesic_arcsec_cy
    return {"p96_precession_rate_arcsec_cy": p96, "model_precession_rate_arcsec_cy": model,
            MODEL_MINUS_P96_ARCSEC_CY: model - p96}, {}
