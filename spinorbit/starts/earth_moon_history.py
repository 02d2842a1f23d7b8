"""earth_moon_history's model: today's Earth-Moon state, the tide its keys choose (calibrated to the recession
rate), and the history run back through the integrator door until the span's end or the state the equations
stop at (the Roche limit, or an unphysical state), with the reason."""
import math
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..bodies.table import gm_km3_d2
from ..constants import JULIAN_YEAR_D
from ..errors import IntegrationError

GYR_D = 1e9 * JULIAN_YEAR_D
AU_KM = 1.495978707e8                  # IAU 2012 Resolution B2
SUN_ECCENTRICITY = 0.0167086           # the Earth-Moon barycentre's, J2000 (Simon et al. 1994)
OBLIQUITY_DEG = 23.4392911             # IAU 2006, J2000
LOVE_K2 = 0.30                         # the solid Earth's degree-2 Love number, to quote a time lag
SOLID_Q = 280.0                        # the solid Earth's Q at M2 (Ray, Eanes & Lemoine 2001, GJI 146, 781)
STOP_REFINEMENT = 1000                 # outputs that bracket the stop inside one output step


@dataclass
class History:
    """A history: output times (TDB d) and states up to where it stops, the equations' constants and tidal
    response, the run's point (simulate), why it stopped ("" if it reached the span's end) and when."""

    t: np.ndarray
    y: np.ndarray
    constants: np.ndarray
    response: np.ndarray
    point: dict
    stop_reason: str = ""
    stop_t: float | None = None
    solution: object = None


def constants(stop_radii):
    from ..bodies import earth
    from ..models.tidal_history import equations

    radius = earth.EQUATORIAL_RADIUS_KM
    return equations.constants(gm_km3_d2("earth"), gm_km3_d2("moon"), gm_km3_d2("sun"), radius, earth.C_MR2,
                               AU_KM, SUN_ECCENTRICITY, stop_radii * radius)


def today(c):
    """The state at J2000: the Moon's mean orbit (bodies.moon), the Earth's rotation, IAU 2006's obliquity."""
    from ..bodies import earth, moon
    from ..models.tidal_history import equations

    return equations.state(c, moon.MEAN_DISTANCE_KM, moon.MEAN_ECCENTRICITY, earth.ERA_RATE_RAD_D,
                           math.radians(OBLIQUITY_DEG), math.radians(moon.MEAN_INCLINATION_DEG))


def tide(p, c, y0, model):
    """The tidal response of ``model`` calibrated to tides.recession_rate (cm/yr): the one parameter of the
    simple tides, an ocean's drag at its depth (tides.ocean_depth for the ocean with its continent,
    tides.global_ocean_depth for the global one; each depth fitted with the Moon's age by ``python -m
    spinorbit.fit_tides``)."""
    from ..errors import ScenarioError
    from ..models.tidal_history import calibration, cap_ocean, equations, ocean, response, solid

    rate = p["tides.recession_rate"]
    if model not in ("global_ocean", "ocean"):
        return calibration.calibrated(c, response.MODELS[model], y0, rate)
    radius = c[equations.RADIUS]
    water = ocean.constants(c[equations.GM_EARTH] / radius**2, radius)
    key = "tides.ocean_depth" if model == "ocean" else "tides.global_ocean_depth"
    andrade = None
    if model == "ocean":
        water = cap_ocean.constants(water, p["tides.continent_radius"], p["tides.continent_colatitude"],
                                    p["tides.continent_until"] * GYR_D, p["tides.global_ocean_from"] * GYR_D)
        mean_motion = math.sqrt((c[equations.GM_EARTH] + c[equations.GM_MOON]) / y0[0] ** 3)
        andrade = solid.constants(2.0 * (y0[2] - mean_motion))                 # today's M2
    depth = p[key]
    drag = calibration.ocean_drag(c, y0, depth, rate, LOVE_K2 / SOLID_Q, water, model, andrade)
    if drag is None:
        raise ScenarioError(key, depth, f"a depth at which some drag gives the recession "
                            f"tides.recession_rate = {rate} cm/yr (e.g. 3 to 8 km)")
    return response.responses(model, LOVE_K2 / SOLID_Q, depth=depth, drag=drag, ocean=water, solid=andrade)


def run(p, model, t, integrate, part=None):
    """The history of ``model`` over the output times t (from J2000 back), integrated by the runner's
    ``integrate(system, times, part, ...)`` (spinorbit.scene.Run)."""
    from ..models.tidal_history import equations

    c = constants(p["moon.stop_distance"])
    y0 = today(c)
    system = equations.history(c, tide(p, c, y0, model), y0)
    try:
        solution, point = integrate(system, t, part)
        reached = t.size
    except IntegrationError as exc:            # the stop: the rates run away at the Roche limit
        reached = exc.partial.t.size           # the outputs reached, today's (t0's) among them
        if reached < 3:
            raise
        solution, point = integrate(system, t[:reached], f"{part or model} to the stop")
    y = solution.y
    outside = [k for k in range(y.shape[0]) if equations.stop(y[k], c)]
    if outside:                                 # frozen past the stop (the rhs is zero there)
        reached = outside[0]
    elif reached == t.size:
        return History(t, y, c, system.params[1], point, solution=solution)
    t, y = t[:reached], y[:reached]
    refine = partial(integrate, part=f"{part or model} stop", estimate_error=False)
    stop_t, reason = _stop(system, t[-1], y[-1], 2 * t[-1] - t[-2], c, refine)
    return History(t, y, c, system.params[1], point, reason, stop_t, solution)


def _stop(system, t_last, y_last, t_next, c, refine, levels=2):
    """(the time and the reason) the history stops between t_last and t_next, found to an output step over
    STOP_REFINEMENT**levels by ``refine(system, times) -> (solution, point)``.

    The equations are zero outside their domain; an adaptive step cannot cross that edge where the rates run
    away (the Moon at the Roche limit, ~a^-6.5), so there the run ends: the time is the last state reached,
    and the reason the Roche limit when the Moon is within twice its distance."""
    from ..models.tidal_history import equations

    fine = np.linspace(t_last, t_next, STOP_REFINEMENT + 1)
    start = replace(system, t0=float(t_last), y0=np.asarray(y_last, dtype=float))
    try:
        solution, _ = refine(start, fine[1:])
    except IntegrationError as exc:
        solution = exc.partial
    times, states = [t_last, *solution.t], [np.asarray(y_last, dtype=float), *solution.y]
    for k, (tk, yk) in enumerate(zip(times, states)):
        if equations.stop(yk, c):
            if levels > 1 and k > 0:
                return _stop(system, times[k - 1], states[k - 1], tk, c, refine, levels - 1)
            return float(tk), equations.stop(yk, c)
    if len(times) == fine.size:
        return float(times[-1]), ""
    if levels > 1:
        return _stop(system, times[-1], states[-1], fine[len(times)], c, refine, levels - 1)
    a = states[-1][0]
    if a < 2 * c[equations.STOP_A]:
        at_limit = np.array(states[-1])
        at_limit[0] = c[equations.STOP_A]
        return float(times[-1]), equations.stop(at_limit, c)
    e = math.sqrt(max(states[-1][1], 0.0))
    return float(times[-1]), f"the integration could not go on (a = {a:.6g} km, e = {e:.3g})"
