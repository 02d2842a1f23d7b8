"""coupled_conservation's comparison: the closed Earth-Moon system's |L|, L vector and energy against their
start -- the largest relative change over the span and per century (times a century over the span), and
whether each is within the tolerance on a span long enough to judge."""
import numpy as np

from ..base.constants import JULIAN_CENTURY_D

# The relative changes, and the summary's keys of their largest over the span
L_NORM_REL_DRIFT, L_VECTOR_REL_DRIFT, ENERGY_REL_DRIFT = "L_norm_rel_drift", "L_vector_rel_drift", "energy_rel_drift"
METRICS = (L_NORM_REL_DRIFT, L_VECTOR_REL_DRIFT, ENERGY_REL_DRIFT)
PASSED = "passed"


def per_century(metric):
    """The summary's key of ``metric`` (one of METRICS) scaled to a century, read by the verdict."""
    return f"{metric}_per_century"


def changes(system, solution, t):
    """{metric: the relative change at each output} of |L|, the L vector (over |L|) and E from the first, in
    the order of METRICS."""
    energy, big_l = system.invariants(solution.y, t)
    norm = np.linalg.norm(big_l, axis=1)
    return {L_NORM_REL_DRIFT: np.abs(norm / norm[0] - 1),
            L_VECTOR_REL_DRIFT: np.linalg.norm(big_l - big_l[0], axis=1) / norm[0],
            ENERGY_REL_DRIFT: np.abs(energy / energy[0] - 1)}


def metrics(change, span_d, tolerance, min_span_d):
    """({metric: value}, {"comparison.<metric>": why not measured}): each change's largest, per century, and
    whether all are within ``tolerance`` per century (not judged on a span under ``min_span_d``)."""
    centuries = span_d / JULIAN_CENTURY_D
    comparison = {"checks": "relative drift of the closed system's |L|, L vector and E over the span, and "
                            "per century (linear scaling), within stress.tolerance_per_century"}
    for name in METRICS:
        comparison[name] = float(change[name].max())
        comparison[per_century(name)] = comparison[name] / centuries
    not_measured = {}
    if span_d >= min_span_d:
        comparison[PASSED] = all(comparison[per_century(n)] <= tolerance for n in METRICS)
    else:
        comparison[PASSED] = None
        not_measured[f"comparison.{PASSED}"] = "a span under 10 yr: the per-century drift is not judged"
    return comparison, not_measured


def table(t, r, change):
    """The output table: the geocentric Moon ``r`` (km) and each relative change."""
    from astropy import units as u
    from astropy.table import QTable

    from ..scene.schema import tdb_days_to_time

    out = QTable()
    out["time"] = tdb_days_to_time(t)
    for k, axis in enumerate("xyz"):
        out[f"moon_geocentric_{axis}"] = r[:, k] * u.km
    for name in METRICS:
        out[name.replace("_drift", "_change")] = change[name]
    return out
