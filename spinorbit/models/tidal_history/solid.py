"""The solid Earth's tidal response as an Andrade body: a homogeneous incompressible sphere whose complex
compliance is J(chi) = J_u [1 + Gamma(1 + alpha) (i chi tau_A)^(-alpha) - i / (chi tau_M)] (Andrade creep with a
Maxwell flow; Efroimsky 2012, ApJ 746, 150, eq. 9, with tau_A = tau_M as there), so that

    k2(chi) = (3/2) / (1 + (19/2) / (rho g R J(chi)))        (Love 1911, the homogeneous sphere),

and its lag K(sigma) = -Im k2(|sigma|) sign(sigma).  alpha = 0.25 (Efroimsky 2012: 0.2-0.3 for the mantle);
the unrelaxed rigidity (through J_u) and the Maxwell time are chosen so that today's semi-diurnal lunar tide
(M2) sees Re k2 = 0.298 (IERS Conventions 2010) and k2/Q = 0.298/280 (Q = 280, Ray, Eanes & Lemoine 2001):
an effective body standing for the layered Earth, with the frequency dependence Q ~ chi^alpha of a mantle
(Auclair-Desrotour et al. 2023 use an Andrade solid part; their parameters could not be read here).
"""
import math

import numpy as np
from numba import njit

ALPHA = 0.25
K2_TODAY, Q_TODAY = 0.298, 280.0
# Indices into the solid Earth's constants: 1 / (rho g R J_u) (19/2 folded in), the Maxwell time (days), alpha,
# Gamma(1 + alpha).
STIFFNESS, MAXWELL_TIME, EXPONENT, GAMMA = range(4)
SIZE = 4


@njit(cache=True, nogil=True)
def love_number(chi, p):
    """(Re, Im) of k2 at the tidal frequency chi > 0 (rad/day)."""
    x = chi * p[MAXWELL_TIME]
    creep = p[GAMMA] * x ** (-p[EXPONENT]) * complex(math.cos(0.5 * math.pi * p[EXPONENT]),
                                                     -math.sin(0.5 * math.pi * p[EXPONENT]))
    compliance = 1.0 + creep - 1j / x
    k = 1.5 / (1.0 + p[STIFFNESS] / compliance)
    return k.real, k.imag


@njit(cache=True, nogil=True)
def lag(sigma, p):
    """K(sigma) = -Im k2(|sigma|) sign(sigma): the lagging part, with the sign of sigma."""
    if sigma == 0.0:
        return 0.0
    return math.copysign(-love_number(abs(sigma), p)[1], sigma)


def constants(m2_frequency, k2=K2_TODAY, q=Q_TODAY, alpha=ALPHA):
    """The constants of the Andrade body whose k2 at ``m2_frequency`` (rad/day) has the real part k2 and the
    lagging part k2 / q (solved: the rigidity from the real part, the Maxwell time from the lag)."""
    from scipy.optimize import brentq

    out = np.zeros(SIZE)
    out[EXPONENT], out[GAMMA] = alpha, math.gamma(1.0 + alpha)

    def mismatch(log_tau):
        out[MAXWELL_TIME] = math.exp(log_tau)
        for _ in range(60):                                 # the real part: fixed point on the stiffness
            re, _ = love_number(m2_frequency, out)
            out[STIFFNESS] = max(out[STIFFNESS] * (1.5 / k2 - 1.0) / (1.5 / re - 1.0), 1e-12) \
                if out[STIFFNESS] else 1.5 / k2 - 1.0
        return -love_number(m2_frequency, out)[1] - k2 / q

    brentq(mismatch, math.log(1e-2 / m2_frequency), math.log(1e12 / m2_frequency), xtol=1e-12)
    return out
