"""earth_moon_history's model: today's Earth-Moon state, the tide its keys choose (calibrated to the recession
rate), and the history run back through the integrator door until the span's end or the state the equations
stop at (the Roche limit, or an unphysical state), with the reason."""
import math
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..base.constants import JULIAN_YEAR_D
from ..base.errors import IntegrationError
from ..bodies.table import gm_km3_d2

GYR_D = 1e9 * JULIAN_YEAR_D
AU_KM = 1.495978707e8                  # IAU 2012 Resolution B2
SUN_ECCENTRICITY = 0.0167086           # the Earth-Moon barycentre's, J2000 (Simon et al. 1994)
OBLIQUITY_DEG = 23.4392911             # IAU 2006, J2000
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
    """The tidal response of ``model`` (tides.TIDES) calibrated to tides.recession_rate (cm/yr): the one
    parameter of the simple tides, an ocean's drag at its depth (its key; fitted with the Moon's age by
    ``python benchmarks/fit_tides.py``), the continent from its keys; costly tables kept in the cache."""
    from ..base.errors import ScenarioError
    from ..models.tidal_history.tides import TIDES, Continent, NoDrag, Setting

    chosen = TIDES[model]
    depth = None if chosen.depth is None else getattr(p.tides, chosen.depth.field)
    continent = Continent(p.tides.continent_radius, p.tides.continent_colatitude,
                          p.tides.continent_until, p.tides.global_ocean_from)
    setting = Setting(c, y0, p.tides.recession_rate, depth, continent, keep_table)
    try:
        return chosen.response(setting)
    except NoDrag:
        raise ScenarioError(chosen.depth.key, depth, "a depth at which some drag gives the recession "
                            f"tides.recession_rate = {setting.recession_cm_per_yr} cm/yr with this continent "
                            f"(the stored fit's {chosen.depth.fitted()['depth_km']:.4g} km does with the default)")


def fit_trial(p, model, depth_km, recession_cm_per_yr, span_gyr=-4.6):
    """The parameters of one history of an ocean's depth fit (models.tidal_history.fit): ``p`` with tide
    ``model`` at ``depth_km`` (its depth key, tides.TIDES), its drag fitted to ``recession_cm_per_yr``, run
    ``span_gyr`` from its start, without the other tides beside it nor an error estimate; each value converted
    by its key (params.converted)."""
    import astropy.units as u

    from ..models.tidal_history.tides import TIDES
    from ..scene.params import converted

    kind, depth = type(p), TIDES[model].depth
    tides = replace(p.tides, model=model,
                    recession_rate=converted(kind, "tides.recession_rate", recession_cm_per_yr * u.cm / u.yr),
                    **{depth.field: converted(kind, depth.key, depth_km * u.km)})
    trial = replace(p, tides=tides, compare=replace(p.compare, models=False),
                    integrator=replace(p.integrator, estimate_error=False))
    return trial.with_span(p.span.start, p.span.start + (span_gyr * u.Gyr).to_value(u.d))


def keep_table(name, settings, compute):
    """``compute()``'s array kept in spinorbit's verified cache (spinorbit.base.verified: ``<cache>/tables/<name>-<hash>
    .npz``, its record the settings and the tidal-history modules' source, every array hashed, written aside
    and renamed), else computed and kept there; a damaged file is computed again, said in one line; a cache
    that cannot be read or written is done without, said in one line."""
    import hashlib
    import json
    from pathlib import Path

    from ..base import verified
    from ..base.linker import cache
    from ..models import tidal_history

    source = hashlib.sha256()
    for module in sorted(Path(tidal_history.__file__).parent.glob("*.py")):
        source.update(module.read_bytes())
    record = {**settings, "source": source.hexdigest()}
    key = hashlib.sha256(json.dumps(record, sort_keys=True).encode()).hexdigest()[:24]
    try:
        path = verified.folder("tables") / f"{name}-{key}.npz"
        entry = verified.read(path, record)
        if entry is not None:
            return entry.arrays["values"]
    except verified.Damaged as exc:
        cache.say(f"the table {path} is damaged ({exc}); computing it again")
        verified.discard(path)
    except OSError as exc:
        cache.say(f"the tables' cache could not be read ({exc.strerror}); computing the {name} table unkept")
        return compute()
    values = np.ascontiguousarray(compute())
    try:
        verified.write(path, {"values": values}, record)
    except OSError as exc:
        cache.say(f"the {name} table could not be kept in {path.parent} ({exc.strerror}); it is used unkept")
    return values


def run(p, model, t, integrate, part=None):
    """The history of ``model`` over the output times t (from J2000 back), integrated by the runner's
    ``integrate(system, times, part, ...)`` (spinorbit.scene.declaration.Run); its error estimated as the scenario says
    for the main run (``part`` None), not for a tide beside it (the summary reports the main run's alone)."""
    from ..models.tidal_history import equations

    c = constants(p.moon.stop_distance)
    y0 = today(c)
    system = equations.history(c, tide(p, c, y0, model), y0)
    integrate = partial(integrate, estimate_error=None if part is None else False)
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
