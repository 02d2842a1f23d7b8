"""The solar system integrated as one -- the Sun, the planets, Pluto, the Earth and the Moon -- against DE421.

Every centre in one state with the Moon's mantle and core and the Earth's spin (spinorbit.models.assemblies.
solar_system): DE421's model, every constant from its header, started from DE421's initial conditions at its
epoch JDEPOC (1969-06-28; ``start.epoch = "span"``: DE421's states at span.start) and integrated both ways,
the Earth on its forced motion about the IAU 2006/2000A pole; nothing fitted.  INPOP05 did the same with
DE405 (Fienga et al. 2008, A&A 477, 315, Table 2).  Compared with DE421 (comparisons/solar_system_de421.py):
the Moon's direction and range, the lunar pole and longitude, every planet's heliocentric position.  DE421
integrated 343 asteroids this does not; what they move in each planet is stated beside its figure
(comparisons.solar_system_de421.ASTEROIDS_KM).
Runs with the Taylor integrator (``integrator.method = "taylor"``) or any other.
"""
from ..models.assemblies.solar_system import SWITCHES
from ..plots.solar_system import moon_vs_de421, planets_vs_de421
from ..scene.declaration import Model, Outcome, Scene, Stored
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import solar_system as start
from ..starts.earth_moon import EarthMoonTermsTable
from . import common


@table
class ModelTable(EarthMoonTermsTable):
    """The model's terms, each switched by a key (spinorbit.models.assemblies.solar_system.SWITCHES)."""

    sun_j2: bool = key(type=bool, default=True, help=SWITCHES["sun_j2"])


@table
class StartTable:
    epoch: str = key(type=str, default="de421", choices=("de421", "span"),
                     help="DE421's initial conditions at its epoch JDEPOC, or its states at span.start")


@table
class SolarSystemParams(Params):
    model: ModelTable
    start: StartTable


TARGET = ("the issue's target (INPOP05 re-integrated DE405 to 0.17 mas and 0.034 m over 100 yr, Fienga et "
          "al. 2008); DE421's asteroids, absent here, move the Moon by 2.3 mas and 0.54 m "
          "(comparisons.solar_system_de421.ASTEROIDS_MOON)")


def verdict(p, comparison):
    """The Moon against DE421 (direction, range, pole, longitude); each planet against what asteroids move."""
    from ..comparisons import solar_system_de421 as vs

    checks = [Check("Moon direction", vs.MOON_DIRECTION_ERROR_MAX_MAS, 1.0, " mas", TARGET),
              Check("Moon range", vs.MOON_RANGE_ERROR_MAX_M, 0.1, " m", TARGET),
              Check("lunar pole", vs.POLE_ERROR_MAX_MAS, 1.0, " mas", TARGET),
              Check("libration longitude", vs.LONGITUDE_ERROR_MAX_MAS, 1.0, " mas", TARGET)]
    largest = ("2x what DE421's largest asteroids move it, scaled by mass "
               "(comparisons.solar_system_de421.ASTEROIDS_KM)")
    checks += [Check(name, vs.heliocentric_error_max_km(name), 2 * km, " km", largest)
               for name, km in vs.ASTEROIDS_KM.items()]
    return Verdict("DE421", tuple(checks))


def build(p, times):
    return Model(start.system(p))


def bench(p, model, times):
    """The lunar attitude's error against a converged RK8 run, rad."""
    from ..analysis.ladder import converged_error

    error, model.system.meta["reference_agreement_rad"] = converged_error(model.system, times, 0.125)
    return error


def compare_run(p, run):
    from ..comparisons import solar_system_de421 as vs

    t, solution, model = run.times, run.solution, run.model.system
    direction, distance = vs.orbit_errors(t, solution.part("moon.r"))
    mats, pole, longitude, lunar = vs.lunar(t, solution.part("moon.q"))
    planets = vs.planet_errors(t, vs.heliocentric(model, solution))
    sections = {"reference": "DE421 (Folkner, Williams & Boggs 2008, IPN PR 42-178)",
                "model": {"switches": list(model.meta["switches"]), "t0_tdb_d": model.t0,
                          "asteroids_km": vs.ASTEROIDS_KM, "asteroids_moon": vs.ASTEROIDS_MOON}}
    errors = {"direction": direction, "range": distance, "pole": pole, "longitude": longitude}
    table = vs.table(t, solution.part("moon.r"), mats, errors, planets)
    year = common.decimal_year(t)
    figures = {"moon_vs_de421": moon_vs_de421(year, table["moon_direction_error"].value, table["pole_error"].value,
                                              table["longitude_error"].value, "mas"),
               "planets_vs_de421": planets_vs_de421(year, planets)}
    return Outcome(vs.metrics(direction, distance, lunar, planets), figures=figures, sections=sections,
                   table=table)


DE421_EPOCH_TDB_D = -11144.5        # DE421's JDEPOC, 2440400.5 TDB (1969-06-28): its initial conditions' epoch
STORED = Stored(segment_d=4.0, degree=13, anchor=DE421_EPOCH_TDB_D, own_start=start.own_start)
# every term a function of the state: heyoka's Taylor integrator takes it; from DE421's epoch both ways
SCENE = Scene(SolarSystemParams, build, compare_run, verdict, bench=bench, backward=True, taylor=True,
              restart=start.started_at, nbody_counts=start.nbody_counts, stored=STORED)
