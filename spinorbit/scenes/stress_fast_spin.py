"""Stress: a fast, nearly symmetric spinner on a slow orbit (spin/orbit frequency ratio 1e5).

An oblate body (A ~ B < C) spins at eps about its figure axis, at obliquity n
to the plane of a point mass F on a uniform circle at delta = eps/ratio
(Euler ch. 16 P96, §844-849).  Its figure axis regresses about the orbit pole
at the averaged rate N cos n cc/aa (theory.SymmetricPrecession with the
gyroscopic ratio aa/cc; N = theory.precession_constant, cc = (A + B)/2,
the B - A part averages out over the spin).  GM/s^3 is set by
``stress.precession_over_orbit`` = N/delta (the orbit is prescribed, not Keplerian).

Every run in ``stress.runs`` (a method, its options, a span fraction; analysis.ladder.work_precision)
reports its cost (scaled per orbit when it covers only ``span_fraction`` of the span) and its errors
against a converged run (``stress.reference``): the attitude (which includes the spin phase, 6e5 rad
per orbit, so rounding alone leaves ~1e-8 rad), the figure axis (P96's precession and nutation), and
the precession rate fitted over the span (§847) against the closed form, first order in N/delta.
Passes when the reference's figure axis agrees with the best other run to
``stress.reference_agreement_max`` rad and every full-span rate is within ``stress.rate_rel_tol``.
"""
import numpy as np

from ..comparisons.fast_spin_p96 import PRECESSION_RATE_REL_ERROR_MAX, REFERENCE_AGREEMENT_AXIS_RAD, compare_run
from ..scene.declaration import Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
from . import common


def verdict(p, comparison):
    """Converged runs agree, and every full-span run's precession rate matches P96's N cos n."""
    return Verdict("a converged suzuki4 run; P96's N cos n", (
        Check("converged runs agree", REFERENCE_AGREEMENT_AXIS_RAD, p.stress.reference_agreement_max,
              " rad", "stress.reference_agreement_max: the figure axis of two converged runs"),
        Check("rate vs P96", PRECESSION_RATE_REL_ERROR_MAX, p.stress.rate_rel_tol, "",
              "P96 is first order in N/delta = 1e-3 (stress.rate_rel_tol)")))


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="A <= B < C, nearly symmetric about C")
    spin: float = key(**SPIN, help="spin rate eps about the figure axis")
    obliquity: float = key(**ANGLE, help="angle n of the figure axis from the orbit pole")


@table
class StressTable:
    spin_over_orbit: float = key(unit="", default=1e5, help="eps/delta")
    precession_over_orbit: float = key(unit="", default=1e-3, help="N/delta (sets GM/s^3)")
    runs: list = key(type=list,
                     help="[{method, <its options, e.g. step (d) or rtol, atol>, span_fraction}]")
    reference: list = key(type=list, help="[{method, <its options>}]: the converged run")
    rate_rel_tol: float = key(unit="", default=1e-3, help="pass: |rate/closed form - 1| for full-span runs")
    reference_agreement_max: float = key(
        unit="", default=1e-9, help="pass: figure-axis difference, reference vs best other run, rad")


@table
class StressFastSpinParams(Params):
    body: BodyTable
    stress: StressTable


def build(p, times):
    """No main run (a converged reference and the ladder of ``stress.runs``, compare): the spinner started on
    Euler's forced solution (§844), its closed form."""
    return start.fast_spinner(p)


SCENE = Scene(StressFastSpinParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales)
