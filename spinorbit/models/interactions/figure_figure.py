"""An oblate attractor's J2 on the degree-2 figure (figure-figure), e.g. the Earth's J2 on the Moon.

Folkner et al. 2014 (IPN PR 42-196), the figure-figure torque N_figM-figE on the Moon's
inertia I from the Earth's J2, with u = r/r (the attractor seen from the figure), p its unit
pole and s = u.p (all in the figure's body axes):

    N = 15 GM J2 R^2 / (2 r^5) [ (1 - 7 s^2) u x I u + 2 s (u x I p + p x I u) - 2/5 p x I p ]

It derives from the interaction energy of the figure in the attractor's J2 potential,
E = -1/2 I : grad grad U_J2 (U_J2 = GM J2 R^2 (3 (p.x)^2/x^2 - 1) / (2 x^3), harmonic, so
the trace of I drops out).  The force on the attractor and the torque on its own figure follow
from E by differentiation (closed forms in :func:`energy_gradients`): F = -grad_r E,
N_attractor = -p x grad_p E; action equals reaction (rot N + r x F + N_attractor = 0).
"""
import math
from dataclasses import dataclass

import numpy as np

from ...base.linker import cached
from ...base.rotations import cross3, dot3, mat_t_vec3, matvec3
from .base import Interaction, needs_forces
from .point_mass import anisotropic


@cached(nogil=True)
def pole_at(t, grid, samples):
    """Unit vector at TDB day t, linear in the table (grid [t0, h], (m, 3) samples), clamped to its ends."""
    s = min(max((t - grid[0]) / grid[1], 0.0), samples.shape[0] - 1.000001)
    k = int(s)
    v = samples[k] + (s - k) * (samples[k + 1] - samples[k])
    return v / math.sqrt(dot3(v, v))


@cached(nogil=True)
def figure_torque(inertia, r, pole, gm_j2_r2):
    """Folkner et al. 2014 N_figM-figE (body axes): r the attractor from the figure (km), pole its unit pole."""
    inertia = anisotropic(inertia)
    r2 = dot3(r, r)
    rn = math.sqrt(r2)
    u = r / rn
    s = dot3(u, pole)
    iu, ip = matvec3(inertia, u), matvec3(inertia, pole)
    return 7.5 * gm_j2_r2 / (r2 * r2 * rn) * ((1.0 - 7.0 * s * s) * cross3(u, iu)
                                              + 2.0 * s * (cross3(u, ip) + cross3(pole, iu))
                                              - 0.4 * cross3(pole, ip))


@cached(nogil=True)
def energy(inertia, x, pole, gm_j2_r2):
    """E = -1/2 I : grad grad U_J2 at x (km), [inertia unit]/d^2; real or complex (the tests differentiate it)."""
    inertia = anisotropic(inertia)              # grad grad U_J2 is trace-free: the isotropic part adds 0
    r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2]
    r = np.sqrt(r2)
    s = pole[0] * x[0] + pole[1] * x[1] + pole[2] * x[2]
    inv5 = 1.0 / (r2 * r2 * r)
    inv7, inv9 = inv5 / r2, inv5 / (r2 * r2)
    total = 0.0 * r2
    for i in range(3):
        for j in range(3):
            d = 1.0 if i == j else 0.0
            ss = (2.0 * pole[i] * pole[j] * inv5 - 10.0 * s * (pole[i] * x[j] + pole[j] * x[i]) * inv7
                  - 5.0 * s * s * d * inv7 + 35.0 * s * s * x[i] * x[j] * inv9)
            rr = 15.0 * x[i] * x[j] * inv7 - 3.0 * d * inv5
            total += inertia[i, j] * (3.0 * ss - rr)
    return -0.25 * gm_j2_r2 * total


@cached(nogil=True)
def energy_gradients(inertia, r, pole, gm_j2_r2):
    """(grad_r E, grad_p E), body axes, [inertia unit]/(km d^2) and [inertia unit]/d^2, of :func:`energy`
    at r (km), pole p treated as a free vector.  With k = gm_j2_r2 (GM J2 R^2, km^5/d^2), A = anisotropic(I)
    (I symmetric), u = r/|r|, s = u.p, a = u.A u, b = p.A u, c = p.A p, T = tr A, E = -k Q / (4 |r|^5) with
    Q = 6 c - 60 s b + (105 s^2 - 15) a + (3 - 15 s^2) T, and with m = 210 s a - 60 b - 30 T s

        dQ/du = m p - 60 s A p + (210 s^2 - 30) A u,     dQ/dp = m u - 60 s A u + 12 A p,
        grad_r E = -k / (4 |r|^6) [dQ/du - (5 Q + u.dQ/du) u],     grad_p E = -k / (4 |r|^5) dQ/dp."""
    inertia = anisotropic(inertia)
    rn = math.sqrt(dot3(r, r))
    u = r / rn
    s = dot3(u, pole)
    iu, ip = matvec3(inertia, u), matvec3(inertia, pole)
    a, b, c = dot3(u, iu), dot3(pole, iu), dot3(pole, ip)
    trace = inertia[0, 0] + inertia[1, 1] + inertia[2, 2]
    q = 6.0 * c - 60.0 * s * b + (105.0 * s * s - 15.0) * a + (3.0 - 15.0 * s * s) * trace
    m = 210.0 * s * a - 60.0 * b - 30.0 * trace * s
    radial = 5.0 * q + m * s - 60.0 * s * b + (210.0 * s * s - 30.0) * a      # 5 Q + u.dQ/du
    scale = -0.25 * gm_j2_r2 / (rn * rn * rn * rn * rn)
    grad_r, grad_p = np.empty(3), np.empty(3)
    for k in range(3):          # written out by component: no temporary arrays
        grad_r[k] = scale / rn * (m * pole[k] - 60.0 * s * ip[k] + (210.0 * s * s - 30.0) * iu[k] - radial * u[k])
        grad_p[k] = scale * (m * u[k] - 60.0 * s * iu[k] + 12.0 * ip[k])
    return grad_r, grad_p


@cached(nogil=True)
def with_pole(rot, inertia, r_icrf, pole_icrf, gm_j2_r2):
    """(torque on the figure, body axes; force on the attractor, inertial; torque on the attractor's figure,
    inertial), r_icrf (3,) km the attractor from the figure, pole_icrf its unit pole (inertial axes)."""
    r, pole = mat_t_vec3(rot, r_icrf), mat_t_vec3(rot, pole_icrf)
    grad_r, grad_p = energy_gradients(inertia, r, pole, gm_j2_r2)
    force = -matvec3(rot, grad_r)
    reaction = matvec3(rot, -cross3(pole, grad_p))
    return figure_torque(inertia, r, pole, gm_j2_r2), force, reaction


@dataclass(frozen=True)
class PoleTable:
    """An attractor's pole prescribed: unit vectors (m, 3, inertial) on the grid [t0, h] (TDB days), linear
    between samples (two equal rows: a fixed pole), and its GM J2 R^2 (km^5/d^2)."""

    grid: np.ndarray
    samples: np.ndarray
    gm_j2_r2: float


@dataclass(frozen=True)
class FigureFigure(Interaction):
    """``attractor``'s J2 on ``figure``'s degree 2.  The attractor's pole and strength are its own (its figure
    axis and C - A) when it turns in the System, else ``pole`` (a PoleTable)."""

    figure: str
    attractor: str
    pole: PoleTable | None = None
    citation = "Folkner et al. 2014 (IPN PR 42-196), N_figM-figE"

    def bodies(self):
        return (self.figure, self.attractor)

    def tidal_attractors(self, name):
        """None: a J2 on a degree-2 figure is not a point mass's tidal tensor; the figure axis leaves it out."""
        return ()

    def _pole(self, code):
        """(pole variable (inertial), strength expression)."""
        if self.pole is None:
            rot, inertia = code.rot(self.attractor), code.inertia(self.attractor)
            pole = code.once(("pole", self.attractor), lambda: _column(code, rot, self.attractor))
            return pole, f"({inertia}[2, 2] - {inertia}[0, 0])"
        name = f"{self.attractor}_pole"
        pole = code.local(name)
        code.line(f"{pole} = {code.bind(pole_at)}(t, {code.param(f'{name}_grid', self.pole.grid)}, "
                  f"{code.param(f'{name}_samples', self.pole.samples)})")
        return pole, code.param(f"{self.attractor}_gm_j2_r2", float(self.pole.gm_j2_r2))

    def emit(self, code):
        rot, inertia = code.rot(self.figure), code.inertia(self.figure)
        r = code.relative(self.figure, self.attractor)
        pole, strength = self._pole(code)
        turning = code.system.bodies[self.attractor].rotator is not None if self.attractor in code.system.bodies \
            else False
        if not (turning or needs_forces(code, self.figure, (self.attractor,))):
            code.add_torque(self.figure, f"{code.bind(figure_torque)}({inertia}, {code.bind(mat_t_vec3)}({rot}, {r}), "
                                         f"{code.bind(mat_t_vec3)}({rot}, {pole}), {strength})")
            return
        torque, pull, reaction = code.local("ff_torque"), code.local("ff_pull"), code.local("ff_reaction")
        code.line(f"{torque}, {pull}, {reaction} = {code.bind(with_pole)}({rot}, {inertia}, {r}, {pole}, {strength})")
        code.add_torque(self.figure, torque)
        code.add_force(self.attractor, pull)
        code.add_force(self.figure, f"-{pull}")
        if turning:
            code.add_torque(self.attractor, reaction, "inertial")

    def energy(self, code):
        rot, inertia = code.rot(self.figure), code.inertia(self.figure)
        r = code.relative(self.figure, self.attractor)
        pole, strength = self._pole(code)
        return (f"{code.bind(energy, 'figure_figure_energy')}({inertia}, {code.bind(mat_t_vec3)}({rot}, {r}), "
                f"{code.bind(mat_t_vec3)}({rot}, {pole}), {strength})")


def _column(code, rot, body):
    pole = code.local(f"pole_{body}")
    code.line(f"{pole} = np.array([{rot}[0, 2], {rot}[1, 2], {rot}[2, 2]])")
    return pole
