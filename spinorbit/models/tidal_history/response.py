"""The Earth's tidal response at a tidal frequency: the dissipative part K(sigma) = |k2(sigma)| sin(lag),
odd in sigma, of the degree-2 Love number, for each tidal model.

* constant time lag (Mignard 1979, Moon Planets 20, 301; Touma & Wisdom 1994, AJ 108, 1943): the bulge is the
  equilibrium tide of a time dt earlier, K = k2 sigma dt (linear in the frequency, Mignard's form);
* constant Q (Goldreich 1966, Rev. Geophys. 4, 411; MacDonald 1964): a phase lag independent of the
  frequency, K = (k2/Q) sign(sigma).

sigma in rad/day; the models' constants in one array: ``MODEL``, ``STRENGTH`` (k2 dt in days for the time
lag, k2/Q for constant Q) and the factors of the zonal, diurnal and semi-diurnal bands (order |m| = 0, 1, 2 of
the tide in the Earth), 1 unless a model gives each band its own Love number and lag (DE421's K2E_m TAUE_m).
"""
import math

import numpy as np
from numba import njit

CONSTANT_TIME_LAG, CONSTANT_Q = 0, 1
MODELS = {"constant_time_lag": CONSTANT_TIME_LAG, "constant_q": CONSTANT_Q}
# Indices into the response's constants.
MODEL, STRENGTH, BAND = 0, 1, 2           # BAND + |m|: the band's factor
SIZE = 5


def responses(model, strength, bands=(1.0, 1.0, 1.0)):
    """The constants array of a model (a MODELS name or code)."""
    out = np.zeros(SIZE)
    out[MODEL] = MODELS.get(model, model)
    out[STRENGTH] = strength
    out[BAND:] = bands
    return out


@njit(cache=True, nogil=True)
def dissipation(sigma, order, response):
    """K(sigma) for the band of order |m| = ``order``: the lagging part of the Love number, with the sign of
    sigma (the bulge lags the forcing)."""
    scale = response[STRENGTH] * response[BAND + order]
    if response[MODEL] == CONSTANT_TIME_LAG:
        return scale * sigma
    if sigma == 0.0:
        return 0.0
    return math.copysign(scale, sigma)
