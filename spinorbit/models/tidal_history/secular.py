"""The secular tidal exchange between the Earth's spin and an orbit about it, for a tidal response K(sigma)
(``response.dissipation``): the torque on the Earth along its spin axis and along the orbit normal, and the
orbit's rate of energy, averaged over the mean anomaly, the Earth's rotation and the argument of pericentre.

The degree-2 tidal potential of the perturber (mass m', semi-major axis a, eccentricity e, orbit normal at an
angle I from the spin axis) is a sum of terms (m, k, q): the harmonic Y_2^k of the orbit's frame (k = 0, +-2)
turned into the Earth's equatorial frame by the Wigner matrix d^2_{mk}(I) (Y_2^m there, the Earth turning
under it at the rate Omega), times the Hansen coefficient X_q^{-3,k}(e) of the perturber's motion (Kaula 1964,
Rev. Geophys. 2, 661: the G_{2pq}(e) to O(e^2)): the term's frequency in the Earth is sigma = m Omega - q n.
Each term, weighted by W = |d^2_{mk}(I)|^2 c_k (X_q^{-3,k})^2 (c_2 = 1, c_0 = 2/3: |Y_2^0 / Y_2^2|^2 on the
orbit's plane), lags by K(sigma) and contributes, in units of F = (3/8) G m'^2 R^5 / a^6,

    torque on the Earth along its spin axis       -m W K(sigma),
    torque on the orbit along its normal          +k W K(sigma),
    rate of the orbit's energy                    +q n W K(sigma),

summed over m = -2..2, k = -2, 0, 2 and q = k - 1, k, k + 1 (each real term twice, as (m, k, q) and its
conjugate (-m, -k, -q)).  The power each term dissipates, sigma W K(sigma), is never negative.  For the
equatorial circular orbit the axial torque is (3/2) G m'^2 R^5 / a^6 K(2 Omega - 2 n), the classical one; to
O(e^2) the sums give Hut's (1981, A&A 99, 126) constant-time-lag f-functions (tests/models/test_tidal_history.py).
"""
import numpy as np
from numba import njit

from ...base.linker import cached
from .response import dissipation

# (k, q, c_k X_q^{-3,k}(e)^2 as (constant, e^2 coefficient)): Kaula's G_{2pq} to O(e^2).
#   k = 2:  X_1 = -e/2, X_2 = 1 - 5 e^2 / 2, X_3 = 7 e / 2;   k = 0: X_{+-1} = 3 e / 2, X_0 = (1 - e^2)^(-3/2)
#   (the k = 0, q = 0, m = 0 term has sigma = 0 and no lag).
TERMS = ((2, 1, 0.0, 0.25), (2, 2, 1.0, -5.0), (2, 3, 0.0, 12.25),
         (0, -1, 0.0, 1.5), (0, 0, 2.0 / 3.0, 3.0), (0, 1, 0.0, 1.5),
         (-2, -1, 0.0, 0.25), (-2, -2, 1.0, -5.0), (-2, -3, 0.0, 12.25))


@njit(cache=True, nogil=True)
def wigner_squared(m, k, c):
    """|d^2_{mk}(I)|^2 for k = 0, 2, -2 with c = cos I (|d_{mk}| = |d_{-m,-k}|)."""
    s2 = 1.0 - c * c
    if k == 0:
        if m == 0:
            return (1.5 * c * c - 0.5) ** 2
        if m == 1 or m == -1:
            return 1.5 * s2 * c * c
        return 0.375 * s2 * s2
    if k == -2:
        m = -m
    if m == 2:
        return (0.5 * (1.0 + c)) ** 4
    if m == 1:
        return 0.25 * (1.0 + c) ** 2 * s2
    if m == 0:
        return 0.375 * s2 * s2
    if m == -1:
        return 0.25 * (1.0 - c) ** 2 * s2
    return (0.5 * (1.0 - c)) ** 4


@cached(nogil=True)
def lags(spin, n, response, t):
    """K(m spin - q n) for m = -2..2 (rows m + 2) and q = -3..3 (columns q + 3) at the time t (days): each
    term's lag, computed once for every orientation the rates are averaged over.  The term (-m, -q) is the
    conjugate of (m, q): K(-sigma) of the order -m is -K(sigma) of the order m for every response (a real
    tide's), so half the table is computed and the other half follows."""
    out = np.zeros((5, 7))
    for m in range(0, 3):
        for q in range(-3, 4):
            if m == 0 and q <= 0:
                continue
            value = dissipation(m * spin - q * n, m, spin, response, t)
            out[m + 2, q + 3] = value
            out[2 - m, 3 - q] = -value
    return out


@njit(cache=True, nogil=True)
def exchange(n, e2, cos_i, lag_table):
    """(axial, normal, power): the sums above over F: the torque on the Earth along its spin axis, the torque
    on the orbit along its normal, and the orbit's energy rate, for the mean motion ``n`` (rad/day), e^2, the
    cosine of the angle between the spin axis and the orbit normal, and the terms' lags (``lags``)."""
    axial, normal, power = 0.0, 0.0, 0.0
    for k, q, w0, w2 in TERMS:
        hansen = w0 * (1.0 + w2 * e2) if w0 != 0.0 else w2 * e2
        for m in range(-2, 3):
            weight = wigner_squared(m, k, cos_i) * hansen
            if weight == 0.0:
                continue
            lag = weight * lag_table[m + 2, q + 3]
            axial -= m * lag
            normal += k * lag
            power += q * n * lag
    return axial, normal, power


@njit(cache=True, nogil=True)
def torque_on_spin(axial, normal, cos_i):
    """(along the spin axis s, along the orbit normal k) of the torque on the Earth T = alpha s + beta k (it
    lies in their plane: the dissipative torque has no part along s x k) whose projections are T.s = axial
    and T.k = -normal (the orbit's gain is the Earth's loss)."""
    s2 = 1.0 - cos_i * cos_i
    if s2 < 1e-14:                                   # aligned: the torque is along the common axis
        return axial, 0.0
    return (axial + cos_i * normal) / s2, (-normal - cos_i * axial) / s2


@njit(cache=True, nogil=True)
def strength(gm_perturber, gm_earth, radius_km, semi_major_axis_km):
    """F / M_earth = (3/8) (G m')^2 / (G M) R^5 / a^6 (km^2/day^2: the torque per unit Earth mass)."""
    return 0.375 * gm_perturber**2 / gm_earth * radius_km**5 / semi_major_axis_km**6

