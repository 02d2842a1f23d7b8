"""Mars's pole and prime meridian in the IAU 2015 report (Archinal et al. 2018, CMDA 130:22, Table 2; from
Kuchynka et al. 2014, Icarus 229, 340, Opportunity's tracking), ICRF, T Julian centuries TDB from J2000.

alpha0 = 317.269202 - 0.10927547 T + sum a_k sin(phase_k + rate_k T), delta0 = 54.432516 - 0.05827105 T +
sum d_k cos(...), W = 176.049863 + 350.891982443297 d + sum w_k sin(...), degrees: the four short-period
terms of each are the rigid nutation seen in the pole, the long-period one (0.5042615 deg/cy) the precession
written as part of a slow circle.  Valid as a fit over the tracking's decades, not as a long-term model.
"""
import numpy as np

from ..base.constants import JULIAN_CENTURY_D
from .base import Comparable

# (amplitude deg, phase deg, rate deg/cy)
RA_DEG = (317.269202, -0.10927547, ((0.000068, 198.991226, 19139.4819985), (0.000238, 226.292679, 38280.8511281),
                                    (0.000052, 249.663391, 57420.7251593), (0.000009, 266.183510, 76560.6367950),
                                    (0.419057, 79.398797, 0.5042615)))
DEC_DEG = (54.432516, -0.05827105, ((0.000051, 122.433576, 19139.9407476), (0.000141, 43.058401, 38280.8753272),
                                    (0.000031, 57.663379, 57420.7517205), (0.000005, 79.476401, 76560.6495004),
                                    (1.591274, 166.325722, 0.5042615)))
W_DEG = (176.049863, 350.891982443297 * JULIAN_CENTURY_D,
         ((0.000145, 129.071773, 19140.0328244), (0.000157, 36.352167, 38281.0473591),
          (0.000040, 56.668646, 57420.9295360), (0.000001, 67.364003, 76560.2552215),
          (0.000001, 104.792680, 95700.4387578), (0.584542, 95.391654, 0.5042615)))
CITATION = "Archinal et al. 2018, CMDA 130:22 (IAU 2015), after Kuchynka et al. 2014, Icarus 229, 340"


def _series(coefficients, t_tdb_d, trig):
    constant, rate, terms = coefficients
    big_t = np.asarray(t_tdb_d, dtype=float) / JULIAN_CENTURY_D
    return np.radians(constant + rate * big_t + sum(a * trig(np.radians(p + r * big_t)) for a, p, r in terms))


def angles(t_tdb_d):
    """(alpha0, delta0, W) rad at TDB days from J2000."""
    return (_series(RA_DEG, t_tdb_d, np.sin), _series(DEC_DEG, t_tdb_d, np.cos), _series(W_DEG, t_tdb_d, np.sin))


def pole(t_tdb_d):
    """The pole (n, 3), ICRF unit vectors."""
    ra, dec, _ = angles(t_tdb_d)
    return np.column_stack([np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra), np.sin(dec)])


class IauMarsPole:
    """The IAU 2015 Mars pole as a ``references.base.Reference``: ``pole`` (n, 3) and ``pole_ra_rad``,
    ``pole_dec_rad``, ``prime_meridian_rad``."""

    name = "IAU 2015 Mars pole"

    def __call__(self, t_tdb_d):
        ra, dec, w = angles(t_tdb_d)
        return Comparable(np.asarray(t_tdb_d, dtype=float),
                          {"pole": pole(t_tdb_d), "pole_ra_rad": ra, "pole_dec_rad": dec, "prime_meridian_rad": w},
                          {"model": "IAU 2015 Mars rotational elements", "citation": CITATION})
