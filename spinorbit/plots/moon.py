"""The Moon's physical libration: monthly means and the first year, the spectrum of tau beside the
published terms, the last years beside DE421, and a run minus the same run driven by another orbit."""
from functools import partial

import numpy as np

from .common import plain_log_labels, plot_panels, plot_series, thinned, titled


def moon_libration(t, table, rows, labelled, zoom, zoom_reference):
    """The Moon scene's figures: residuals and physical libration from ``table`` (arcsec columns), the
    spectrum of tau with the fitted ``rows``, and the librations ``zoom_reference`` (rad) of DE421 over
    the times ``zoom`` (a mask) beside the model's; without DE421's data (``zoom`` None) no residuals."""
    from ..base.constants import ARCSEC

    years = 2000.0 + np.asarray(t) / 365.25
    column = lambda *names: np.array([table[name].value for name in names])
    tau_rho = column("libration_longitude", "libration_latitude")
    first_year = years <= years[0] + 1.0
    mean_years, means = monthly_means(years, tau_rho)
    figures = {"physical_libration": titled(plot_panels(np.concatenate([mean_years, years[first_year]]), [
                   (np.concatenate([means, np.full((2, first_year.sum()), np.nan)], axis=1), ["τ", "ρ"],
                    "monthly mean [arcsec]"),
                   (np.concatenate([np.full((2, mean_years.size), np.nan), tau_rho[:, first_year]], axis=1),
                    ["τ", "ρ"], "first year [arcsec]")], "year (TDB)", sharex=False),
                   "physical libration τ, ρ"),
               "libration_spectrum": titled(libration_spectrum(t, table["libration_longitude"].value, rows, labelled),
                                            "libration in longitude τ, amplitude spectrum")}
    if zoom is None:
        return figures
    model = {k: table[name].value[zoom] for k, name in (("tau", "libration_longitude"), ("rho", "libration_latitude"))}
    reference = {k: zoom_reference[k] / ARCSEC for k in ("tau", "rho")}
    return {"residuals_vs_de421": titled(plot_panels(years, [
                ([table["pole_error"].value], ["angle between the poles"], "pole: |model, DE421| [arcsec]"),
                ([table["longitude_error"].value], ["model − DE421"], "longitude [arcsec]")], "year (TDB)"),
                "pole separation (unsigned) and longitude difference from DE421"), **figures,
            "libration_zoom_vs_de421": titled(libration_zoom(years[zoom], model, reference),
                                              "the last two years, model and DE421")}


def monthly_means(years, ys, month_d=27.321661):
    """(the middle years, the means (k, m)) of ``ys`` (k, n) over consecutive sidereal months of ``years``;
    a month the series does not cover whole (the last, cut by the span's end) is left out."""
    elapsed = np.abs(years - years[0]) * 365.25 / month_d
    bins = np.floor(elapsed).astype(int)
    counts = np.bincount(bins)
    kept = (counts > 0) & (np.arange(counts.size) < int(np.floor(elapsed[-1] + 1e-9)))
    means = np.array([np.bincount(bins, weights=y)[kept] / counts[kept] for y in np.atleast_2d(ys)])
    return np.bincount(bins, weights=years)[kept] / counts[kept], means


def plot_spectrum(period, amplitude, span, terms, labelled):
    """Amplitude of tau against period (up to ``span``), with the published and fitted amplitudes of the
    terms marked: ``terms`` = (periods, published, fitted), ``labelled`` = [(name, period, amplitude), ...]."""
    keep = period <= span
    return partial(_spectrum, period=period[keep], amplitude=amplitude[keep], terms=terms, labelled=labelled)


def _spectrum(fig, period, amplitude, terms, labelled):
    ax = fig.add_subplot()
    ax.loglog(*thinned(period, amplitude, log=True), lw=0.7, color="0.3", label="model tau spectrum")
    ax.scatter(terms[0], terms[1], marker="o", facecolors="none", edgecolors="C3", s=40,
               label="published (Eckhardt, in Meeus ch. 53)", zorder=3)
    ax.scatter(terms[0], terms[2], marker="x", color="C0", s=30, label="fitted at fixed arguments", zorder=3)
    for name, p, a in labelled:
        ax.annotate(name, (p, a), textcoords="offset points", xytext=(4, 6), fontsize=7)
    ax.set_xlabel("period [d]")
    ax.set_ylabel("amplitude of tau [arcsec]")
    ax.set_ylim(1e-3, None)
    plain_log_labels(ax)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3, which="both")


def libration_spectrum(t, tau_arcsec, rows, labelled):
    """Physical libration in longitude: amplitude against period, with the published (Eckhardt, in Meeus)
    and fitted amplitudes of the fitted ``rows`` (references.eckhardt.beside_published), the names of
    the ``labelled`` terms written beside them."""
    from ..analysis.spectrum import amplitude_spectrum

    rows = [r for r in rows if r["fitted_arcsec"] is not None]
    periods = [_period_d(r["period"]) for r in rows]
    published, fitted = ([abs(r[k]) for r in rows] for k in ("published_arcsec", "fitted_arcsec"))
    names = [(r["term"], p, a) for r, p, a in zip(rows, periods, published) if r["term"] in labelled]
    return plot_spectrum(*amplitude_spectrum(t, tau_arcsec), abs(t[-1] - t[0]), (periods, published, fitted), names)


def _period_d(text):
    """Days in a period written "27.55 d" or "273 yr"."""
    value, unit = text.split()
    return float(value) * (365.25 if unit == "yr" else 1.0)


def libration_zoom(years, model, reference):
    """tau and rho (arcsec) of a model beside a reference's, and their difference in mas or arcsec."""
    diff = np.array([model[k] - reference[k] for k in ("tau", "rho")])
    scale, unit = (1000.0, "mas") if np.abs(diff).max() < 1.0 else (1.0, "arcsec")
    return plot_panels(years, [
        ([model["tau"], reference["tau"]], ["model", "DE421"], "longitude τ [arcsec]"),
        ([model["rho"], reference["rho"]], ["model", "DE421"], "latitude ρ [arcsec]"),
        (diff * scale, ["τ", "ρ"], f"model − DE421 [{unit}]")], "year (TDB)")


def driven_by(t, pole_rad, lon_rad, source, other):
    """A lunar run's pole and longitude minus the same run's driven by ``other`` (arcsec), against the year."""
    from ..base.constants import ARCSEC

    return plot_series(2000.0 + np.asarray(t) / 365.25, np.array([pole_rad, lon_rad]) / ARCSEC, "year (TDB)",
                       f"{source} - {other} driven [arcsec]", ["pole", "longitude"])
