"""The fundamental arguments of the luni-solar theories, computed once for every scene (ERFA).

Delaunay arguments (l, l', F, D, Om) of the IERS Conventions 2003 (ERFA ``fal03``,
``falp03``, ``faf03``, ``fad03``, ``faom03``; the Moon's mean longitude is L = F + Om), and
the mean ecliptic and equinox of date (IAU 2006, ERFA ``ecm06``).  Times are TDB days
from J2000.0 (passed to ERFA as TT: they differ by < 2 ms); angles in rad.
"""
import numpy as np

from ..base.constants import J2000_JD, JULIAN_CENTURY_D


def delaunay(t_tdb_d):
    """Delaunay arguments (l, l', F, D, Om), rad, shape (5, n)."""
    import erfa

    t = np.asarray(t_tdb_d, dtype=float) / JULIAN_CENTURY_D
    return np.array([erfa.fal03(t), erfa.falp03(t), erfa.faf03(t), erfa.fad03(t), erfa.faom03(t)])


def phases(t_tdb_d, multipliers):
    """Phases (K, n), rad, and rates (K,), rad/d, of the arguments sum_j m_kj F_j (F_j Delaunay's)."""
    m = np.asarray(multipliers, dtype=float)
    t = np.asarray(t_tdb_d, dtype=float)
    step = np.diff(delaunay(np.array([t.mean() - 0.5, t.mean() + 0.5])), axis=1)[:, 0]
    rates = m @ ((step + np.pi) % (2 * np.pi) - np.pi)
    return m @ delaunay(t), rates


def ecliptic_of_date(t_tdb_d):
    """ICRS -> mean ecliptic and equinox of date matrices (n, 3, 3) (IAU 2006, ERFA ecm06)."""
    import erfa

    return erfa.ecm06(J2000_JD, np.asarray(t_tdb_d, dtype=float))


def named(t_tdb_d, multipliers):
    """name -> (phase (n,) rad, rate rad/d) of the arguments ``multipliers`` = {name: (l, l', F, D, Om)},
    in the same order: the ``arguments`` of analysis.harmonics.fit_harmonics."""
    phase, rate = phases(t_tdb_d, list(multipliers.values()))
    return {name: (p, r) for name, p, r in zip(multipliers, phase, rate)}
