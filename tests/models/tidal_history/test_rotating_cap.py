"""The ocean with its continent on the rotating Earth (spinorbit.models.tidal_history.rotating_cap): the
Galerkin solution of the Laplace tidal equations with the Coriolis force in a spherical-cap basin, against the
global rotating ocean where the cap vanishes (ocean.love_number: the spectral chain of Longuet-Higgins 1968,
converged to 1e-9) and against the non-rotating cap's damped resonances where the spin is zero
(cap_ocean.love_number_imag: an independent Rayleigh-Ritz eigen-expansion)."""
import math

import numpy as np
import pytest

from spinorbit.bodies import earth
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.models.tidal_history import cap_ocean, ocean, rotating_cap

R = earth.EQUATORIAL_RADIUS_KM
SPIN = earth.ERA_RATE_RAD_D
N = 0.2300                                        # the Moon's mean motion today, rad/day
WATER = ocean.constants(gm_km3_d2("earth") / R**2, R)
LOADS = (WATER[ocean.DENSITY_RATIO], WATER[ocean.LOAD_K2], WATER[ocean.LOAD_H2])
# Today's semi-diurnal, diurnal and fortnightly lunar tides in the rotating convention (forcing Y_2^m, w).
TIDES = ((-2, 2 * (SPIN - N)), (-1, SPIN - N), (0, 2 * N))
# The truncation's floor (ORDERS_MAX = 6, MODES = 5): measured against 8 and 8 at 4 km.
TRUNCATION = 5e-3


def test_without_a_cap_the_rotating_basin_is_the_global_ocean():
    """No continent: the basin's Galerkin solution in a frame tilted by 90 deg (where the Coriolis parameter
    couples every order) is the global ocean's spectral chain, at two depths and drags."""
    colatitude = 90.0
    basin = rotating_cap.basin(0.0, colatitude, *LOADS)
    for depth, drag in ((4.0, 1.0), (8.0, 0.5)):
        for m, w in TIDES:
            k = rotating_cap.love_number(m, w, SPIN, depth, drag, WATER, basin)
            reference = complex(*ocean.love_number(m, w, SPIN, depth, drag, WATER))
            assert abs(k - reference) <= TRUNCATION * abs(reference), (colatitude, depth, m)


@pytest.mark.parametrize("cap, colatitude", [(90.0, 90.0), (65.4, 43.0)])
def test_without_rotation_the_basin_is_the_caps_damped_resonances(cap, colatitude, monkeypatch):
    """Spin zero: the Galerkin solution is cap_ocean's sum of damped resonances, weighted by the orientation
    (each computed with its own basis: MODES per order against 48; cap_ocean's table reduced to this cap)."""
    basin = rotating_cap.basin(cap, colatitude, *LOADS)
    monkeypatch.setattr(cap_ocean, "CAP_GRID_DEG", np.array([0.0, cap]))
    cap_ocean.table.cache_clear()
    continent = cap_ocean.constants(WATER, cap, colatitude, 1e30, 2e30)
    cap_ocean.table.cache_clear()
    for depth, drag in ((4.0, 1.0), (8.75, 1.78)):
        for m, w in TIDES:
            k = rotating_cap.love_number(m, w, 0.0, depth, drag, WATER, basin)
            reference = cap_ocean.love_number_imag(-m, w, drag, depth, cap, continent)
            assert k.imag == pytest.approx(reference, rel=2e-3), (cap, depth, m)


def test_the_coriolis_force_does_no_work():
    """w Im k >= 0 at every frequency and order (the drag alone dissipates), with and without rotation."""
    basin = rotating_cap.basin(90.0, 90.0, *LOADS)
    for order in range(3):
        w = SPIN * np.linspace(-3.0, 3.0, 61)
        w = w[w != 0.0]
        for spin in (0.0, SPIN):
            k = rotating_cap.love_numbers(order, w, spin, 4.0, 1.0, WATER, basin)
            assert np.all(w * k.imag >= -1e-15 * np.abs(k))


def test_the_drag_poles_are_the_direct_solution():
    """DragPoles (one eigen-decomposition per frequency) give the direct solve's k at any drag."""
    basin = rotating_cap.basin(90.0, 90.0, *LOADS)
    w = SPIN * np.array([-2.07, -2.0, -1.93])
    poles = rotating_cap.drag_poles(2, w, SPIN, 4.0, WATER, basin)
    for drag in (0.1, 1.0, 5.0):
        direct = rotating_cap.love_numbers(2, w, SPIN, 4.0, drag, WATER, basin)
        assert poles.love_numbers(drag) == pytest.approx(direct, rel=1e-9)


def test_the_rhs_reads_the_table_within_its_interpolation_floor():
    """The rhs's table (4-point Lagrange in log spin and in nu) against the direct solution at spins and
    frequencies between its nodes, with the response.dissipation convention (the Earth's term e^{i(m phi +
    sigma t)}, the forcing Y_2^{-m}): within 2% of the largest response (the spin step's floor)."""
    basin = rotating_cap.basin(90.0, 90.0, *LOADS)
    spins = rotating_cap.spin_nodes(SPIN)[:8]
    table = rotating_cap.table(4.0, 1.0, WATER, basin, spins)
    constants = rotating_cap.constants(WATER, 1e30, 2e30, spins, table)
    rng = np.random.default_rng(7)
    errors = []
    for _ in range(30):
        spin = spins[1] * math.exp(rng.uniform(0.0, math.log(spins[-2] / spins[1])))
        m, q = int(rng.integers(-2, 3)), int(rng.integers(-3, 4))
        sigma = m * spin - q * spin * rng.uniform(0.02, 0.04)
        if sigma == 0.0:
            continue
        read = rotating_cap.love_number_imag(m, sigma, spin, 0.0, 4.0, 1.0, constants)
        direct = rotating_cap.love_number(-m, sigma, spin, 4.0, 1.0, WATER, basin).imag
        errors.append(abs(read - direct))
    assert max(errors) <= 0.02 * np.abs(table).max()


def test_the_continent_gives_way_to_the_global_ocean():
    """Before the continent's shrinking the table alone, after it the global ocean alone, between them their
    responses weighted by the continent's area (linear in the age)."""
    basin = rotating_cap.basin(90.0, 90.0, *LOADS)
    spins = rotating_cap.spin_nodes(SPIN)[:6]
    until, gone = 1000.0, 3000.0
    constants = rotating_cap.constants(WATER, until, gone, spins, rotating_cap.table(4.0, 1.0, WATER, basin,
                                                                                     spins))
    sigma = 2 * (SPIN - N)
    cap = rotating_cap.love_number_imag(2, sigma, SPIN, -500.0, 4.0, 1.0, constants)
    world = ocean.love_number(-2, sigma, SPIN, 4.0, 1.0, WATER)[1]
    assert rotating_cap.love_number_imag(2, sigma, SPIN, -4000.0, 4.0, 1.0, constants) == world
    middle = rotating_cap.love_number_imag(2, sigma, SPIN, -1500.0, 4.0, 1.0, constants)
    assert middle == pytest.approx(0.75 * cap + 0.25 * world, rel=1e-12)
