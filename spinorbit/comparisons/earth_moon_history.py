"""earth_moon_history's quantities and metrics: the history's elements, periods and angular momentum at the
output times; today's rates; the Moon's age (where the history stops at the Roche limit); each geological
proxy's residual in its own sigma and in its unit (spinorbit.references.lunar_proxies), and the day the
history gives at Xiamaling's distance, beside the day Meyers & Malinverno derived there."""
import math

import numpy as np

from ..starts.earth_moon_history import GYR_D

DAY_AT_XIAMALING = "length_of_day_at_xiamaling_distance_h"
# The metrics `metrics` computes that the scene's verdict judges (the summary's comparison keys)
RECESSION_RATE_TODAY_CM_PER_YR = "recession_rate_today_cm_per_yr"
ANGULAR_MOMENTUM_RELATIVE_ERROR_MAX = "angular_momentum_relative_error_max"
OBLIQUITY_PERIOD_TODAY_KYR, PRECESSION_PERIOD_TODAY_KYR = "obliquity_period_today_kyr", "precession_period_today_kyr"
MOON_AGE_GYR = "moon_age_gyr"


def residual_sigma(proxy):
    """The summary's key of the proxy named ``proxy``'s residual in its own sigma."""
    return f"{proxy}_residual_sigma"


XIAMALING_DISTANCE_RESIDUAL_SIGMA = residual_sigma("xiamaling_distance")
XIAMALING_PRECESSION_CONSTANT_RESIDUAL_SIGMA = residual_sigma("xiamaling_precession_constant")


def quantities(history):
    """The table's columns (see table.COLUMNS) of a History, in the table's units."""
    from ..models.tidal_history import calibration, equations, milankovitch

    c = history.constants
    el = equations.elements(history.y, c)
    n_sun = math.sqrt((c[equations.GM_SUN] + c[equations.GM_EARTH] + c[equations.GM_MOON])
                      / c[equations.SUN_A] ** 3)
    factor = milankovitch.luni_solar_factor(el["semi_major_axis"], el["eccentricity"], el["inclination"],
                                            c[equations.GM_MOON], n_sun, c[equations.SUN_E2])
    today = (el["rotation"][0], el["obliquity"][0], factor[0])
    precession = milankovitch.precession_constant(el["rotation"], el["obliquity"], factor, today)
    momentum = el["angular_momentum_z"]
    laplace = laplace_radius(el["rotation"], c)
    return {"laplace_radius_ratio": el["semi_major_axis"] / laplace,
            "t_gyr": history.t / GYR_D, "semi_major_axis": el["semi_major_axis"],
            "eccentricity": el["eccentricity"], "length_of_day": calibration.solar_day_h(el["rotation"], c),
            "obliquity": np.degrees(el["obliquity"]), "lunar_inclination": np.degrees(el["inclination"]),
            "precession_constant": precession, **milankovitch.periods_kyr(precession),
            "angular_momentum_error": (momentum - momentum[0]) / abs(momentum[0])}


def metrics(history, q):
    """{metric: value} and {"comparison.<metric>": why not measured}."""
    from ..models.tidal_history import calibration
    from ..references.lunar_proxies import PROXIES

    rates = calibration.today_rates(history.constants, history.response, history.y[0])
    out = {RECESSION_RATE_TODAY_CM_PER_YR: rates["recession_rate_cm_per_yr"],
           "length_of_day_rate_today_ms_per_cy": rates["length_of_day_rate_ms_per_cy"],
           "eccentricity_rate_today_per_gyr": rates["eccentricity_rate_per_gyr"],
           "obliquity_rate_today_mas_per_cy": rates["obliquity_rate_mas_per_cy"],
           ANGULAR_MOMENTUM_RELATIVE_ERROR_MAX: float(np.abs(q["angular_momentum_error"]).max()),
           OBLIQUITY_PERIOD_TODAY_KYR: float(q["obliquity_period"][0]),
           PRECESSION_PERIOD_TODAY_KYR: float(q["precession_period"][0]),
           MOON_AGE_GYR: None if history.stop_t is None else -history.stop_t / GYR_D,
           "laplace_radius_reached_gyr": _first_age(q, q["laplace_radius_ratio"] < 1.0)}
    if out["laplace_radius_reached_gyr"] is None and history.stop_t is not None:
        out["laplace_radius_reached_gyr"] = float(-q["t_gyr"][-1])      # crossed after the last output
    not_measured = {}
    if out["laplace_radius_reached_gyr"] is None:
        not_measured["comparison.laplace_radius_reached_gyr"] = "the Moon stays beyond the Laplace radius"
    if history.stop_t is None:
        not_measured[f"comparison.{MOON_AGE_GYR}"] = ("the history reaches the span's end without the Moon "
                                                   "at the Roche limit")
    ages = -q["t_gyr"]
    for proxy in PROXIES:
        key, residual = residual_sigma(proxy.name), f"{proxy.name}_residual_{proxy.unit}"
        if proxy.age_gyr > ages[-1]:
            out[residual] = out[key] = None
            not_measured[f"comparison.{key}"] = not_measured[f"comparison.{residual}"] = (
                f"the history stops at {ages[-1]:.3f} Gyr, before the proxy's {proxy.age_gyr} Gyr")
            continue
        model_value = float(np.interp(proxy.age_gyr, ages, proxy_series(q, proxy.quantity)))
        out[residual] = model_value - proxy.value
        out[key] = proxy.residual_sigma(model_value)
        if out[key] is None:
            not_measured[f"comparison.{key}"] = "the source's uncertainty could not be read here"
    xiamaling = next(p for p in PROXIES if p.name == "xiamaling_distance")
    out[DAY_AT_XIAMALING] = day_at_distance(q, xiamaling.value)
    if out[DAY_AT_XIAMALING] is None:
        not_measured[f"comparison.{DAY_AT_XIAMALING}"] = "the history does not reach Xiamaling's distance"
    return out, not_measured


RESONANCE_PROMINENCE = 0.02            # of the log of the recession rate: a peak 2% above its valleys


def resonances(q):
    """The distance history's fast steps (the tide's resonances crossed): [{age_gyr, width_myr,
    recession_rate_cm_per_yr}] at the peaks of the recession rate |da/dt| over the outputs, before the final
    collapse (the last 1% of the history, where the rate only grows), whose log stands RESONANCE_PROMINENCE
    above the valleys beside it; the width is the peak's full width at half that prominence."""
    from scipy.signal import find_peaks, peak_widths

    age_myr = -q["t_gyr"] * 1e3
    if age_myr.size < 5:
        return []
    rate = np.abs(np.gradient(q["semi_major_axis"], age_myr)) * 0.1                 # km/Myr -> cm/yr
    log_rate = np.log(rate[age_myr <= 0.99 * age_myr[-1]])
    peaks, _ = find_peaks(log_rate, prominence=RESONANCE_PROMINENCE)
    widths = peak_widths(log_rate, peaks, rel_height=0.5)[0] * (age_myr[1] - age_myr[0])
    return [{"age_gyr": float(age_myr[k] / 1e3), "width_myr": float(w), "recession_rate_cm_per_yr": float(rate[k])}
            for k, w in zip(peaks, widths)]


def day_at_distance(q, distance_km):
    """The history's length of day (h) where the Moon is at ``distance_km`` (the first crossing back in time),
    None if it never is: the day the model's own angular-momentum bookkeeping ties to a distance."""
    a = q["semi_major_axis"]
    below = np.flatnonzero(a <= distance_km)
    if below.size == 0 or below[0] == 0:
        return None
    k = below[0]
    return float(np.interp(distance_km, a[[k, k - 1]], q["length_of_day"][[k, k - 1]]))


def proxy_series(q, quantity):
    """The model's series for a proxy's quantity."""
    if quantity == "distance_ratio":
        return q["semi_major_axis"] / q["semi_major_axis"][0]
    return q[quantity]


def laplace_radius(rotation, c):
    """The Laplace radius r_L (km; Tremaine, Touma & Namouni 2009, AJ 137, 3706: r_L^5 = J2 R^2 a_sun^3
    (1 - e_sun^2)^(3/2) M_earth/M_sun), inside which the Moon's orbit precesses about the Earth's equator
    rather than the ecliptic: where this model's averaging over the node about the ecliptic stops holding.
    J2 follows the rotation hydrostatically (~ Omega^2) from today's."""
    from ..bodies import earth
    from ..models.tidal_history import equations

    j2 = earth.J2 * (np.asarray(rotation) / earth.ERA_RATE_RAD_D) ** 2
    return (j2 * c[equations.RADIUS] ** 2 * c[equations.SUN_A] ** 3 * (1 - c[equations.SUN_E2]) ** 1.5
            * c[equations.GM_EARTH] / c[equations.GM_SUN]) ** 0.2


def _first_age(q, mask):
    """The first age (Gyr before present) where ``mask`` holds, None if it never does."""
    where = np.flatnonzero(mask)
    return None if where.size == 0 else float(-q["t_gyr"][where[0]])


def histories(p, run):
    """({tide: History}, {tide: its quantities}): the chosen tide's (``tides.model``) first, then with
    ``compare.models`` every other model's, each run to its stop through ``run.integrate``."""
    from ..models.tidal_history.tides import TIDES
    from ..starts import earth_moon_history as model

    chosen = p.tides.model
    names = [chosen] + ([m for m in TIDES if m != chosen] if p.compare.models else [])
    runs = {name: model.run(p, name, run.times, run.integrate, None if name == chosen else name)
            for name in names}
    return runs, {name: quantities(h) for name, h in runs.items()}


def sections(chosen, runs, q):
    """The summary's sections of the histories ``runs`` (their quantities ``q``): the chosen tide's run, model,
    resonances and stop; every other model's metrics, description and stop; the proxies' provenance."""
    from ..references.lunar_proxies import provenance
    from .earth_moon_history_figures import description

    main = runs[chosen]
    return {"run": main.point, "model": {"tides": chosen, **description(main, chosen)},
            "resonances": resonances(q[chosen]),      # the distance's fast steps
            "stop": {"reason": main.stop_reason or "the span's end",
                     "t_gyr": None if main.stop_t is None else main.stop_t / GYR_D},
            "other_models": {name: {**metrics(h, q[name])[0], **description(h, name),
                                    "stop": h.stop_reason or "the span's end"}
                             for name, h in runs.items() if name != chosen},
            "reference": provenance()}
