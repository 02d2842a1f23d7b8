"""Segments.evaluate gathers the dates' segments a block at a time: many dates, in any order, across blocks and
segments, give the polynomial the series were fitted to (the closed form)."""
import numpy as np

from spinorbit.solutions import chebyshev


def test_dates_across_blocks_and_segments_give_the_fitted_polynomial():
    def poly(t):
        return np.stack([1.0 + 0.3 * t - 0.02 * t**2 + 1e-4 * t**5, 2.0 - 5e-4 * t**3], axis=-1)

    count = 40
    grid = chebyshev.Segments(0.0, 2.0, -7, np.zeros((count, 2, 8)))
    nodes, _ = grid.nodes(-7, count)
    segments = chebyshev.fitted(0.0, 2.0, -7, poly(nodes).transpose(0, 2, 1))
    lo, hi = segments.span
    t = np.random.default_rng(4).uniform(lo, hi, 3 * chebyshev.EVALUATED_AT_ONCE + 17)      # unsorted, 4 blocks
    expected = poly(t)
    scale = np.abs(expected).max(axis=0)
    assert np.all(np.abs(segments.evaluate(t) - expected) <= 1e-13 * scale)
