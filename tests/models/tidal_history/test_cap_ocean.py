"""The ocean with its continent (spinorbit.models.tidal_history.cap_ocean): its Neumann eigenmodes against the
exact ones (every P_n^mu for the global ocean, P_n^mu with n - mu even for the hemisphere, scipy's P_nu^mu of
non-integer degree otherwise), its response against the non-rotating global ocean's closed form and against
the landed global-ocean model without rotation, the Wigner weights, and the continent's schedule."""
import math

import numpy as np
import pytest
from scipy.special import lpmv

from spinorbit.bodies import earth
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.models.tidal_history import cap_ocean, ocean

R = earth.EQUATORIAL_RADIUS_KM
GYR_D = 1e9 * 365.25


def water():
    return ocean.constants(gm_km3_d2("earth") / R**2, R)


@pytest.mark.parametrize("mu", [0, 1, 2])
def test_global_and_hemispheric_eigenvalues_are_integer_degrees(mu):
    """No cap: lambda = n (n + 1), n >= mu; a hemisphere bounded by its equator: only the P_n^mu even about
    it, n - mu even (Rayleigh-Ritz is exact there: the modes are in its space; 1e-9 is rounding)."""
    global_values = cap_ocean.neumann_modes(mu, 0.0)[0][:6]
    expected = [n * (n + 1.0) for n in range(mu, mu + 6)]
    assert global_values == pytest.approx(expected, rel=1e-9, abs=1e-9)
    hemisphere = cap_ocean.neumann_modes(mu, 90.0)[0][:5]
    assert hemisphere == pytest.approx([n * (n + 1.0) for n in range(mu, mu + 10, 2)], rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("mu, cap", [(0, 40.0), (2, 60.0)])
def test_a_caps_modes_are_legendre_functions_of_non_integer_degree(mu, cap):
    """The first three modes outside a 40 or 60 degree cap: nu from lambda = nu (nu + 1), and scipy's Ferrers
    P_nu^mu(-cos theta) (regular opposite the cap) has a vanishing derivative at the coast, to 1e-7 of its
    scale (a centred difference of 1e-5 rad)."""
    values = cap_ocean.neumann_modes(mu, cap)[0]
    values = values[values > 1e-9][:3]
    theta, h = math.radians(cap), 1e-5
    for value in values:
        nu = 0.5 * (math.sqrt(1.0 + 4.0 * value) - 1.0)
        assert abs(nu - round(nu)) > 1e-3                       # genuinely non-integer
        slope = (lpmv(mu, nu, -math.cos(theta + h)) - lpmv(mu, nu, -math.cos(theta - h))) / (2 * h)
        scale = np.abs(lpmv(mu, nu, -np.cos(np.linspace(theta, math.pi, 200)))).max() * nu
        assert abs(slope) <= 1e-7 * scale


def test_without_a_cap_the_response_is_the_global_oceans():
    """theta_c = 0: one resonance per order at lambda' = 6 (1 - alpha_2) with weight 6 (the non-rotating
    global ocean's closed form, w_2^2 = 6 g H / R^2 (1 - alpha_2)); and its Im k against the landed global
    model (ocean.love_number, a separate computation: the Laplace tidal equations' chain) with the rotation
    1e-12 rad/day, to 1e-8, below, near and above the resonance; away from it (at 2 and 12 rad/day, the
    resonance at 5.9) a 1-degree cap changes it by less than 1e-3 (its area is 8e-5 of the sphere; near the
    resonance the shift is amplified by its quality factor)."""
    p = water()
    alpha = 3 * ocean.SEAWATER_OVER_MEAN_DENSITY / 5 * (1 + ocean.LOAD_NUMBERS[0] - ocean.LOAD_NUMBERS[1])
    for mu in range(3):
        lam, weight = cap_ocean.poles(mu, 0.0, ocean.SEAWATER_OVER_MEAN_DENSITY, *ocean.LOAD_NUMBERS)
        main = int(np.argmax(weight))
        assert lam[main] == pytest.approx(6 * (1 - alpha), rel=1e-12)
        assert weight[main] == pytest.approx(6.0, rel=1e-12)
        assert weight.sum() == pytest.approx(6.0, rel=1e-12)
    table = cap_ocean.constants(p, 90.0, 90.0, 1.0, 2.0)
    one = cap_ocean.constants(p, 1.0, 90.0, 1.0, 2.0)
    depth, drag = 4.0, 0.3
    for w in (2.0, 6.0, 12.0):
        for m in (1, 2):
            landed = ocean.love_number(-m, w, 1e-12, depth, drag, p)[1]
            assert cap_ocean.love_number_imag(m, w, drag, depth, 0.0, table) == pytest.approx(landed, rel=1e-8)
            if w != 6.0:
                assert cap_ocean.love_number_imag(m, w, drag, depth, 1.0, one) == pytest.approx(landed, rel=1e-3)


def test_no_self_attraction_puts_the_resonance_at_the_gravity_waves_frequency():
    """Without self-attraction (rho_o = 0) the degree-2 pole is lambda' = 6 exactly: the resonance at
    sqrt(g H l (l + 1)) / R, l = 2, the uniform ocean's eigenfrequency; its Im k peaks there."""
    lam, weight = cap_ocean.poles(2, 0.0, 0.0, *ocean.LOAD_NUMBERS)
    assert lam[np.argmax(weight)] == pytest.approx(6.0, rel=1e-12)


def test_orientation_weights():
    """sum_mu d^2_{m mu}(theta_0)^2 = 1 for every m (the Wigner matrix is unitary); a polar cap keeps the order
    (W = identity); an equatorial one shares Y_2^2 as 3/8, 1/2, 1/8 among |mu| = 0, 1, 2."""
    for colatitude in (0.0, 33.0, 90.0, 140.0):
        assert cap_ocean.orientation_weights(colatitude).sum(axis=1) == pytest.approx(np.ones(3), rel=1e-14)
    assert cap_ocean.orientation_weights(0.0) == pytest.approx(np.eye(3), abs=1e-15)
    assert cap_ocean.orientation_weights(90.0)[2] == pytest.approx([0.375, 0.5, 0.125], rel=1e-14)


def test_the_continent_shrinks_with_its_area_linear_in_the_age():
    """Today's radius until the first age; half the area halfway; none from the second age on."""
    k = cap_ocean.constants(water(), 90.0, 90.0, 2.5 * GYR_D, 3.5 * GYR_D)[ocean.SIZE:]
    assert cap_ocean.cap_radius(-1.0 * GYR_D, k) == 90.0
    assert cap_ocean.cap_radius(-3.0 * GYR_D, k) == pytest.approx(60.0, rel=1e-12)   # 1 - cos 60 = 1/2
    assert cap_ocean.cap_radius(-3.6 * GYR_D, k) == 0.0


def test_the_andrade_solid_earth_holds_todays_k2_and_q_and_andrades_frequency_law():
    """The Andrade body (solid.py) calibrated at today's M2 (12.14 rad/day): Re k2 = 0.298 (IERS) and k2/Q =
    0.298/280 (Ray et al. 2001) to 1e-9; well above the Maxwell frequency the lag falls as chi^-alpha
    (Andrade creep: Q ~ chi^alpha, Efroimsky 2012), so Q(48)/Q(24) = 2^0.25 within 1% (the elastic part's
    share of the phase, (Aμ)^-1 corrections, is frequency-independent to that order); K is odd in sigma."""
    from spinorbit.models.tidal_history import solid

    m2 = 12.1408
    p = solid.constants(m2)
    re, im = solid.love_number(m2, p)
    assert re == pytest.approx(0.298, rel=1e-9)
    assert -im == pytest.approx(0.298 / 280, rel=1e-9)
    q = {chi: solid.love_number(chi, p)[0] / -solid.love_number(chi, p)[1] for chi in (24.0, 48.0)}
    assert q[48.0] / q[24.0] == pytest.approx(2**0.25, rel=0.01)
    assert -solid.lag(-m2, p) == solid.lag(m2, p) > 0
