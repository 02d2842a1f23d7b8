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
