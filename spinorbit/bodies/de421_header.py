"""The DE421 header constants, as shipped by the ``de421`` package (Folkner, Williams & Boggs 2008,
IPN PR 42-178; IOM 343R-08-003): name -> value in DE units (au, day, rad)."""
from functools import cache
from pathlib import Path

import numpy as np


@cache
def header():
    """Every DE421 header constant, name -> value (au, day, rad)."""
    import de421

    path = Path(de421.__file__).parent / "constants.npy"
    return {name.decode(): float(value) for name, value in np.load(path)}


# Body name -> key of its GM in the header (au^3/d^2); the Earth and the Moon share GMB by EMRAT.
GM_KEYS = {"sun": "GMS", "mercury": "GM1", "venus": "GM2", "mars": "GM4", "jupiter": "GM5",
           "saturn": "GM6", "uranus": "GM7", "neptune": "GM8", "pluto": "GM9"}


def gm_km3_d2(name):
    """GM of a body from the header (planets: their system barycentres), km^3/d^2."""
    h = header()
    if name in ("earth", "moon"):
        earth_share = h["EMRAT"] / (1 + h["EMRAT"])
        gm = h["GMB"] * (earth_share if name == "earth" else 1 - earth_share)
    else:
        gm = h[GM_KEYS[name]]
    return gm * h["AU"] ** 3
