"""Stress: the closed Earth-Moon system keeps its angular momentum and energy.

The Earth-Moon assembly of the DE421 scene (spinorbit.models.assemblies.earth_moon) with its orbit source
removed: the relative orbit, the Moon and the Earth in one state, every interaction with its reaction, no
Sun and no dissipation (the Moon rigid: its core's friction and its delayed tide take energy), started
from DE421 at ``span.start``: the geocentric Moon (position, velocity), DE421's lunar orientation and
angular velocity, the Earth on its forced motion about the IAU 2006/2000A pole (ERFA) at the Earth
rotation angle's rate.  ``model.*`` turns each interaction on or off; ``model.earth_rotator`` is the
DE421 scene's gyroscopic Earth or a rigid one with its daily spin resolved.  The scene reports the
largest relative change over the span of |L|, of the L vector (over |L|) and of the energy (over |E|),
and each per century (times a century over the span: rounding walks as sqrt(steps), so scaling a
shorter run up linearly overstates it).  Passes when all three are within
``stress.tolerance_per_century`` (basis: benchmarks/RESULTS.md, the closed Earth-Moon system); a span
under 10 yr is not compared.
"""
from ..comparisons import conservation
from ..models.assemblies.earth_moon import FIGURES
from ..scene.declaration import Cost, Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import earth_moon as start
from . import common


@table
class ModelTable:
    moon_figure: bool = key(type=bool, default=True, help=FIGURES["moon_figure"])
    moon_harmonics: bool = key(type=bool, default=True, help=FIGURES["moon_harmonics"])
    earth_figure: bool = key(type=bool, default=True, help=FIGURES["earth_figure"])
    earth_harmonics: bool = key(type=bool, default=True, help=FIGURES["earth_harmonics"])
    figure_figure: bool = key(type=bool, default=True, help=FIGURES["figure_figure"])
    earth_rotator: str = key(
        type=str, default="gyroscopic", choices=("gyroscopic", "rigid"),
        help="the DE421 scene's gyroscopic Earth, or a rigid Earth with its daily spin")


@table
class StressTable:
    tolerance_per_century: float = key(unit="", default=1e-12, min=1e-16, max=1e-3,
                                       help="pass: relative drift of |L|, L and E per century")


@table
class CoupledConservationParams(Params):
    model: ModelTable
    stress: StressTable


# Scaled linearly to a century, the rounding walk (~eps sqrt(steps)) of a run under 10 yr exceeds 1e-12
# by itself.
MIN_SPAN_D = 10 * 365.25


def verdict(p, comparison):
    """Each drift per century within stress.tolerance_per_century."""
    tolerance = p.stress.tolerance_per_century
    source = ("the rounding floor of RK8 on this system: 3e-13 to 7e-13 per century at 0.1 d "
              "(benchmarks/RESULTS.md)")
    return Verdict("conservation (closed system)", (
        Check("L_norm_rel_drift", conservation.per_century(conservation.L_NORM_REL_DRIFT), tolerance, "", source,
              min_span_d=MIN_SPAN_D),
        Check("L_vector_rel_drift", conservation.per_century(conservation.L_VECTOR_REL_DRIFT), tolerance, "",
              source, min_span_d=MIN_SPAN_D),
        Check("energy_rel_drift", conservation.per_century(conservation.ENERGY_REL_DRIFT), tolerance, "", source,
              min_span_d=MIN_SPAN_D)))


def build(p, times):
    """The closed Earth-Moon System of the scenario's figures and Earth, started from DE421 at span.start."""
    return Model(start.closed_system(p))


def compare_run(p, run):
    t, solution = run.times, run.solution
    change = conservation.changes(run.model.system, solution, t)
    comparison, not_measured = conservation.metrics(change, abs(t[-1] - p.span.start),
                                                    p.stress.tolerance_per_century, MIN_SPAN_D)
    figures = {"drift": common.plot_series(common.decimal_year(t), list(change.values()),
                                           "year (TDB)", "relative change", ["|L|", "L vector", "E"])}
    return Outcome(comparison, figures=figures, not_measured=not_measured,
                   table=conservation.table(t, solution.part("moon.r"), change))


SCENE = Scene(CoupledConservationParams, build, compare_run, verdict, Cost(step_s=1e-4), taylor=True)
