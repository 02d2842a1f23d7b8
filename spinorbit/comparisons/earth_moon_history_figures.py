"""earth_moon_history's figure data: each model's series against age, the proxies as error bars, and a
model's description for the summary."""
import numpy as np


def series(quantities):
    """({model: age (Gyr before present)}, {model: {distance (Earth radii), length_of_day, periods...}})."""
    from ..bodies import earth

    ages = {name: -q["t_gyr"] for name, q in quantities.items()}
    out = {name: {"distance": q["semi_major_axis"] / earth.EQUATORIAL_RADIUS_KM,
                  **{k: q[k] for k in ("length_of_day", "precession_constant", "obliquity_period",
                                       "precession_period")}}
           for name, q in quantities.items()}
    return ages, out


def proxies():
    """{"distance" | "length_of_day" | "precession_constant": [(age, value, below, above, site)]} in Earth
    radii, hours and "/yr."""
    from ..bodies import earth, moon
    from ..references.lunar_proxies import PROXIES

    scale = {"semi_major_axis": ("distance", 1.0 / earth.EQUATORIAL_RADIUS_KM),
             "distance_ratio": ("distance", moon.MEAN_DISTANCE_KM / earth.EQUATORIAL_RADIUS_KM),
             "length_of_day": ("length_of_day", 1.0), "precession_constant": ("precession_constant", 1.0)}
    out = {key: [] for key, _ in scale.values()}
    for p in PROXIES:
        if p.quantity not in scale:
            continue
        key, factor = scale[p.quantity]
        below = None if p.sigma_below is None else p.sigma_below * factor
        above = None if p.sigma_above is None else p.sigma_above * factor
        out[key].append((p.age_gyr, p.value * factor, below, above, p.name.split("_", 1)[0]))
    return out


def description(history, model):
    """The tide's fitted parameters (tides.TIDES[model].describe) for the summary."""
    from ..models.tidal_history.tides import TIDES

    return TIDES[model].describe(history.response)


BAND_KEYS = ("distance", "length_of_day", "precession_constant", "obliquity_period", "precession_period")


def band(tables):
    """({"age", key: (low, high)}, the first member's series) over the members' tables (a sweep's), on the
    ages every member reaches (a member that stops earlier ends the band there)."""
    members = []
    for table in tables:
        q = {name: np.asarray(getattr(table[name], "value", table[name]), dtype=float)
             for name in ("t_gyr", "semi_major_axis", "length_of_day", "precession_constant",
                          "obliquity_period", "precession_period")}
        members.append(series({"member": q}))
    reach = min(float(ages["member"][-1]) for ages, _ in members)
    age = np.linspace(0.0, reach, 500)
    out = {"age": age}
    for key in BAND_KEYS:
        curves = np.array([np.interp(age, ages["member"], s["member"][key]) for ages, s in members])
        out[key] = (curves.min(axis=0), curves.max(axis=0))
    return out, members[0]
