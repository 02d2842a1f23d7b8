"""The forms of a transfer function: resonance expansion, two-layer Earth, table with a form between.

Every form offers ``transfer(sigma)`` (complex, shape of sigma), ``additive(sigma)`` (terms the model adds
outside the transfer function, complex amplitudes in rad of exp(+i nu Omega t) in the plane (dpsi sin eps,
deps); zero but for a table), ``normal_modes()`` (Chandler wobble, free core nutation) and ``rigid_h``, the
dynamical ellipticity (C - A)/C of the rigid Earth whose amplitudes T multiplies (None: the rigid run's own).
Frequencies sigma in cpsd, terrestrial frame, time dependence exp(+i sigma Omega t): a free mode decays
when Im s > 0.
"""
from dataclasses import dataclass, field

import numpy as np

from ...bodies.earth import ERA_RATE_RAD_D

SIDEREAL_PER_SOLAR_DAY = ERA_RATE_RAD_D / (2.0 * np.pi)


def celestial_period_days(sigma):
    """Period (solar days) in space of a wobble of terrestrial frequency sigma (cpsd); < 0 retrograde."""
    return 1.0 / ((1.0 + sigma.real) * SIDEREAL_PER_SOLAR_DAY)


def wobble_period_days(sigma):
    """Period (solar days) in the terrestrial frame of a wobble of frequency sigma (cpsd)."""
    return 1.0 / (sigma.real * SIDEREAL_PER_SOLAR_DAY)


@dataclass(frozen=True)
class Mode:
    """A free mode: its complex terrestrial frequency s (cpsd) and its strength A in the resonance form."""

    name: str
    frequency: complex
    strength: complex


@dataclass(frozen=True)
class ResonanceExpansion:
    """T(sigma) = R + R' (1 + sigma) + sum over the free modes of A / (sigma - s) (Mathews, Buffett, Herring
    & Shapiro 1991, JGR 96, 8219)."""

    r: complex
    r_prime: complex
    modes: tuple
    rigid_h: float = None

    def transfer(self, sigma):
        """Non-rigid / rigid amplitude at terrestrial frequencies sigma (cpsd), complex, shape of sigma."""
        s = np.asarray(sigma, dtype=complex)
        return self.r + self.r_prime * (1 + s) + sum(m.strength / (s - m.frequency) for m in self.modes)

    def additive(self, sigma):
        return np.zeros(np.shape(sigma), dtype=complex)

    def normal_modes(self):
        """(Chandler wobble, free core nutation) terrestrial frequencies, cpsd: the poles of T."""
        poles = {m.name: m.frequency for m in self.modes}
        return poles["CW"], poles["FCN"]


def fit_resonance(sigma, values, weights, modes, rigid_h=None):
    """The ResonanceExpansion with free modes at ``modes`` = {name: s} whose T best reproduces ``values`` at
    ``sigma`` (cpsd) in the least-squares sense with ``weights`` (linear: R, R' and the strengths)."""
    s = np.asarray(sigma, dtype=complex)
    w = np.asarray(weights, dtype=float)[:, None]
    design = np.column_stack([np.ones_like(s), 1 + s] + [1 / (s - pole) for pole in modes.values()])
    coef = np.linalg.lstsq(design * w, np.asarray(values) * w[:, 0], rcond=None)[0]
    strengths = coef[2:]
    return ResonanceExpansion(complex(coef[0]), complex(coef[1]), tuple(
        Mode(name, pole, complex(a)) for (name, pole), a in zip(modes.items(), strengths)), rigid_h)


@dataclass(frozen=True, eq=False)
class Tabulated:
    """A transfer function known at frequencies ``sigma`` (cpsd): there the tabulated ``values`` (and the
    ``additive`` terms, rad), elsewhere the resonance form ``between``.  A frequency within ``match_cpsd``
    of a tabulated one is that one (the arguments' rates drift by < 3e-9 cpsd over 1900-2100)."""

    sigma: np.ndarray
    values: np.ndarray
    additive_rad: np.ndarray
    between: ResonanceExpansion
    rigid_h: float
    match_cpsd: float = field(default=5e-8)

    def _rows(self, sigma):
        s = np.asarray(sigma, dtype=float).real
        distance = np.abs(s[..., None] - self.sigma)
        return np.argmin(distance, axis=-1), np.min(distance, axis=-1) < self.match_cpsd

    def transfer(self, sigma):
        """The table's value at a tabulated frequency, the resonance form between."""
        row, found = self._rows(np.real(sigma))
        return np.where(found, self.values[row], self.between.transfer(sigma))

    def additive(self, sigma):
        """The table's additive term (rad) at a tabulated frequency, zero elsewhere."""
        row, found = self._rows(np.real(sigma))
        return np.where(found, self.additive_rad[row], 0.0)

    def normal_modes(self):
        return self.between.normal_modes()


@dataclass(frozen=True)
class EarthParameters:
    """The two-layer Earth (elastic mantle and fluid core) of Sasao, Okubo & Saito (1980) in the form of
    Mathews, Buffett, Herring & Shapiro (1991, JGR 96, 8219): the angular momentum of the whole Earth and of
    the fluid core in the terrestrial frame, linearised; m = mantle wobble, m_f = the core's differential
    wobble, phi = the tidal forcing (the rigid Earth's wobble is e phi / (e - sigma)):

        [sigma - e + (1 + sigma) kappa] m + (1 + sigma)(A_f/A + xi) m_f = [(1 + sigma) kappa - e] phi
        sigma (1 + gamma) m + [1 + sigma (1 + beta) + e_f + K_CMB] m_f = sigma gamma phi

    (kappa, xi, gamma, beta: the mantle's and the core's deformation compliances, c/A = kappa (m - phi) +
    xi m_f, c_f/A_f = gamma (m - phi) + beta m_f; K_CMB the core-mantle coupling constant).  Its normal
    modes (Chandler wobble and free core nutation) are the roots of the determinant.  All dimensionless."""

    e: float              # dynamical ellipticity (C - A)/A of the whole Earth
    e_f: float            # dynamical ellipticity of the fluid core
    a_f: float            # A_f / A, fluid core over whole Earth
    kappa: float          # mantle compliances (elastic)
    xi: float
    gamma: float          # core compliances (elastic)
    beta: float
    k_cmb: complex        # core-mantle boundary coupling constant
    rigid_h = None        # T relative to a rigid Earth of the same e

    def transfer(self, sigma):
        """Non-rigid / rigid amplitude at terrestrial frequencies sigma (cpsd), complex, shape of sigma."""
        m, rhs = self._matrices(sigma)
        if self.a_f == 0.0:                    # no core: the mantle equation alone
            wobble = rhs[..., 0] / m[..., 0, 0]
        else:
            wobble = np.linalg.solve(m, rhs[..., None])[..., 0, 0]
        s = np.atleast_1d(np.asarray(sigma, dtype=complex))
        return (wobble * (self.e - s) / self.e).reshape(np.shape(sigma))

    def additive(self, sigma):
        return np.zeros(np.shape(sigma), dtype=complex)

    def normal_modes(self):
        """(Chandler wobble, free core nutation) terrestrial frequencies, cpsd: the roots of det M(sigma)."""
        mantle = np.poly1d([1 + self.kappa, self.kappa - self.e])
        core = np.poly1d([1 + self.beta, 1 + self.e_f + self.k_cmb])
        det = mantle * core - np.poly1d([1.0, 1.0]) * (self.a_f + self.xi) * np.poly1d([1 + self.gamma, 0.0])
        roots = sorted(det.roots, key=lambda r: r.real)
        return complex(roots[1]), complex(roots[0])

    def _matrices(self, sigma):
        """(M, rhs) of the two-layer equations at sigma (cpsd): shapes (..., 2, 2), (..., 2)."""
        s = np.atleast_1d(np.asarray(sigma, dtype=complex))
        m = np.empty(s.shape + (2, 2), dtype=complex)
        m[..., 0, 0] = s - self.e + (1 + s) * self.kappa
        m[..., 0, 1] = (1 + s) * (self.a_f + self.xi)
        m[..., 1, 0] = s * (1 + self.gamma)
        m[..., 1, 1] = 1 + s * (1 + self.beta) + self.e_f + self.k_cmb
        rhs = np.stack([(1 + s) * self.kappa - self.e, s * self.gamma], axis=-1)
        return m, rhs
