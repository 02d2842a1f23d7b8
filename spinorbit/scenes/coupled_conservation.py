"""Stress: the closed Earth-Moon system (spinorbit.coupled) keeps its angular momentum and energy.

The relative orbit, the rigid Moon and the rigid axisymmetric Earth in one state, every interaction
with its reaction, no Sun and no dissipation, started from DE421 at ``span.start``: the geocentric
Moon (position, velocity), DE421's lunar orientation and angular velocity, the Earth's figure axis on
the IAU 2006/2000A pole (ERFA) spinning at the Earth rotation angle's rate.  ``model.*`` turns each
interaction on or off.  Integrated by the compiled RK8 at ``integrator.step``, in chunks with progress,
checkpointed (``spinorbit run --resume`` continues an interrupted run); the scene reports the largest
relative change over the span of |L|, of the L vector (over |L|) and of the energy (over |E|),
and each per century (times a century over the span: rounding walks as sqrt(steps), so scaling a
shorter run up linearly overstates it).  Passes when all three are within
``stress.tolerance_per_century`` (basis: benchmarks/RESULTS.md, the closed Earth-Moon system); a span
under 10 yr is not compared.
"""
import numpy as np

from ..constants import JULIAN_CENTURY_D
from ..errors import ScenarioError
from ..schema import Key
from ..verdict import Check, Verdict
from . import common

FIGURES = ("moon_figure", "moon_harmonics", "earth_figure", "earth_harmonics", "figure_figure")
HELP = {"moon_figure": "the Moon's degree 2 and the Earth as a point mass",
        "moon_harmonics": "the Moon's degrees 3-4 (DE421) and the Earth as a point mass",
        "earth_figure": "the Earth's degree 2 (H_d, C/Ma^2) and the Moon as a point mass",
        "earth_harmonics": "the Earth's J3 (DE421 header), J4 (EGM2008) and the Moon as a point mass",
        "figure_figure": "the Earth's J2 with the Moon's degree 2"}
SCHEMA = {
    **{f"model.{name}": Key(type=bool, default=True, help=text) for name, text in HELP.items()},
    "stress.tolerance_per_century": Key(unit="", default=1e-12, min=1e-16, max=1e-3,
                                        help="pass: relative drift of |L|, L and E per century"),
}
METRICS = ("L_norm_rel_drift", "L_vector_rel_drift", "energy_rel_drift")
# Scaled linearly to a century, the rounding walk (~eps sqrt(steps)) of a run under 10 yr exceeds 1e-12 by itself.
MIN_SPAN_D = 10 * 365.25


def verdict(scenario, comparison):
    """Each drift per century within stress.tolerance_per_century."""
    tolerance = scenario["stress.tolerance_per_century"]
    source = "the rounding floor of RK8 on this system (benchmarks/RESULTS.md); issue 11 asks 1e-12 per century"
    return Verdict("conservation (closed system)", tuple(
        Check(name, f"{name}_per_century", tolerance, "", source, min_span_d=MIN_SPAN_D) for name in METRICS))


def start_state(t0):
    """DE421's Earth-Moon state and lunar orientation at t0 (TDB days), the Earth on the IAU pole."""
    from ..bodies import earth
    from ..coupled import attitude_with_pole, state
    from ..orbits.kernel import open_ephemeris
    from ..references import erfa_pole, moon_de421

    pos, vel = open_ephemeris("de421", t0, t0).relative_states("moon", "earth", [t0])
    moon = moon_de421.initial_state(t0)
    q_e, w_e = attitude_with_pole(erfa_pole.cip_vector(t0), earth.ERA_RATE_RAD_D)
    return state(pos[0], vel[0], moon[:4], moon[4:7], q_e, w_e)


def run(scenario):
    from .. import coupled

    if scenario["integrator.method"] != "rk8":
        raise ScenarioError("integrator.method", scenario["integrator.method"], "rk8 (the compiled fixed step)")
    t0, t = scenario.t_start, scenario.output_times()
    p = coupled.parameters(tuple(name for name in FIGURES if scenario[f"model.{name}"]))
    states, point = common.fixed_step_run(scenario, coupled.rhs, p, start_state(t0), 0.05, scenario.checkpoint,
                                          scenario.name)

    energy, big_l = coupled.invariants(states, p)
    norm = np.linalg.norm(big_l, axis=1)
    changes = {"L_norm_rel_drift": np.abs(norm / norm[0] - 1),
               "L_vector_rel_drift": np.linalg.norm(big_l - big_l[0], axis=1) / norm[0],
               "energy_rel_drift": np.abs(energy / energy[0] - 1)}
    centuries = abs(t[-1] - t0) / JULIAN_CENTURY_D
    comparison = {"checks": "relative drift of the closed system's |L|, L vector and E over the span, and per "
                            "century (linear scaling), within stress.tolerance_per_century"}
    for name in METRICS:
        comparison[name] = float(changes[name].max())
        comparison[f"{name}_per_century"] = comparison[name] / centuries
    summary = {"comparison": comparison}
    if abs(t[-1] - t0) >= MIN_SPAN_D:
        comparison["passed"] = all(comparison[f"{n}_per_century"] <= scenario["stress.tolerance_per_century"]
                                   for n in METRICS)
    else:
        comparison["passed"] = None
        summary["not_measured"] = {"comparison.passed": "a span under 10 yr: the per-century drift is not judged"}

    from astropy.table import QTable

    from ..schema import tdb_days_to_time

    u = common.u()
    table = QTable()
    table["time"] = tdb_days_to_time(t)
    for k, axis in enumerate("xyz"):
        table[f"moon_geocentric_{axis}"] = states[:, k] * u.km
    for name in METRICS:
        table[name.replace("_drift", "_change")] = changes[name]
    figures = {"drift": common.plot_series(common.decimal_year(t), [changes[n] for n in METRICS], "year (TDB)",
                                           "relative change", ["|L|", "L vector", "E"])}
    return common.result(scenario, table, {**summary, "run": point}, figures, None)
