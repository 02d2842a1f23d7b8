"""Euler's precession of the equinoxes (Theoria motus ch. 16, P96, §846) on his hypothesis: the Moon and the
Sun on uniform circles, the rate N cos n of each added (theory.SymmetricPrecession)."""
import math

from ..constants import GM_KM3_D2

# Euler's circles: mean distance (km) and sidereal period (d) of the Moon and the Sun.
CIRCLES = {"moon": (384400.0, 27.321661), "sun": (149597870.7, 365.256363)}


def precession_rate(moments, spin_rad_d, tilt_rad):
    """Euler's P96 rate (rad/d) of a body of principal ``moments`` spinning at ``spin_rad_d``, its equator
    at ``tilt_rad`` to the circles' plane: sum over Moon and Sun of N cos n, N = 3/2 GM (C - A)/(w C r^3)."""
    from ..theory import SymmetricPrecession

    rate = 0.0
    for name, (radius, period) in CIRCLES.items():
        big_n = 1.5 * GM_KM3_D2[name] * (moments[2] - moments[0]) / (spin_rad_d * moments[2] * radius**3)
        rate += SymmetricPrecession(spin_rad_d, 2 * math.pi / period, big_n, tilt_rad).precession_rate
    return rate
