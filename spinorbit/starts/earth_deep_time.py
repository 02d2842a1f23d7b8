"""earth_deep_time's model: the orbital solution its orbit keys name, and the averaged spin equations on it,
the axis started on IAU 2006's mean pole at J2000."""
import math
import time
from dataclasses import dataclass

import numpy as np

from ..base.constants import ARCSEC, DAY_S, JULIAN_CENTURY_D, JULIAN_YEAR_D
from ..base.errors import InputError, ScenarioError
from ..orbits.sources import OrbitSource
from ..scene.params import key, source_key, table

KYR_D = 1000 * JULIAN_YEAR_D
MYR_D = 1000 * KYR_D
ERFA_SPAN_D = 2 * KYR_D               # the orbit reaches at least this far: ERFA's comparison


@table
class DeepTimeOrbitTable:
    """The orbital solution's keys (earth_deep_time, mars_deep_time)."""

    ephemeris: OrbitSource = source_key("the JPL ephemeris whose J2000 state starts the solar system",
                                        choices=("de421", "de440"))
    step: float = key(unit="d", default=5.0, min=1.0, max=5.0,
                      help="WHFast step, 1 to 5 d (5 d: the e vector within 7e-8 of 1 d's over 200 kyr; 8 d "
                           "meets a step resonance, 7e-5)")
    output: float = key(unit="d", default=36525.0, min=365.0, max=182625.0,
                        help="cadence of the orbital solution, a whole number of steps (at most 500 yr)")
    moon: str = key(type=str, default="ring", choices=("ring", "static_ring", "none"),
                    help="the Moon as the barycentre's quadrupole: measured against the Moon as a body, "
                         "the first-order ring, or none")
    relativity: bool = key(type=bool, default=True, help="the Sun's GR on the orbits")
    file: str = key(type=str, default="", help="an orbital solution file (default: the cache's)")


MAX_SPAN_D = 100 * MYR_D
ORBIT_KEYS = {"step": "orbit.step", "output": "orbit.output", "moon": "orbit.moon",
              "orbit_file": "orbit.file"}


def check_span(p):
    """ScenarioError unless the span starts at J2000, reaches at most 100 Myr, and rk8 steps at most 1 kyr."""
    if abs(p.span.start) > 1e-6:
        raise ScenarioError("span.start", p.span.start, "J2000, '2000-01-01T12:00:00' (the solar "
                            "system starts from the ephemeris's state and the axis from its pole there)")
    if abs(p.span.end) > MAX_SPAN_D:
        raise ScenarioError("span.end", p.span.end, "at most 100 Myr either way of J2000 (the "
                            "tidal law and the averaged Moon are not vouched for beyond; La2004 stops at "
                            "-101 Myr)")
    if p.integrator.method != "rk8":
        raise ScenarioError("integrator.method", p.integrator.method, "rk8 (the compiled fixed step)")
    step = p.integrator.step or 0.0                             # rk8's own default: 1 d
    if step > KYR_D:
        raise ScenarioError("integrator.step", step, "at most 1 kyr (26 steps a precession cycle)")


def nbody_counts(p):
    """The N-body stage the up-front estimate counts: the orbital solution's steps not yet in the cache."""
    return {"WHFast steps": steps_to_compute(p)}


def settings(p):
    """The orbital solution's Settings from the scenario's orbit keys."""
    from ..orbits.solution import Settings

    return Settings(ephemeris=p.orbit.ephemeris.name, step_d=p.orbit.step, output_d=p.orbit.output,
                    relativity=p.orbit.relativity, moon=p.orbit.moon)


def orbit_end(p):
    """Where the orbital solution must reach: the span's end, at least ERFA_SPAN_D from J2000."""
    return math.copysign(max(abs(p.span.end), ERFA_SPAN_D), p.span.end)


def steps_to_compute(p):
    """The WHFast steps of the orbital solution this run still has to compute (none when it is cached)."""
    from ..orbits import solution

    return solution.steps_to_compute(settings(p), p.span.start, orbit_end(p), path=p.orbit.file or None)


def orbital_solution(p, label):
    """The solution covering the span (and at least 2 kyr of it), from the cache or orbit.file."""
    from ..orbits import solution

    end = orbit_end(p)
    try:
        return solution.solve(settings(p), p.span.start, end, path=p.orbit.file or None, label=label)
    except InputError as exc:
        raise ScenarioError(ORBIT_KEYS.get(exc.name, exc.name), exc.given, exc.accepted) from None


def timed_orbital_solution(p, label):
    """(orbital_solution(p, label), the wall time it took, s: the N-body run when the cache lacks it)."""
    started = time.perf_counter()
    orbit = orbital_solution(p, label)
    return orbit, time.perf_counter() - started


@dataclass
class SpinModel:
    """The averaged equations on the orbit (``system``, run through integrators.simulate), where they start
    (the spin axis and the orbit normal at J2000) and a record of their constants."""

    system: object
    spin_axis0: np.ndarray
    normal0: np.ndarray
    description: dict


def spin_model(p, orbit):
    """The averaged spin equations' parameters on ``orbit``, the axis started on IAU 2006's mean pole."""
    import erfa

    from ..bodies import earth
    from ..bodies.de421_header import header
    from ..models import deep_time
    from ..orbits.solution import MOON
    from ..references.erfa_pole import PSI_A_RATE_ARCSEC_CY

    grid = np.column_stack([orbit.normal, orbit.eccentricity_vector])
    j2000 = int(np.searchsorted(orbit.t_d, 0.0))
    normal0, e0 = orbit.normal[j2000], float(orbit.eccentricity[j2000])
    spin_axis0 = erfa.pmat06(2451545.0, 0.0)[2]                 # the mean pole of J2000 in the GCRS
    obliquity0 = math.acos(spin_axis0 @ normal0)
    h = header()
    a_km, c_km_d = h["AU"], h["CLIGHT"] * DAY_S
    geodesic = deep_time.geodesic_rate(a_km, c_km_d) / (1 - e0**2)
    per_cy = ARCSEC / JULIAN_CENTURY_D
    if p.model.precession == "iau2006_rate":
        alpha0 = deep_time.constant_from_rate(PSI_A_RATE_ARCSEC_CY * per_cy, obliquity0, geodesic)
    else:
        alpha0 = deep_time.constant_from_ellipticity(earth.H_D, earth.ERA_RATE_RAD_D, a_km, e0)
    tilt = earth.TIDAL_OBLIQUITY_RATE_ARCSEC_CY * per_cy if p.model.tidal_tilt else 0.0
    params = deep_time.parameters(grid, orbit.t_d[0], p.orbit.output, alpha0, e0, a_km, c_km_d,
                                  earth.ERA_RATE_RAD_D, ed=p.model.Ed, td=p.model.Td,
                                  tilt_rad_d=tilt, obliquity0=obliquity0)
    alpha = alpha0 * p.model.Ed
    description = {
        "precession_constant_arcsec_per_cy": alpha / per_cy,
        "precession_constant_from": p.model.precession,
        "dynamical_ellipticity": deep_time.implied_ellipticity(alpha, earth.ERA_RATE_RAD_D, a_km, e0),
        "psi_rate_j2000_arcsec_per_cy": (alpha * math.cos(obliquity0) - geodesic) / per_cy,
        "geodesic_arcsec_per_cy": geodesic / per_cy, "obliquity_j2000_deg": math.degrees(obliquity0),
        "tidal_obliquity_rate_arcsec_per_cy": tilt * p.model.Td / per_cy,
        "moon_quadrupole_factor": MOON[p.orbit.moon], "Td": p.model.Td,
        "Ed": p.model.Ed}
    return SpinModel(deep_time.averaged_spin(params, spin_axis0), spin_axis0, normal0, description)
