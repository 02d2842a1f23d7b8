"""analysis.lyapunov: Benettin's exponent against flows whose exponents are known in closed form."""
import math

import numpy as np
from numba import njit

from spinorbit.analysis.lyapunov import benettin, compiled_flow, displaced, ensemble_mean, scipy_flow


@njit(cache=True)
def saddle_and_rotation(t, y, p):
    """Copies of (x, y): x' = p[0] x, y' = -p[0] y (a saddle, exponent p[0]) plus a rotation at rate p[1]."""
    dy = np.empty_like(y)
    for i in range(0, y.shape[0], 2):
        dy[i] = p[0] * y[i] + p[1] * y[i + 1]
        dy[i + 1] = -p[0] * y[i + 1] - p[1] * y[i]
    return dy


def test_saddle_gives_its_eigenvalue_and_a_rotation_gives_zero():
    """About the fixed point 0, the flow is linear and renormalising does not turn the separation: the saddle
    x' = 0.5 x gives ln |(e^{k/2}, e^{-k/2})/sqrt 2| / k = 0.5 - ln(sqrt 2)/k after k unit intervals; a pure
    rotation keeps every distance: 0 to the integration error."""
    d0, k = 1e-8, 200
    pairs = displaced([[0.0, 0.0]], d0, [1.0, 1.0])
    saddle = benettin(compiled_flow(saddle_and_rotation, np.array([0.5, 0.0]), 0.0, 1.0, 0.05), pairs, d0, k,
                      [1.0, 1.0])
    assert np.all(np.abs(saddle[-1] - (0.5 - math.log(math.sqrt(2)) / k)) < 1e-6)
    flow = scipy_flow(saddle_and_rotation, np.array([0.0, 2.0]), 0.0, 1.0, atol=1e-22)
    rotation = benettin(flow, pairs, d0, 50, [1.0, 1.0])
    assert np.all(np.abs(rotation[-1]) < 1e-6)
    mean, stderr = ensemble_mean(np.array([1.0, 2.0, 3.0]))
    assert mean == 2.0 and abs(stderr - 1 / math.sqrt(3)) < 1e-15
