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
import numpy as np

from ..base.constants import JULIAN_CENTURY_D
from ..models.assemblies.earth_moon import FIGURES
from ..scene.declaration import Cost, Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from . import common


@table
class ModelTable:
    moon_figure: bool = key(type=bool, default=True, help=FIGURES["moon_figure"])
    moon_harmonics: bool = key(type=bool, default=True, help=FIGURES["moon_harmonics"])
    earth_figure: bool = key(type=bool, default=True, help=FIGURES["earth_figure"])
    earth_harmonics: bool = key(type=bool, default=True, help=FIGURES["earth_harmonics"])
    figure_figure: bool = key(type=bool, default=True, help=FIGURES["figure_figure"])
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


METRICS = ("L_norm_rel_drift", "L_vector_rel_drift", "energy_rel_drift")
# Scaled linearly to a century, the rounding walk (~eps sqrt(steps)) of a run under 10 yr exceeds 1e-12
# by itself.
MIN_SPAN_D = 10 * 365.25


def verdict(p, comparison):
    """Each drift per century within stress.tolerance_per_century."""
    tolerance = p.stress.tolerance_per_century
    source = ("the rounding floor of RK8 on this system: 3e-13 to 7e-13 per century at 0.1 d "
              "(benchmarks/RESULTS.md)")
    return Verdict("conservation (closed system)", tuple(
        Check(name, f"{name}_per_century", tolerance, "", source, min_span_d=MIN_SPAN_D) for name in METRICS))


def build(p, times):
    """The closed Earth-Moon System of the scenario's figures and Earth, started from DE421 at span.start."""
    from ..bodies import earth
    from ..models.assemblies.earth_moon import closed
    from ..models.rotators import Rigid
    from ..models.start import earth_moon_de421
    from ..references.erfa_pole import cip_vector

    t0 = p.span.start
    rotator = Rigid() if p.model.earth_rotator == "rigid" else None
    built = closed(tuple(name for name in FIGURES if getattr(p.model, name)), t0, earth_rotator=rotator,
                   moon_core=False)
    built.y0 = built.layout.pack(earth_moon_de421(built, t0, cip_vector(t0), earth.ERA_RATE_RAD_D))
    return Model(built)


def compare_run(p, run):
    from astropy.table import QTable

    from ..scene.schema import tdb_days_to_time

    t, t0, solution = run.times, p.span.start, run.solution
    energy, big_l = run.model.system.invariants(solution.y, t)
    norm = np.linalg.norm(big_l, axis=1)
    changes = {"L_norm_rel_drift": np.abs(norm / norm[0] - 1),
               "L_vector_rel_drift": np.linalg.norm(big_l - big_l[0], axis=1) / norm[0],
               "energy_rel_drift": np.abs(energy / energy[0] - 1)}
    centuries = abs(t[-1] - t0) / JULIAN_CENTURY_D
    comparison = {"checks": "relative drift of the closed system's |L|, L vector and E over the span, and "
                            "per century (linear scaling), within stress.tolerance_per_century"}
    for name in METRICS:
        comparison[name] = float(changes[name].max())
        comparison[f"{name}_per_century"] = comparison[name] / centuries
    not_measured = {}
    if abs(t[-1] - t0) >= MIN_SPAN_D:
        comparison["passed"] = all(comparison[f"{n}_per_century"] <= p.stress.tolerance_per_century
                                   for n in METRICS)
    else:
        comparison["passed"] = None
        not_measured["comparison.passed"] = "a span under 10 yr: the per-century drift is not judged"
    table = QTable()
    table["time"] = tdb_days_to_time(t)
    for k, axis in enumerate("xyz"):
        table[f"moon_geocentric_{axis}"] = solution.part("moon.r")[:, k] * common.u().km
    for name in METRICS:
        table[name.replace("_drift", "_change")] = changes[name]
    figures = {"drift": common.plot_series(common.decimal_year(t), [changes[n] for n in METRICS],
                                           "year (TDB)", "relative change", ["|L|", "L vector", "E"])}
    return Outcome(comparison, figures=figures, not_measured=not_measured, table=table)


SCENE = Scene(CoupledConservationParams, build, compare_run, verdict, Cost(step_s=1e-4), taylor=True)
