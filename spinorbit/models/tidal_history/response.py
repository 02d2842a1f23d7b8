"""The Earth's tidal response at a tidal frequency: the dissipative part K(sigma) = |k2(sigma)| sin(lag),
odd in sigma, of the degree-2 Love number, for each tidal model.

* constant time lag (Mignard 1979, Moon Planets 20, 301; Touma & Wisdom 1994, AJ 108, 1943): the bulge is the
  equilibrium tide of a time dt earlier, K = k2 sigma dt (linear in the frequency, Mignard's form);
* constant Q (Goldreich 1966, Rev. Geophys. 4, 411; MacDonald 1964): a phase lag independent of the
  frequency, K = (k2/Q) sign(sigma);
* a global ocean (``ocean.love_number``: a thin ocean of uniform depth under the Laplace tidal equations with
  linear drag, on the rotating Earth) plus the solid Earth's constant lag (k2/Q_solid sign(sigma));
* the ocean with its continent on the rotating Earth (``rotating_cap.love_number_imag``: the ocean outside a
  spherical cap, the Laplace tidal equations with the Coriolis force, tabulated over the spin; the
  continent's area shrinking with the age to a global ocean) plus an Andrade solid Earth (``solid.lag``: the
  same k2 and Q at today's M2, Q growing as chi^0.25 with the frequency);
* the same ocean without the Coriolis force (``cap_ocean.love_number_imag``: its damped resonances; the
  cap's size follows the age, ``cap_ocean.cap_radius``), with the same solid Earth.

sigma in rad/day, for the term e^{i(m phi + sigma t)} in the Earth (m > 0, sigma > 0: a westward wave); the
models' constants in one array: ``MODEL``, ``STRENGTH`` (k2 dt in days for the time lag, k2/Q for constant Q,
the solid Earth's k2/Q under the ocean), the factors of the zonal, diurnal and semi-diurnal bands (order |m| =
0, 1, 2 of the tide in the Earth; 1 unless a model gives each band its own Love number and lag, as DE421's
K2E_m TAUE_m), the ocean's depth (km) and drag frequency (rad/day), the Andrade solid Earth's constants
(solid.constants; zero unless the model is "ocean"), then the ocean's constants.
"""
import math

import numpy as np

from ...base.linker import cached
from .cap_ocean import cap_radius, love_number_imag
from .ocean import SIZE as OCEAN_SIZE
from .ocean import love_number
from .rotating_cap import love_number_imag as rotating_love_number_imag
from .solid import SIZE as SOLID_SIZE
from .solid import lag as andrade_lag

CONSTANT_TIME_LAG, CONSTANT_Q, GLOBAL_OCEAN, OCEAN_WITHOUT_CORIOLIS, OCEAN_WITH_CONTINENT = 0, 1, 2, 3, 4
MODELS = {"constant_time_lag": CONSTANT_TIME_LAG, "constant_q": CONSTANT_Q, "global_ocean": GLOBAL_OCEAN,
          "ocean_without_coriolis": OCEAN_WITHOUT_CORIOLIS, "ocean": OCEAN_WITH_CONTINENT}
WITH_ANDRADE = (OCEAN_WITHOUT_CORIOLIS, OCEAN_WITH_CONTINENT)
# Indices into the response's constants.
MODEL, STRENGTH, BAND, DEPTH, DRAG, SOLID = 0, 1, 2, 5, 6, 7     # BAND + |m|: the band's factor
OCEAN = SOLID + SOLID_SIZE


def responses(model, strength, bands=(1.0, 1.0, 1.0), depth=0.0, drag=0.0, ocean=None, solid=None):
    """The constants array of a model (a MODELS name or code); ``ocean``: ocean.constants(...) (the global
    ocean), rotating_cap.constants(...) (the ocean with its continent) or cap_ocean.constants(...) (without
    the Coriolis force); ``solid``: solid.constants(...) (the Andrade solid Earth under the last two)."""
    extra = np.zeros(0) if ocean is None else np.asarray(ocean, dtype=float)
    out = np.zeros(OCEAN + extra.size)
    out[MODEL] = MODELS.get(model, model)
    out[STRENGTH] = strength
    out[BAND:BAND + 3] = bands
    out[DEPTH], out[DRAG] = depth, drag
    if out[MODEL] in WITH_ANDRADE:
        if solid is None:
            raise ValueError("the ocean with its continent needs its solid Earth: solid=solid.constants(...)")
        out[SOLID:OCEAN] = solid
    out[OCEAN:] = extra
    return out


@cached(nogil=True)
def dissipation(sigma, m, spin, response, t):
    """K(sigma) of the term of order m: the lagging part of the Love number, with the sign of sigma (the bulge
    lags the forcing); ``spin`` the Earth's rotation rate (rad/day), which the global ocean's response depends
    on, t (days) the time, which sets the continent's size."""
    scale = response[STRENGTH] * response[BAND + abs(m)]
    if response[MODEL] == CONSTANT_TIME_LAG:
        return scale * sigma
    if sigma == 0.0:
        return 0.0
    solid = math.copysign(scale, sigma)
    if response[MODEL] == CONSTANT_Q:
        return solid
    if response[MODEL] == OCEAN_WITH_CONTINENT:
        return andrade_lag(sigma, response[SOLID:OCEAN]) + rotating_love_number_imag(
            m, sigma, spin, t, response[DEPTH], response[DRAG], response[OCEAN:])
    if response[MODEL] == OCEAN_WITHOUT_CORIOLIS:
        cap = cap_radius(t, response[OCEAN + OCEAN_SIZE:])
        return andrade_lag(sigma, response[SOLID:OCEAN]) + love_number_imag(m, sigma, response[DRAG],
                                                                             response[DEPTH], cap, response[OCEAN:])
    _, lag = love_number(-m, sigma, spin, response[DEPTH], response[DRAG], response[OCEAN:])
    return solid + lag
