"""The Earth's tides on the Moon's orbit (spinorbit.models.interactions.tides, Folkner et al. 2014 eq. 32):
the zero-delay limit against the static Love-number potential, the semi-diurnal recession of a
circular equatorial orbit against the lagged-bulge torque, and the reaction torque against Euler's
P91 torque of the Moon on the tidal bulge's inertia."""
import math

import numpy as np
import pytest

from spinorbit.bodies.de421_header import header
from spinorbit.bodies.earth import de421_tides
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.models.interactions import point_mass, tides
from tests.units import arcsec


def de421_parameters():
    """The tides' parameters from the DE421 header: [GM_E, GM_M, GM_S (km^3/d^2), R_E (km), k20, k21, k22,
    tau0, tau1, tau2 (d)] (Folkner et al. 2014, the tidal acceleration)."""
    love = de421_tides()
    return np.array([gm_km3_d2("earth"), gm_km3_d2("moon"), gm_km3_d2("sun"), header()["RE"],
                     *(love[m][0] for m in range(3)), *(love[m][1] for m in range(3))])


P = de421_parameters()
GM_E, GM_M, GM_S, R_E = P[:4]
Q = GM_M / GM_E
OMEGA = 6.300387486754831          # the Earth's spin, rad/d
DAY_PER_CY = 36525.0


def unit(v):
    return v / np.linalg.norm(v)


def geometry():
    """A Moon, a Sun and a pole in general position (km, km/d, rad/d; ICRF)."""
    rng = np.random.default_rng(11)
    pole = unit(np.array([0.1, -0.35, 0.93]))
    r = 384400.0 * unit(rng.normal(size=3))
    v = 88000.0 * unit(np.cross(unit(rng.normal(size=3)), r))
    r_sun = 1.496e8 * unit(rng.normal(size=3))
    v_sun = 2.57e6 * unit(np.cross(pole, r_sun))
    return r, v, r_sun, v_sun, OMEGA * pole


def parameters_with(k2=None, tau=None, gm_sun=None):
    """DE421's parameters with the Love numbers, the delays or the Sun's GM replaced."""
    p = P.copy()
    if k2 is not None:
        p[4:7] = k2
    if tau is not None:
        p[7:10] = tau
    if gm_sun is not None:
        p[2] = gm_sun
    return p


def test_zero_delay_equal_love_numbers_is_the_static_tide():
    """k20 = k21 = k22 = k2, no delay, the Moon's own tide: the static Love-number potential
    k2 GM_M R^5 / r^6 (a body's own tide, P2(1) = 1) pulls (1 + q) 3 k2 GM_M R^5 r / r^8, radially."""
    r, v, r_sun, v_sun, spin = geometry()
    p = parameters_with(k2=0.3, tau=0.0, gm_sun=0.0)
    a = tides.acceleration(r, v, r_sun, v_sun, spin, p)
    s = np.linalg.norm(r)
    expected = -3.0 * 0.3 * (1 + Q) * GM_M * R_E**5 * r / s**8
    assert np.linalg.norm(a - expected) < 1e-14 * np.linalg.norm(expected)
    torque = tides.torque_on_earth(r, v, r_sun, v_sun, spin, p)
    mu = GM_E * GM_M / (GM_E + GM_M)
    assert np.linalg.norm(torque) < 1e-14 * mu * s * np.linalg.norm(a)


def static_potential(r, pole, k2):
    """(1 + q) GM_M R^5 / (4 r^10) sum_m k2m A_m(r, r): half the static band potential at the Moon
    itself (A_0 = (2 z^2 - rho^2)^2 / 2, A_1 = 6 z^2 rho^2, A_2 = 3/2 rho^4); complex-step safe."""
    z = r @ pole
    r2 = r @ r
    rho2 = r2 - z * z
    bands = k2[0] * 0.5 * (2 * z * z - rho2)**2 + k2[1] * 6 * z * z * rho2 + k2[2] * 1.5 * rho2 * rho2
    return (1 + Q) * GM_M * R_E**5 * bands / (4 * r2**5)


def test_zero_delay_is_the_gradient_of_the_static_band_potential():
    """With DE421's unequal k2m and no delay the Moon's own tide is conservative, the gradient of the
    band potential above (by the complex step), but not central: it torques the Earth."""
    r, v, r_sun, v_sun, spin = geometry()
    p = parameters_with(tau=0.0, gm_sun=0.0)
    a = tides.acceleration(r, v, r_sun, v_sun, spin, p)
    pole = unit(spin)
    h = 1e-20 * np.linalg.norm(r)
    grad = np.array([static_potential(r + 1j * h * e, pole, P[4:7]).imag / h for e in np.eye(3)])
    assert np.linalg.norm(a - grad) < 1e-13 * np.linalg.norm(grad)
    assert np.linalg.norm(np.cross(unit(r), unit(a))) > 1e-4      # k20 != k22: off the Earth-Moon line


def test_semidiurnal_recession_is_the_lagged_bulge_closed_form():
    """Circular equatorial orbit, the Moon's semi-diurnal tide (k22, tau2 of DE421): the bulge leads by
    delta = (Omega - n) tau2, its torque is 3/2 k2 G m^2 R^5 sin(2 delta) / a^6 (Murray & Dermott
    1999, Solar System Dynamics, ch. 4), whence da/dt = 3 k2 q n a (R/a)^5 sin 2 delta and
    dn/dt = -3/2 (n/a) da/dt, with n^2 a^3 = G(M_E + M_M) (the small-lag form 6 k2 tau2 (Omega - n)
    in place of 3 sin 2 delta is 1.06e-3 larger).  The model's along-track acceleration T gives
    da/dt = 2 T / n (Gauss, e = 0).  Its delayed position is two-body exact to (n tau2)^3/6 = 6e-10
    rad, i.e. 1.4e-8 of delta: 1e-7."""
    pole = unit(np.array([0.3, -0.2, 0.9]))                      # any pole: the formula is frame-free
    x_axis = unit(np.cross(pole, [1.0, 0.0, 0.0]))
    a_km = 383400.0
    n = math.sqrt((GM_E + GM_M) / a_km**3)
    r = a_km * x_axis
    v = n * a_km * np.cross(pole, x_axis)
    k22, tau2 = P[6], P[9]
    p = parameters_with(k2=[0.0, 0.0, k22], gm_sun=0.0)
    acc = tides.acceleration(r, v, np.array([1.5e8, 0, 0]), np.zeros(3), OMEGA * pole, p)
    along = acc @ unit(v)
    da_dt = 2.0 * along / n
    dn_dt = -1.5 * n / a_km * da_dt
    two_delta = 2.0 * (OMEGA - n) * tau2
    da_dt_closed = 3.0 * k22 * Q * n * a_km * (R_E / a_km)**5 * math.sin(two_delta)
    dn_dt_closed = -4.5 * k22 * Q * n * n * (R_E / a_km)**5 * math.sin(two_delta)
    assert abs(da_dt / da_dt_closed - 1) < 1e-7
    assert abs(dn_dt - dn_dt_closed) * DAY_PER_CY**2 < 3e-6 * arcsec          # 1e-7 of 26"/cy^2
    assert abs(acc @ pole) < 1e-12 * np.linalg.norm(acc)                     # no force off the plane


def band_inertia(s, pole, k2, gm):
    """G times the Earth's inertia change from the tide raised from s (ICRF): MacCullagh matched to
    the band potentials, G dI_m = -k2m GM R^5 / (3 s^5) Q_m, Q_m the order-m part (in the pole frame)
    of the trace-free 3 s s^T - s^2 1."""
    e1 = unit(np.cross(pole, [1.0, 0.0, 0.0]))
    frame = np.array([e1, np.cross(pole, e1), pole])               # rows: ICRF -> pole frame
    qp = frame @ (3 * np.outer(s, s) - (s @ s) * np.eye(3)) @ frame.T
    zonal = qp[2, 2] / 2 * np.diag([-1.0, -1.0, 2.0])
    diurnal = np.zeros((3, 3))
    diurnal[2, :2], diurnal[:2, 2] = qp[2, :2], qp[:2, 2]
    sectorial = np.zeros((3, 3))
    sectorial[:2, :2] = qp[:2, :2] - np.trace(qp[:2, :2]) / 2 * np.eye(2)
    bands = (k2[0] * zonal + k2[1] * diurnal + k2[2] * sectorial) * gm * R_E**5 / (-3 * np.linalg.norm(s)**5)
    return frame.T @ bands @ frame


@pytest.mark.parametrize("gm_sun", [0.0, GM_S])
def test_reaction_is_the_moons_torque_on_the_tidal_bulge(gm_sun):
    """The orbit's angular momentum change mu r x a plus Euler's torque (§815, interactions.point_mass) of
    the Moon on the tidal bulge's inertia (band by band, each delayed) vanish to rounding, and
    torque_on_earth is that torque: for the Moon-raised tide and with the Sun-raised one."""
    r, v, r_sun, v_sun, spin = geometry()
    p = parameters_with(gm_sun=gm_sun)
    pole, rate = unit(spin), np.linalg.norm(spin)
    inertia = np.zeros((3, 3))
    for x, u, gm, gm_pair in ((r, v, GM_M, GM_E + GM_M), (r_sun, v_sun, gm_sun, GM_S + GM_E + GM_M)):
        for m in range(3):
            s = tides.delayed(x, u, gm_pair, pole, rate, P[7 + m], m)
            k2 = np.zeros(3)
            k2[m] = P[4 + m]
            inertia += band_inertia(s, pole, k2, gm)
    euler = point_mass.torque(np.eye(3), inertia, r[None], np.array([GM_M]))
    mu = GM_E * GM_M / (GM_E + GM_M)
    orbit = mu * np.cross(r, tides.acceleration(r, v, r_sun, v_sun, spin, p))
    assert np.linalg.norm(orbit + euler) < 1e-12 * np.linalg.norm(euler)
    torque = tides.torque_on_earth(r, v, r_sun, v_sun, spin, p)
    assert np.linalg.norm(torque - euler) < 1e-12 * np.linalg.norm(euler)
