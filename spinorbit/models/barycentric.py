"""Every body's centre in the state: the solar system integrated as one, about its barycentre.

The free bodies (the Sun, the planets) carry their barycentric position and velocity (``<name>.r``, ``.v``: km,
km/d, ICRF); a pair (the Earth and the Moon) is carried as the ephemerides carry it, its barycentre's position
and velocity (``earth_moon_barycenter.r``, ``.v``) and the secondary seen from the primary (``moon.r``, ``.v``),
so that the geocentric Moon keeps the precision of its own 4e5 km, not that of the 1.5e8 km of the Earth's orbit
(Folkner et al. 2014, IPN PR 42-196, §III; Newhall, Standish & Williams 1983).

A force F (G-scaled) on a free body accelerates it by F / GM; on a pair member it accelerates the pair's
barycentre by F / (GM_p + GM_s) and the relative orbit by +-F / GM_s,p.  Point-mass accelerations computed for
every body (Newton's, the EIH correction) move the free bodies, and the pair's barycentre by the mass-weighted
mean of its members'; the relative orbit takes the pair's monopole exactly and every other mass as the
difference of its pulls (spinorbit.models.interactions.newton).  Nothing is read from an orbit source.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..base.linker import cached
from ..base.rotations import cross3, dot3, put
from .distortion import taylor_back
from .motion import PairRelatives


@njit(cache=True, nogil=True)
def place(y, n_free, share):
    """(x (n, 3), w (n, 3)): the barycentric positions and velocities of the free bodies (the first 6 n_free
    components of y, r and v each), then the pair's primary and secondary from its barycentre (the next 6) and
    the secondary seen from the primary (the next 6); ``share`` = GM_s / (GM_p + GM_s)."""
    x, w = np.empty((n_free + 2, 3)), np.empty((n_free + 2, 3))
    for i in range(n_free):
        for k in range(3):
            x[i, k], w[i, k] = y[6 * i + k], y[6 * i + 3 + k]
    b = 6 * n_free
    for k in range(3):
        x[n_free, k] = y[b + k] - share * y[b + 6 + k]
        w[n_free, k] = y[b + 3 + k] - share * y[b + 9 + k]
        x[n_free + 1, k] = y[b + k] + (1.0 - share) * y[b + 6 + k]
        w[n_free + 1, k] = y[b + 3 + k] + (1.0 - share) * y[b + 9 + k]
    return x, w


@njit(cache=True, nogil=True)
def shared(accelerations, share):
    """(n_free + 1, 3): the free bodies' accelerations, then the pair's barycentre's, the mean of its members'
    (the last two rows of ``accelerations``) weighted by their GM."""
    n = accelerations.shape[0]
    out = np.empty((n - 1, 3))
    for i in range(n - 2):
        for k in range(3):
            out[i, k] = accelerations[i, k]
    for k in range(3):
        out[n - 2, k] = (1.0 - share) * accelerations[n - 2, k] + share * accelerations[n - 1, k]
    return out


@cached(nogil=True)
def kinetic_energy(y, gm):
    """sum GM |v|^2 / 2 over the carried centres (r, v in y by sixes, GM per centre; G-scaled)."""
    total = 0.0
    for i in range(gm.shape[0]):
        v = y[6 * i + 3:6 * i + 6]
        total += 0.5 * gm[i] * dot3(v, v)
    return total


@cached(nogil=True)
def angular_momentum(y, gm):
    """sum GM r x v over the carried centres (G-scaled)."""
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        total += gm[i] * cross3(y[6 * i:6 * i + 3], y[6 * i + 3:6 * i + 6])
    return total


@dataclass(frozen=True)
class Barycentric(PairRelatives):
    """The free bodies ``free`` (names) with GMs ``gm_free`` (km^3/d^2), and the pair ``primary``, ``secondary``
    (GMs ``gm_primary``, ``gm_secondary``) about ``barycentre``: all in the state (module docstring)."""

    free: tuple
    gm_free: tuple
    primary: str
    secondary: str
    gm_primary: float
    gm_secondary: float
    barycentre: str = "earth_moon_barycenter"
    closed = True
    carries_centres = True

    @property
    def names(self):
        return (*self.free, self.primary, self.secondary)

    @property
    def share(self):
        return self.gm_secondary / (self.gm_primary + self.gm_secondary)

    def gm(self, name):
        return {**dict(zip(self.free, self.gm_free)), self.primary: self.gm_primary,
                self.secondary: self.gm_secondary}[name]

    def slices(self):
        out = []
        for name in self.free:
            out += [(f"{name}.r", 3, "vector", "km, barycentric, ICRF"), (f"{name}.v", 3, "vector", "km/d, ICRF")]
        return out + [(f"{self.barycentre}.r", 3, "vector", "km, barycentric, ICRF"),
                      (f"{self.barycentre}.v", 3, "vector", "km/d, ICRF"),
                      (f"{self.secondary}.r", 3, "vector", f"km, from {self.primary}, ICRF"),
                      (f"{self.secondary}.v", 3, "vector", "km/d, ICRF")]

    def moves(self, body):
        return body in self.names

    def prologue(self, code):
        b = 6 * len(self.free)
        code.line(f"r, v = y[{b + 6}:{b + 9}], y[{b + 9}:{b + 12}]")
        code.line("rel_acc = np.zeros(3)")
        code.line(f"bary_acc = np.zeros(({len(self.free) + 1}, 3))")
        code.line(f"x_all, w_all = {code.bind(place)}(y, {len(self.free)}, {code.param('pair_share', self.share)})")

    def _row(self, name):
        return self.names.index(name)

    def _position(self, code, body, velocity=False):
        return f"{'w_all' if velocity else 'x_all'}[{self._row(body)}]"

    def point_mass_names(self):
        return list(self.names)

    def point_masses(self, code):
        """Variables (x, w, mu): every body, barycentric, the pair last."""
        return "x_all", "w_all", code.param("gm_all", np.array([self.gm(n) for n in self.names]))

    def accelerated_rows(self):
        """The rows of :meth:`point_masses` whose accelerations move the state: all."""
        return np.arange(len(self.names), dtype=np.int64)

    def add_point_mass_accelerations(self, code, accelerations):
        """Accelerations (n, 3) of every point mass: the free bodies' and the pair's barycentre's, and the pair's
        difference on its relative orbit."""
        self.add_centre_accelerations(code, accelerations)
        super().add_point_mass_accelerations(code, accelerations)

    def add_force(self, code, body, force):
        if body in self.free:
            code.line(f"bary_acc[{self._row(body)}] += {force} / {code.param(f'gm_{body}', self.gm(body))}")
            return
        total = code.param("gm_pair", self.gm_primary + self.gm_secondary)
        code.line(f"bary_acc[{len(self.free)}] += {force} / {total}")
        super().add_force(code, body, force)

    def add_centre_accelerations(self, code, accelerations):
        """Accelerations (n, 3) of every body (rows of :meth:`point_masses`): the free bodies' and the pair's
        barycentre's; the relative orbit's share is added apart (add_relative_acceleration)."""
        code.line(f"bary_acc += {code.bind(shared)}({accelerations}, {code.param('pair_share', self.share)})")

    def delayed(self, code, body, raiser, tau):
        """(position, velocity) of ``raiser`` seen from ``body`` a time ``tau`` ago (the pair: by Taylor expansion
        of the relative orbit with the acceleration so far and the two-body jerk)."""
        if {body, raiser} != {self.primary, self.secondary}:
            raise ValueError(f"a pair distorts its members by each other, not {body!r} by {raiser!r}")
        then, then_v = code.local(f"{raiser}_then"), code.local(f"{raiser}_then_v")
        gm_pair = code.param("gm_pair", self.gm_primary + self.gm_secondary)
        code.line(f"{then}, {then_v} = {code.bind(taylor_back)}(r, v, rel_acc, {gm_pair}, {tau})")
        if body == self.secondary:
            code.line(f"{then}, {then_v} = -{then}, -{then_v}")
        return then, then_v

    def derivatives(self, code, dy):
        for k in range(len(self.free) + 2):
            source = "bary_acc" if k <= len(self.free) else None
            code.line(f"{code.bind(put)}({dy}[{6 * k}:{6 * k + 3}], y[{6 * k + 3}:{6 * k + 6}])")
            code.line(f"{code.bind(put)}({dy}[{6 * k + 3}:{6 * k + 6}], {f'{source}[{k}]' if source else 'rel_acc'})")

    def _reduced(self):
        return np.array([*self.gm_free, self.gm_primary + self.gm_secondary,
                         self.gm_primary * self.gm_secondary / (self.gm_primary + self.gm_secondary)])

    def kinetic_energy(self, code):
        return (f"{code.bind(kinetic_energy, 'barycentric_kinetic_energy')}(y, "
                f"{code.param('gm_carried', self._reduced())})")

    def angular_momentum(self, code):
        return (f"{code.bind(angular_momentum, 'barycentric_angular_momentum')}(y, "
                f"{code.param('gm_carried', self._reduced())})")

    def momentum(self, states):
        """The total momentum (n, 3), G-scaled (km^4/d^3), of states (n, size) (Python level)."""
        states = np.atleast_2d(states)
        n = len(self.free) + 2
        carried = states[:, :6 * n].reshape(len(states), n, 6)[:, :-1, 3:]
        return np.einsum("i,nik->nk", self._reduced()[:-1], carried)

    def positions(self, t, states, a, others, shift=0.0):
        """(len(t), len(others), 3): the bodies ``others`` seen from ``a`` at TDB days t (Python level), from the
        states (at t - shift) carried by their velocities."""
        states = np.atleast_2d(states)
        n = len(self.free) + 2
        carried = states[:, :6 * n].reshape(len(states), n, 6)
        carried = carried[..., :3] + shift * carried[..., 3:]
        x = np.concatenate([carried[:, :-2], carried[:, -2:-1] - self.share * carried[:, -1:],
                            carried[:, -2:-1] + (1.0 - self.share) * carried[:, -1:]], axis=1)
        if {a, *others} <= {self.primary, self.secondary}:
            r = carried[:, -1]
            return np.stack([(r if b == self.secondary else -r) for b in others], axis=1)
        return np.stack([x[:, self._row(b)] - x[:, self._row(a)] for b in others], axis=1)
