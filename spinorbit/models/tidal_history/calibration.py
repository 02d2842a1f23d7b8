"""Today's tidal rates of the Earth-Moon equations, and the strength of a one-parameter tide (constant time
lag, constant Q) that gives a recession rate: da/dt is linear in the strength, so the fit is exact."""
import math

import numpy as np

from ...base.constants import DAY_S, JULIAN_CENTURY_D, JULIAN_YEAR_D, MAS
from .equations import GM_EARTH, GM_MOON, GM_SUN, INERTIA, RADIUS, SUN_A, rhs
from .response import STRENGTH, responses

CM_PER_KM = 1e5
DRAG_FLOOR = 0.05                       # rad/day: the weakest drag calibrated
def solar_day_h(rotation_rad_d, c):
    """The length of the (mean solar) day in hours for rotation rates (rad/day): 2 pi / (Omega - n_sun)."""
    n_sun = math.sqrt((c[GM_SUN] + c[GM_EARTH] + c[GM_MOON]) / c[SUN_A] ** 3)
    return 24.0 * 2 * np.pi / (np.asarray(rotation_rad_d) - n_sun)


def today_rates(c, response, y0):
    """{recession_rate_cm_per_yr, length_of_day_rate_ms_per_cy, eccentricity_rate_per_gyr,
    obliquity_rate_mas_per_cy, solar_share_of_spin_torque_z} from the rhs at y0."""
    dy = rhs(0.0, y0, (c, response))
    h_spin = c[INERTIA] * c[RADIUS] ** 2 * y0[2]
    sin_eps = math.sqrt(1.0 - (y0[3] / h_spin) ** 2)
    obliquity_rate = -(dy[3] - y0[3] * dy[2] / y0[2]) / (h_spin * sin_eps)     # from X = h cos(eps)
    lod_s = solar_day_h(y0[2], c) * 3600.0
    n_sun = math.sqrt((c[GM_SUN] + c[GM_EARTH] + c[GM_MOON]) / c[SUN_A] ** 3)
    return {"recession_rate_cm_per_yr": dy[0] * CM_PER_KM * JULIAN_YEAR_D,
            "length_of_day_rate_ms_per_cy": -lod_s / (y0[2] - n_sun) * dy[2] * JULIAN_CENTURY_D * 1e3,
            "eccentricity_rate_per_gyr": dy[1] / (2 * math.sqrt(y0[1])) * JULIAN_YEAR_D * 1e9,
            "obliquity_rate_mas_per_cy": obliquity_rate * JULIAN_CENTURY_D / MAS,
            "solar_share_of_spin_torque_z": dy[5] / (dy[4] + dy[5]) if dy[4] + dy[5] else 0.0}


def calibrated(c, model, y0, recession_cm_per_yr):
    """The response array of ``model`` (response.MODELS code) whose recession today is the one given."""
    unit = responses(model, 1.0)
    rate = today_rates(c, unit, y0)["recession_rate_cm_per_yr"]
    out = unit.copy()
    out[STRENGTH] = recession_cm_per_yr / rate
    return out


def time_lag_s(response, k2):
    """The constant time lag (s) of a calibrated response for a Love number k2."""
    return response[STRENGTH] / k2 * DAY_S


def ocean_drag(c, y0, recession_cm_per_yr, response_at):
    """The drag frequency (rad/day) of an ocean whose recession today is the one given, ``response_at(drag)``
    its response array at a drag: on the rising side of the rate's dependence on the drag (the weaker drag
    of the two that give it) when the weakest drag tried gives less, else on the falling side (near a
    resonance); None when no drag gives it.  The drags tried run from DRAG_FLOOR: a weaker one (a decay
    time beyond 20 days, against the ocean's ~1-2 days) only finds the rate on a resonance's needle."""
    from scipy.optimize import brentq

    def rate(drag):
        return today_rates(c, response_at(drag), y0)["recession_rate_cm_per_yr"] - recession_cm_per_yr

    drags = np.geomspace(DRAG_FLOOR, 30.0, 60)
    rates = np.array([rate(d) for d in drags])
    top = int(np.argmax(rates))
    if rates[top] < 0.0:
        return None
    above = np.flatnonzero(rates[:top + 1] >= 0.0)
    if above[0] > 0:
        return brentq(rate, drags[above[0] - 1], drags[above[0]], xtol=1e-14, rtol=1e-13)
    below = np.flatnonzero(rates[top:] < 0.0)
    if below.size == 0:
        return None
    k = top + below[0]
    return brentq(rate, drags[k - 1], drags[k], xtol=1e-14, rtol=1e-13)
