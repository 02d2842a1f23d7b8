"""Laskar's insolation solutions La2004 and La93, read offline from the ``inso`` package (a test dependency).

La2004 (Laskar et al. 2004, A&A 428, 261) and La93 (Laskar, Joutel & Boudin 1993, A&A 270, 522) as IMCCE
distributes them and ``inso`` ships them (``inso/astrofiles/``): t in kyr from J2000, the eccentricity e, the
obliquity eps (rad) and the longitude of perihelion from the moving equinox varpi_bar (rad), every kyr.
La2004: 0 to -51 Myr (``INSOLN.LA2004.BTL.ASC``), to -101 Myr at 6 decimals (``...BTL.100.ASC``), 0 to +21 Myr
(``INSOLP...``).  Mars's La2004 and La2003 (Laskar et al. 2004, Icarus 170, 343): -21 to +11 Myr, the same
columns for Mars.  La93 with (CMAR, FGAM) = (0, 1), no tidal dissipation, and (1, 1), Quinn et al. 1991's
tides: 0 to -20 Myr and 0 to +10 Myr.  Fortran ``D`` exponents.
"""
import functools
import importlib.util
from pathlib import Path

import numpy as np

from ..base.errors import InputError
from .base import Comparable

KYR_D = 365250.0
# solution -> (files, past first), citation
SOLUTIONS = {
    "La2004": (("Laskar2004/INSOLN.LA2004.BTL.ASC", "Laskar2004/INSOLN.LA2004.BTL.100.ASC",
                "Laskar2004/INSOLP.LA2004.BTL.ASC"), "Laskar et al. 2004, A&A 428, 261"),
    "La93_01": (("Laskar1993/INSOLN.LA93_01.BTL.ASC", "Laskar1993/INSOLP.LA93_01.BTL.ASC"),
                "Laskar, Joutel & Boudin 1993, A&A 270, 522: no tidal dissipation (CMAR 0, FGAM 1)"),
    "La93_11": (("Laskar1993/INSOLN.LA93_11.BTL.ASC", "Laskar1993/INSOLP.LA93_11.BTL.ASC"),
                "Laskar, Joutel & Boudin 1993, A&A 270, 522: Quinn et al. 1991's tides (CMAR 1, FGAM 1)"),
    "La2004_Mars": (("LaskarMars2003-2004/INSOLN.LA2004.MARS.ASC", "LaskarMars2003-2004/INSOLP.LA2004.MARS.ASC"),
                    "Laskar et al. 2004, Icarus 170, 343: Mars, initial conditions after Yoder et al. 2003, "
                    "p = -7.597\"/yr, k2 = 0.149, Q = 92 (the files' README)"),
    "La2003_Mars": (("LaskarMars2003-2004/INSOLN.LA2003.MARS.ASC", "LaskarMars2003-2004/INSOLP.LA2003.MARS.ASC"),
                    "Laskar et al. 2004, Icarus 170, 343: Mars, La2003, p = -7.576\"/yr (Folkner et al. 1997), "
                    "k2 = 0.14, Q = 50 (the files' README)"),
}


def _folder():
    """inso's astrofiles folder, found without importing inso (which imports matplotlib), or None."""
    spec = importlib.util.find_spec("inso")
    return None if spec is None else Path(spec.submodule_search_locations[0]) / "astrofiles"


def available():
    """None when ``inso`` is installed, else the reason it is not (for "not compared")."""
    if _folder() is None:
        return "the inso package (La2004, La93) is not installed: pip install inso, or the [test] extra"
    return None


def _read(name):
    """(t_kyr, e, eps, varpi_bar) of one file, ascending in t."""
    table = np.array((_folder() / name).read_text().replace("D", "E").split(), dtype=float).reshape(-1, 4)
    return table[np.argsort(table[:, 0])]


@functools.cache
def table(solution):
    """The whole solution (t_kyr, e, eps, varpi_bar) (k, 4), ascending, each kyr once (the longer file's
    rows replaced by the full-precision ones where both have them)."""
    files, _ = SOLUTIONS[solution]
    rows = {}
    for name in sorted(files, key=lambda f: "100" not in f):          # the 6-decimal file first, overwritten
        for row in _read(name):
            rows[round(row[0])] = row
    return np.array([rows[k] for k in sorted(rows)])


class Insolation:
    """A Laskar solution as a ``references.base.Reference``: at TDB days that fall on its kyr grid, values
    ``eccentricity``, ``obliquity_rad``, ``perihelion_longitude_rad`` (varpi_bar from the moving equinox)."""

    def __init__(self, solution="La2004"):
        if solution not in SOLUTIONS:
            raise InputError("solution", solution, f"one of {sorted(SOLUTIONS)}")
        self.name = solution

    def span_kyr(self):
        t = table(self.name)[:, 0]
        return float(t[0]), float(t[-1])

    def __call__(self, t_tdb_d):
        t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
        rows = table(self.name)
        kyr = t / KYR_D
        index = np.round(kyr - rows[0, 0]).astype(int)
        inside = (index >= 0) & (index < len(rows))
        if not inside.all() or np.abs(rows[index, 0] - kyr).max() > 1e-6:
            raise InputError("t_out", f"{kyr.min():.6g} to {kyr.max():.6g} kyr",
                             f"whole kyr from J2000 inside {self.name}'s {self.span_kyr()} kyr")
        picked = rows[index]
        values = {"eccentricity": picked[:, 1], "obliquity_rad": picked[:, 2],
                  "perihelion_longitude_rad": picked[:, 3]}
        return Comparable(t, values, self.provenance())

    def provenance(self):
        from importlib.metadata import version

        files, citation = SOLUTIONS[self.name]
        return {"name": self.name, "data": f"inso {version('inso')}: {', '.join(files)}",
                "citation": citation, "span": "{:g} to {:g} kyr from J2000".format(*self.span_kyr())}
