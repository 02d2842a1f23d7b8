"""A planet's spin axis over millions of years: the averaged precession of an oblate planet torqued by the Sun
and (the Earth) the orbit-averaged Moon, on a given orbit of the planet, with geodesic precession and tidal
dissipation.  Written for the Earth below; a planet without a large moon (Mars) has the Moon's terms zero and
the Sun's tide instead (:func:`planet_parameters`).

The averaged equations (Ward 1974; Bills 1990; Neron de Surgy & Laskar 1997, A&A 318, 975, in Andoyer
variables; Laskar et al. 2004, A&A 428, 261, sect. 3) in vector form, as Zeebe & Lourens (2022, snvec)
write them: with s the unit spin axis and n the unit normal of the Earth's heliocentric orbit (the Earth-Moon
barycentre's), both in inertial axes,

    ds/dt = [Omega_g - alpha (n . s)] (n x s),

    alpha = (3/2) (E_d / omega) [GM_sun / (a^3 (1 - e^2)^(3/2)) + GM_moon K / a_m^3],

the Sun's torque averaged over the Earth's orbit (a, e) and the Moon's over its orbit and its nodal regression
about the ecliptic (K = (1 - e_m^2)^(-3/2) (1 - 3/2 sin^2 i_m), Kinoshita 1977); E_d = (C - A)/C the dynamical
ellipticity, omega the rotation rate, Omega_g = (3/2) GM_sun n / (c^2 a (1 - e^2)) the geodesic (de Sitter)
precession about n (prograde).  alpha (n . s) is the luni-solar precession rate; the ecliptic's own motion
(the planetary precession) enters through n(t).

Tidal dissipation moves the Moon out and slows the Earth: a_m' = Td x 38.30 mm/yr (a_m0/a_m)^(11/2) (lunar
laser ranging today, Williams & Boggs 2016; the a^(-11/2) of a constant tidal lag, Goldreich 1966), and
omega' = 51 n_m' (Lambeck 1980, as in Quinn et al. 1991, AJ 101, 2287, eq. 11: the lunar and solar tidal
torques); the Earth's figure follows its rotation hydrostatically, E_d ~ omega^2 (Laskar et al. 2004), so
alpha ~ omega.  The tides also tilt the axis away from n: d(eps)/dt = Td x 2.4 mas/cy today,
~ sin(eps) cos(eps) (Williams 1994, AJ 108, 711; IAU 2006's budget, Capitaine et al. 2003, Table 3) and,
here, ~ a_m^-6 with the lunar tidal torque.  Td and Ed scale today's dissipation and dynamical ellipticity
(snvec's keys).

A planet without a large moon (Mars): alpha = (3/2) (E_d / omega) GM_sun / (a^3 (1 - e^2)^(3/2)), its figure
fixed (C - A constant, not hydrostatic: alpha ~ 1/omega), and the Sun's tide with a constant Q slowing the
rotation and tilting the axis (Mignard 1980; Neron de Surgy & Laskar 1997, eqs. 23-24; Correia & Laskar 2010,
in Exoplanets, ed. Seager, eqs. 9-10, for omega >> n, e -> 0):

    omega' = -(G/C) [(1 + cos^2 eps)/2 - (n/omega) cos eps],   eps' = (G/(C omega)) sin eps [cos eps/2 - n/omega],

    G = (3/2) (k2/Q) GM_sun^2 R^5 / (G a^6), so G/C = (3/2) (k2/Q) GM_sun^2 R^3 / (GM (C/MR^2) a^6).

State y = (s_x, s_y, s_z, a_m/a_m0, omega/omega0); time TDB days from J2000; rates rad/day.  The orbit comes
as samples of the normal and the eccentricity vector on a uniform grid, interpolated by cubic Lagrange
polynomials (``orbit_at`` in the rhs, ``orbit_series`` for output times).
"""
import math

import numpy as np
from numba import njit

from ..base.constants import JULIAN_YEAR_D
from ..base.errors import InputError
from ..base.layout import Layout
from ..base.linker import cached
from ..base.rotations import cross3, dot3
from ..bodies import moon
from ..bodies.table import gm_km3_d2
from .ode import Ode

LAMBECK_SPIN_TIDE = 51.0          # omega' = 51 n_m' (Lambeck 1980; Quinn et al. 1991 eq. 11)
# Indices into the model's constants (``parameters``): FIGURE the power of omega in alpha (+1 hydrostatic,
# -1 a fixed figure); SOLAR_TIDE the Sun's tidal G/(C omega0) (1/day), MEAN_MOTION n/omega0.
ALPHA0, SOLAR0, BETA0, GEODESIC, RECESSION, SPIN_TIDE, TILT, FIGURE, SOLAR_TIDE, MEAN_MOTION = range(10)


@njit(cache=True, nogil=True)
def orbit_at(t, grid, t0, h):
    """(n, e) at t from samples ``grid`` (k, 6) = (normal, eccentricity vector) at t0 + k h: cubic Lagrange on
    the four nearest samples (the first or last four at the ends), n renormalised."""
    x = (t - t0) / h
    k = min(max(math.floor(x) - 1, 0), grid.shape[0] - 4)
    u = x - k - 1.0                          # in [0, 1] between samples k + 1 and k + 2 inside the grid
    w0 = -u * (u - 1.0) * (u - 2.0) / 6.0
    w1 = (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0
    w2 = -(u + 1.0) * u * (u - 2.0) / 2.0
    w3 = (u + 1.0) * u * (u - 1.0) / 6.0
    v = w0 * grid[k] + w1 * grid[k + 1] + w2 * grid[k + 2] + w3 * grid[k + 3]
    n = v[:3] / math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return n, math.sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5])


def orbit_series(t, grid, t0, h):
    """(normal (k, 3), eccentricity vector (k, 3)) at times t, interpolated as ``orbit_at`` does."""
    x = (np.asarray(t, dtype=float) - t0) / h
    k = np.clip(np.floor(x).astype(int) - 1, 0, grid.shape[0] - 4)
    u = (x - k - 1.0)[:, None]
    v = (-u * (u - 1) * (u - 2) / 6 * grid[k] + (u + 1) * (u - 1) * (u - 2) / 2 * grid[k + 1]
         - (u + 1) * u * (u - 2) / 2 * grid[k + 2] + (u + 1) * u * (u - 1) / 6 * grid[k + 3])
    return _unit(v[:, :3]), v[:, 3:]


@cached(nogil=True)
def rhs(t, y, p):
    """dy/dt of the averaged spin axis and the tidal evolution; p = (grid, t0, h, constants)."""
    grid, t0, h, c = p
    n, e = orbit_at(t, grid, t0, h)
    s = y[:3]
    distance, spin = y[3], y[4]                   # a_m / a_m0, omega / omega0
    one_e2 = 1.0 - e * e
    recession = c[RECESSION] * distance ** -5.5
    solar = one_e2 ** -1.5
    lunar = c[BETA0] * distance ** -3.0
    alpha = c[ALPHA0] * spin ** c[FIGURE] * (solar + lunar) / (c[SOLAR0] + c[BETA0])
    cos_eps = dot3(n, s)
    rate = c[GEODESIC] / one_e2 - alpha * cos_eps
    ds = rate * cross3(n, s)
    # the tides' own tilt of the axis away from n (eps' / sin eps): the Moon's, ~ sin(eps) cos(eps) and the
    # lunar tidal torque (a_m^-6); the Sun's on a planet without a large moon
    nu = c[MEAN_MOTION] / spin
    tilt = c[TILT] * cos_eps * distance**-6.0 + c[SOLAR_TIDE] / spin * (0.5 * cos_eps - nu)
    for i in range(3):
        ds[i] += tilt * (s[i] * cos_eps - n[i])
    out = np.empty(5)
    out[0], out[1], out[2] = ds[0], ds[1], ds[2]
    out[3] = recession
    out[4] = (-c[SPIN_TIDE] * distance ** -2.5 * recession
              - c[SOLAR_TIDE] * (0.5 * (1.0 + cos_eps * cos_eps) - nu * cos_eps))
    return out


def geodesic_rate(semi_major_axis_km, c_km_d):
    """(3/2) GM_sun n / (c^2 a), rad/day: the de Sitter precession of a spin on a circular heliocentric orbit
    (divided by 1 - e^2 for an ellipse)."""
    gm = gm_km3_d2("sun")
    return 1.5 * gm * math.sqrt(gm / semi_major_axis_km**3) / (c_km_d**2 * semi_major_axis_km)


def lunar_ratio(semi_major_axis_km):
    """The Moon's share of the precession constant over the Sun's (e = 0): GM_moon K a^3 / (GM_sun a_m^3)."""
    return (gm_km3_d2("moon") / gm_km3_d2("sun") * moon.orbit_average_factor()
            * (semi_major_axis_km / moon.MEAN_DISTANCE_KM) ** 3)


def constant_from_rate(psi_rate_rad_d, obliquity, geodesic):
    """The precession constant alpha (rad/day) whose luni-solar precession less the geodesic, alpha cos(eps) -
    Omega_g, is ``psi_rate_rad_d``, the precession in longitude of the equator at J2000 (IAU 2006's
    5038.481507"/cy, Capitaine et al. 2003): the rate the equations give at t = 0 when n does not move."""
    return (psi_rate_rad_d + geodesic) / math.cos(obliquity)


def constant_from_ellipticity(ellipticity, spin_rad_d, semi_major_axis_km, eccentricity):
    """alpha (rad/day) of the formula above from a dynamical ellipticity E_d = (C - A)/C and rotation rate."""
    n2 = gm_km3_d2("sun") / semi_major_axis_km**3
    solar = (1 - eccentricity**2) ** -1.5
    return 1.5 * ellipticity / spin_rad_d * n2 * (solar + lunar_ratio(semi_major_axis_km))


def implied_ellipticity(alpha, spin_rad_d, semi_major_axis_km, eccentricity):
    """E_d = (C - A)/C for which the formula gives ``alpha``."""
    return alpha / constant_from_ellipticity(1.0, spin_rad_d, semi_major_axis_km, eccentricity)


def parameters(grid, t0, h, alpha0, eccentricity0, semi_major_axis_km, c_km_d, spin_rad_d, ed=1.0, td=1.0,
               tilt_rad_d=0.0, obliquity0=0.4090928):
    """The rhs's p for orbit samples ``grid`` (k, 6) at t0 + k h (TDB d), the precession constant ``alpha0``
    (rad/day) at J2000 where the eccentricity is ``eccentricity0``, the Earth's mean heliocentric semi-major
    axis (km), the speed of light (km/d), today's rotation rate omega0 (rad/day), and the factors Ed, Td of
    today's dynamical ellipticity and tidal dissipation."""
    if not ed > 0:
        raise InputError("Ed", ed, "a positive factor of today's dynamical ellipticity")
    if not td >= 0:
        raise InputError("Td", td, "a factor >= 0 of today's tidal dissipation")
    n_moon = math.sqrt((gm_km3_d2("earth") + gm_km3_d2("moon")) / moon.MEAN_DISTANCE_KM**3)
    constants = np.zeros(10)
    constants[FIGURE] = 1.0                    # the Earth's figure follows its rotation (E_d ~ omega^2)
    constants[ALPHA0] = alpha0 * ed
    constants[SOLAR0] = (1 - eccentricity0**2) ** -1.5
    constants[BETA0] = lunar_ratio(semi_major_axis_km)
    constants[GEODESIC] = geodesic_rate(semi_major_axis_km, c_km_d)
    constants[RECESSION] = td * moon.RECESSION_KM_PER_YR / JULIAN_YEAR_D / moon.MEAN_DISTANCE_KM
    constants[SPIN_TIDE] = 1.5 * LAMBECK_SPIN_TIDE * n_moon / spin_rad_d
    constants[TILT] = td * tilt_rad_d / (math.sin(obliquity0) * math.cos(obliquity0))
    return (np.ascontiguousarray(grid, dtype=float), float(t0), float(h), constants)


def planet_parameters(grid, t0, h, alpha0, eccentricity0, semi_major_axis_km, c_km_d, spin_rad_d,
                      solar_tide_rad_d=0.0):
    """The rhs's p for a planet without a large moon (Mars): the precession constant ``alpha0`` (rad/day, the
    Sun's alone) at J2000 where the eccentricity is ``eccentricity0``, a fixed figure (alpha ~ 1/omega), the
    Sun's tide ``solar_tide_rad_d`` = G/(C omega0) (:func:`solar_tide`), the planet's mean semi-major axis (km)
    and today's rotation rate omega0 (rad/day)."""
    constants = np.zeros(10)
    constants[ALPHA0] = alpha0
    constants[SOLAR0] = (1 - eccentricity0**2) ** -1.5
    constants[GEODESIC] = geodesic_rate(semi_major_axis_km, c_km_d)
    constants[FIGURE] = -1.0
    constants[SOLAR_TIDE] = solar_tide_rad_d
    constants[MEAN_MOTION] = math.sqrt(gm_km3_d2("sun") / semi_major_axis_km**3) / spin_rad_d
    return (np.ascontiguousarray(grid, dtype=float), float(t0), float(h), constants)


def solar_tide(k2, q, gm_planet, radius_km, moment, semi_major_axis_km, spin_rad_d):
    """G/(C omega0), 1/day: the Sun's constant-Q tidal torque on a planet (Love number ``k2``, quality factor
    ``q``, polar moment ``moment`` = C/(M R^2)) over its spin angular momentum, on a circular orbit."""
    if not k2 >= 0:
        raise InputError("k2", k2, "a Love number >= 0")
    if not q > 0:
        raise InputError("Q", q, "a tidal quality factor > 0")
    gm_sun = gm_km3_d2("sun")
    return (1.5 * k2 / q * gm_sun**2 * radius_km**3 / (gm_planet * moment * semi_major_axis_km**6)
            / spin_rad_d)


def layout(planet):
    """The state's layout for ``planet`` ("earth", "mars")."""
    return Layout([(f"{planet}.spin", 3, "vector", "unit spin axis, inertial (ICRF/GCRS) axes"),
                   ("moon.distance", 1, "vector", "a_m / a_m0 (1: no large moon)"),
                   (f"{planet}.rotation", 1, "vector", "omega / omega0")])


class AveragedSpin(Ode):
    """The averaged equations as the integrator door runs them (integrators.simulate), from J2000; ``orbit(t)``
    gives the orbit's normal and eccentricity vector at output times as the rhs sees them."""

    def orbit(self, t):
        grid, t0, h, _ = self.params
        return orbit_series(t, grid, t0, h)


def averaged_spin(params, spin_axis, planet="earth"):
    """The equations with ``params`` (from :func:`parameters` or :func:`planet_parameters`), started at J2000
    on ``spin_axis``."""
    return AveragedSpin(rhs, params, 0.0, start_state(spin_axis), layout(planet), name=f"{planet}_deep_time")


def start_state(spin_axis):
    """y0: the unit spin axis, the Moon at today's distance, the Earth at today's rotation."""
    s = np.asarray(spin_axis, dtype=float)
    return np.array([*(s / np.linalg.norm(s)), 1.0, 1.0])


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _rotate(v, axis, angle):
    """Rodrigues: rotate vectors v (k, 3) about unit axes (k, 3) by angles (k,)."""
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return v * c + np.cross(axis, v) * s + axis * np.sum(axis * v, axis=1, keepdims=True) * (1 - c)


def _angle_in_plane(a, b, normal):
    """Angle (rad) from a to b about ``normal`` (vectors (k, 3))."""
    return np.arctan2(np.sum(np.cross(a, b) * normal, axis=1), np.sum(a * b, axis=1))


def climate_angles(spin_axis, normal, eccentricity_vector, spin_axis0, normal0):
    """La2004's quantities from the spin axis s, the orbit normal n and eccentricity vector (k, 3), inertial:

    obliquity (rad) = angle(s, n); perihelion_longitude (rad, [0, 2 pi)) = varpi_bar, the angle in the orbit
    plane from the equinox of date (s x n) to the perihelion, in the sense of the motion; precession (rad,
    unwrapped) = psi, the angle from the equinox of date to the J2000 equinox (s0 x n0) carried into the orbit
    plane by the rotation about the node of the orbit on the J2000 one, so that varpi_bar = varpi + psi with
    varpi the longitude of perihelion from the J2000 equinox (Laskar et al. 2004, sect. 3: psi the general
    precession in longitude).
    """
    s, n = _unit(np.atleast_2d(spin_axis)), _unit(np.atleast_2d(normal))
    perihelion = np.atleast_2d(eccentricity_vector)
    perihelion = _unit(perihelion - n * np.sum(perihelion * n, axis=1, keepdims=True))
    equinox = _unit(np.cross(s, n))
    n0 = np.broadcast_to(_unit(np.asarray(normal0, dtype=float)), n.shape)
    equinox0 = np.broadcast_to(_unit(np.cross(spin_axis0, normal0)), n.shape)
    node = np.cross(n0, n)
    size = np.linalg.norm(node, axis=1)
    inclination = np.arctan2(size, np.sum(n0 * n, axis=1))
    node = np.where(size[:, None] > 0, node / np.where(size > 0, size, 1.0)[:, None], 0.0)
    origin = _rotate(equinox0, node, inclination)
    return {"obliquity": np.arccos(np.clip(np.sum(s * n, axis=1), -1, 1)),
            "perihelion_longitude": np.mod(_angle_in_plane(equinox, perihelion, n), 2 * np.pi),
            "precession": np.unwrap(_angle_in_plane(equinox, origin, n))}
