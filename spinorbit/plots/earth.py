"""The Earth's precession-nutation: CIP X, Y against IAU 2006/2000A, the nutation beside IAU 2000A's, and the
full model's figure axis minus the gyroscopic one's."""
import numpy as np

from .common import plot_panels, plot_series, titled


def earth_precession_nutation(t, dx_mas, dy_mas, nutation, iau, model="rigid model"):
    """The Earth scene's figures: CIP X, Y minus IAU 2006/2000A (mas) and, given the model's ``nutation``
    (dpsi, deps about its mean pole, rad), its nutation beside IAU 2000A's (``iau``: a Comparable); ``model``
    labels the model's curves."""
    from ..base.constants import ARCSEC

    years = 2000.0 + np.asarray(t) / 365.25
    figures = {"residual_vs_erfa": titled(plot_series(years, [dx_mas, dy_mas], "year (TDB)",
                                                      "CIP model - IAU 2006/2000A [mas]", ["X", "Y"]),
                                          "CIP X, Y minus IAU 2006/2000A")}
    if nutation:
        dpsi, deps = nutation["dpsi"] / ARCSEC, nutation["deps"] / ARCSEC
        dpsi_iau, deps_iau = iau["dpsi_rad"] / ARCSEC, iau["deps_rad"] / ARCSEC
        figures["nutation"] = titled(plot_panels(years, [
            ([dpsi, dpsi_iau], [model, "IAU 2000A"], "Δψ [arcsec]"),
            ([deps, deps_iau], [model, "IAU 2000A"], "Δε [arcsec]"),
            ([(dpsi - dpsi_iau) * 1000, (deps - deps_iau) * 1000], ["Δψ", "Δε"], "model - IAU [mas]")],
            "year (TDB)"), "nutation Δψ, Δε vs IAU 2000A")
    return figures


def full_minus_gyroscopic(t, diff_mas):
    """The full model's figure axis minus the gyroscopic model's, mas, against the year."""
    return plot_series(2000.0 + np.asarray(t) / 365.25, diff_mas, "year (TDB)", "full - gyroscopic figure axis [mas]")
