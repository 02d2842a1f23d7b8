"""Mars's orientation (Euler ch. 16 P91/P96): its precession and nutation against Konopliv et al. 2016's rate,
the rigid-Mars nutation series and the IAU 2015 pole.

Rigid Mars (spinorbit.bodies.mars: MRO120D's J2 and C22, C/MR^2 = 0.36367, Baland et al. 2020's from
Konopliv et al. 2016's rate; models.assemblies.planet) under
the Sun's torque on its figure, with Phobos and Deimos as rings held to its equator
(models.interactions.rings), the planets' direct torques and the geodesic precession, each a key; the Sun
and the planets from DE421 (or DE440), or the Sun on its Kepler ellipse; started at mars.start on the IAU 2015
pole and spin (starts/mars.py).  The rate, the nutation, the pole against IAU 2015, the rate's budget and
the verdict: comparisons/mars_orientation.py.
"""
from ..bodies import mars
from ..comparisons.mars_orientation import POLE_MINUS_IAU2015_MAX_ARCSEC, answer_table, verdict
from ..models.assemblies.planet import MODELS
from ..orbits.sources import OrbitSource
from ..scene.declaration import Answer, Cost, Model, Scene, Stored
from ..scene.params import Params, key, source_key, table, time_key
from ..scene.schema import SAMPLE_STEP
from ..starts.mars import restarted, start_epoch


@table
class MarsTable:
    model: str = key(type=str, default="gyroscopic", choices=MODELS,
                     help="the spin angular momentum alone, or Euler's equations with the day (and C22)")
    c_mr2: float = key(unit="", default=mars.C_MR2, min=0.2, max=0.4,
                       help="polar moment C/(M R^2) at 3396 km (Baland et al. 2020; Konopliv et al. 2011: 0.3644)")
    start: float = time_key("ISO TDB epoch of the IAU 2015 start", default="2000-01-01T12:00:00")
    satellites: bool = key(type=bool, default=True, help="Phobos and Deimos as rings on the equator")
    geodesic_precession: bool = key(type=bool, default=True)


@table
class OrbitTable:
    source: OrbitSource = source_key("'de421', 'de440' (or a .bsp), or 'kepler' (the Sun alone)")
    planets: bool = key(type=bool, default=True, help="the direct torques of the planets and the Moon")
    sample_step: float = key(**SAMPLE_STEP, default=1.0)


@table
class ComparisonTable:
    budget: bool = key(type=bool, default=True, help="the rate's budget: five further runs")


@table
class MarsOrientationParams(Params):
    mars: MarsTable
    orbit: OrbitTable
    comparison: ComparisonTable


def build(p, times):
    """Rigid Mars started on the IAU 2015 pole (starts/mars.py)."""
    from ..starts import mars as start

    return Model(start.build(p))


def compare_run(p, run):
    from ..comparisons import mars_orientation as vs

    return vs.outcome(p, run)


# kept as a solution from J2000 on 8-d segments of degree 14, answered with Mars's attitude layer (its pole and
# prime meridian); a run started elsewhere (mars.start) is its own
STORED = Stored(segment_d=8.0, degree=14, anchor=0.0, attitude="mars", attitude_table=answer_table,
                own_start=start_epoch)
# spinorbit.orientation("mars"): the attitude layer of the scene's stored solution (benchmarks/RESULTS.md)
ANSWER = Answer(
    "mars", "mars_orientation", {"pole_arcsec": POLE_MINUS_IAU2015_MAX_ARCSEC},
    statistic="a bound at every date of 1980-2030: the largest angle of the pole from IAU 2015's",
    basis="the Mars scene against IAU 2015 (Archinal et al. 2018) over 1980-2030 (measured 0.072\"): IAU 2015's "
          "precession is a fitted circle, 3.0 mas/yr slower than the model's, whose rate is 0.75 mas/yr from "
          "Konopliv et al. 2016's (benchmarks/RESULTS.md)",
    beyond_de421="no reference judges these dates",
    columns=("pole_ra", "pole_dec", "prime_meridian", "pole_minus_iau2015"),
    body="mars", about="the pole and prime meridian")

SCENE = Scene(MarsOrientationParams, build, compare_run, verdict, Cost(step_s=3e-5, sample_bytes=300), backward=True,
              restart=restarted, stored=STORED, answers=(ANSWER,))
