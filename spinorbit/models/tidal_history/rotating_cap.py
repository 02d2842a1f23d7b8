"""The tidal response of an ocean outside a spherical-cap continent on the rotating Earth: the linearised
Laplace tidal equations with the Coriolis force, drag, self-attraction and loading, solved by Galerkin's method
over the basin's own modes (Proudman 1917, Proc. London Math. Soc. 2, 51: the flow as the gradient of a
potential plus the curl of a stream function, each expanded in the basin's eigenfunctions; Rao 1966, J.
Fluid Mech. 25, 337, for a rotating basin).

The flow is u = grad Phi + r x grad Psi: Phi in the Neumann modes phi_a of the ocean (no gradient across the
coast, weakly) and Psi in its Dirichlet modes psi_b (Psi = 0 on the coast: no flow through it), both from
``cap_ocean``'s Ritz method in the cap's frame (x = -cos(theta') on [x_c, 1], orders |mu| <= ORDERS_MAX, the
lowest MODES of each order and parity).  With the basis vectors e = grad phi_a, r x grad psi_b, the weak form
of the momentum and continuity equations (w~ = w + i sigma_R, a time factor e^{-i w t})

    -i w~ M X + 2 Omega C X + M_Phi G / R = 0,     -i w z + (H / R) M_Phi^T X = 0,
    G = g (1 - S) z - gamma_2 U,

with M_ij = <e_i, e_j> over the ocean, C_ij = <e_i, f r x e_j> (f = cos of the colatitude on the Earth: the
cap centred at colatitude theta_0 makes it couple every order), S the self-attraction and loading in the
Neumann modes (as ``cap_ocean``), U the forcing's projections, gives one linear system for the velocity's
coefficients X at each (w, Omega).  The elevation z = i H M_Phi^T X / (w R), and zeta_2 = <Y_2^m, zeta> gives
the Love number (1 + k'_2) (3 rho_o / 5 rho_bar) g zeta_2 / U, as ``ocean``.  The Coriolis force does no work
(C is antisymmetric), so w Im k >= 0; without rotation this is ``cap_ocean``'s pole sum, and without a cap the
global ocean of ``ocean`` (tests/models/tidal_history/test_rotating_cap.py).

At run time the response is read from a table over the spin (log-spaced) and the frequency relative to the
spin, nu = w / Omega, near each order's band (``table``, read by ``love_number_imag``), for the run's depth
and drag.
"""
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit
from scipy.linalg import eigh, null_space
from scipy.special import sph_harm_y

from ...base.linker import cached
from .cap_ocean import gram, load_factors, projections, ritz_basis
from .ocean import DENSITY_RATIO, GRAVITY, LOAD_K2, RADIUS, SOLID_H2, SOLID_K2
from .ocean import SIZE as OCEAN_SIZE
from .ocean import love_number as global_love_number

ORDERS_MAX = 6                  # |mu| <= ORDERS_MAX in the cap's frame
MODES = 5                       # the lowest Neumann and Dirichlet modes of each order and parity
RITZ = 24                       # Legendre polynomials in the radial Ritz basis
NODES_X = 96                    # Gauss-Legendre nodes on [x_c, 1]
NODES_PHI = 32                  # points around the cap's axis


@dataclass(frozen=True)
class Basin:
    """The Galerkin matrices of one basin (a cap of radius cap_deg centred at colatitude colatitude_deg):
    the metric M, the Coriolis matrix C (for f = cos of the Earth's colatitude), the Neumann block's index,
    the self-attraction S, and the forcing's projections U[m] on the Neumann modes for the Earth's Y_2^m, m =
    0, 1, 2 (normalised: the integral of |Y|^2 over the sphere is 1)."""

    metric: np.ndarray
    coriolis: np.ndarray
    neumann: int
    self_attraction: np.ndarray
    forcing: np.ndarray


def _radial_modes(mu, x_c, dirichlet, size=RITZ, nodes=NODES_X):
    """(F, dF/dx, x, weights): the lowest MODES Neumann (or Dirichlet: zero at x_c) eigenfunctions of order mu,
    orthonormal on [x_c, 1], at the Gauss nodes; the constant Neumann mode (mu = 0) left out."""
    x, w, phi, dphi = ritz_basis(mu, x_c, size, nodes)
    s2 = 1.0 - x * x
    stiffness = gram(dphi, w * s2, dphi)
    if mu:
        stiffness += mu * mu * gram(phi, w / s2, phi)
    mass = gram(phi, w, phi)
    if dirichlet:
        at_coast = _basis_at(mu, x_c, size)
        if np.abs(at_coast).max() > 1e-12:
            keep = null_space(at_coast[None, :])
            stiffness, mass = keep.T @ stiffness @ keep, keep.T @ mass @ keep
            phi, dphi = keep.T @ phi, keep.T @ dphi
    values, vectors = eigh(stiffness, mass)
    first = 1 if (mu == 0 and not dirichlet) else 0
    vectors = vectors[:, first:first + MODES]
    return vectors.T @ phi, vectors.T @ dphi, x, w


def _basis_at(mu, x_c, size):
    """The radial Ritz basis (1 - x^2)^(mu/2) L_i(t) at the coast x = x_c (t = -1)."""
    i = np.arange(size)
    return (1.0 - x_c * x_c) ** (0.5 * mu) * (-1.0) ** i


@lru_cache(maxsize=32)
def basin(cap_deg, colatitude_deg, density_ratio, load_k2, load_h2):
    """The Basin of a cap of radius cap_deg (0: the global ocean) centred at colatitude_deg."""
    x_c = -math.cos(math.radians(cap_deg))
    angle = np.arange(NODES_PHI) * 2 * math.pi / NODES_PHI
    weight_phi = 2 * math.pi / NODES_PHI
    fields = {"neumann": [], "dirichlet": []}          # (value, d/dtheta, d/dphi / sin) on the grid
    sal_blocks = []
    for mu in range(ORDERS_MAX + 1):
        for kind in ("neumann", "dirichlet"):
            f, df, x, w = _radial_modes(mu, x_c, kind == "dirichlet")
            sin_t = np.sqrt(1.0 - x * x)
            for parity, (trig, dtrig) in enumerate(((np.cos(mu * angle), -mu * np.sin(mu * angle)),
                                                    (np.sin(mu * angle), mu * np.cos(mu * angle)))):
                if mu == 0 and parity == 1:
                    continue
                norm = 1.0 / math.sqrt(2 * math.pi if mu == 0 else math.pi)
                value = norm * f[:, :, None] * trig[None, None, :]
                d_theta = norm * (df * sin_t)[:, :, None] * trig[None, None, :]        # d/dtheta' = sin d/dx
                d_phi = norm * (f / sin_t)[:, :, None] * dtrig[None, None, :]
                fields[kind].append((value, d_theta, d_phi))
                if kind == "neumann":
                    c = projections(f, x, w, mu)
                    sal_blocks.append((c * load_factors(mu, density_ratio, load_k2, load_h2)) @ c.T)
    area = (w[:, None] * np.full(NODES_PHI, weight_phi)[None, :]).ravel()
    neumann = [np.concatenate([b[k] for b in fields["neumann"]]).reshape(-1, area.size) for k in range(3)]
    dirichlet = [np.concatenate([b[k] for b in fields["dirichlet"]]).reshape(-1, area.size) for k in range(3)]
    # the basis vectors' (theta, phi) components: grad phi = (d_theta, d_phi); r x grad psi = (-d_phi, d_theta)
    e_theta = np.concatenate([neumann[1], -dirichlet[2]])
    e_phi = np.concatenate([neumann[2], dirichlet[1]])
    cos_t = -np.repeat(x, NODES_PHI)
    sin_t = np.sqrt(1.0 - cos_t * cos_t)
    c0, s0 = math.cos(math.radians(colatitude_deg)), math.sin(math.radians(colatitude_deg))
    f = c0 * cos_t + s0 * sin_t * np.tile(np.cos(angle), x.size)     # the Earth's pole at (theta_0, phi' = 0)
    metric = gram(e_theta, area, e_theta) + gram(e_phi, area, e_phi)
    coriolis = gram(e_theta, area * f, -e_phi) + gram(e_phi, area * f, e_theta)
    sal = np.zeros((neumann[0].shape[0],) * 2)
    start = 0
    for block in sal_blocks:
        size = block.shape[0]
        sal[start:start + size, start:start + size] = block
        start += size
    earth_theta, earth_phi = _earth_angles(cos_t, sin_t, np.tile(angle, x.size), c0, s0)
    forcing = np.array([gram(neumann[0], area, sph_harm_y(2, m, earth_theta, earth_phi)[None, :])[:, 0]
                        for m in range(3)])
    return Basin(metric, coriolis, neumann[0].shape[0], sal, forcing)


def _earth_angles(cos_t, sin_t, phi, c0, s0):
    """(colatitude, longitude) on the Earth of the cap frame's points: the cap's axis at colatitude theta_0
    and longitude 0, its phi' = 0 meridian through the Earth's pole."""
    v = np.array([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t])
    x_axis = np.array([-c0, 0.0, s0])
    z_axis = np.array([s0, 0.0, c0])
    y_axis = np.cross(z_axis, x_axis)
    earth = x_axis[:, None] * v[0] + y_axis[:, None] * v[1] + z_axis[:, None] * v[2]
    return np.arccos(np.clip(earth[2], -1.0, 1.0)), np.arctan2(earth[1], earth[0])


def _pieces(order, depth, p, b):
    """(M_Phi (M_Phi (1 - S) M_Phi^T) scaled, the forcing's right-hand side, the output row, the Love number's
    factor): the parts of the system that do not depend on the frequencies."""
    g, r = p[GRAVITY], p[RADIUS]
    gamma = 1.0 + p[SOLID_K2] - p[SOLID_H2]
    mp = b.metric[:, :b.neumann]
    pressure = (g * depth / (r * r)) * (mp @ ((np.eye(b.neumann) - b.self_attraction) @ mp.T))
    forcing = (gamma / r) * (mp @ b.forcing[order])
    output = (depth / r) * (np.conj(b.forcing[order]) @ mp.T)
    factor = (1.0 + p[LOAD_K2]) * 3.0 * p[DENSITY_RATIO] / 5.0 * g
    return pressure, forcing, output, factor


def love_numbers(order, w, spin, depth, drag, p, b):
    """Complex k_2 for the forcing Y_2^order e^{i(order phi - w t)} (order = 0, 1, 2) at the frequencies w
    (rad/day, nonzero) with the spins ``spin`` (broadcast together), drag in rad/day, depth km, ``p`` =
    ocean.constants(...), ``b`` a Basin: one batched solve."""
    pressure, forcing, output, factor = _pieces(order, depth, p, b)
    w, spin = np.broadcast_arrays(np.asarray(w, dtype=float), np.asarray(spin, dtype=float))
    flat_w, flat_spin = w.ravel(), spin.ravel()
    systems = (-1j * (flat_w + 1j * drag)[:, None, None] * b.metric
               + 2.0 * flat_spin[:, None, None] * b.coriolis + (1j / flat_w)[:, None, None] * pressure)
    rhs = np.broadcast_to(forcing, (flat_w.size, forcing.size))[..., None]
    velocity = np.linalg.solve(systems, rhs)[..., 0]
    return (factor * 1j * (velocity @ output) / flat_w).reshape(w.shape)


def love_number(m, w, spin, depth, drag, p, b):
    """Complex k_2 of the ocean for the forcing Y_2^m e^{i(m phi - w t)} (m = -2..2, w rad/day), spin and drag
    in rad/day, depth km; ``p`` = ocean.constants(...), ``b`` a Basin."""
    if w == 0.0:
        return 0j
    if m < 0:                                       # the conjugate problem: k(-m, -w) = conj(k(m, w))
        return np.conj(love_number(-m, -w, spin, depth, drag, p, b))
    return complex(love_numbers(m, w, spin, depth, drag, p, b))


@dataclass(frozen=True)
class DragPoles:
    """The Love numbers at fixed frequencies and spin as functions of the drag: k(sigma_R) = sum_j weights_j
    / (poles_j + sigma_R) for each frequency (rows), from the eigenvectors of M^-1 A_0 (the drag enters the
    system as sigma_R M): the drag fitted at the cost of one eigen-decomposition per frequency."""

    poles: np.ndarray
    weights: np.ndarray

    def love_numbers(self, drag):
        return (self.weights / (self.poles + drag)).sum(axis=-1)


def drag_poles(order, w, spin, depth, p, b):
    """DragPoles of the forcing Y_2^order at each frequency of ``w`` (nonzero) with the spin ``spin``."""
    from scipy.linalg import eig, solve

    pressure, forcing, output, factor = _pieces(order, depth, p, b)
    poles, weights = [], []
    for wk in np.atleast_1d(w):
        reduced = solve(b.metric, -1j * wk * b.metric + 2.0 * spin * b.coriolis + (1j / wk) * pressure)
        values, vectors = eig(reduced)
        right = np.linalg.solve(vectors, np.linalg.solve(b.metric, forcing))
        poles.append(values)
        weights.append(factor * 1j / wk * (output @ vectors) * right)
    return DragPoles(np.array(poles), np.array(weights))


# The table the rhs reads: Im k_2 over the spin (log-spaced from a node below today's, today's the second
# node) and nu = w / spin about each order's band -order (Lagrange's 4-point interpolation in both).
SPIN_STEP = 0.025                          # log step of the spins
SPIN_SPAN = 3.0                            # the spins tabulated: today's to SPIN_SPAN times (a day of 8 h)
NU_HALF, NU_STEP = 0.2, 0.025              # nu in -order +- NU_HALF: |q| n / spin up to 3 x 0.066


def resolution():
    """The settings a table depends on beyond its depth, drag, basin and spins (its cache's key)."""
    return {"orders_max": ORDERS_MAX, "modes": MODES, "ritz": RITZ, "nodes_x": NODES_X, "nodes_phi": NODES_PHI,
            "nu_half": NU_HALF, "nu_step": NU_STEP}


def spin_nodes(spin_today):
    count = int(math.ceil(math.log(SPIN_SPAN) / SPIN_STEP)) + 3
    return spin_today * np.exp(SPIN_STEP * (np.arange(count) - 1.0))


def nu_nodes(order):
    half = int(round(NU_HALF / NU_STEP))
    return -order + NU_STEP * np.arange(-half, half + 1)


def table(depth, drag, p, b, spins):
    """Im k_2 (3 orders, spins, nus): the rhs's table of the basin ``b`` at the depth and drag."""
    out = np.zeros((3, len(spins), nu_nodes(0).size))
    for order in range(3):
        nus = nu_nodes(order)
        solved = nus != 0.0                         # nu = 0: no tide (Im k is odd in nu for order 0)
        w = np.multiply.outer(spins, nus[solved])
        out[order][:, solved] = love_numbers(order, w, np.broadcast_to(spins[:, None], w.shape), depth, drag,
                                             p, b).imag
    return out


def today_tables(depth, p, b, spins):
    """drag -> a table holding, at every spin node, the Love numbers at spins[1] (today's spin): what the rhs
    reads today, exactly (the interpolation's weights at a node are 0, 1, 0, 0), for any drag at the cost
    of one DragPoles (``drag_poles``) per frequency."""
    parts = []
    for order in range(3):
        nus = nu_nodes(order)
        solved = nus != 0.0
        parts.append((solved, drag_poles(order, nus[solved] * spins[1], spins[1], depth, p, b)))

    def at(drag):
        out = np.zeros((3, len(spins), nu_nodes(0).size))
        for order, (solved, poles) in enumerate(parts):
            out[order][:, solved] = poles.love_numbers(drag).imag[None, :]
        return out

    return at


# Indices into the rotating ocean's constants (after ocean.constants' SIZE): the cap's radius today (deg,
# the table's), the ages (days) until which the continent keeps it and from which the ocean is global, the
# first spin node's log, the spin and nu steps and counts, then the table (3, spins, nus).
FULL_UNTIL, GLOBAL_FROM, LOG_SPIN0, SPINS, NUS, TABLE = 0, 1, 2, 3, 4, 5


def constants(water, full_until_d, global_from_d, spins, imag_table):
    """The rotating ocean's constants: ``water`` (ocean.constants(...)) followed by the continent's schedule
    and the table (``table(...)`` over ``spins`` = spin_nodes(...))."""
    head = np.zeros(TABLE)
    head[FULL_UNTIL], head[GLOBAL_FROM] = full_until_d, global_from_d
    head[LOG_SPIN0], head[SPINS], head[NUS] = math.log(spins[0]), len(spins), imag_table.shape[2]
    return np.concatenate([np.asarray(water, dtype=float), head, imag_table.ravel()])


@njit(cache=True, nogil=True)
def _lagrange(u, count):
    """(the first of 4 nodes, their weights) of 4-point Lagrange interpolation at u on nodes 0..count-1."""
    i = min(max(int(math.floor(u)) - 1, 0), count - 4)
    f = u - i
    return i, ((f - 1) * (f - 2) * (f - 3) / -6.0, f * (f - 2) * (f - 3) / 2.0, f * (f - 1) * (f - 3) / -2.0,
               f * (f - 1) * (f - 2) / 6.0)


@njit(cache=True, nogil=True)
def continent_share(t, k):
    """The continent's area at the time t (days, negative in the past) over today's: 1 until FULL_UNTIL,
    falling linearly with the age to 0 at GLOBAL_FROM."""
    age = -t
    if age <= k[FULL_UNTIL]:
        return 1.0
    if age >= k[GLOBAL_FROM]:
        return 0.0
    return (k[GLOBAL_FROM] - age) / (k[GLOBAL_FROM] - k[FULL_UNTIL])


@njit(cache=True, nogil=True)
def table_imag(order, nu, spin, k):
    """Im k_2 of the table (``k``: the constants after ocean's) at nu and the spin, clamped to the table."""
    spins, nus = int(k[SPINS]), int(k[NUS])
    u = min(max((math.log(spin) - k[LOG_SPIN0]) / SPIN_STEP, 0.0), spins - 1.0)
    v = min(max((nu + order + NU_HALF) / NU_STEP, 0.0), nus - 1.0)
    i, wi = _lagrange(u, spins)
    j, wj = _lagrange(v, nus)
    base = TABLE + order * spins * nus
    total = 0.0
    for a in range(4):
        row = base + (i + a) * nus + j
        total += wi[a] * (wj[0] * k[row] + wj[1] * k[row + 1] + wj[2] * k[row + 2] + wj[3] * k[row + 3])
    return total


@cached(nogil=True)
def love_number_imag(m, sigma, spin, t, depth, drag, p):
    """Im k_2 of the ocean for the Earth's term e^{i(m phi + sigma t)} (response.dissipation's convention:
    the forcing Y_2^{-m} at w = sigma): the basin's table while the continent has today's size, the global
    rotating ocean (ocean.love_number) once it is gone, and between the two their responses weighted by the
    continent's area (a stated simplification: the shrinking continent is not tabulated)."""
    k = p[OCEAN_SIZE:]
    share = continent_share(t, k)
    total = 0.0
    if share < 1.0:
        total += (1.0 - share) * global_love_number(-m, sigma, spin, depth, drag, p)[1]
    if share > 0.0:
        if m <= 0:
            total += share * table_imag(-m, sigma / spin, spin, k)
        else:                                   # conjugate: k(-m', -w) = conj k(m', w)
            total -= share * table_imag(m, -sigma / spin, spin, k)
    return total
