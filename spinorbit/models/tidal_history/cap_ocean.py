"""The tidal response of an ocean bounded by one continent, a spherical cap of angular radius theta_c: the
ocean's eigenmodes and its degree-2 Love number as a sum of damped resonances.

Derived here from the shallow-water (Laplace tidal) equations, after the setting of Auclair-Desrotour et al.
(2023, A&A 680, A13: a spherical-cap continent; the derivation is ours, their text could not be read here):
a thin ocean of uniform depth H with linear drag sigma_R, its self-attraction and the solid Earth's yield
under its load, forced by a degree-2 harmonic U at the frequency w, *without the Coriolis force* (as Webb
1980, 1982 for his hemispherical ocean).  Then u = grad G / (i w~ R) (w~ = w + i sigma_R) and the continuity
equation give w w~ zeta = -(H / R^2) Lap G, G = g zeta - g SAL[zeta] - gamma_2 U, with no flow through the
coast: G's normal derivative vanishes there.

In the cap's frame (its centre at the pole, x = -cos(theta') in [x_c, 1], x_c = -cos(theta_c)) the ocean's
Neumann eigenmodes are F(x) e^{i mu phi'}, F the associated Legendre functions P_nu^mu of non-integer degree
nu whose derivative vanishes at the coast (eigenvalue lambda = nu (nu + 1); the integer P_n^mu with n - mu
even for the hemisphere, every P_n^mu for the global ocean).  They are found by the Rayleigh-Ritz method on
(1 - x^2)^(mu/2) times Legendre polynomials of x mapped onto [x_c, 1] (exact where the true modes are in
that space: the global ocean and the hemisphere; tests compare scipy's P_nu^mu elsewhere).  The
self-attraction SAL[zeta] = sum_n alpha_n zeta_n, alpha_n = 3 rho_o / ((2n + 1) rho_bar) (1 + k'_2 - h'_2),
couples the modes through their projections c_jn on the spherical harmonics Y_n^mu (the land dry).  With
eps = g H / R^2, D = diag(lambda), S = c diag(alpha) c^T and the forcing's projections b_j = c_j2, the
degree-2 response of the block mu is

    zeta_2 / (gamma_2 U / g) = sum_p eps a_p / (eps lambda'_p - w w~),

lambda'_p the eigenvalues of D^(1/2) (1 - S) D^(1/2) (eigenvectors q_p) and a_p = (q_p . D^(1/2) b)^2 >= 0:
damped oscillators whose frequencies eps lambda'_p and weights depend on the cap alone, not on H or the
drag, so they are tabulated once over theta_c (kept by the caller's cache, ``constants(keep=...)``) and the
rhs sums them.  Without a cap this is the global
ocean's closed form (one pole, lambda' = 6 (1 - alpha_2), a = 6).

A cap centred at colatitude theta_0 turns the Earth's Y_2^m into sum_mu d^2_{m mu}(theta_0) Y_2^mu of the cap's
frame (Wigner); the response each block gives back on Y_2^m, the part that carries the torque (the other
orders beat at other frequencies and average out), is sum_mu d^2_{m mu}(theta_0)^2 times the block's.
"""
import math
from functools import lru_cache

import numpy as np
from numba import njit
from scipy.linalg import eigh
from scipy.special import assoc_legendre_p_all, legendre_p_all, roots_legendre

from ...base.linker import cached
from .ocean import DENSITY_RATIO, GRAVITY, LOAD_H2, LOAD_K2, RADIUS, SOLID_H2, SOLID_K2
from .ocean import SIZE as OCEAN_SIZE

ORDERS = 3                      # |mu| = 0, 1, 2
RITZ = 48                       # Legendre polynomials in the Ritz basis: the number of poles per order
SAL_DEGREES = 120               # degrees of the self-attraction
NODES = 240                     # Gauss-Legendre nodes on [x_c, 1]
CAP_GRID_DEG = np.linspace(0.0, 90.0, 91)      # the cap radii tabulated (1 degree)


@lru_cache(maxsize=2)
def _legendre_nodes(size, nodes):
    """(t, w, L_i(t), L_i'(t)) at the Gauss-Legendre nodes on [-1, 1]."""
    t, w = roots_legendre(nodes)
    legendre, d_legendre = legendre_p_all(size - 1, t, diff_n=1)
    return t, w, legendre, d_legendre


def ritz_basis(mu, x_c, size, nodes):
    """(x, weights, phi, dphi/dx) of the basis (1 - x^2)^(mu/2) L_i(t(x)) at Gauss-Legendre nodes on [x_c, 1]."""
    t, w, legendre, d_legendre = _legendre_nodes(size, nodes)
    half = 0.5 * (1.0 - x_c)
    x = x_c + half * (t + 1.0)
    weights = w * half
    s2 = 1.0 - x * x
    envelope = s2 ** (0.5 * mu)
    phi = envelope * legendre
    dphi = envelope * d_legendre / half - mu * x * s2 ** (0.5 * mu - 1.0) * legendre if mu else \
        envelope * d_legendre / half
    return x, weights, phi, dphi


def gram(f, weights, g):
    """sum_k f[i, k] weights[k] g[j, k] (einsum: these small products are slower through a threaded BLAS)."""
    return np.einsum("ik,jk->ij", f * weights, g)


def neumann_modes(mu, cap_deg, size=RITZ, nodes=NODES):
    """(lambda, F, x, weights): the ocean's Neumann eigenvalues nu (nu + 1) of order mu outside a cap of radius
    cap_deg, ascending, and their eigenfunctions F (size, nodes) at the nodes x, orthonormal on [x_c, 1]."""
    x_c = -math.cos(math.radians(cap_deg))
    x, w, phi, dphi = ritz_basis(mu, x_c, size, nodes)
    s2 = 1.0 - x * x
    stiffness = gram(dphi, w * s2, dphi)
    if mu:
        stiffness += mu * mu * gram(phi, w / s2, phi)
    values, vectors = eigh(stiffness, gram(phi, w, phi))
    return values, np.einsum("ij,ik->jk", vectors, phi), x, w


def projections(modes, x, weights, mu, degrees=SAL_DEGREES):
    """c_jn = <F_j, Y_n^mu> over the ocean, n = mu .. degrees (columns n - mu), Y_n^mu at cos(theta') = -x."""
    harmonics = assoc_legendre_p_all(degrees, mu, -x, norm=True)[0, mu:, mu]      # int_{-1}^{1} ybar^2 = 1
    return gram(modes, weights, harmonics)


def load_factors(mu, density_ratio, load_k2, load_h2, degrees=SAL_DEGREES):
    """alpha_n for n = mu .. degrees: the ocean's self-attraction and the solid Earth's yield under its load."""
    n = np.arange(mu, degrees + 1)
    return 3.0 * density_ratio / (2 * n + 1.0) * (1.0 + load_k2 - load_h2)


def poles(mu, cap_deg, density_ratio, load_k2, load_h2, size=RITZ):
    """(lambda'_p, a_p), ascending in lambda': the block mu's resonances (in units of g H / R^2) and weights."""
    values, modes, x, w = neumann_modes(mu, cap_deg, size)
    c = projections(modes, x, w, mu)
    alpha = load_factors(mu, density_ratio, load_k2, load_h2)
    keep = values > 1e-9 * values.max()                # the constant mode (mu = 0): mass kept, no response
    root = np.sqrt(values[keep])
    c = c[keep]
    coupling = np.eye(root.size) - (c * alpha) @ c.T
    symmetric = root[:, None] * coupling * root[None, :]
    resonances, q = eigh(symmetric)
    forcing = root * c[:, 2 - mu]
    return resonances, (q.T @ forcing) ** 2


@lru_cache(maxsize=4)
def table(density_ratio, load_k2, load_h2, size=RITZ):
    """(cap radii (deg), lambda' (caps, ORDERS, size), a (caps, ORDERS, size)) over CAP_GRID_DEG (zero-padded
    where the mu = 0 block has one pole fewer)."""
    caps = CAP_GRID_DEG
    lam = np.zeros((caps.size, ORDERS, size))
    weight = np.zeros((caps.size, ORDERS, size))
    for i, cap in enumerate(caps):
        for mu in range(ORDERS):
            values, a = poles(mu, cap, density_ratio, load_k2, load_h2, size)
            lam[i, mu, :values.size] = values
            weight[i, mu, :values.size] = a
    return caps, lam, weight


def orientation_weights(colatitude_deg):
    """W[|m|, |mu|] = sum over the signs of mu of d^2_{m mu}(theta_0)^2: how the Earth's Y_2^m shares itself
    among the cap frame's orders (each row sums to 1)."""
    c = math.cos(math.radians(colatitude_deg))
    s2 = 1.0 - c * c
    d2 = {(2, 2): (0.5 * (1 + c)) ** 4, (2, 1): 0.25 * (1 + c) ** 2 * s2, (2, 0): 0.375 * s2 * s2,
          (2, -1): 0.25 * (1 - c) ** 2 * s2, (2, -2): (0.5 * (1 - c)) ** 4,
          (1, 1): (0.5 * (1 + c) * (2 * c - 1)) ** 2, (1, 0): 1.5 * s2 * c * c,
          (1, -1): (0.5 * (1 - c) * (2 * c + 1)) ** 2, (1, 2): 0.25 * (1 + c) ** 2 * s2,
          (1, -2): 0.25 * (1 - c) ** 2 * s2,
          (0, 0): (1.5 * c * c - 0.5) ** 2, (0, 1): 1.5 * s2 * c * c, (0, -1): 1.5 * s2 * c * c,
          (0, 2): 0.375 * s2 * s2, (0, -2): 0.375 * s2 * s2}
    out = np.zeros((3, ORDERS))
    for (m, mu), value in d2.items():
        out[m, abs(mu)] += value
    return out


# Indices into the continent's constants (after ocean.constants' SIZE): the cap's radius today (deg), the
# ages (days) until which it keeps that size and from which the ocean is global, the colatitude's weights
# W[|m|, |mu|] (9), the grid (caps, poles, step in deg), then lambda' and a (caps, ORDERS, poles) each.
RADIUS_TODAY, FULL_UNTIL, GLOBAL_FROM, WEIGHTS, CAPS, POLES, STEP, TABLES = 0, 1, 2, 3, 12, 13, 14, 15


def constants(water, radius_deg, colatitude_deg, full_until_d, global_from_d, keep=None):
    """The cap ocean's constants: ``water`` (ocean.constants(...)) followed by the continent's (above);
    ``keep(name, settings, compute)``: the caller's cache for the poles' table (computed when None)."""
    loads = (float(water[DENSITY_RATIO]), float(water[LOAD_K2]), float(water[LOAD_H2]))
    settings = {"density_ratio": loads[0], "load_k2": loads[1], "load_h2": loads[2], "ritz": RITZ,
                "nodes": NODES, "sal_degrees": SAL_DEGREES, "caps": CAP_GRID_DEG.tolist()}

    def compute():
        _, lam, weight = table(*loads)
        return np.stack([lam, weight])

    lam, weight = compute() if keep is None else keep("cap_ocean", settings, compute)
    caps = CAP_GRID_DEG
    head = np.zeros(TABLES)
    head[RADIUS_TODAY], head[FULL_UNTIL], head[GLOBAL_FROM] = radius_deg, full_until_d, global_from_d
    head[WEIGHTS:WEIGHTS + 9] = orientation_weights(colatitude_deg).ravel()
    head[CAPS], head[POLES], head[STEP] = caps.size, lam.shape[2], caps[1] - caps[0]
    return np.concatenate([np.asarray(water, dtype=float), head, lam.ravel(), weight.ravel()])


@njit(cache=True, nogil=True)
def cap_radius(t, k):
    """The continent's angular radius (deg) at the time t (days, negative in the past): today's until
    FULL_UNTIL, its area shrinking linearly with the age to nothing at GLOBAL_FROM (``k``: the continent's
    constants)."""
    age = -t
    if age <= k[FULL_UNTIL]:
        return k[RADIUS_TODAY]
    if age >= k[GLOBAL_FROM]:
        return 0.0
    area = 0.5 * (1.0 - math.cos(math.radians(k[RADIUS_TODAY])))
    area *= (k[GLOBAL_FROM] - age) / (k[GLOBAL_FROM] - k[FULL_UNTIL])
    return math.degrees(math.acos(1.0 - 2.0 * area))


@cached(nogil=True)
def love_number_imag(m, w, drag, depth, cap_deg, p):
    """Im k_2 of the ocean outside a cap of radius cap_deg for the Earth's Y_2^m at the frequency w (rad/day; Im
    has its sign), drag in rad/day, depth in km; ``p`` = ``constants(...)``: the poles interpolated linearly
    in the cap's radius, pole by pole."""
    k = p[OCEAN_SIZE:]
    g, r = p[GRAVITY], p[RADIUS]
    eps = g * depth / (r * r)
    caps, poles = int(k[CAPS]), int(k[POLES])
    position = min(max(cap_deg / k[STEP], 0.0), caps - 1.000001)
    i = int(position)
    frac = position - i
    block = ORDERS * poles
    lam = k[TABLES:TABLES + caps * block]
    weight = k[TABLES + caps * block:TABLES + 2 * caps * block]
    damping = drag * w
    total = 0.0
    for mu in range(ORDERS):
        share = k[WEIGHTS + 3 * abs(m) + mu]
        if share == 0.0:
            continue
        low, high = i * block + mu * poles, (i + 1) * block + mu * poles
        part = 0.0
        for j in range(poles):
            a = (1.0 - frac) * weight[low + j] + frac * weight[high + j]
            detune = eps * ((1.0 - frac) * lam[low + j] + frac * lam[high + j]) - w * w
            part += a / (detune * detune + damping * damping)
        total += share * part
    gamma = 1.0 + p[SOLID_K2] - p[SOLID_H2]
    return (1.0 + p[LOAD_K2]) * 3.0 * p[DENSITY_RATIO] / 5.0 * gamma * eps * damping * total
