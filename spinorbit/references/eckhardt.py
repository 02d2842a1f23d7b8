"""Eckhardt's physical libration of the Moon in longitude, as tabulated by Meeus (Astronomical
Algorithms, 2nd ed., ch. 53): the published terms the fitted libration tau is set beside.

Each term: (name, period, coefficient in arcsec, "sin"/"cos", argument).  The arguments are
multipliers of the Delaunay arguments (l, l', F, D, Om) of ``references.arguments`` (Meeus's
M' = l, M = l'), or Eckhardt's Venus argument K1 = 119.75 deg + 131.849 deg T (T in Julian
centuries).  Meeus's K2 term (1780 yr, 0.83") cannot be told from the trend over 150 yr and is
left out.  The first MAIN terms are the ones compared in reports.
"""
import numpy as np

from ..base.constants import JULIAN_CENTURY_D
from . import arguments

_DEG = 3600.0                                   # arcsec per degree
K1 = "K1"
TERMS = (
    ("annual", "365.26 d", 0.02520 * _DEG, "sin", (0, 1, 0, 0, 0)),
    ("1095 d", "1095.2 d", 0.00473 * _DEG, "sin", (2, 0, -2, 0, 0)),
    ("anomalistic month", "27.55 d", -0.00467 * _DEG, "sin", (1, 0, 0, 0, 0)),
    ("206 d", "205.9 d", 0.00276 * _DEG, "sin", (2, 0, 0, -2, 0)),
    ("18.6 yr", "6798 d", 0.00196 * _DEG, "sin", (0, 0, 0, 0, 1)),
    ("K1 (Venus, 273 yr)", "273 yr", 0.00396 * _DEG, "sin", K1),
    ("M'-F (also -0.00039 deg sin)", "6.0 yr", -0.00183 * _DEG, "cos", (1, 0, -1, 0, 0)),
    ("M'-2D", "31.8 d", 0.00115 * _DEG, "sin", (1, 0, 0, -2, 0)),
    ("M'-D", "411.8 d", -0.00096 * _DEG, "sin", (1, 0, 0, -1, 0)),
    ("2F-2D", "173.3 d", 0.00046 * _DEG, "sin", (0, 0, 2, -2, 0)),
    ("M'-M-D", "8.85 yr", -0.00032 * _DEG, "sin", (1, -1, 0, -1, 0)),
    ("2M'-M-2D", "472 d", 0.00027 * _DEG, "sin", (2, -1, 0, -2, 0)),
)
MAIN = 5


def term_arguments(t_tdb_d):
    """name -> (phase (n,) rad, rate rad/d) of every term, in TERMS order."""
    t = np.asarray(t_tdb_d, dtype=float)
    delaunay = arguments.named(t, {name: m for name, *_, m in TERMS if m != K1})
    k1 = (np.radians(119.75 + 131.849 * t / JULIAN_CENTURY_D), np.radians(131.849) / JULIAN_CENTURY_D)
    return {name: k1 if m == K1 else delaunay[name] for name, *_, m in TERMS}


def beside_published(fit):
    """Rows {term, period, function, fitted_arcsec, quadrature_arcsec, published_arcsec[, not_fitted]}
    of an ``analysis.harmonics`` fit of tau in arcsec: the coefficient of the published function
    and of its quadrature, or None and why."""
    rows = []
    for name, period, published, function, _ in TERMS:
        row = {"term": name, "period": period, "function": function, "fitted_arcsec": None,
               "quadrature_arcsec": None, "published_arcsec": round(published, 2)}
        if fit.sin[name] is not None:
            same, other = (fit.sin, fit.cos) if function == "sin" else (fit.cos, fit.sin)
            row.update(fitted_arcsec=same[name], quadrature_arcsec=other[name])
        else:
            row["not_fitted"] = fit.refused[name]
        rows.append(row)
    return rows


def physical_librations(t_tdb_d, icrf_to_body, earth_from_moon):
    """tau, rho, sigma and the sub-Earth point (rad) of lunar orientations (n, 3, 3) at TDB days ``t``, about
    the mean elements of date (analysis.librations.physical_librations on references.arguments)."""
    from ..analysis.librations import physical_librations

    _, _, f, _, om = arguments.delaunay(t_tdb_d)
    return physical_librations(icrf_to_body, arguments.ecliptic_of_date(t_tdb_d), f + om, om, earth_from_moon)


def fit_longitude_terms(t_tdb_d, tau_arcsec, free_period_d):
    """Eckhardt's terms fitted to tau (arcsec) at fixed arguments, with a free libration of ``free_period_d``
    (last: it parts from the 1095-d term only over ~40 yr) and a constant + linear trend.

    Returns ({"main": rows, "other": rows, "free_libration_..._amplitude_arcsec"}, {term: why not fitted}),
    rows as ``beside_published``."""
    from ..analysis.harmonics import fit_harmonics

    t = np.asarray(t_tdb_d, dtype=float)
    free = f"free libration ({free_period_d:.0f} d)"
    fit = fit_harmonics(t, tau_arcsec, {**term_arguments(t), free: (2 * np.pi * t / free_period_d,
                        2 * np.pi / free_period_d)}, degree=1, origin_d=t.mean())
    rows = beside_published(fit)
    amplitude = None if fit.sin[free] is None else float(np.hypot(fit.sin[free], fit.cos[free]))
    return ({"main": rows[:MAIN], "other": rows[MAIN:],
             f"free_libration_{free_period_d:.0f}d_amplitude_arcsec": amplitude},
            fit.refused)
