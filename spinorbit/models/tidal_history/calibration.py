"""Today's tidal rates of the Earth-Moon equations, and the strength of a one-parameter tide (constant time
lag, constant Q) that gives a recession rate: da/dt is linear in the strength, so the fit is exact."""
import json
import math
from pathlib import Path

import numpy as np

from ...constants import DAY_S, JULIAN_CENTURY_D, JULIAN_YEAR_D, MAS
from .equations import GM_EARTH, GM_MOON, GM_SUN, INERTIA, RADIUS, SUN_A, rhs
from .response import STRENGTH, responses

CM_PER_KM = 1e5
OCEAN_FIT = Path(__file__).with_name("ocean_fit.json")
GLOBAL_OCEAN_FIT = Path(__file__).with_name("global_ocean_fit.json")


def ocean_fit(path=OCEAN_FIT):
    """An ocean's fitted depth and drag, with the command that fitted them (ocean_fit.json: the ocean with
    its continent; global_ocean_fit.json: the global ocean)."""
    return json.loads(Path(path).read_text())


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


def ocean_drag(c, y0, depth_km, recession_cm_per_yr, solid_k2_over_q, water, model="global_ocean", solid=None):
    """The drag frequency (rad/day) of an ocean of ``depth_km`` whose recession today is the one given: on
    the rising side of the rate's dependence on the drag (the weaker drag of the two that give it) when the
    weakest drag tried (1e-3/day) gives less, else on the falling side (near a resonance); None when no drag
    gives it.  ``water``: ocean.constants(...) for "global_ocean", cap_ocean.constants(...) for "ocean" (with
    ``solid``: solid.constants(...), its Andrade solid Earth)."""
    from scipy.optimize import brentq

    def rate(drag):
        response = responses(model, solid_k2_over_q, depth=depth_km, drag=drag, ocean=water, solid=solid)
        return today_rates(c, response, y0)["recession_rate_cm_per_yr"] - recession_cm_per_yr

    drags = np.geomspace(1e-3, 30.0, 60)
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
