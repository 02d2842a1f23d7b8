"""What a span of data can measure: the resolvability of periodic terms in a least-squares fit.

Layer 2 (numpy).  Every harmonic fit in the package (the Moon's libration terms, the
Earth's nutation terms, the non-rigid decomposition) asks this module which terms a
span separates, so that a short run reports "not measured, needs N days" instead of
the meaningless amplitudes of a degenerate fit.
"""
import numpy as np


def resolvable(rates, span_d, separate=True):
    """Mask of the arguments kept, in order, for a fit over ``span_d`` days: each must beat by more than half
    a cycle over the span against the quadratic (rate 0) and, with either sign, against every argument kept
    before it (e.g. l' and 2F - 2D + 2Om - l', annual both, beat in ~10^4 yr: the second is dropped and
    the first's term carries both).  ``separate=False`` checks against the quadratic only: for a fit whose
    periodic terms are only summed again (their sum is well determined), never reported one by one."""
    kept = []
    for k, rate in enumerate(rates):
        others = [0.0] + ([rates[j] for j in kept] + [-rates[j] for j in kept] if separate else [])
        if all(abs(rate - other) * span_d > np.pi for other in others):
            kept.append(k)
    mask = np.zeros(len(rates), dtype=bool)
    mask[kept] = True
    return mask


def refusals(names, rates, span_d, separate=True):
    """{name: why it is not fitted} for each argument ``resolvable`` drops, with the span it needs.

    The span needed is half its period, or half the beat period with a term kept before it,
    whichever is longer (``rates`` in rad/d, ``span_d`` days).
    """
    rates = np.asarray(rates, dtype=float)
    keep = resolvable(rates, span_d, separate)
    out = {}
    for k in np.flatnonzero(~keep):
        beats = [(np.pi / abs(rates[k] - sign * rates[j]), names[j])
                 for j in np.flatnonzero(keep[:k]) for sign in (1, -1) if rates[k] != sign * rates[j]]
        need, partner = max([(np.pi / abs(rates[k]), None)] + [b for b in beats if b[0] >= span_d], key=lambda b: b[0])
        out[names[k]] = (f"needs a span of {need:.0f} d, the run has {span_d:.0f} d"
                         + (f" (it beats with {partner})" if partner else " (half its period)"))
    return out
