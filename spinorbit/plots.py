"""Drawing functions for reports.write_plots (edge: matplotlib is imported by the caller of ``draw``).

Each function returns ``draw(fig)``, a ``functools.partial`` of a module-level function and its data (so
that it pickles: reports.Painter sends it to the process that draws); ``titled`` gives it the title
written above it, and a ``figsize`` attribute, when present, sizes the figure.
"""
from functools import partial

import numpy as np


def plot_series(x, ys, xlabel, ylabel, labels=None, logy=False):
    """One or more curves against x."""
    return partial(_series, x=x, ys=np.atleast_2d(ys), xlabel=xlabel, ylabel=ylabel, labels=labels, logy=logy)


def _series(fig, x, ys, xlabel, ylabel, labels, logy):
    ax = fig.add_subplot()
    for i, y in enumerate(ys):
        ax.plot(*thinned(x, y), lw=0.8, label=None if labels is None else labels[i])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if logy:
        ax.set_yscale("log")
        plain_log_labels(ax)
    if labels is not None:
        ax.legend()
    ax.grid(alpha=0.3)


def plot_panels(x, panels, xlabel, sharex=True):
    """Stacked panels sharing x (NaN leaves a panel's part out: ``sharex=False`` then fits each to its own);
    ``panels`` = [(ys, labels, ylabel), ...]; the second curve of a panel is drawn dashed over the first (a
    reference overlaid)."""
    draw = partial(_panels, x=x, panels=panels, xlabel=xlabel, sharex=sharex)
    draw.figsize = (8, 1.0 + 2.2 * len(panels))          # read by reports.write_plots
    return draw


def _panels(fig, x, panels, xlabel, sharex):
    axes = fig.subplots(len(panels), 1, sharex=sharex)
    for ax, (ys, labels, ylabel) in zip(np.atleast_1d(axes), panels):
        for i, (y, label) in enumerate(zip(np.atleast_2d(ys), labels)):
            shown = np.isfinite(y)
            ax.plot(*thinned(np.asarray(x)[shown], y[shown]), lw=1.2 if i == 0 else 0.9, ls="-" if i == 0 else "--",
                    label=label)
        ax.set_ylabel(ylabel)
        # above the panel, off the curves (which run to both edges)
        ax.legend(fontsize=8, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=len(labels), frameon=False,
                  borderaxespad=0.1, handlelength=1.5)
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel(xlabel)


def monthly_means(years, ys, month_d=27.321661):
    """(the middle years, the means (k, m)) of ``ys`` (k, n) over consecutive sidereal months of ``years``;
    a month the series does not cover whole (the last, cut by the span's end) is left out."""
    elapsed = np.abs(years - years[0]) * 365.25 / month_d
    bins = np.floor(elapsed).astype(int)
    counts = np.bincount(bins)
    kept = (counts > 0) & (np.arange(counts.size) < int(np.floor(elapsed[-1] + 1e-9)))
    means = np.array([np.bincount(bins, weights=y)[kept] / counts[kept] for y in np.atleast_2d(ys)])
    return np.bincount(bins, weights=years)[kept] / counts[kept], means


COLUMNS = 1000      # intervals across a plot's width: more than its axes' pixels (~740 at 8 in, 110 dpi)


def thinned(x, y, log=False):
    """(x, y) without the points that cannot show: of each run of consecutive points within one of COLUMNS
    equal intervals of x (of log10 x), only the lowest and the highest (in their order) and the ends are
    kept.  Drawn at the figure's width the line covers the same pixels; Agg draws ~10x fewer points
    (the Moon's physical libration, 2 x 27,393 points: 0.45 -> 0.19 s)."""
    x, y = np.asarray(x), np.asarray(y)
    if x.size <= 4 * COLUMNS:
        return x, y
    u = np.log10(x) if log else x
    column = ((u - u[0]) / (u[-1] - u[0]) * COLUMNS).astype(int)
    run = np.concatenate([[0], np.cumsum(column[1:] != column[:-1])])
    order = np.lexsort((y, run))                       # by run, then by y: each run's lowest first
    first = np.flatnonzero(np.diff(run[order], prepend=-1))
    last = np.append(first[1:] - 1, y.size - 1)
    keep = np.unique(np.concatenate([order[first], order[last], [0, y.size - 1]]))
    return x[keep], y[keep]


def plain_log_labels(ax):
    """Label the decades of ``ax``'s log axes as plain numbers ("100", "0.001"), not mathtext's 10^k,
    which costs ~40 ms a label to parse (0.35 s of the Moon's spectrum figure)."""
    from matplotlib.ticker import FuncFormatter

    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_scale() == "log":
            axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))


def titled(draw, title):
    """Give a drawing function the plot title reports.write_plots puts above it (with scene and span)."""
    draw.title = title
    return draw


def plot_error_vs_cost(rows, errors, methods=(("rk8", "o-"), ("dop853", "s--"))):
    """Max error against wall time, log-log, one curve per method and error: ``errors`` = [(key of the
    rows, label, alpha), ...], ``rows`` as from analysis.ladder (rows that failed are left out)."""
    return partial(_error_vs_cost, rows=rows, errors=errors, methods=methods)


def _error_vs_cost(fig, rows, errors, methods):
    ax = fig.add_subplot()
    for method, marker in methods:
        sel = [r for r in rows if r["method"] == method and "failed" not in r]
        for key, label, alpha in errors:
            ax.loglog([r["wall_s"] for r in sel], [max(r[key], 1e-9) for r in sel], marker, alpha=alpha,
                      label=f"{method} {label}")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("max attitude error [arcsec]")
    plain_log_labels(ax)
    ax.legend()
    ax.grid(alpha=0.3, which="both")


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
    from .analysis.spectrum import amplitude_spectrum

    rows = [r for r in rows if r["fitted_arcsec"] is not None]
    periods = [_period_d(r["period"]) for r in rows]
    published, fitted = ([abs(r[k]) for r in rows] for k in ("published_arcsec", "fitted_arcsec"))
    names = [(r["term"], p, a) for r, p, a in zip(rows, periods, published) if r["term"] in labelled]
    return plot_spectrum(*amplitude_spectrum(t, tau_arcsec), abs(t[-1] - t[0]), (periods, published, fitted), names)


def libration_zoom(years, model, reference):
    """tau and rho (arcsec) of a model beside a reference's, and their difference in mas or arcsec."""
    diff = np.array([model[k] - reference[k] for k in ("tau", "rho")])
    scale, unit = (1000.0, "mas") if np.abs(diff).max() < 1.0 else (1.0, "arcsec")
    return plot_panels(years, [
        ([model["tau"], reference["tau"]], ["model", "DE421"], "longitude τ [arcsec]"),
        ([model["rho"], reference["rho"]], ["model", "DE421"], "latitude ρ [arcsec]"),
        (diff * scale, ["τ", "ρ"], f"model − DE421 [{unit}]")], "year (TDB)")


def moon_libration(t, table, rows, labelled, zoom, zoom_reference):
    """The Moon scene's figures: residuals and physical libration from ``table`` (arcsec columns), the
    spectrum of tau with the fitted ``rows``, and the librations ``zoom_reference`` (rad) of DE421 over
    the times ``zoom`` (a mask) beside the model's; without DE421's data (``zoom`` None) no residuals."""
    from .constants import ARCSEC

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


def moon_vs_de421(year, direction, pole, longitude, unit):
    """The Moon against DE421 in three panels, each on its own scale: the angle between the model's and
    DE421's geocentric directions and between their lunar poles (unsigned), and the libration longitude's
    signed difference, in ``unit``."""
    return titled(plot_panels(year, [([direction], ["angle between the directions"], f"Moon direction [{unit}]"),
                                     ([pole], ["angle between the poles"], f"lunar pole [{unit}]"),
                                     ([longitude], ["model − DE421"], f"libration longitude [{unit}]")],
                              "year (TDB)"),
                  "the Moon against DE421: direction and pole (unsigned), libration longitude (signed)")


def planets_vs_de421(year, errors_km, floor_km=1e-3):
    """Each planet's heliocentric distance from DE421 (km) on a log axis from ``floor_km`` (the start, where
    the run and DE421 agree, dips below it), the legend above the curves."""
    return titled(partial(_planets, year=year, errors_km=errors_km, floor_km=floor_km),
                  "the planets against DE421, heliocentric")


def _planets(fig, year, errors_km, floor_km):
    ax = fig.add_subplot()
    for name, error in errors_km.items():
        ax.plot(*thinned(year, error), lw=0.8, label=name)
    ax.set_yscale("log")
    top = max(float(np.nanmax(error)) for error in errors_km.values())
    ax.set_ylim(floor_km, 100 * top)                  # a decade and more above the curves: the legend's room
    plain_log_labels(ax)
    ax.set_xlabel("year (TDB)")
    ax.set_ylabel("|model − DE421| [km]")
    ax.legend(fontsize=8, loc="upper center", ncol=5, frameon=False)
    ax.grid(alpha=0.3, which="both")


def plot_lyapunov_map(theta, rate, exponent, threshold):
    """Lyapunov exponent (1/T) over a grid of theta - f (rad) and rate / n at periapsis, the chaotic border
    (``threshold``) drawn."""
    return partial(_lyapunov_map, theta=theta, rate=rate, exponent=exponent, threshold=threshold)


def _lyapunov_map(fig, theta, rate, exponent, threshold):
    ax = fig.add_subplot()
    image = ax.pcolormesh(np.degrees(theta), rate, exponent, shading="nearest", cmap="magma")
    ax.contour(np.degrees(theta), rate, exponent, [threshold], colors="cyan", linewidths=0.8)
    fig.colorbar(image, ax=ax, label="Lyapunov exponent [1/orbital period]")
    ax.set_xlabel("theta - f at periapsis [deg]")
    ax.set_ylabel("dtheta/dt / n at periapsis")
    ax.set_title(f"Hyperion-like, planar: chaotic (> {threshold:g}/T, cyan) vs regular")


def earth_precession_nutation(t, dx_mas, dy_mas, nutation, iau, model="rigid model"):
    """The Earth scene's figures: CIP X, Y minus IAU 2006/2000A (mas) and, given the model's ``nutation``
    (dpsi, deps about its mean pole, rad), its nutation beside IAU 2000A's (``iau``: a Comparable); ``model``
    labels the model's curves."""
    from .constants import ARCSEC

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


def driven_by(t, pole_rad, lon_rad, source, other):
    """A lunar run's pole and longitude minus the same run's driven by ``other`` (arcsec), against the year."""
    from .constants import ARCSEC

    return plot_series(2000.0 + np.asarray(t) / 365.25, np.array([pole_rad, lon_rad]) / ARCSEC, "year (TDB)",
                       f"{source} - {other} driven [arcsec]", ["pole", "longitude"])


def full_minus_gyroscopic(t, diff_mas):
    """The full model's figure axis minus the gyroscopic model's, mas, against the year."""
    return plot_series(2000.0 + np.asarray(t) / 365.25, diff_mas, "year (TDB)", "full - gyroscopic figure axis [mas]")


def _period_d(text):
    """Days in a period written "27.55 d" or "273 yr"."""
    value, unit = text.split()
    return float(value) * (365.25 if unit == "yr" else 1.0)


# The astronomical periods of the climate record (kyr): obliquity, climatic precession, eccentricity.
MILANKOVITCH_KYR = {"41": 41.0, "23": 23.0, "19": 19.0, "100": 100.0, "405": 405.0}


def deep_time(t_kyr, model, reference, name):
    """Obliquity (deg) and climatic precession e sin(varpi_bar) against kyr from J2000, the reference (e.g.
    La2004) dashed over the model, and below each the model minus the reference; ``model``/``reference`` =
    {"obliquity_deg": .., "climatic_precession": ..} (``reference`` None: the model alone)."""
    panels = []
    for key, label in (("obliquity_deg", "obliquity [deg]"), ("climatic_precession", "e sin(ϖ̄)")):
        if reference is None:
            panels.append(([model[key]], ["model"], label))
            continue
        panels += [([model[key], reference[key]], ["model", name], label),
                   ([model[key] - reference[key]], [f"model − {name}"], f"{label.split(' [')[0]}: "
                    f"model − {name}" + (" [deg]" if "[deg]" in label else ""))]
    return titled(plot_panels(t_kyr, panels, "kyr from J2000"),
                  "obliquity and climatic precession" + ("" if reference is None else f" ({name} dashed)"))


DEEP_TIME_LABELS = {"obliquity_deg": "obliquity [deg]", "climatic_precession": "e sin(ϖ̄)",
                    "eccentricity": "eccentricity"}


def deep_time_spectra(t_kyr, model, reference, name):
    """Amplitude spectra of the obliquity, the climatic precession and the eccentricity (model, and the
    reference dashed), the periods of MILANKOVITCH_KYR marked."""
    from .analysis.spectrum import amplitude_spectrum

    series = {}
    for key in DEEP_TIME_LABELS:
        curves = [amplitude_spectrum(t_kyr, model[key])]
        if reference is not None:
            curves.append(amplitude_spectrum(t_kyr, reference[key]))
        series[key] = curves
    span = abs(t_kyr[-1] - t_kyr[0])
    draw = partial(_deep_time_spectra, series=series, span=span, name=name)
    draw.figsize = (8, 8.5)
    return titled(draw, "spectra, the periods marked in kyr")


def _deep_time_spectra(fig, series, span, name):
    axes = fig.subplots(len(series), 1, sharex=True)
    for ax, (key, curves) in zip(axes, series.items()):
        for i, (period, amplitude) in enumerate(curves):
            keep = period <= span / 2
            ax.loglog(*thinned(period[keep], amplitude[keep], log=True), lw=1.0 if i == 0 else 0.8,
                      ls="-" if i == 0 else "--", label="model" if i == 0 else name)
        marked = {text: period for text, period in MILANKOVITCH_KYR.items() if period <= span / 2}
        for period in marked.values():
            ax.axvline(period, color="0.6", lw=0.6, ls=":")
        if ax is axes[0] and marked:                 # the periods named once, above the plots, off the curves
            top = ax.secondary_xaxis("top")
            top.set_xticks(list(marked.values()), [f"{text}" for text in marked], fontsize=7)
            top.tick_params(which="minor", top=False, labeltop=False)
        ax.set_ylabel(f"amplitude of {DEEP_TIME_LABELS[key]}")
        ax.legend(fontsize=8, loc="lower right")
        ax.grid(alpha=0.3, which="both")
        plain_log_labels(ax)
    axes[-1].set_xlabel("period [kyr]")


def earth_moon_history(age_gyr, models, proxies, band=None):
    """The Moon's distance (Earth radii) and the length of day (h) against age (Gyr before present): one
    curve per tidal model (``models`` = {name: {"distance": .., "length_of_day": ..}}, each on its own ages
    ``age_gyr[name]``), the geological proxies with their error bars (``proxies`` = {"distance" |
    "length_of_day" | "precession_constant": [(age, value, below, above, label), ...]}, below/above None: no
    bar; one colour per site in every panel), and a sweep's band (``band`` = {"age": .., "distance": (low,
    high), "length_of_day": (low, high)}) shaded."""
    draw = partial(_earth_moon_history, age_gyr=age_gyr, models=models, proxies=proxies, band=band)
    draw.figsize = (8, 7)
    return titled(draw, "the Moon's distance and the length of day, with the geological proxies")


PROXY_MARKERS = "osD^v<>"


def _proxy_styles(proxies):
    """{site label: (colour, marker)}, the same for a site in every panel (tab10 after the models' colours)."""
    import matplotlib

    sites = sorted({p[4] for key in proxies for p in proxies[key]})
    colours = matplotlib.colormaps["tab10"].colors
    return {site: (colours[(k + 4) % len(colours)], PROXY_MARKERS[k % len(PROXY_MARKERS)])
            for k, site in enumerate(sites)}


def _draw_proxies(ax, proxies, styles):
    for age, value, below, above, text in proxies:
        bars = None if below is None else [[below], [above]]
        colour, marker = styles[text]
        ax.errorbar([age], [value], yerr=bars, fmt=marker, color=colour, ms=4, capsize=3, label=text)


def _earth_moon_history(fig, age_gyr, models, proxies, band):
    axes = fig.subplots(2, 1, sharex=True)
    styles = _proxy_styles(proxies)
    for ax, key, label in zip(axes, ("distance", "length_of_day"), ("Moon's semi-major axis [Earth radii]",
                                                                    "length of day [h]")):
        if band is not None:
            ax.fill_between(band["age"], *band[key], color="0.8", label="sweep")
        for name, series in models.items():
            ax.plot(age_gyr[name], series[key], lw=1.0, label=name)
        _draw_proxies(ax, proxies.get(key, ()), styles)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1].set_xlabel("age [Gyr before present]")
    axes[-1].invert_xaxis()


def milankovitch_periods(age_gyr, models, band=None, proxies=None):
    """The precession constant ("/yr) and the obliquity and climatic-precession periods (kyr) against age
    (Gyr before present), one curve per model (``models`` = {name: {"precession_constant": .., ...}}), a
    sweep's band shaded (``band`` = {"age": .., key: (low, high)}), the precession-constant proxies
    (``proxies`` as earth_moon_history's).  The precession constant on a log scale: ~50"/yr today, ~1e4"/yr
    in the final collapse."""
    draw = partial(_milankovitch_periods, age_gyr=age_gyr, models=models, band=band, proxies=proxies or {})
    draw.figsize = (8, 8)
    return titled(draw, "the precession constant and the Milankovitch periods")


def _milankovitch_periods(fig, age_gyr, models, band, proxies):
    keys = (("precession_constant", "precession constant [″/yr]"),
            ("obliquity_period", "k + s3 period [kyr]"), ("precession_period", "k + g5 period [kyr]"))
    axes = fig.subplots(len(keys), 1, sharex=True)
    styles = _proxy_styles(proxies)
    for ax, (key, label) in zip(axes, keys):
        if band is not None:
            ax.fill_between(band["age"], *band[key], color="0.8", label="sweep")
        for name, series in models.items():
            ax.plot(age_gyr[name], series[key], lw=1.0, label=name)
        _draw_proxies(ax, proxies.get(key, ()), styles)
        if key == "precession_constant":              # ~50"/yr today, ~1e4"/yr in the final collapse
            ax.set_yscale("log")
            plain_log_labels(ax)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("age [Gyr before present]")
    axes[-1].invert_xaxis()


def obliquity_band(t_kyr, low, high, nominal, reference, name):
    """A sweep's obliquity band (deg, min to max over its members at each time) shaded, its first member and
    the reference (e.g. La2004 Mars) over it, against kyr from J2000; below, the band's width."""
    draw = partial(_obliquity_band, t_kyr=t_kyr, low=low, high=high, nominal=nominal, reference=reference,
                   name=name)
    draw.figsize = (8, 6)
    return titled(draw, f"obliquity: the sweep's band and {name}")


def _obliquity_band(fig, t_kyr, low, high, nominal, reference, name):
    axes = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    axes[0].fill_between(t_kyr, low, high, color="0.75", label="sweep (min to max)")
    axes[0].plot(*thinned(t_kyr, nominal), lw=0.8, label="first member")
    if reference is not None:
        axes[0].plot(*thinned(t_kyr[:len(reference)], reference), lw=0.8, ls="--", label=name)
    axes[0].set_ylabel("obliquity [deg]")
    axes[0].legend(fontsize=8)
    axes[1].semilogy(t_kyr, np.maximum(high - low, 1e-6), lw=0.8)
    axes[1].set_ylabel("band width [deg]")
    axes[1].set_xlabel("kyr from J2000")
    for ax in axes:
        ax.grid(alpha=0.3)
