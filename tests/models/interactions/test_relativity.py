"""relativity: the EIH point-mass accelerations against the closed forms of 1PN celestial mechanics."""
import math

import numpy as np
from numba import njit

from spinorbit.base.constants import JULIAN_YEAR_D
from spinorbit.bodies.de421_header import header
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.models.assemblies.earth_moon import c_km_d
from spinorbit.models.interactions.relativity import accelerations
from tests.units import mas


@njit     # not cached: numba's disk cache would keep a stale copy of relativity.accelerations
def nbody_rhs(t, y, p):
    """y = (positions (N, 3), velocities (N, 3)) flattened, km and km/d; p = (gm (N,), c km/d, eih 0 or 1)."""
    gm, c, eih = p
    n = gm.shape[0]
    pos = y[:3 * n].reshape((n, 3))
    vel = y[3 * n:].reshape((n, 3))
    newton, correction = accelerations(pos, vel, gm, c, np.arange(n))
    dy = np.empty_like(y)
    for i in range(3 * n):
        dy[i] = y[3 * n + i]
    for i in range(n):
        for x in range(3):
            dy[3 * n + 3 * i + x] = newton[i, x] + eih * correction[i, x]
    return dy


def test_test_particle_correction_is_the_schwarzschild_acceleration():
    """A massless body about one mass at rest: EIH reduces to the 1PN Schwarzschild acceleration in harmonic
    coordinates (PPN beta = gamma = 1; Moyer 2003 eq. 4-26 with one attracting body)
    GM/(c^2 r^3) [(4 GM/r - v^2) r + 4 (r.v) v], and Newton to -GM r/r^3."""
    mu, c = gm_km3_d2("sun"), c_km_d()
    r = np.array([4.6e7, -2.1e7, 3.0e6])
    v = np.array([2.9e6, 3.7e6, -4.0e5])
    pos = np.array([[0.0, 0.0, 0.0], r])
    vel = np.array([[0.0, 0.0, 0.0], v])
    newton, correction = accelerations(pos, vel, np.array([mu, 0.0]), c, np.array([1, 0]))
    d = np.linalg.norm(r)
    schwarzschild = mu / (c**2 * d**3) * ((4 * mu / d - v @ v) * r + 4 * (r @ v) * v)
    assert np.allclose(newton[0], -mu * r / d**3, rtol=1e-15, atol=0.0)
    assert np.max(np.abs(correction[0] - schwarzschild)) < 4e-16 * np.max(np.abs(schwarzschild))
    assert np.all(newton[1] == 0.0) and np.all(correction[1] == 0.0)     # the test particle does not pull



def test_two_bodies_in_their_centre_of_mass_frame_follow_the_1pn_relative_acceleration():
    """Two comparable masses (1 and 0.4 solar) about their centre of mass: the relative acceleration is
    -(G m/r^2) [(1 + A/c^2) n + (B/c^2) v] with A = v^2 (1 + 3 nu) - 3/2 nu rdot^2 - (G m/r)(4 + 2 nu) and
    B = -(4 - 2 nu) rdot (the 1PN terms of Blanchet, Living Rev. Relativ. 9, 4 (2006), eqs. 182-183;
    m = m1 + m2, nu = m1 m2/m^2).  With the Newtonian centre-of-mass relations the two agree
    algebraically, so to rounding; every coefficient of the EIH braces enters (v1.v2 = -nu v^2 != 0)."""
    c, au = c_km_d(), header()["AU"]
    m1, m2 = gm_km3_d2("sun"), 0.4 * gm_km3_d2("sun")
    m, nu = m1 + m2, m1 * m2 / (m1 + m2)**2
    x, v = np.array([0.3 * au, 0.1 * au, -0.02 * au]), np.array([-1.2e6, 3.1e6, 2.0e5])
    newton, correction = accelerations(np.array([m2 / m * x, -m1 / m * x]), np.array([m2 / m * v, -m1 / m * v]),
                                       np.array([m1, m2]), c, np.array([0, 1]))
    r = np.linalg.norm(x)
    n, rdot = x / r, x @ v / r
    a_coef = (v @ v) * (1 + 3 * nu) - 1.5 * nu * rdot**2 - m / r * (4 + 2 * nu)
    b_coef = -(4 - 2 * nu) * rdot
    expected = -m / r**2 * (a_coef * n + b_coef * v) / c**2
    assert np.max(np.abs(correction[0] - correction[1] - expected)) < 1e-14 * np.max(np.abs(expected))
    assert np.allclose(newton[0] - newton[1], -m * n / r**2, rtol=1e-15, atol=0.0)


def perihelion(y, mu):
    """(direction of perihelion rad, time to it d) from a state (body 0 at rest, body 1 about it) near
    perihelion: the direction of r advanced by the rate h/r^2 over -rdot/rddot (Newtonian rddot)."""
    r, v = y[3:6], y[9:12]
    r2 = r @ r
    rdot = r @ v / math.sqrt(r2)
    dt = -rdot / ((v @ v - rdot**2) / math.sqrt(r2) - mu / r2)
    return math.atan2(r[1], r[0]) + dt * np.cross(r, v)[2] / r2, dt


def test_perihelion_advance_of_a_mercury_like_orbit_is_6_pi_gm_over_c2_p():
    """A massless body on Mercury's a, e about the Sun, 4 orbits by the compiled RK8 (0.25-d steps): the
    perihelion advances by 6 pi GM / (c^2 a (1 - e^2)) per orbit (103.5 mas).  Perihelion is found where
    rdot = 0 (one refinement of the landing time, so that the 1PN change of the period, ~1e-5 d per
    orbit, does not enter).  Bound 1e-4 mas per orbit: the next order of the closed form is ~ GM/(c^2 a)
    = 2.5e-8 of it (2.6e-6 mas), and the Newtonian run, the method's floor, is held to the same bound."""
    mu, c, au = gm_km3_d2("sun"), c_km_d(), header()["AU"]
    a, e, orbits = 0.387098 * au, 0.205630, 4
    period = 2 * math.pi * math.sqrt(a**3 / mu)
    y0 = np.array([0.0, 0, 0, a * (1 - e), 0, 0, 0, 0, 0, 0, math.sqrt(mu * (1 + e) / (a * (1 - e))), 0])
    closed = 6 * math.pi * mu / (c**2 * a * (1 - e**2))
    tolerance = 1e-4 * mas
    for eih, expected in ((0.0, 0.0), (1.0, closed)):
        t = period * np.arange(1, orbits + 1)
        for _ in range(2):
            found = [perihelion(y, mu) for y in fixed_step(nbody_rhs, (np.array([mu, 0.0]), c, eih), 0.0, y0, t,
                                                           0.25)]
            t = t + np.array([dt for _, dt in found])
        advance = np.array([angle for angle, _ in found]) / np.arange(1, orbits + 1)
        assert np.all(np.abs(advance - expected) < tolerance), (eih, (advance - expected) / mas)


def orbit_precession(a_km, inclination, node, c, phases=32):
    """(rate about the ecliptic pole, rate of inclination), rad/d, of a circular satellite orbit of radius a_km
    about the Earth (GM of the Moon, inclination and node to the ecliptic z = 0, rad) from the EIH
    correction alone: the torque r x (correction_moon - correction_earth) on h = r x u, averaged over
    the satellite's and the Earth-Moon barycentre's phases (circular, 1 au about the Sun at rest)."""
    gm = np.array([gm_km3_d2("sun"), gm_km3_d2("earth"), gm_km3_d2("moon")])
    au, mu = header()["AU"], gm[1] + gm[2]
    speed, u0 = math.sqrt(gm.sum() / au), math.sqrt(mu / a_km)
    x = np.array([math.cos(node), math.sin(node), 0.0])
    y = np.array([-math.cos(inclination) * math.sin(node), math.cos(inclination) * math.cos(node),
                  math.sin(inclination)])
    torque = np.zeros(3)
    angles = 2 * math.pi * np.arange(phases) / phases
    for lam in angles:
        barycentre = au * np.array([math.cos(lam), math.sin(lam), 0.0])
        velocity = speed * np.array([-math.sin(lam), math.cos(lam), 0.0])
        for phi in angles + 0.1:
            r = a_km * (math.cos(phi) * x + math.sin(phi) * y)
            u = u0 * (-math.sin(phi) * x + math.cos(phi) * y)
            pos = np.array([[0.0, 0, 0], barycentre - gm[2] / mu * r, barycentre + gm[1] / mu * r])
            vel = np.array([[0.0, 0, 0], velocity - gm[2] / mu * u, velocity + gm[1] / mu * u])
            _, correction = accelerations(pos, vel, gm, c, np.array([1, 2]))
            torque += np.cross(r, correction[1] - correction[0])
    h_dot = torque / phases**2
    h = a_km * u0 * np.cross(x, y)
    along_node = np.cross([0.0, 0.0, 1.0], h)                 # d h / d node
    along_inclination = np.cross(h, along_node) / np.linalg.norm(along_node)
    return h_dot @ along_node / (along_node @ along_node), h_dot @ along_inclination / (h @ h)


def test_geodetic_precession_of_a_satellite_orbit_is_three_halves_gm_n_over_c2_a():
    """De Sitter: an orbit about the Earth precesses about the ecliptic pole at (3/2) GM_sun n_E / (c^2 a_E)
    (19.19 mas/yr), with no change of inclination.  The closed form is the leading term in n_E / n_sat:
    at a fixed heliocentric radius the correction also weakens the solar tide (by 3.00 GM_sun/(c^2 a_E) of
    the Newtonian regression (3/4)(n_E^2/n_sat) cos i, as measured here: +2.1 mas/yr, 11 %, at the Moon's
    distance; an ephemeris absorbs it in its fitted n_E), so the orbit is a compact one, 10 000 km
    (n_E / n_sat = 3e-4, ~0.01 mas/yr): bound 0.05 mas/yr.  The averages over 32 x 32 phases are exact to
    rounding for these circular orbits (the inclination rate comes out ~1e-9 mas/yr; bound 1e-4 mas/yr)."""
    c, au = c_km_d(), header()["AU"]
    gm_sun, gm_total = gm_km3_d2("sun"), gm_km3_d2("sun") + gm_km3_d2("earth") + gm_km3_d2("moon")
    closed = 1.5 * gm_sun / (c**2 * au) * math.sqrt(gm_total / au**3)
    for inclination, node in ((0.1, 0.3), (1.0, 2.0)):
        node_rate, inclination_rate = orbit_precession(1.0e4, inclination, node, c)
        assert abs(node_rate - closed) * JULIAN_YEAR_D < 0.05 * mas, (node_rate - closed) * JULIAN_YEAR_D / mas
        assert abs(inclination_rate) * JULIAN_YEAR_D < 1e-4 * mas
    assert 19.1 * mas < closed * JULIAN_YEAR_D < 19.3 * mas


def momenta(y, gm, c):
    """(Newtonian sum mu_a v_a, 1PN total momentum) of a flat state, km^4/d^3.  The 1PN momentum (the 1PN
    terms of de Andrade, Blanchet & Faye 2001, CQG 18, 753, summed over pairs; its drift under EIH scales
    as c^-4 when c is divided by 3, 10, 30) is  sum_a mu_a v_a [1 + v_a^2/(2c^2) - sum_b mu_b/(2 c^2 r_ab)]
    - sum_{a != b} mu_a mu_b/(2 c^2 r_ab) (n_ab.v_a) n_ab."""
    n = gm.shape[0]
    pos, vel = y[:3 * n].reshape(n, 3), y[3 * n:].reshape(n, 3)
    total = np.zeros(3)
    for a in range(n):
        factor = 1 + (vel[a] @ vel[a]) / (2 * c**2)
        for b in range(n):
            if b != a:
                d = pos[a] - pos[b]
                r = np.linalg.norm(d)
                factor -= gm[b] / (2 * c**2 * r)
                total -= gm[a] * gm[b] / (2 * c**2 * r) * (d @ vel[a]) / r * d / r
        total += gm[a] * vel[a] * factor
    return (gm[:, None] * vel).sum(axis=0), total


def test_three_bodies_conserve_the_1pn_momentum():
    """Three strongly coupled bodies (1, 0.29 and 0.095 solar masses at 0.4 and 0.9 au), 400 d of EIH:
    sum mu v changes at the 1PN order ((v/c)^2 ~ 1e-8 of the momentum) while the 1PN momentum holds to
    the next order, c^-4 ~ 1e-16, and the integration floor (1e-14 measured; the same run without the
    correction keeps sum mu v to it): bound 1e-12."""
    c, au = c_km_d(), header()["AU"]
    gm = np.array([gm_km3_d2("sun"), 300 * gm_km3_d2("jupiter"), 100 * gm_km3_d2("jupiter")])
    pos = np.array([[0.0, 0, 0], [0.4 * au, 0, 0], [0, -0.9 * au, 0.05 * au]])
    vel = np.array([[0.0, 0, 0], [0, 1.1 * math.sqrt(gm[0] / (0.4 * au)), 0], [math.sqrt(gm[0] / (0.9 * au)), 0, 1e5]])
    vel[0] = -(gm[1:, None] * vel[1:]).sum(axis=0) / gm[0]
    y0 = np.concatenate([pos.ravel(), vel.ravel()])
    scale = np.abs(gm[:, None] * vel).sum()
    t = np.linspace(0.0, 400.0, 41)
    for eih in (0.0, 1.0):
        start = momenta(y0, gm, c)
        drift = np.array([[np.linalg.norm(p - p0) for p, p0 in zip(momenta(y, gm, c), start)]
                          for y in fixed_step(nbody_rhs, (gm, c, eih), 0.0, y0, t, 0.05)]).max(axis=0) / scale
        if eih:
            assert drift[0] > 1e-9 and drift[1] < 1e-12, drift
        else:
            assert drift[0] < 1e-12, drift


def test_sun_mercury_earth_moon_jupiter_agree_with_reboundx_gr_full():
    """The same five bodies, one year, by the compiled RK8 (0.1-d steps) with these accelerations and by
    REBOUND's IAS15 with REBOUNDx's ``gr_full`` (Newhall, Standish & Williams 1983, coded independently):
    the 1PN correction moves Mercury by 333 km, the Earth by 55 km, the Moon by 59 km (4.5 km about the Earth);
    the two codes agree to 0.2 m on every body, with the correction as without it (the integrators' floor,
    0.16 m on the Moon without it): bound 1 m."""
    import rebound
    import reboundx

    c, au = c_km_d(), header()["AU"]
    gm = np.array([gm_km3_d2(name) for name in ("sun", "mercury", "earth", "moon", "jupiter")])
    r_moon, emb = 384400.0 * np.array([math.cos(0.09), 0, math.sin(0.09)]), np.array([0, au, 0])
    u_moon, v_emb = 1.02 * math.sqrt((gm[2] + gm[3]) / 384400.0) * np.array([0, 1.0, 0]), np.array([-2.57e6, 0, 0])
    share = gm[3] / (gm[2] + gm[3])
    pos = np.array([[0.0, 0, 0], [0.3077 * au, 0, 0], emb - share * r_moon, emb + (1 - share) * r_moon,
                    [-5.2 * au, 0, 0]])
    vel = np.array([[0.0, 0, 0], [0, 5.0e6 * math.cos(0.12), 5.0e6 * math.sin(0.12)], v_emb - share * u_moon,
                    v_emb + (1 - share) * u_moon, [0, -1.134e6, 0]])
    pos -= (gm[:, None] * pos).sum(axis=0) / gm.sum()
    vel -= (gm[:, None] * vel).sum(axis=0) / gm.sum()
    year = JULIAN_YEAR_D
    ours, theirs = {}, {}
    for eih in (0.0, 1.0):
        y = fixed_step(nbody_rhs, (gm, c, eih), 0.0, np.concatenate([pos.ravel(), vel.ravel()]), [year], 0.1)
        ours[eih] = y[0, :15].reshape(5, 3)
        sim = rebound.Simulation()
        sim.G, sim.integrator = 1.0, "ias15"
        for i in range(5):
            sim.add(m=gm[i], x=pos[i, 0], y=pos[i, 1], z=pos[i, 2], vx=vel[i, 0], vy=vel[i, 1], vz=vel[i, 2])
        extras = reboundx.Extras(sim)
        if eih:
            force = extras.load_force("gr_full")
            extras.add_force(force)
            force.params["c"] = c
        sim.integrate(year, exact_finish_time=1)
        theirs[eih] = np.empty((5, 3))
        sim.serialize_particle_data(xyz=theirs[eih])
        assert np.linalg.norm(ours[eih] - theirs[eih], axis=1).max() < 1e-3, (eih, ours[eih] - theirs[eih])
    effect = np.linalg.norm(ours[1.0] - ours[0.0], axis=1)
    assert np.all(effect[1:4] > 10.0), effect             # km: the comparison sees the correction
