"""How a System's bodies move: where each one is, and how forces on them become state derivatives.

* :class:`Centred` -- one body at the origin, the others read from an orbit source relative to it (every
  ephemeris-driven spin model: the Moon on DE421, the Earth, Euler's problems).  Nothing translational is
  integrated; forces on centres are not needed.
* :class:`Pair` -- two bodies integrated as the secondary seen from the primary (r, v: the geocentric Moon),
  placed about their barycentre, which an orbit source gives (DE421's Earth-Moon barycentre) or which rests
  at the origin (the closed system).  The other bodies, if any, come from the orbit source (barycentric).
  The relative acceleration is F_s / m_s - F_p / m_p; the pair's monopole is taken exactly and every other
  mass's pull as the difference of its pulls on the two (spinorbit.models.interactions.newton).

Every motion follows :class:`Motion` (spinorbit.models.barycentric's too): interactions and rotators ask it what
they need and branch on nothing else.  Positions are km and velocities km/d in inertial axes (ICRF); t TDB days
from J2000.
"""
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numba import njit

from ..base.rotations import put
from ..orbits.interpolant import hermite_states
from .distortion import DIFFERENCE_D, taylor_back


@njit(cache=True, nogil=True)
def stack_point_masses(ext, ext_v, ext_gm, keep, x_p, v_p, gm_p, x_s, v_s, gm_s):
    """(x (n, 3), w (n, 3), mu (n,)): the point masses ``keep`` of the orbit source, then the pair."""
    n = keep.shape[0] + 2
    x, w, mu = np.empty((n, 3)), np.empty((n, 3)), np.empty(n)
    for k in range(keep.shape[0]):
        j = keep[k]
        x[k], w[k], mu[k] = ext[j], ext_v[j], ext_gm[j]
    x[n - 2], w[n - 2], mu[n - 2] = x_p, v_p, gm_p
    x[n - 1], w[n - 1], mu[n - 1] = x_s, v_s, gm_s
    return x, w, mu


def relative_rows(code, motion, a, others):
    """Generated lines stacking the bodies ``others`` seen from ``a`` as rows (k, 3); (that variable, their GMs
    as a parameter)."""
    rows = code.local(f"rows_{a}")
    code.line(f"{rows} = np.empty(({len(others)}, 3))")
    for k, b in enumerate(others):
        code.line(f"{code.bind(put)}({rows}[{k}], {code.relative(a, b)})")
    return rows, code.param(f"gm_of_{'_'.join(others)}", np.array([motion.gm(b) for b in others], dtype=float))


class Motion(Protocol):
    """What a System's motion answers (the generated code's variables are named by the motion, never assumed).

    Every motion:
      ``names``, ``gm(name)``: the bodies it places and their GM (km^3/d^2);
      ``closed``: True when nothing is read from an orbit source (a conserved energy and angular momentum);
      ``slices()``: its state slices; ``moves(body)``: whether a force on ``body`` changes the state;
      ``prologue(code)``, ``derivatives(code, dy)``: its lines at the start and end of the rhs;
      ``relative(code, a, b)``: the variable holding b seen from a; ``rows(code, a, others)``: (rows (k, 3),
      their GMs as a parameter); ``delayed(code, body, raiser, tau)``: the raiser seen from body tau ago;
      ``kinetic_energy(code)``, ``angular_momentum(code)``: expressions; ``positions(t, states, a, others,
      shift)``: the same places at the Python level.
    A motion with a pair in the state (Pair, Barycentric) also: ``primary``, ``secondary``;
      ``relative_velocity(code, a, b)``; ``add_force(code, body, force)``; ``add_relative_acceleration(code,
      acceleration)``; ``point_masses(code)``: variables (x, w, mu), barycentric, the pair's primary and
      secondary last; ``point_mass_names()``; ``accelerated_rows()``: the rows of the point masses whose
      accelerations move the state, the pair's last; ``add_point_mass_accelerations(code, accelerations)``:
      accelerations (k, 3) of those rows into the state (the relative orbit takes the pair's difference);
      ``carries_centres``: True when the state holds every centre (then ``add_centre_accelerations(code,
      accelerations)`` takes every point mass's barycentric acceleration; the relative orbit apart).
    """

    names: tuple
    closed: bool

    def gm(self, name): ...

    def relative(self, code, a, b): ...


@dataclass(frozen=True)
class Centred:
    """Body ``origin`` at the origin; ``externals`` (spinorbit.orbits.Orbits: names, gm, kernel(t, data) -> (n, 3),
    data) the others relative to it, or None."""

    origin: str
    externals: object = None

    @property
    def closed(self):
        return self.externals is None

    @property
    def names(self):
        return (self.origin,) + (tuple(self.externals.names) if self.externals is not None else ())

    def gm(self, name):
        return float(self.externals.gm[self.externals.names.index(name)])

    def slices(self):
        return []

    def moves(self, body):
        return False

    def prologue(self, code):
        if self.externals is not None:
            code.line(f"ext = {code.bind(self.externals.kernel, 'external_positions')}(t, {_data(code, self)})")

    def _row(self, name):
        return self.externals.names.index(name)

    def relative(self, code, a, b):
        if a == self.origin:
            return f"ext[{self._row(b)}]"
        if b == self.origin:
            out = code.local(f"{a}_to_{b}")
            code.line(f"{out} = -ext[{self._row(a)}]")
            return out
        out = code.local(f"{a}_to_{b}")
        code.line(f"{out} = ext[{self._row(b)}] - ext[{self._row(a)}]")
        return out

    def relative_velocity(self, code, a, b):
        raise ValueError("a Centred system reads positions only; velocities need a Pair (or a state) motion")

    def rows(self, code, a, others):
        if a == self.origin and others == tuple(self.externals.names):
            return "ext", code.param("external_gm", np.asarray(self.externals.gm, dtype=float))
        return relative_rows(code, self, a, others)

    def delayed(self, code, body, raiser, tau):
        """(position, velocity) of ``raiser`` seen from ``body`` (the origin) a time ``tau`` ago, from the source."""
        if body != self.origin:
            raise ValueError(f"a Centred system distorts only its origin body {self.origin!r}, not {body!r}")
        kernel, row = code.bind(self.externals.kernel, "external_positions"), self._row(raiser)
        then, then_v = code.local(f"{raiser}_then"), code.local(f"{raiser}_then_v")
        step = repr(DIFFERENCE_D)
        data = _data(code, self)
        code.line(f"{then_v} = ({kernel}(t - {tau} + {step}, {data})[{row}] - "
                  f"{kernel}(t - {tau} - {step}, {data})[{row}]) / (2 * {step})")
        code.line(f"{then} = {kernel}(t - {tau}, {data})[{row}]")
        return then, then_v

    def derivatives(self, code, dy):
        pass

    def kinetic_energy(self, code):
        return "0.0"

    def angular_momentum(self, code):
        return "np.zeros(3)"

    def positions(self, t, states, a, others, shift=0.0):
        """(len(t), len(others), 3): the bodies ``others`` seen from ``a`` at TDB days t (Python level; states at
        t - shift, which a Centred system does not read)."""
        if a != self.origin:
            raise ValueError(f"a Centred system gives positions from its origin {self.origin!r}, not {a!r}")
        return self.externals.positions(t)[:, [self._row(b) for b in others]]


class PairRelatives:
    """A motion with a pair (primary, secondary) in the state, ``r`` and ``v`` from primary to secondary and
    ``rel_acc`` their relative acceleration: bodies seen from each other (every body's place from
    ``_position(code, body, velocity)``) and forces on the pair's relative orbit."""

    def add_force(self, code, body, force):
        """A force on a body of the pair, as GM times acceleration (km^4/d^2): the relative orbit takes its share."""
        if body == self.secondary:
            code.line(f"rel_acc += {force} / {code.param('gm_secondary', self.gm_secondary)}")
        else:
            code.line(f"rel_acc -= {force} / {code.param('gm_primary', self.gm_primary)}")

    def add_relative_acceleration(self, code, acceleration):
        """An acceleration of the secondary relative to the primary (km/d^2), internal to the pair."""
        code.line(f"rel_acc += {acceleration}")

    def relative(self, code, a, b):
        if (a, b) == (self.primary, self.secondary):
            return "r"
        out = code.local(f"{a}_to_{b}")
        if (a, b) == (self.secondary, self.primary):
            code.line(f"{out} = -r")
        else:
            code.line(f"{out} = {self._position(code, b)} - {self._position(code, a)}")
        return out

    def relative_velocity(self, code, a, b):
        if (a, b) == (self.primary, self.secondary):
            return "v"
        out = code.local(f"{a}_to_{b}_v")
        code.line(f"{out} = {self._position(code, b, True)} - {self._position(code, a, True)}")
        return out

    def rows(self, code, a, others):
        return relative_rows(code, self, a, others)

    def accelerated_rows(self):
        """The rows of :meth:`point_masses` whose accelerations move the state: the pair's (the last two)."""
        n = len(self.point_mass_names())
        return np.array([n - 2, n - 1], dtype=np.int64)

    def add_point_mass_accelerations(self, code, accelerations):
        """Accelerations (k, 3) of :meth:`accelerated_rows` into the state: the pair's difference on its relative
        orbit."""
        k = len(self.accelerated_rows())
        self.add_relative_acceleration(code, f"{accelerations}[{k - 1}] - {accelerations}[{k - 2}]")


@dataclass(frozen=True)
class Pair(PairRelatives):
    """``secondary`` integrated relative to ``primary`` (state ``<secondary>.r``, ``.v``), the two about their
    ``barycentre`` (a name among the externals, or None: at rest at the origin); ``externals``: a HermiteOrbits
    of barycentric states (or None); ``gm``: {primary: GM, secondary: GM} (km^3/d^2)."""

    primary: str
    secondary: str
    gm_primary: float
    gm_secondary: float
    barycentre: str | None = None
    externals: object = None
    carries_centres = False          # the pair's relative orbit only (spinorbit.models.barycentric: every centre)

    @property
    def closed(self):
        return self.externals is None

    @property
    def names(self):
        return (self.primary, self.secondary) + (tuple(self.externals.names) if self.externals is not None else ())

    def gm(self, name):
        if name == self.primary:
            return self.gm_primary
        if name == self.secondary:
            return self.gm_secondary
        return float(self.externals.gm[self.externals.names.index(name)])

    def slices(self):
        return [(f"{self.secondary}.r", 3, "vector", f"km, from {self.primary}, inertial"),
                (f"{self.secondary}.v", 3, "vector", "km/d, inertial")]

    def moves(self, body):
        return body in (self.primary, self.secondary)

    def prologue(self, code):
        layout = code.system.layout
        r, v = layout[f"{self.secondary}.r"], layout[f"{self.secondary}.v"]
        code.line(f"r, v = y[{r.start}:{r.stop}], y[{v.start}:{v.stop}]")
        code.line("rel_acc = np.zeros(3)")
        if self.externals is not None:
            code.line(f"ext, ext_v = {code.bind(hermite_states)}(t, {_data(code, self)})")

    def _place(self, code, body):
        """Variables (x, w): the barycentric position and velocity of a pair member."""
        def emit():
            share = self.gm_secondary / (self.gm_primary + self.gm_secondary)
            f = code.param("pair_mass_fraction", share)
            sign, weight = ("-", f) if body == self.primary else ("+", f"(1.0 - {f})")
            x, w = code.local(f"x_{body}"), code.local(f"v_{body}")
            if self.barycentre is None:
                code.line(f"{x}, {w} = {sign}{weight} * r, {sign}{weight} * v")
            else:
                b = self.externals.names.index(self.barycentre)
                code.line(f"{x}, {w} = ext[{b}] {sign} {weight} * r, ext_v[{b}] {sign} {weight} * v")
            return x, w
        return code.once(("place", body), emit)

    def _position(self, code, body, velocity=False):
        if body in (self.primary, self.secondary):
            return self._place(code, body)[1 if velocity else 0]
        return f"{'ext_v' if velocity else 'ext'}[{self.externals.names.index(body)}]"

    def point_mass_names(self):
        """The point masses of :meth:`point_masses`, in order."""
        ext = [] if self.externals is None else [n for n, gm in zip(self.externals.names, self.externals.gm)
                                                 if gm > 0 and n != self.barycentre]
        return [*ext, self.primary, self.secondary]

    def point_masses(self, code):
        """Variables (x, w, mu): the barycentric point masses, the orbit source's first, the pair last."""
        def emit():
            x_p, v_p = self._place(code, self.primary)
            x_s, v_s = self._place(code, self.secondary)
            if self.externals is None:
                keep, ext, ext_v, ext_gm = np.zeros(0, dtype=np.int64), "np.zeros((0, 3))", "np.zeros((0, 3))", \
                    "np.zeros(0)"
            else:
                keep = np.array([j for j, (name, gm) in enumerate(zip(self.externals.names, self.externals.gm))
                                 if gm > 0 and name != self.barycentre], dtype=np.int64)
                ext, ext_v = "ext", "ext_v"
                ext_gm = code.param("external_gm", np.asarray(self.externals.gm, dtype=float))
            names = ("x_all", "w_all", "mu_all")
            code.line(f"{', '.join(names)} = {code.bind(stack_point_masses)}({ext}, {ext_v}, {ext_gm}, "
                      f"{code.param('point_masses', keep)}, {x_p}, {v_p}, {code.param('gm_primary', self.gm_primary)}, "
                      f"{x_s}, {v_s}, {code.param('gm_secondary', self.gm_secondary)})")
            return names
        return code.once("point_masses", emit)

    def delayed(self, code, body, raiser, tau):
        """(position, velocity) of ``raiser`` seen from ``body`` a time ``tau`` ago, by Taylor expansion of the
        relative orbit with the acceleration so far (the point masses') and the two-body jerk."""
        if {body, raiser} != {self.primary, self.secondary}:
            raise ValueError(f"a Pair distorts its members by each other, not {body!r} by {raiser!r}")
        then, then_v = code.local(f"{raiser}_then"), code.local(f"{raiser}_then_v")
        gm_pair = code.param("gm_pair", self.gm_primary + self.gm_secondary)
        code.line(f"{then}, {then_v} = {code.bind(taylor_back)}(r, v, rel_acc, {gm_pair}, {tau})")
        if body == self.secondary:                      # the primary seen from the secondary: -r
            code.line(f"{then}, {then_v} = -{then}, -{then_v}")
        return then, then_v

    def positions(self, t, states, a, others, shift=0.0):
        """(len(t), len(others), 3): the bodies ``others`` seen from ``a`` at TDB days t (Python level), the pair
        carried from the states (at t - shift) by its velocity."""
        states, t = np.atleast_2d(states), np.atleast_1d(t)
        r = states[:, 0:3] + shift * states[:, 3:6]
        share = self.gm_secondary / (self.gm_primary + self.gm_secondary)
        if self.externals is not None:
            ext = self.externals.positions(t)
            centre = ext[:, self.externals.names.index(self.barycentre)] if self.barycentre else 0.0
        else:
            ext, centre = None, 0.0

        def where(name):
            if name == self.primary:
                return centre - share * r
            if name == self.secondary:
                return centre + (1.0 - share) * r
            return ext[:, self.externals.names.index(name)]

        if {a, *others} <= {self.primary, self.secondary}:          # the pair alone: exactly +-r
            return np.stack([(r if b == self.secondary else -r) for b in others], axis=1)
        return np.stack([where(b) - where(a) for b in others], axis=1)

    def derivatives(self, code, dy):
        layout = code.system.layout
        code.line(f"{code.bind(put)}({dy}[{_span(layout, f'{self.secondary}.r')}], v)")
        code.line(f"{code.bind(put)}({dy}[{_span(layout, f'{self.secondary}.v')}], rel_acc)")

    def reduced_mass(self):
        return self.gm_primary * self.gm_secondary / (self.gm_primary + self.gm_secondary)

    def kinetic_energy(self, code):
        return f"0.5 * {code.param('reduced_mass', self.reduced_mass())} * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])"

    def angular_momentum(self, code):
        from ..base.rotations import cross3

        return f"{code.param('reduced_mass', self.reduced_mass())} * {code.bind(cross3)}(r, v)"


def _data(code, motion):
    return code.param("external_data", motion.externals.data)


def _span(layout, name):
    index = layout[name]
    return f"{index.start}:{index.stop}"
