"""What a span of data can measure: the resolvability of periodic terms in a least-squares fit.

Layer 2 (numpy).  Every harmonic fit in the package (the Moon's libration terms, the
Earth's nutation terms, the non-rigid decomposition) asks this module which terms a
span separates, so that a short run reports "not measured, needs N days" instead of
the meaningless amplitudes of a degenerate fit.
"""
import numpy as np


def resolvable(rates, span_d):
    """Mask of the arguments kept, in order, for a fit over ``span_d`` days: each must beat by more than half
    a cycle over the span against the quadratic (rate 0) and, with either sign, against every argument kept
    before it (e.g. l' and 2F - 2D + 2Om - l', annual both, beat in ~10^4 yr: the second is dropped and
    the first's term carries both)."""
    kept = []
    for k, rate in enumerate(rates):
        others = [0.0] + [rates[j] for j in kept] + [-rates[j] for j in kept]
        if all(abs(rate - other) * span_d > np.pi for other in others):
            kept.append(k)
    mask = np.zeros(len(rates), dtype=bool)
    mask[kept] = True
    return mask
