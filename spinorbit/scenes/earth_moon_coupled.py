"""The Earth-Moon system integrated as one, orbit and spin coupled both ways, against DE421.

One state holds the geocentric Moon's orbit, the Moon's mantle and core (level 3 of spinorbit.moon) and the
Earth's spin (gyroscopic); every interaction acts with its reaction, the Sun, the planets and the Earth-Moon
barycentre come from DE421 (spinorbit.earth_moon), or with ``orbit.source = "rebound"`` from a REBOUND N-body
run started from DE421 a day before the span (for epochs no ephemeris covers).  Started from DE421's state at
span.start (the Moon's orbit, orientation, rates and core), the Earth spinning at the Earth rotation angle's
rate about the IAU 2006/2000A pole; nothing fitted.  Compared with DE421: the Moon's direction and range, the
lunar pole and longitude; the Earth's axis against the CIP (reported, not judged: DE421 turned its Earth by
IAU 1976).

``compare.tides_off``: the same run again without the Earth's tides; the difference gives the Moon's tidal
secular acceleration (n_dot, "/cy^2) and recession (mm/yr), judged against lunar laser ranging (Williams &
Boggs 2016: -25.8"/cy^2, 38.3 mm/yr, +-1) on spans of 100 yr or more.
"""
import time

from ..errors import ScenarioError
from ..schema import Key
from ..verdict import Check, Verdict
from . import common

HELP = {"relativity": "the EIH (1PN) point-mass correction on the orbit",
        "earth_tides": "the tides raised on the Earth by the Moon and the Sun (DE421's K2E, TAUE)",
        "moon_distortion": "the Moon's tidal and rotational distortion (DE421's K2M, TAUM)",
        "geodesic": "the geodesic precession of the Earth's axis",
        "planets": "Mercury to Pluto as point masses on the orbit"}
SCHEMA = {
    **{f"model.{name}": Key(type=bool, default=True, help=text) for name, text in HELP.items()},
    "orbit.source": Key(type=str, default="de421", choices=("de421", "rebound"),
                        help="the Sun, planets and Earth-Moon barycentre: DE421, or a REBOUND run from its state"),
    "orbit.step": Key(unit="d", default=1.0, min=0.0625, max=4.0,
                      help="sampling step of the Sun, planets and Earth-Moon barycentre"),
    "compare.tides_off": Key(type=bool, default=False,
                             help="also run without the Earth's tides: the Moon's tidal secular acceleration"),
}
LLR = "Williams & Boggs 2016 (lunar laser ranging), the issue's +-1 band"
TARGETS = "issue 11 (aim 0.05\" and 0.1 km): the same equations as DE421, started from its state"
MIN_TIDAL_SPAN_D = 100 * 365.25 - 1.0


def verdict(scenario, comparison):
    """The Moon against DE421 (direction, range, pole, longitude); the tidal acceleration against LLR."""
    checks = [Check("Moon direction", "moon_direction_error_max_arcsec", 1.0, "″", TARGETS),
              Check("Moon range", "moon_range_error_max_km", 2.0, " km", TARGETS),
              Check("lunar pole", "pole_error_max_arcsec", 0.1, "″", TARGETS),
              Check("libration longitude", "longitude_error_max_arcsec", 1.0, "″", TARGETS)]
    if scenario["compare.tides_off"]:
        checks += [Check("n_dot", "tidal_n_dot_arcsec_per_cy2", 1.0, "″/cy²", LLR, expected=-25.8,
                         min_span_d=MIN_TIDAL_SPAN_D),
                   Check("recession", "tidal_recession_mm_per_yr", 1.0, " mm/yr", LLR, expected=38.3,
                         min_span_d=MIN_TIDAL_SPAN_D)]
    return Verdict("DE421", tuple(checks))


def external_bodies(scenario):
    """(the Sun, planets and EMB sampled from orbit.source over the span, the sampling's wall time s)."""
    from .. import earth_moon

    first, last = scenario.bounds
    started = time.perf_counter()
    external = earth_moon.sample_external(first - 1.0, last + 1.0, scenario["orbit.step"], scenario["orbit.source"])
    return external, time.perf_counter() - started


def run(scenario):
    from .. import earth_moon
    from .. import earth_moon_vs_de421 as vs
    from ..bodies import earth
    from ..references.erfa_pole import cip_vector

    if scenario["integrator.method"] != "rk8":
        raise ScenarioError("integrator.method", scenario["integrator.method"], "rk8 (the compiled fixed step)")
    switches = tuple(name for name in earth_moon.SWITCHES if scenario[f"model.{name}"])
    t, t0 = scenario.output_times(), scenario.t_start
    external, sampled = external_bodies(scenario)
    p = earth_moon.parameters(external.data, switches)
    y0 = vs.start_state(t0, cip_vector(t0), earth.ERA_RATE_RAD_D, p)
    states, point = common.fixed_step_run(scenario, earth_moon.rhs, p, y0, 0.5, scenario.checkpoint, scenario.name)
    direction, distance = vs.orbit_errors(t, states)
    mats, de421, pole, longitude, lunar = vs.lunar_errors(t, states)
    axis = earth_moon.earth_axis(states)
    axis_error = vs.earth_axis_error(t, axis)
    summary = {"comparison": vs.metrics(direction, distance, lunar, axis_error), "run": point,
               "reference": de421.provenance, "model": {"switches": list(switches)},
               "external_bodies": {"source": external.source, "step_d": external.step, "wall_s": sampled}}
    if scenario["compare.tides_off"]:
        if "earth_tides" not in switches:
            raise ScenarioError("compare.tides_off", True, "false when model.earth_tides is false")
        part = None if scenario.checkpoint is None else scenario.checkpoint.part("tides_off")
        tides_off = earth_moon.parameters(external.data, tuple(s for s in switches if s != "earth_tides"))
        without, point_off = common.fixed_step_run(scenario, earth_moon.rhs, tides_off, y0, 0.5, part,
                                                   f"{scenario.name} (tides off)")
        tidal = vs.tidal_acceleration(t, states, without)
        summary["comparison"].update({f"tidal_{name}": value for name, value in tidal.items()})
        summary["run_tides_off"] = point_off
    errors = {"direction": direction, "range": distance, "pole": pole, "longitude": longitude,
              "earth_axis": axis_error}
    table = vs.table(t, states, mats, errors, axis)
    year = common.decimal_year(t)
    figures = {"moon_vs_de421": common.plot_series(
        year, [table["moon_direction_error"].value, table["pole_error"].value, table["longitude_error"].value],
        "year (TDB)", "error [arcsec]", ["Moon direction", "lunar pole", "libration longitude"]),
        "moon_range_vs_de421": common.plot_series(year, [distance], "year (TDB)", "range error [km]", ["range"])}
    return common.result(scenario, table, summary, figures, None)
