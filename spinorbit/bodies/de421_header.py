"""The DE421 header constants, as shipped by the ``de421`` package (Folkner, Williams & Boggs 2008,
IPN PR 42-178; IOM 343R-08-003): name -> value in DE units (au, day, rad)."""
from functools import cache
from pathlib import Path

import numpy as np

J2000_JD = 2451545.0


@cache
def header():
    """Every DE421 header constant, name -> value (au, day, rad)."""
    import de421

    path = Path(de421.__file__).parent / "constants.npy"
    return {name.decode(): float(value) for name, value in np.load(path)}


def gm_km3_d2(name):
    """GM of the Sun, Earth or Moon from the header (GMS, GMB and EMRAT), km^3/d^2."""
    h = header()
    au3 = h["AU"] ** 3
    earth_share = h["EMRAT"] / (1 + h["EMRAT"])
    return {"sun": h["GMS"], "earth": h["GMB"] * earth_share, "moon": h["GMB"] * (1 - earth_share)}[name] * au3
