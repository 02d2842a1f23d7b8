"""DE421's lunar mantle orientation as the ``de421`` package ships it: Chebyshev series of the JPL 3-1-3 angles.

``jpl-librations.npy``: shape (records x 4 sub-intervals, 3 angles, 10 coefficients), 8-day sub-intervals from
``jalpha`` = JD 2414992.5 (Williams, Boggs & Folkner 2008, JPL IOM 335-JW,DB,WF-20080314-001).  The angles
(phi, theta, psi) take the ICRF to the lunar principal axes, M = Rz(psi) Rx(theta) Rz(phi); psi is continuous.
:func:`angles_and_rates` evaluates them from Python (numpy), :func:`mantle` inside compiled code.
"""
import math
from functools import cache
from pathlib import Path

import numpy as np
from numpy.polynomial import chebyshev

from ..base.constants import J2000_JD
from ..base.errors import EphemerisRangeError
from ..base.linker import OnDemand
from .de421_header import header

compiled = OnDemand(cache=True, nogil=True)      # the kernels' series, compiled when first asked for


@cache
def series():
    """The Chebyshev coefficients (n, 3, 10)."""
    import de421

    return np.ascontiguousarray(np.load(Path(de421.__file__).parent / "jpl-librations.npy"))


def span():
    """(start, end) TDB days from J2000 that the series covers."""
    h = header()
    return h["jalpha"] - J2000_JD, h["jomega"] - J2000_JD


def check_span(t):
    start, end = span()
    if np.min(t) < start or np.max(t) > end:
        raise EphemerisRangeError("de421 librations", (np.min(t), np.max(t)), (start, end),
                                  "Outside it a lunar run starts from the nearest epoch DE421 covers and is "
                                  "integrated out (spinorbit.models.start)")


def angles_and_rates(t_tdb_d):
    """The angles (n, 3) rad and their rates (n, 3) rad/day at TDB days ``t``."""
    t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
    check_span(t)
    coefficients, (start, end) = series(), span()
    length = (end - start) / coefficients.shape[0]                    # 8 days
    index = np.minimum(((t - start) // length).astype(int), coefficients.shape[0] - 1)
    x = 2.0 * (t - start - index * length) / length - 1.0
    picked = coefficients[index]                                      # (n, 3, 10)
    angles, rates = np.empty((t.size, 3)), np.empty((t.size, 3))
    for k in range(3):
        c = picked[:, k, :].T                                         # (10, n): one series per time
        angles[:, k] = chebyshev.chebval(x, c, tensor=False)
        rates[:, k] = chebyshev.chebval(x, chebyshev.chebder(c), tensor=False) * 2.0 / length
    return angles, rates


@compiled
def _chebyshev(c, x):
    """(sum c_k T_k(x), its derivative in x), by the recurrences T_k+1 = 2x T_k - T_k-1, U likewise."""
    t_prev, t_now, u_prev, u_now = 1.0, x, 0.0, 1.0
    value, slope = c[0] + c[1] * x, c[1]
    for k in range(2, c.shape[0]):
        t_prev, t_now = t_now, 2.0 * x * t_now - t_prev
        u_prev, u_now = u_now, 2.0 * x * u_now - u_prev
        value += c[k] * t_now
        slope += c[k] * k * u_now
    return value, slope


@compiled
def mantle(t, coefficients, start, length):
    """(M (3, 3) ICRF -> body, w (3,) body axes rad/d) at TDB day t inside the series' span."""
    index = min(int((t - start) // length), coefficients.shape[0] - 1)
    x = 2.0 * (t - start - index * length) / length - 1.0
    phi, dphi = _chebyshev(coefficients[index, 0], x)
    theta, dtheta = _chebyshev(coefficients[index, 1], x)
    psi, dpsi = _chebyshev(coefficients[index, 2], x)
    dphi, dtheta, dpsi = dphi * 2.0 / length, dtheta * 2.0 / length, dpsi * 2.0 / length
    cf, sf, ct, st, cp, sp = math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta), math.cos(psi), \
        math.sin(psi)
    m = np.array([[cp * cf - sp * ct * sf, cp * sf + sp * ct * cf, sp * st],
                  [-sp * cf - cp * ct * sf, -sp * sf + cp * ct * cf, cp * st],
                  [st * sf, -st * cf, ct]])
    omega = np.array([dphi * st * sp + dtheta * cp, dphi * st * cp - dtheta * sp, dphi * ct + dpsi])
    return m, omega


__getattr__ = compiled.hide(globals())
