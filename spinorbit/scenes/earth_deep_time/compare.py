"""earth_deep_time's work below the scene: the orbital solution it names, the spin model started at J2000, the
table in La2004's quantities, and the comparisons with ERFA's long-term precession, La2004 and La93."""
import math
from dataclasses import dataclass

import numpy as np

from ...constants import ARCSEC, DAY_S, JULIAN_CENTURY_D
from ...errors import InputError, ScenarioError

KYR_D = 365250.0
WINDOWS_MYR = (1, 10)                 # the spans the issue sets targets over
CHAOS_MYR = 50.0                      # La2004: "age calibrations of paleoclimatic data over 40 to 50 Myr"
ERFA_SPAN_D = 2 * KYR_D
ERFA_STEP_D = 10 * 365.25
ORBIT_KEYS = {"step": "orbit.step", "output": "orbit.output", "moon": "orbit.moon",
              "orbit_file": "orbit.file"}


def settings(scenario):
    """The orbital solution's Settings from the scenario's orbit keys."""
    from ...orbits.solution import Settings

    return Settings(ephemeris=scenario["orbit.ephemeris"], step_d=scenario["orbit.step"],
                    output_d=scenario["orbit.output"], relativity=scenario["orbit.relativity"],
                    moon=scenario["orbit.moon"])


def orbital_solution(scenario, label):
    """The solution covering the span (and at least 2 kyr of it), from the cache or orbit.file."""
    from ...orbits import solution

    end = math.copysign(max(abs(scenario.t_end), ERFA_SPAN_D), scenario.t_end)
    try:
        return solution.solve(settings(scenario), scenario.t_start, end, path=scenario["orbit.file"] or None,
                              label=label)
    except InputError as exc:
        raise ScenarioError(ORBIT_KEYS.get(exc.name, exc.name), exc.given, exc.accepted) from None


@dataclass
class SpinModel:
    params: tuple
    y0: np.ndarray
    spin_axis0: np.ndarray
    normal0: np.ndarray
    description: dict


def spin_model(scenario, orbit):
    """The averaged spin equations' parameters on ``orbit``, the axis started on IAU 2006's mean pole."""
    import erfa

    from ...bodies import earth
    from ...bodies.de421_header import header
    from ...models import deep_time
    from ...orbits.solution import MOON
    from ...references.erfa_pole import PSI_A_RATE_ARCSEC_CY

    grid = np.column_stack([orbit.normal, orbit.eccentricity_vector])
    j2000 = int(np.searchsorted(orbit.t_d, 0.0))
    normal0, e0 = orbit.normal[j2000], float(orbit.eccentricity[j2000])
    spin_axis0 = erfa.pmat06(2451545.0, 0.0)[2]                 # the mean pole of J2000 in the GCRS
    obliquity0 = math.acos(spin_axis0 @ normal0)
    h = header()
    a_km, c_km_d = h["AU"], h["CLIGHT"] * DAY_S
    geodesic = deep_time.geodesic_rate(a_km, c_km_d) / (1 - e0**2)
    per_cy = ARCSEC / JULIAN_CENTURY_D
    if scenario["model.precession"] == "iau2006_rate":
        alpha0 = deep_time.constant_from_rate(PSI_A_RATE_ARCSEC_CY * per_cy, obliquity0, geodesic)
    else:
        alpha0 = deep_time.constant_from_ellipticity(earth.H_D, earth.ERA_RATE_RAD_D, a_km, e0)
    tilt = earth.TIDAL_OBLIQUITY_RATE_ARCSEC_CY * per_cy if scenario["model.tidal_tilt"] else 0.0
    params = deep_time.parameters(grid, orbit.t_d[0], scenario["orbit.output"], alpha0, e0, a_km, c_km_d,
                                  earth.ERA_RATE_RAD_D, ed=scenario["model.Ed"], td=scenario["model.Td"],
                                  tilt_rad_d=tilt, obliquity0=obliquity0)
    alpha = alpha0 * scenario["model.Ed"]
    description = {
        "precession_constant_arcsec_per_cy": alpha / per_cy,
        "precession_constant_from": scenario["model.precession"],
        "dynamical_ellipticity": deep_time.implied_ellipticity(alpha, earth.ERA_RATE_RAD_D, a_km, e0),
        "psi_rate_j2000_arcsec_per_cy": (alpha * math.cos(obliquity0) - geodesic) / per_cy,
        "geodesic_arcsec_per_cy": geodesic / per_cy, "obliquity_j2000_deg": math.degrees(obliquity0),
        "tidal_obliquity_rate_arcsec_per_cy": tilt * scenario["model.Td"] / per_cy,
        "moon_quadrupole_factor": MOON[scenario["orbit.moon"]], "Td": scenario["model.Td"],
        "Ed": scenario["model.Ed"]}
    return SpinModel(params, deep_time.start_state(spin_axis0), spin_axis0, normal0, description)


def quantities(t, states, orbit, model):
    """La2004's quantities and the rest of the table at times t from the spin states and the orbit."""
    import erfa

    from ...bodies import moon
    from ...models import deep_time
    from ...orbits.solution import elements

    normal, eccentricity_vector = deep_time.orbit_series(t, *model.params[:3])
    angles = deep_time.climate_angles(states[:, :3], normal, eccentricity_vector, model.spin_axis0,
                                      model.normal0)
    e, varpi, inclination, node = elements(normal, eccentricity_vector, erfa.ecm06(2451545.0, 0.0))
    return {"t_kyr": t / KYR_D, "eccentricity": e, **angles,
            "climatic_precession": e * np.sin(angles["perihelion_longitude"]),
            "perihelion_longitude_j2000": varpi, "inclination": inclination, "node": node,
            "lunar_distance": states[:, 3] * moon.MEAN_DISTANCE_KM, "length_of_day": 24.0 / states[:, 4]}


COLUMNS = {  # name: (unit, description)
    "t_kyr": ("kyr", "time from J2000 (TDB), as La2004"),
    "eccentricity": ("", "the Earth-Moon barycentre's heliocentric osculating eccentricity"),
    "obliquity": ("rad", "angle between the spin axis and the orbit's normal"),
    "perihelion_longitude": ("rad", "varpi_bar: longitude of perihelion from the moving equinox"),
    "climatic_precession": ("", "e sin(varpi_bar)"),
    "precession": ("rad", "psi: general precession in longitude from J2000 (varpi_bar = varpi + psi)"),
    "perihelion_longitude_j2000": ("rad", "varpi: longitude of perihelion from the J2000 equinox, ecliptic"),
    "inclination": ("rad", "the orbit's inclination to the J2000 ecliptic (IAU 2006)"),
    "node": ("rad", "the orbit's ascending node on the J2000 ecliptic, from the J2000 equinox"),
    "lunar_distance": ("km", "the Moon's mean distance under tidal dissipation"),
    "length_of_day": ("h", "length of day under tidal dissipation (24 h today)"),
}


def table(t, q):
    import astropy.units as u
    from astropy.table import QTable

    from ...schema import tdb_days_to_time

    out = QTable()
    out["time"] = tdb_days_to_time(t)
    for name, (unit, text) in COLUMNS.items():
        out[name] = q[name] * u.Unit(unit) if unit else q[name]
        out[name].info.description = text
    return out


def erfa_metrics(scenario, orbit, model):
    """Obliquity and mean equator against ERFA's long-term precession over the span's first 2 kyr (arcsec)."""
    from ...integrators.rk8 import fixed_step
    from ...models import deep_time
    from ...references.long_term_precession import LongTermPrecession

    reach = min(ERFA_SPAN_D, abs(scenario.t_end))
    t = math.copysign(1.0, scenario.t_end) * np.arange(ERFA_STEP_D, reach + 1.0, ERFA_STEP_D)
    states = fixed_step(deep_time.rhs, model.params, 0.0, model.y0, t, ERFA_STEP_D)
    normal, _ = deep_time.orbit_series(t, *model.params[:3])
    reference = LongTermPrecession()(t)
    obliquity = np.arccos(np.clip(np.sum(states[:, :3] * normal, axis=1), -1, 1))
    equator = np.arccos(np.clip(np.sum(states[:, :3] * reference["equator_pole"], axis=1), -1, 1))
    obliquity_error = np.abs(obliquity - reference["obliquity_rad"]).max()
    return ({"erfa_obliquity_max_arcsec": float(obliquity_error / ARCSEC),
             "erfa_equator_max_arcsec": float(equator.max() / ARCSEC),
             "erfa_compared_kyr": float(reach / KYR_D)}, reference.provenance)


def laskar_metrics(t, q):
    """Against La2004 over each window and the span up to CHAOS_MYR, with La93's tidal variants' spread beside
    it where La93 reaches: (metrics, not_measured, provenance, La2004's series at t or None)."""
    from ...references import laskar

    reason = laskar.available()
    kyr = t / KYR_D
    if reason is None and not np.allclose(kyr, np.round(kyr), rtol=0, atol=1e-6):
        reason = "outputs off La2004's whole-kyr grid: give span.step a whole number of kyr"
    reach = min(abs(kyr[-1]), CHAOS_MYR * 1000)
    windows = [*((f"{m}myr", m * 1000.0) for m in WINDOWS_MYR if reach >= m * 1000), ("span", reach)]
    if reason is not None:
        keys = [f"la2004_{name}_{w}" for w, _ in windows for name in DIFFERENCES]
        return dict.fromkeys(keys), {f"comparison.{k}": f"not compared: {reason}" for k in keys}, None, None
    inside = np.abs(kyr) <= reach + 1e-9
    solutions = {"model": {"eccentricity": q["eccentricity"][inside], "obliquity_rad": q["obliquity"][inside],
                           "perihelion_longitude_rad": q["perihelion_longitude"][inside]}}
    for name in ("La2004", "La93_01", "La93_11"):
        low, high = laskar.Insolation(name).span_kyr()
        covered = inside & (kyr >= low) & (kyr <= high)
        solutions[name] = laskar.Insolation(name)(t[covered]).values if covered.any() else None
    metrics = {}
    for prefix, a, b in (("la2004", "model", "La2004"), ("la93_tides", "La93_11", "La93_01"),
                         ("la2004_minus_la93", "La2004", "La93_11")):
        for window, limit in windows:
            size = int(np.sum(np.abs(kyr[inside]) <= limit + 1e-9))
            if solutions[a] is not None and solutions[b] is not None and min(
                    len(solutions[a]["eccentricity"]), len(solutions[b]["eccentricity"])) >= size:
                metrics.update({f"{prefix}_{k}_{window}": v for k, v in
                                _differences(solutions[a], solutions[b], slice(0, size)).items()})
    not_measured = {}
    if abs(kyr[-1]) > reach:
        not_measured["comparison.la2004_span"] = (
            f"compared to {reach / 1000:g} Myr only: beyond, the solar system's chaos leaves any solution "
            "uncertain (La2004: 40 to 50 Myr)")
    la2004 = solutions["La2004"]
    reference = {"t_kyr": kyr[inside], "obliquity_deg": np.degrees(la2004["obliquity_rad"]),
                 "climatic_precession": la2004["eccentricity"] * np.sin(la2004["perihelion_longitude_rad"]),
                 "eccentricity": la2004["eccentricity"]}
    return metrics, not_measured, laskar.Insolation("La2004").provenance(), reference


DIFFERENCES = ("eccentricity_max", "obliquity_max_deg", "climatic_precession_vector_max",
               "perihelion_longitude_end_deg")


def figure_series(q, la2004):
    """(kyr, the model's obliquity (deg) and climatic precession, La2004's or None), where La2004 reaches."""
    size = len(q["t_kyr"]) if la2004 is None else len(la2004["t_kyr"])
    ours = {"obliquity_deg": np.degrees(q["obliquity"][:size]),
            "climatic_precession": q["climatic_precession"][:size], "eccentricity": q["eccentricity"][:size]}
    reference = None if la2004 is None else {k: v for k, v in la2004.items() if k != "t_kyr"}
    return q["t_kyr"][:size], ours, reference


def _differences(a, b, part):
    """Max differences of two solutions' values over ``part``: e, obliquity (deg), e exp(i varpi_bar); the
    varpi_bar difference at the window's end (deg)."""
    def vector(x):
        return x["eccentricity"][part] * np.exp(1j * x["perihelion_longitude_rad"][part])

    end = np.angle(vector(a)[-1] / vector(b)[-1])
    return {"eccentricity_max": float(np.abs(a["eccentricity"][part] - b["eccentricity"][part]).max()),
            "obliquity_max_deg": float(np.degrees(np.abs(a["obliquity_rad"][part]
                                                         - b["obliquity_rad"][part]).max())),
            "climatic_precession_vector_max": float(np.abs(vector(a) - vector(b)).max()),
            "perihelion_longitude_end_deg": float(np.degrees(end))}
