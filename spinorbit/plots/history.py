"""The Earth-Moon tidal history against age: the Moon's distance and the length of day, the precession
constant and the Milankovitch periods, with the geological proxies and a sweep's band."""
from functools import partial

from .common import plain_log_labels, titled


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
