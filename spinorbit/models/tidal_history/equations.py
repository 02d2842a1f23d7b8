"""The Earth-Moon system averaged over its orbits and precessions, under the tides the Moon and the Sun raise
on the Earth, written so that the angular momentum is kept.

State y = (a, e^2, Omega, X, Y, S): the Moon's semi-major axis (km), its eccentricity squared, the Earth's
rotation rate (rad/day), and three angular momenta per unit Earth mass (km^2/day) along the ecliptic's normal
z: the Earth's spin X = c R^2 Omega cos(eps), the lunar orbit's Y = m/(M + m) sqrt(mu a (1 - e^2)) cos(i), and
S, what the solar tide has passed from the Earth's spin to the heliocentric orbit.  The obliquity eps and the
Moon's inclination i to the ecliptic follow from X and Y.

The tides (``secular.exchange``) give the torque on the Earth along its axis and along the orbit normal; its
part along z changes X, and the lunar orbit takes it back (Y), the Sun's share going to S.  The spin axis
precesses about z (26 kyr) and the lunar node regresses about it (18.6 yr today): both fast against the
tides, so the rates are averaged over the angle phi between the two nodes (the mutual inclination I,
cos I = cos eps cos i + sin eps sin i cos phi), with NODES points (the trapezoid rule, exact for the
polynomials of cos phi the weights are).  The Sun's tide sees I = eps.

X + Y + S changes only by rounding: every Runge-Kutta method keeps a linear invariant, so the Earth-Moon
angular momentum along z is kept by construction, with the solar torque's share tracked in S.

Limits (departures from Touma & Wisdom 1994 and Farhat et al. 2022, A&A 665, L1): the Laplace plane is the
ecliptic (the node regresses about z), true beyond ~15-20 Earth radii today's and closer in the past; the
planetary orbits and the ecliptic are fixed (today's); C = c M R^2 is today's (the rotational flattening's
~1% is left out of the spin's inertia); the Moon's own tide (it damps e and i) is left out; the tidal
expansion is to O(e^2) (Kaula's G_{2pq}).  A state outside the model (the Moon inside the Roche limit, e
outside [0, 0.3), |cos| > 1, no spin) stops the motion: the rhs is zero there and ``stop`` says why.
"""
import math

import numpy as np

from ...base.layout import Layout
from ...base.linker import cached
from ..ode import Ode
from .secular import exchange, lags, strength, torque_on_spin

NODES = 16
# Indices into the constants: gravitational parameters (km^3/d^2), the Earth's radius (km) and c = C/(M R^2),
# the Sun's orbit (semi-major axis km, e^2), where the motion stops (km).
GM_EARTH, GM_MOON, GM_SUN, RADIUS, INERTIA, SUN_A, SUN_E2, STOP_A = range(8)
CONSTANTS = 8
# e^2 may dip below zero by the integration's error where it decays toward 0 (de^2/dt is proportional to e^2,
# so the rates continue linearly through 0 and e^2 = 0 stays a fixed point); beyond this it is unphysical.
E2_FLOOR = -1e-6
E2_MAX = 0.09          # e = 0.3: the O(e^2) expansion's e^4 terms (Hut's coefficients up to ~180) would exceed it

LAYOUT = Layout([("moon.semi_major_axis", 1, "vector", "km"),
                 ("moon.eccentricity_squared", 1, "vector", ""),
                 ("earth.rotation", 1, "vector", "rad/d"),
                 ("earth.spin_z", 1, "vector", "km^2/d per Earth mass"),
                 ("moon.orbit_z", 1, "vector", "km^2/d per Earth mass"),
                 ("sun.tidal_share_z", 1, "vector", "km^2/d per Earth mass")])


@cached(nogil=True)
def orbit_momentum(a, e2, c):
    """The lunar orbit's angular momentum per unit Earth mass, m/(M + m) sqrt(mu a (1 - e^2))."""
    mu = c[GM_EARTH] + c[GM_MOON]
    return c[GM_MOON] / mu * math.sqrt(mu * a * (1.0 - e2))


@cached(nogil=True)
def inside(y, c):
    """Is the state one the equations describe?"""
    a, e2, spin, x, z_orbit = y[0], y[1], y[2], y[3], y[4]
    if not (a > c[STOP_A] and E2_FLOOR <= e2 < E2_MAX and spin > 0.0):
        return False
    return abs(x) <= c[INERTIA] * c[RADIUS] ** 2 * spin and abs(z_orbit) <= orbit_momentum(a, e2, c)


@cached(nogil=True)
def rhs(t, y, p):
    """dy/dt; p = (constants, response)."""
    c, response = p
    out = np.zeros(6)
    if not inside(y, c):
        return out
    a, e2, spin = y[0], y[1], y[2]
    mu = c[GM_EARTH] + c[GM_MOON]
    n = math.sqrt(mu / a**3)
    h_orbit = orbit_momentum(a, e2, c)
    h_spin = c[INERTIA] * c[RADIUS] ** 2 * spin
    cos_i, cos_eps = y[4] / h_orbit, y[3] / h_spin
    sin_i, sin_eps = math.sqrt(max(0.0, 1.0 - cos_i * cos_i)), math.sqrt(max(0.0, 1.0 - cos_eps * cos_eps))
    axial, normal, power, along_z = 0.0, 0.0, 0.0, 0.0
    lunar_lags = lags(spin, n, response, t)
    for j in range(NODES):
        cos_mutual = cos_eps * cos_i + sin_eps * sin_i * math.cos(2.0 * math.pi * (j + 0.5) / NODES)
        ax, no, po = exchange(n, e2, cos_mutual, lunar_lags)
        alpha, beta = torque_on_spin(ax, no, cos_mutual)
        axial += ax
        normal += no
        power += po
        along_z += alpha * cos_eps + beta * cos_i
    lunar = strength(c[GM_MOON], c[GM_EARTH], c[RADIUS], a) / NODES
    n_sun = math.sqrt((c[GM_SUN] + mu) / c[SUN_A] ** 3)
    ax_sun, no_sun, _ = exchange(n_sun, c[SUN_E2], cos_eps, lags(spin, n_sun, response, t))
    alpha, beta = torque_on_spin(ax_sun, no_sun, cos_eps)
    solar = strength(c[GM_SUN], c[GM_EARTH], c[RADIUS], c[SUN_A])
    solar_z = solar * (alpha * cos_eps + beta)
    lunar_z = lunar * along_z
    da = 2.0 * a * a / c[GM_MOON] * lunar * power
    out[0] = da
    out[1] = (1.0 - e2) * (da / a - 2.0 * lunar * normal / h_orbit)
    out[2] = (lunar * axial + solar * ax_sun) / (c[INERTIA] * c[RADIUS] ** 2)
    out[3] = lunar_z + solar_z
    out[4] = -lunar_z
    out[5] = -solar_z
    return out


def constants(gm_earth, gm_moon, gm_sun, radius_km, inertia_factor, sun_a_km, sun_eccentricity, stop_km):
    """The rhs's constants array from named values."""
    out = np.zeros(CONSTANTS)
    out[GM_EARTH], out[GM_MOON], out[GM_SUN] = gm_earth, gm_moon, gm_sun
    out[RADIUS], out[INERTIA] = radius_km, inertia_factor
    out[SUN_A], out[SUN_E2], out[STOP_A] = sun_a_km, sun_eccentricity**2, stop_km
    return out


def state(c, semi_major_axis_km, eccentricity, rotation_rad_d, obliquity_rad, inclination_rad,
          solar_share=0.0):
    """y from the elements (angles in radians)."""
    e2 = eccentricity**2
    h_spin = c[INERTIA] * c[RADIUS] ** 2 * rotation_rad_d
    h_orbit = orbit_momentum(semi_major_axis_km, e2, c)
    return np.array([semi_major_axis_km, e2, rotation_rad_d, h_spin * math.cos(obliquity_rad),
                     h_orbit * math.cos(inclination_rad), solar_share])


def elements(states, c):
    """{semi_major_axis (km), eccentricity, rotation (rad/d), obliquity (rad), inclination (rad),
    angular_momentum_z (X + Y + S)} of states (k, 6)."""
    y = np.atleast_2d(states)
    a, e2, spin = y[:, 0], y[:, 1], y[:, 2]
    mu = c[GM_EARTH] + c[GM_MOON]
    h_orbit = c[GM_MOON] / mu * np.sqrt(mu * a * (1.0 - e2))
    h_spin = c[INERTIA] * c[RADIUS] ** 2 * spin
    return {"semi_major_axis": a, "eccentricity": np.sqrt(np.clip(e2, 0.0, None)), "rotation": spin,
            "obliquity": np.arccos(np.clip(y[:, 3] / h_spin, -1, 1)),
            "inclination": np.arccos(np.clip(y[:, 4] / h_orbit, -1, 1)),
            "angular_momentum_z": y[:, 3] + y[:, 4] + y[:, 5]}


def stop(y, c):
    """Why the equations stop at state y ("" if they do not)."""
    a, e2, spin = y[0], y[1], y[2]
    if not a > c[STOP_A]:
        return f"the Moon reached {c[STOP_A] / c[RADIUS]:.2f} Earth radii (the Roche limit)"
    if not E2_FLOOR <= e2 < E2_MAX:
        return f"the eccentricity left [0, 0.3), where the O(e^2) tides hold (e^2 = {e2:.3g})"
    if not spin > 0.0:
        return "the Earth's rotation stopped"
    if not inside(np.asarray(y, dtype=float), c):
        return "the obliquity or the inclination has no real value (|cos| > 1)"
    return ""


class EarthMoonHistory(Ode):
    """The averaged equations as the integrator door runs them (integrators.simulate)."""

    @property
    def constants(self):
        return self.params[0]


def history(c, response, y0, t0=0.0):
    """The equations with constants ``c`` and tidal ``response`` (response.py) from y0 at t0 (TDB days)."""
    params = (np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(response, dtype=float))
    return EarthMoonHistory(rhs, params, float(t0), np.asarray(y0, dtype=float), LAYOUT,
                            name="earth_moon_history")
