"""The interactions' kernels (spinorbit.models.interactions): each against a closed form or an independent
computation, and action equals reaction for every interaction module.

point_mass: Euler's P, Q, R (§815) and a point cloud (§816, §818); harmonics: degree 2 equals the
point-mass torque, degree 3 against a finite-difference potential; figure_figure (the Earth's or
the Sun's J2): Folkner et al.'s torque against the Hessian of the J2 potential and against three
point masses with the same quadrupole, its force and the attractor's torque against the complex-step
derivatives of the interaction energy; and, for every interaction that acts between bodies, rot N +
sum r x F (+ the attractor's own torque) = 0 and the force as minus the energy's gradient.  (The EIH
correction conserves the 1PN momentum, not the Newtonian one: tests/models/interactions/test_relativity.py; the geodesic
precession turns a frame and acts on no body.)"""
import math
from dataclasses import dataclass

import numpy as np
import pytest

from spinorbit.base.constants import JULIAN_CENTURY_D
from spinorbit.base.errors import InputError, PhysicsError
from spinorbit.base.rotations import matrix_from_quat, quat_angle
from spinorbit.bodies import RigidBody, earth, sun
from spinorbit.bodies.moon import de421
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.integrators import simulate
from spinorbit.models import System
from spinorbit.models.assemblies.earth import figure, rigid_earth
from spinorbit.models.figure import Body
from spinorbit.models.interactions import PointMass, figure_figure, harmonics, newton, point_mass, tides
from spinorbit.models.interactions.base import Interaction
from spinorbit.models.motion import Centred
from spinorbit.models.rotators import Gyroscopic, Rigid, oppolzer_attractors
from spinorbit.models.start import on_pole
from spinorbit.orbits.analytic import CircularOrbits
from tests.units import arcsec

GM = 2.9755e15          # km^3/d^2, about the Earth's
C = de421()


def point_mass_torque(moments, r_body, gm):
    """The point-mass interaction's torque for one mass at r (body axes = ICRF here)."""
    return point_mass.torque(np.eye(3), np.diag(moments), np.atleast_2d(r_body), np.array([gm]))


def figure_force(moments, mass, r_body, gm):
    """Force on the figure's centre (towards the mass) to order 1/s^4, §818: monopole + minus the term's force."""
    r = np.asarray(r_body, dtype=float)
    s = np.linalg.norm(r)
    f_on_mass = point_mass.force(np.eye(3), np.diag(moments), r[None], np.array([gm]))[0]
    return gm * mass * r / s**3 - f_on_mass


def test_components_are_eulers_p_q_r():
    """§815: P = 3 GM (C - B) cos eta cos theta / s^3, Q = 3 GM (A - C) cos zeta cos theta / s^3, R = ..."""
    a, b, c = 0.3930197, 0.3931092, 0.3932677
    zeta, eta = math.radians(50), math.radians(70)
    cos_theta = math.sqrt(1 - math.cos(zeta) ** 2 - math.cos(eta) ** 2)
    cz, ce, ct, s = math.cos(zeta), math.cos(eta), cos_theta, 384400.0
    euler = 3 * GM / s**3 * np.array([(c - b) * ce * ct, (a - c) * cz * ct, (b - a) * cz * ce])
    got = point_mass_torque(np.array([a, b, c]), s * np.array([cz, ce, ct]), GM)
    np.testing.assert_allclose(got, euler, rtol=1e-14)


def test_two_masses_add():
    moments = np.array([1.0, 1.2, 1.5])
    r = np.array([[1e5, 2e5, 3e5], [-4e5, 1e5, 2e5]])
    gm = np.array([GM, 0.3 * GM])
    total = point_mass_torque(moments, r[0], gm[0]) + point_mass_torque(moments, r[1], gm[1])
    both = point_mass.torque(np.eye(3), np.diag(moments), r, gm)
    np.testing.assert_allclose(both, total, rtol=1e-15)


def _cloud(symmetric):
    """A uniform ellipsoid (3, 2, 1) of unit mass as random points; ``symmetric``: closed under r -> -r
    (no odd moments), otherwise a cut ellipsoid (centre of mass moved to the origin)."""
    rng = np.random.default_rng(3)
    p = rng.uniform(-1, 1, size=(60000, 3))
    p = p[np.sum(p * p, axis=1) <= 1] * [3.0, 2.0, 1.0]
    p = np.concatenate([p, -p]) if symmetric else p[p[:, 0] + 0.5 * p[:, 1] > -0.5]
    p = p - p.mean(axis=0)
    m = np.full(len(p), 1.0 / len(p))
    tensor = np.sum(m * np.sum(p * p, axis=1)) * np.eye(3) - np.einsum("i,ij,ik->jk", m, p, p)
    body = RigidBody.from_tensor(tensor)
    return body.moments, p @ body.axes, m                            # points in principal axes


def _brute(points, m, s_vec, gm):
    """Exact force on the cloud and its torque about the centre from a point mass at s_vec."""
    d = s_vec - points
    w = gm * m / np.linalg.norm(d, axis=1) ** 3
    return (w[:, None] * d).sum(axis=0), np.cross(points, w[:, None] * d).sum(axis=0)


U = np.array([0.6, 0.48, 0.64])


def _assert_shrinks(symmetric, order, relative_error):
    """relative_error(moments, points, masses, s) at s = 40, 80, 160 body sizes: below 0.1, falling 2^order-fold."""
    moments, points, m = _cloud(symmetric)
    errors = np.array([relative_error(moments, points, m, s) for s in (40.0, 80.0, 160.0)])
    assert errors[0] < 0.1
    np.testing.assert_allclose(errors[:-1] / errors[1:], 2.0**order, rtol=0.05)


@pytest.mark.parametrize("symmetric, order", [(False, 1), (True, 2)])
def test_torque_remainder_shrinks_as_816_says(symmetric, order):
    """The neglected part is O(size/s) of the 1/s^3 torque, O((size/s)^2) without odd moments (§816)."""
    def error(moments, points, m, s):
        model = point_mass_torque(moments, s * U, 1.0)
        return np.linalg.norm(_brute(points, m, s * U, 1.0)[1] - model) / np.linalg.norm(model)

    _assert_shrinks(symmetric, order, error)


@pytest.mark.parametrize("symmetric, order", [(False, 1), (True, 2)])
def test_figure_force_818_against_cloud(symmetric, order):
    """§818: the force to order 1/s^4; its error relative to the 1/s^4 part shrinks like (size/s)^order."""
    def error(moments, points, m, s):
        model = figure_force(moments, 1.0, s * U, 1.0)
        return np.linalg.norm(_brute(points, m, s * U, 1.0)[0] - model) / np.linalg.norm(model - U / s**2)

    _assert_shrinks(symmetric, order, error)

# --- harmonics --------------------------------------------------------------------------

def test_degree2_harmonics_equal_point_mass_torque():
    """The V/W recursion at degree 2 (C20 = -J2, C22) equals 3 GM/r^5 r x I r (§815)."""
    c_nm, s_nm = np.zeros((5, 5)), np.zeros((5, 5))
    c_nm[2, 0], c_nm[2, 2] = -C.j2, C.c22
    rng = np.random.default_rng(1)
    for r in rng.normal(size=(5, 3)) * 3.8e5:
        expected = point_mass_torque(C.moments, r, 1.0)
        got = harmonics.torque(np.eye(3), r[None], np.array([1.0]), 1.0, C.radius_km, c_nm, s_nm, 2, 2)
        assert np.abs(got - expected).max() < 1e-12 * np.abs(expected).max()


def test_degree3_gradient_against_finite_difference_potential():
    """grad W from the recursion equals the numerical gradient of the explicit degree-3 zonal."""
    c_nm, s_nm = np.zeros((5, 5)), np.zeros((5, 5))
    c_nm[3, 0] = -1e-5                 # C30 = -J3, J3 = 1e-5

    def potential(r):           # W = -J3 (R/r)^3 P3(z/r) / r
        x = r[2] / np.linalg.norm(r)
        return -1e-5 * (C.radius_km / np.linalg.norm(r)) ** 3 * 0.5 * (5 * x**3 - 3 * x) / np.linalg.norm(r)

    r = np.array([2.1e5, -1.4e5, 2.6e5])
    h = 1.0
    numeric = np.array([(potential(r + h * e) - potential(r - h * e)) / (2 * h) for e in np.eye(3)])
    got = harmonics.gradient(r, C.radius_km, c_nm, s_nm, 3, 3)
    assert np.abs(got - numeric).max() < 1e-7 * np.abs(numeric).max()


# --- figure-figure (an oblate attractor's J2) --------------------------------------------

INERTIA = np.diag(C.moments) + 1e-5 * np.array([[0, 1, 2], [1, 0, 3], [2, 3, 0]])
POLE = np.array([0.1, -0.2, 0.97]) / np.linalg.norm([0.1, -0.2, 0.97])


def test_figure_figure_torque_against_numerical_hessian():
    """Folkner et al. (2014) N_figM-figE equals eps_ijk (I H)_jk with H the finite-difference
    Hessian of the Earth's J2 potential GM J2 R^2 P2(p.x/r)/r^3 at the Moon."""
    r = np.array([3.1e5, -2.2e5, 0.4e5])            # the Earth from the Moon, body axes

    def potential(x):                               # x: the Moon from the Earth
        d = np.linalg.norm(x)
        u = POLE @ x / d
        return (1.5 * u * u - 0.5) / d**3

    step = 50.0
    hess = np.empty((3, 3))
    for i, ei in enumerate(np.eye(3) * step):
        for j, ej in enumerate(np.eye(3) * step):
            hess[i, j] = (potential(-r + ei + ej) - potential(-r + ei - ej) - potential(-r - ei + ej)
                          + potential(-r - ei - ej)) / (4 * step * step)
    ih = INERTIA @ hess
    expected = np.array([ih[1, 2] - ih[2, 1], ih[2, 0] - ih[0, 2], ih[0, 1] - ih[1, 0]])
    got = figure_figure.figure_torque(INERTIA, r, POLE, 1.0)
    assert np.abs(got - expected).max() < 1e-6 * np.abs(expected).max()


def test_figure_figure_torque_equals_three_point_masses_with_the_same_quadrupole():
    """An oblate attractor's J2 field is, to degree 2, that of three point masses on its pole: -q at
    +-d and +2q at the centre with 2 q d^2 = M J2 R^2 (zero mass and dipole, the same quadrupole);
    their point-mass torques on the figure equal the figure-figure torque up to the three masses'
    degree-4 field, a remainder ~ (d/r)^2: it falls 4x each time d halves, to 1e-5 at d/r = 1/800."""
    gm, j2, radius, r = 1.0, 0.1, 1.0, np.array([6.0, -3.0, 4.0])      # |r| ~ 8 R
    closed_form = figure_figure.figure_torque(INERTIA, r, POLE, gm * j2 * radius**2)
    errors = []
    for d in (0.04, 0.02, 0.01):
        q = gm * j2 * radius**2 / (2 * d * d)
        masses = np.array([-q, -q, 2 * q])
        positions = r + np.array([d * POLE, -d * POLE, 0 * POLE])
        point_masses = point_mass.torque(np.eye(3), INERTIA, positions, masses)
        errors.append(np.abs(point_masses - closed_form).max() / np.abs(closed_form).max())
    np.testing.assert_allclose(np.array(errors[:-1]) / errors[1:], 4.0, rtol=0.01)
    assert errors[-1] < 2e-5


def complex_step_gradient(f, x, step=1e-20):
    """grad f at real x (3,) by the complex step, exact to rounding: Im f(x + i h e_m) / h, h = step |x|."""
    h = step * np.linalg.norm(x)
    return np.array([f(x + 1j * h * e).imag / h for e in np.eye(3)])


def test_figure_figure_energy_gradients_equal_the_complex_step():
    """The closed-form grad_r E and grad_p E equal the complex-step derivatives of the interaction energy
    at random geometries (inertia off-diagonal, pole off the axes, distances from 2 to 1e6 units)."""
    rng = np.random.default_rng(2014)
    for _ in range(20):
        inertia = np.diag(C.moments) + 1e-4 * rng.standard_normal((3, 3))
        inertia = (inertia + inertia.T) / 2
        r = rng.standard_normal(3) * 10.0 ** rng.uniform(0.3, 6.0)
        pole = rng.standard_normal(3)
        pole /= np.linalg.norm(pole)
        k = 10.0 ** rng.uniform(-3.0, 20.0)
        grad_r, grad_p = figure_figure.energy_gradients(inertia, r, pole, k)
        expected_r = complex_step_gradient(lambda x: figure_figure.energy(inertia, x, pole + 0j, k), r)
        expected_p = complex_step_gradient(lambda x: figure_figure.energy(inertia, r + 0j, x, k), pole)
        assert np.abs(grad_r - expected_r).max() < 1e-13 * np.linalg.norm(expected_r)
        assert np.abs(grad_p - expected_p).max() < 1e-13 * np.linalg.norm(expected_p)


def test_figure_figure_force_is_minus_the_energy_gradient():
    """The interaction's force on the attractor equals a central finite difference of the interaction
    energy."""
    r = np.array([3.1e5, -2.2e5, 0.4e5])
    force = figure_figure.with_pole(np.eye(3), INERTIA, r, POLE, 2.0e20)[1]
    h = 10.0
    numeric = np.array([-(figure_figure.energy(INERTIA, r + h * e, POLE, 2.0e20)
                          - figure_figure.energy(INERTIA, r - h * e, POLE, 2.0e20)) / (2 * h) for e in np.eye(3)])
    assert np.abs(force - numeric).max() < 1e-6 * np.abs(force).max()


def test_figure_figure_torque_is_minus_the_energy_derivative_in_rotation():
    """Turning the figure by a small angle about axis k changes the energy by -N_k angle."""
    r = np.array([3.1e5, -2.2e5, 0.4e5])
    k = 2.0e20
    torque = figure_figure.figure_torque(INERTIA, r, POLE, k)
    h = 1e-6
    for axis in range(3):
        w = np.zeros(3)
        w[axis] = h
        turn = lambda a: np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
        energies = []
        for sign in (1, -1):
            rot = np.eye(3) + turn(sign * w) + turn(sign * w) @ turn(sign * w) / 2
            energies.append(figure_figure.energy(rot @ INERTIA @ rot.T, r, POLE, k))
        assert abs(-(energies[0] - energies[1]) / (2 * h) - torque[axis]) < 1e-6 * np.abs(torque).max()


# --- action equals reaction, every interaction module -------------------------------------------

ROT = matrix_from_quat(np.array([0.9, 0.2, -0.3, 0.25]) / np.linalg.norm([0.9, 0.2, -0.3, 0.25]))
ROWS = np.array([[3.1e5, -2.2e5, 0.4e5], [1.2e8, 0.7e8, 0.3e8]])       # the masses from the figure, inertial
GMS = np.array([GM, 1.3e20])
SCALE = C.gm_km3_d2 * C.radius_km**2          # the field's G-scaled inertia unit, G M R^2


def balance(*parts):
    """(|sum of the angular momentum changes|, the largest of them): the first must vanish to rounding."""
    scale = max(np.abs(part).max() for part in parts)
    assert scale > 0
    return np.abs(sum(parts)).max(), scale


def test_point_mass_action_equals_reaction():
    """rot N + sum_i r_i x F_i = 0 (§818), and the reaction kernel gives the figure minus the pulls and minus
    their moments."""
    inertia = np.diag(C.moments) * SCALE
    torque, pulls = point_mass.torque(ROT, inertia, ROWS, GMS), point_mass.force(ROT, inertia, ROWS, GMS)
    residual, scale = balance(ROT @ torque, np.cross(ROWS, pulls).sum(axis=0))
    assert residual < 1e-13 * scale
    on_figure, turning = point_mass.reaction(ROT, ROWS, pulls)
    assert np.array_equal(on_figure, -pulls.sum(axis=0))
    assert np.abs(turning - torque).max() < 1e-13 * np.abs(torque).max()


def test_harmonics_action_equals_reaction():
    """The Moon's degree 3-4 field (DE421): rot N + sum_i r_i x F_i = 0."""
    args = (SCALE, C.radius_km, np.ascontiguousarray(C.c_nm), np.ascontiguousarray(C.s_nm), 3, 4)
    torque, pulls = harmonics.torque(ROT, ROWS, GMS, *args), harmonics.force(ROT, ROWS, GMS, *args)
    residual, scale = balance(ROT @ torque, np.cross(ROWS, pulls).sum(axis=0))
    assert residual < 1e-13 * scale


def test_figure_figure_action_equals_reaction():
    """An oblate attractor's J2 on the figure: rot N + r x F + N_attractor = 0, the attractor's own torque
    included (its figure turns in a System where it has a rotator)."""
    torque, pull, reaction = figure_figure.with_pole(ROT, np.diag(C.moments) * SCALE, ROWS[0], POLE, 2.0e20)
    residual, scale = balance(ROT @ torque, np.cross(ROWS[0], pull), reaction)
    assert residual < 1e-13 * scale


@pytest.mark.parametrize("gm_sun", [0.0, 1.3e20])
def test_tides_action_equals_reaction(gm_sun):
    """The Earth's tides: the orbit gains mu r x a, the Earth's spin the reaction torque; they sum to zero."""
    p = np.array([GM, 3.6e13, gm_sun, 6378.1363, 0.335, 0.32, 0.3, 0.0, 0.005, 0.006])
    r, v = np.array([3.1e5, -2.2e5, 0.4e5]), np.array([3e4, 6e4, -5e3])
    r_sun, v_sun = np.array([1.2e8, 0.7e8, 0.3e8]), np.array([-1.2e6, 2.1e6, 0.0])
    spin = 6.3 * np.array([0.1, -0.35, 0.93]) / np.linalg.norm([0.1, -0.35, 0.93])
    a = tides.acceleration(r, v, r_sun, v_sun, spin, p)
    mu = p[0] * p[1] / (p[0] + p[1])
    residual, scale = balance(mu * np.cross(r, a), tides.reaction(r, a, p))
    assert residual < 1e-13 * scale


def test_newton_pair_monopole_is_central():
    """The pair's own monopole is central (r x r'' = 0 to rounding): it moves no angular momentum; the other
    masses' pulls are external (their sources are prescribed), with no reaction in the System."""
    r = ROWS[0]
    x, mu = np.array([-0.0121 * r, 0.9879 * r]), np.array([GM, 3.6e13])
    acc = newton.pair_acceleration(x, mu, r)
    assert np.abs(np.cross(r, acc)).max() < 1e-15 * np.linalg.norm(r) * np.linalg.norm(acc)
    np.testing.assert_allclose(acc, -(GM + 3.6e13) * r / np.linalg.norm(r) ** 3, rtol=1e-15)


def test_sun_j2_term_is_the_suns_published_oblateness():
    """The Moon's sun_j2 term carries GM_sun J2 R^2 with the DE421 header's J2SUN and ASUN and the IAU
    pole."""
    from spinorbit.models.assemblies.moon import term
    from spinorbit.orbits.analytic import CircularOrbits

    orbits = CircularOrbits(("earth", "sun"), gm=[GM, 1.3e20], radius=[1.0, 1.0], rate=[0.0, 0.0])
    interaction = term("sun_j2", orbits, None)
    assert (interaction.figure, interaction.attractor) == ("moon", "sun")
    assert interaction.pole.gm_j2_r2 == pytest.approx(1.3e20 * 2.0e-7 * 696000.0**2, rel=1e-15)
    poles = interaction.pole.samples
    ra, dec = math.atan2(poles[0, 1], poles[0, 0]) % (2 * math.pi), math.asin(poles[0, 2])
    assert math.degrees(ra) == pytest.approx(286.13, abs=1e-12)
    assert math.degrees(dec) == pytest.approx(63.87, abs=1e-12)
    assert sun.J2 == 2.0e-7


def test_unknown_term_is_named():
    from spinorbit.models.assemblies.moon import term
    from spinorbit.orbits.analytic import CircularOrbits

    orbits = CircularOrbits(("earth", "sun"), gm=[GM, 1.3e20], radius=[1.0, 1.0], rate=[0.0, 0.0])
    with pytest.raises(InputError, match="^terms: got 'moon_j7'"):
        term("moon_j7", orbits, None)


# What the models ask of each other is said, not assumed: the frame rate a splitting integrator turns the
# attitude by is the System's generated one, and a new figure torque tells a gyroscopic body's figure axis which
# point masses it comes from (spinorbit.models.interactions.base.Interaction.tidal_attractors).


EPS0 = 84381.406 * arcsec
ECLIPTIC_POLE = np.array([0.0, -math.sin(EPS0), math.cos(EPS0)])
RADIUS_KM = {"moon": 384400.0, "sun": 149597870.7, "venus": 1.0e8}
PERIOD_D = {"moon": 27.321661, "sun": 365.256363, "venus": 583.92}


def circles(bodies=("moon", "sun")):
    """The bodies on uniform circles about the Earth in the ecliptic tilted EPS0 (Euler's hypothesis, §844)."""
    return CircularOrbits(bodies, [gm_km3_d2(b) for b in bodies], [RADIUS_KM[b] for b in bodies],
                          [2 * math.pi / PERIOD_D[b] for b in bodies], [0.3, 1.0, 2.0][:len(bodies)],
                          [EPS0] * len(bodies))


def started(system):
    system.y0 = system.layout.pack(on_pole(system, "earth", 0.0, [0.0, 0.0, 1.0], earth.ERA_RATE_RAD_D,
                                           np.array([1.0, 0, 0])))
    return system


@pytest.mark.slow             # 60 s with its compilation on a loaded machine
def test_splitting_keeps_the_geodesic_precession_with_its_annual_term():
    """A full Earth with the geodesic nutation on, 30 d: suzuki4 turning the attitude by the System's generated
    frame rate agrees with a converged rk8 run far inside the geodesic precession over the span, 1.92"/cy x 30 d
    = 7.6e-9 rad (what a splitting that dropped it would miss); bound 1e-10 rad (rk8 at 0.05 d and suzuki4 at
    0.125 d carry ~1e-12 rad each, tests/edge/test_bench.py)."""
    system = started(rigid_earth(circles(), "full", j2_rate=False, ecliptic_pole=ECLIPTIC_POLE,
                                 geodesic_nutation=True))
    t = np.linspace(0.0, 30.0, 31)
    converged, _ = simulate(system, t, "rk8", {"step": 0.05}, estimate_error=False)
    split, _ = simulate(system, t, "suzuki4", {"step": 0.125}, estimate_error=False)
    geodesic_over_span = earth.GEODESIC_PRECESSION_ARCSEC_CY * arcsec * 30.0 / JULIAN_CENTURY_D
    assert geodesic_over_span == pytest.approx(7.6e-9, rel=0.02)
    assert quat_angle(split.quaternion, converged.quaternion).max() < 1e-10


@dataclass(frozen=True)
class VenusOnTheEarthsFigure(Interaction):
    """A new interaction, written in this one module: Venus as a point mass on the Earth's degree-2 figure
    (Euler's P91 torque, §815), with no reaction (Venus is read from the orbit source)."""

    def bodies(self):
        return ("earth", "venus")

    def tidal_attractors(self, name):
        return ("venus",) if name == "earth" else ()

    def emit(self, code):
        rows, gm = code.rows("earth", ("venus",))
        code.add_torque("earth", f"{code.bind(point_mass.torque, 'venus_torque')}({code.rot('earth')}, "
                                 f"{code.inertia('earth')}, {rows}, {gm})")


def earth_with_venus(rotator):
    gm = gm_km3_d2("earth")
    orbits = circles(("moon", "sun", "venus"))
    body = Body("earth", gm, figure(gm, b_minus_a_over_c=0.0 if isinstance(rotator, Gyroscopic) else 1e-5,
                                    j2_rate=False), rotator)
    return started(System("earth", [body], Centred("earth", orbits),
                          [PointMass("earth", ("moon", "sun")), VenusOnTheEarthsFigure()])), orbits


def test_a_new_interaction_acts_from_its_own_module():
    """The Earth's angular acceleration from the rhs is Euler's equations with the P91 torque of the Moon, the
    Sun and the new Venus term, 3 GM/r^5 r x (I r) in body axes (§815), evaluated here by hand; Venus's share is
    what it should be (its torque ~ GM/r^3: 1e-5 of the Sun's at 1e8 km)."""
    system, orbits = earth_with_venus(Rigid())
    y = system.y0
    q, omega = y[system.layout["earth.q"]], y[system.layout["earth.omega"]]
    moments = system.bodies["earth"].figure.moments
    rows = matrix_from_quat(q).T @ orbits.positions([0.0])[0].T                 # body axes, (3, n)
    torque = sum(3 * gm / np.linalg.norm(r) ** 5 * np.cross(r, moments * r) for r, gm in zip(rows.T, orbits.gm))
    venus = 3 * orbits.gm[2] / np.linalg.norm(rows[:, 2]) ** 5 * np.cross(rows[:, 2], moments * rows[:, 2])
    expected = (torque - np.cross(omega, moments * omega)) / moments
    got = system.rhs(0.0, y, system.params)[system.layout["earth.omega"]]
    assert np.abs(got - expected).max() < 1e-12 * np.abs(expected).max()
    assert 1e-7 < np.linalg.norm(venus) / np.linalg.norm(torque) < 1e-4


@dataclass(frozen=True)
class VenusWithoutItsTidalTensor(VenusOnTheEarthsFigure):
    def tidal_attractors(self, name):
        return ()


def test_a_gyroscopic_figure_axis_takes_the_new_interactions_point_mass():
    """The gyroscopic Earth's figure axis comes from every point mass whose tidal tensor acts on its figure,
    Venus's too, as the new interaction says: its spin's rate is that of the Earth with Venus among the
    assembly's own point masses (PointMass, P91) to rounding, and differs from it when Venus is left out of the
    Oppolzer terms (the axial component of the spin's rate, which the figure axis's offset sets, by 8e-5)."""
    system, orbits = earth_with_venus(Gyroscopic())
    assert oppolzer_attractors(system, "earth") == ("moon", "sun", "venus")
    same = System("earth", list(system.bodies.values()), Centred("earth", orbits),
                  [PointMass("earth", ("moon", "sun", "venus"))])
    blind = System("earth", list(system.bodies.values()), Centred("earth", orbits),
                   [PointMass("earth", ("moon", "sun")), VenusWithoutItsTidalTensor()])
    rate, reference, without = (s.rhs(0.0, system.y0, s.params) for s in (system, same, blind))
    assert np.all(np.abs(rate - reference) <= 1e-12 * np.abs(reference))
    assert np.abs(without - reference).max() / np.abs(reference[2]) > 1e-6      # the axial rate: 8e-5 of it


@dataclass(frozen=True)
class SilentTorque(Interaction):
    """A torque on the Earth that does not say where its Oppolzer terms come from."""

    def bodies(self):
        return ("earth",)

    def emit(self, code):
        code.add_torque("earth", "np.zeros(3)")


def test_a_torque_that_does_not_say_what_the_figure_axis_needs_is_refused():
    """No silent loss of Oppolzer terms: on a gyroscopic body an interaction must answer tidal_attractors."""
    gm = gm_km3_d2("earth")
    body = Body("earth", gm, figure(gm, j2_rate=False), Gyroscopic())
    with pytest.raises(PhysicsError, match="SilentTorque acts on 'earth'"):
        System("earth", [body], Centred("earth", circles()), [PointMass("earth", ("moon", "sun")), SilentTorque()])
