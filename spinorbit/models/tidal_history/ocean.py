"""A global ocean's tidal response: a thin ocean of uniform depth H on a rotating Earth under the Laplace tidal
equations with linear (Rayleigh) drag, its self-attraction and loading, forced by one degree-2 harmonic.

For a forcing potential U Y_2^m e^{i(m phi - w t)} (m signed; w > 0 with m < 0 a westward wave) the velocity
is u = grad Phi + r x grad Psi and the elevation zeta; with the drag sigma_R, w~ = w + i sigma_R,

    -i w~ u + 2 Omega cos(theta) r x u = -grad G,   G = g (1 - alpha_n) zeta - gamma_2 U,   -i w zeta + H div u = 0,

(the traditional approximation; gamma_2 = 1 + k2 - h2 the solid Earth's reduction of the forcing, alpha_n =
3 rho_o / ((2n + 1) rho_bar) (1 + k'_2 - h'_2) the ocean's self-attraction and the solid Earth's yield under
its load, with degree 2's load numbers for every degree).  Expanded in normalised Y_n^m, the divergence and
the radial curl of the momentum equation couple Phi_n only to Psi_{n-1}, Psi_{n+1} and Psi_n to Phi_{n-1},
Phi_{n+1} (cos(theta) Y_n = A_{n+1} Y_{n+1} + A_n Y_{n-1}, A_n = sqrt((n^2 - m^2)/(4 n^2 - 1)); sin(theta)
d/dtheta Y_n = n A_{n+1} Y_{n+1} - (n + 1) A_n Y_{n-1}), so the chain ... Psi_1, Phi_2, Psi_3, Phi_4 ... that
the forcing at Phi_2 reaches is tridiagonal (L_n = n (n + 1)):

    Phi_n:  [i w~ L_n + 2 i Omega m - i g H (1 - alpha_n) L_n^2 / (w R^2)] Phi_n
            + 2 Omega [A_n (n^2 - 1) Psi_{n-1} + A_{n+1} n (n + 2) Psi_{n+1}] = -L_2 gamma_2 U [n = 2],
    Psi_n:  [i w~ L_n + 2 i Omega m] Psi_n - 2 Omega [A_n (n^2 - 1) Phi_{n-1} + A_{n+1} n (n + 2) Phi_{n+1}] = 0,

with zeta_n = i H L_n Phi_n / (w R^2) (Longuet-Higgins 1968's spectral form of the Laplace tidal equations;
without rotation each degree is a damped oscillator, zeta_2 = (gamma_2 U / g) w_2^2 / (w_2^2 (1 - alpha_2)
- w w~), w_2^2 = 6 g H / R^2, the test's closed form).  The ocean's degree-2 potential seen outside is
(1 + k'_2) 3 rho_o / (5 rho_bar) g zeta_2: its Love number is that over U.  The drag does all the work;
the Coriolis force none, so w Im k >= 0 for every (m, w) (tests).

This is the global-ocean part of Farhat et al. (2022, A&A 665, L1) and Auclair-Desrotour et al. (2018, A&A
615, A23) as derived here, not their code: no continent, degree-2 load numbers for all degrees, no ocean
stratification.
"""
import math

from numba import njit

from ...base.linker import cached

# Indices into the ocean's constants.
GRAVITY, RADIUS, DENSITY_RATIO, LOAD_K2, LOAD_H2, SOLID_K2, SOLID_H2, DEGREES = range(8)
SIZE = 8
LOAD_NUMBERS = (-0.308, -1.001)         # k'_2, h'_2 (Farrell 1972, Gutenberg-Bullen Earth model)
BODY_NUMBERS = (0.298, 0.606)           # k2, h2 of the solid Earth (IERS Conventions 2010, Table 6.3 / 7.2)
SEAWATER_OVER_MEAN_DENSITY = 1025.0 / 5513.0
TRUNCATION = 60                         # degrees in the chain (their convergence: tests)


@njit(cache=True, nogil=True)
def _a(n, m):
    return math.sqrt(max(n * n - m * m, 0) / (4.0 * n * n - 1.0))


@cached(nogil=True)
def love_number(m, w, spin, depth, drag, p):
    """(Re, Im) of the ocean's degree-2 Love number for the forcing Y_2^m e^{i(m phi - w t)}: w, spin, drag in
    rad/day, depth in km, p the constants (GRAVITY km/d^2, RADIUS km, ...)."""
    if w == 0.0:
        return 0.0, 0.0
    g, r = p[GRAVITY], p[RADIUS]
    start = max(abs(m), 1)
    size = int(p[DEGREES])
    load = 1.0 + p[LOAD_K2] - p[LOAD_H2]
    gamma = 1.0 + p[SOLID_K2] - p[SOLID_H2]
    wt = complex(w, drag)
    # Thomas algorithm on the chain n = start .. start + size - 1 (Phi at n - 2 even, Psi otherwise)
    c_prime = [0j] * size
    d_prime = [0j] * size
    for j in range(size):
        n = start + j
        big_l = n * (n + 1.0)
        diag = 1j * wt * big_l + 2j * spin * m
        sign = 1.0
        if (n - 2) % 2 == 0:
            alpha = 3.0 * p[DENSITY_RATIO] / (2 * n + 1.0) * load
            diag -= 1j * g * depth * (1.0 - alpha) * big_l * big_l / (w * r * r)
        else:
            sign = -1.0
        lower = sign * 2.0 * spin * _a(n, m) * (n * n - 1.0)
        upper = sign * 2.0 * spin * _a(n + 1, m) * n * (n + 2.0)
        rhs = -6.0 * gamma + 0j if n == 2 else 0j
        if j == 0:
            denominator = diag
            c_prime[j] = upper / denominator
            d_prime[j] = rhs / denominator
        else:
            denominator = diag - lower * c_prime[j - 1]
            c_prime[j] = upper / denominator
            d_prime[j] = (rhs - lower * d_prime[j - 1]) / denominator
    x = d_prime[size - 1]
    phi2 = 0j
    for j in range(size - 2, -1, -1):
        x = d_prime[j] - c_prime[j] * x
        if start + j == 2:
            phi2 = x
    if start + size - 1 == 2:
        phi2 = d_prime[size - 1]
    zeta2 = 1j * depth * 6.0 * phi2 / (w * r * r)
    k = (1.0 + p[LOAD_K2]) * 3.0 * p[DENSITY_RATIO] / 5.0 * g * zeta2
    return k.real, k.imag


def constants(gravity_km_d2, radius_km, degrees=TRUNCATION):
    """The ocean's constants array (the unit forcing U = 1 km^2/d^2)."""
    import numpy as np

    out = np.zeros(SIZE)
    out[GRAVITY], out[RADIUS], out[DENSITY_RATIO] = gravity_km_d2, radius_km, SEAWATER_OVER_MEAN_DENSITY
    out[LOAD_K2], out[LOAD_H2] = LOAD_NUMBERS
    out[SOLID_K2], out[SOLID_H2] = BODY_NUMBERS
    out[DEGREES] = degrees
    return out
