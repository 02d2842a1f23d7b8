"""The integrated orbits against DE421 (scenes solar_system and earth_moon_coupled): the Moon's direction,
pole and libration, and each planet's heliocentric distance."""
from functools import partial

import numpy as np

from .common import plain_log_labels, plot_panels, thinned, titled


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
