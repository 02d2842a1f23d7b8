"""JPL DE421 lunar orientation (edge module); the lunar constants are spinorbit.bodies.moon's.

Two independent routes to the DE421 mantle orientation (JPL 3-1-3 angles
phi, theta, psi: ICRF -> lunar principal axes, M = Rz(psi) Rx(theta) Rz(phi)):

* :func:`librations` — the ``de421`` package's Chebyshev arrays
  (``jpl-librations.npy``: shape (records x 4 sub-intervals, 3 angles, 10
  coefficients), 8-day sub-intervals from ``jalpha`` = JD 2414992.5), evaluated with
  ``numpy.polynomial.chebyshev``;
* :func:`pck_matrix` — NAIF's binary PCK ``moon_pa_de421_1900-2050.bpc`` with the
  frame kernel ``moon_080317.tf`` (both shipped by ``lunarsky``), through skyfield's
  ``PlanetaryConstants`` (frame ``MOON_PA_DE421``).

References: Williams, Boggs & Folkner
(2008), JPL IOM 335-JW,DB,WF-20080314-001 "DE421 lunar orbit, physical librations
and surface coordinates"; Folkner et al. (2014), IPN PR 42-196 (the equations).
Times: TDB days from J2000.0.
"""
from functools import cache
from pathlib import Path

import numpy as np
from numba import njit
from numpy.polynomial import chebyshev

from ..bodies.de421_header import header
from ..bodies.moon import de421 as moon_constants
from ..constants import J2000_JD
from ..errors import EphemerisRangeError
from ..rotations import cross3, dot3, matrix_from_euler313, omega_body_from_euler313_rates
from .base import Comparable

FREE_LIBRATION_LONGITUDE_PERIOD_D = 1056.16     # DE421's free libration in longitude (Yang et al. 2017)


def _de421_dir():
    import de421

    return Path(de421.__file__).parent


@cache
def _libration_series():
    return np.load(_de421_dir() / "jpl-librations.npy")


def libration_span():
    """(start, end) TDB days from J2000 covered by the de421 libration arrays."""
    h = header()
    return h["jalpha"] - J2000_JD, h["jomega"] - J2000_JD


def librations(t_tdb_d):
    """DE421 mantle angles (n, 3) rad and their rates (n, 3) rad/day at TDB days ``t``.

    psi is continuous (not reduced modulo 2 pi), as in the ephemeris.
    """
    t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
    series = _libration_series()
    start, end = libration_span()
    if t.min() < start or t.max() > end:
        raise EphemerisRangeError("de421 librations", f"{t.min():.6g} to {t.max():.6g}", (start, end))
    length = (end - start) / series.shape[0]                       # 8 days
    index = np.minimum(((t - start) // length).astype(int), series.shape[0] - 1)
    x = 2.0 * (t - start - index * length) / length - 1.0
    coeffs = series[index]                                         # (n, 3, 10)
    angles = np.empty((t.size, 3))
    rates = np.empty((t.size, 3))
    for k in range(3):
        c = coeffs[:, k, :].T                                      # (10, n): one series per time
        angles[:, k] = chebyshev.chebval(x, c, tensor=False)
        rates[:, k] = chebyshev.chebval(x, chebyshev.chebder(c), tensor=False) * 2.0 / length
    return angles, rates


def orientation(t_tdb_d):
    """DE421 ICRF-to-body matrices (n, 3, 3) and body angular velocities (n, 3) rad/day."""
    angles, rates = librations(t_tdb_d)
    return matrix_from_euler313(*angles.T), omega_body_from_euler313_rates(angles, rates)


class Orientation:
    """DE421's lunar mantle orientation as a ``references.base.Reference``.

    Values: ``icrf_to_body`` (n, 3, 3), ``angles_rad`` (n, 3) the JPL 3-1-3 angles
    (phi, theta, psi), ``omega_body_rad_d`` (n, 3) the body angular velocity.
    """

    name = "DE421"

    def __call__(self, t_tdb_d):
        angles, rates = librations(t_tdb_d)
        return Comparable(np.atleast_1d(np.asarray(t_tdb_d, dtype=float)),
                          {"icrf_to_body": matrix_from_euler313(*angles.T), "angles_rad": angles,
                           "omega_body_rad_d": omega_body_from_euler313_rates(angles, rates)}, provenance())


def provenance():
    """Where DE421's lunar orientation comes from: data package and version, citation, span."""
    from importlib.metadata import version

    start, end = libration_span()
    return {"name": "JPL DE421 lunar mantle orientation (Chebyshev libration angles)",
            "data": f"de421 {version('de421')} (jpl-librations.npy, constants.npy)",
            "citation": "Williams, Boggs & Folkner (2008), JPL IOM 335-JW,DB,WF-20080314-001; "
                        "Folkner et al. (2014), IPN Progress Report 42-196",
            "span_jd_tdb": [start + J2000_JD, end + J2000_JD]}


def _pck_paths():
    import importlib.resources

    data = importlib.resources.files("lunarsky") / "data"
    return (str(data / "fk" / "satellites" / "moon_080317.tf"),
            str(data / "pck" / "moon_pa_de421_1900-2050.bpc"))


@cache
def _pck_frame():
    from skyfield.api import load
    from skyfield.planetarylib import PlanetaryConstants

    text, binary = _pck_paths()
    pc = PlanetaryConstants()
    pc.read_text(load.open(text))
    pc.read_binary(load.open(binary))
    return pc.build_frame_named("MOON_PA_DE421")


@cache
def pck_span():
    """(start, end) TDB days from J2000 covered by the NAIF lunar PCK."""
    from jplephem.pck import PCK

    pck = PCK.open(_pck_paths()[1])
    try:
        return (max(s.initial_jd for s in pck.segments) - J2000_JD,
                min(s.final_jd for s in pck.segments) - J2000_JD)
    finally:
        pck.close()


def pck_matrix(t_tdb_d):
    """ICRF-to-MOON_PA_DE421 matrices (n, 3, 3) from the NAIF PCK via skyfield."""
    from skyfield.api import load

    t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
    start, end = pck_span()
    if t.min() < start or t.max() > end:
        raise EphemerisRangeError("moon_pa_de421 PCK", f"{t.min():.6g} to {t.max():.6g}", (start, end))
    times = load.timescale().tdb_jd(J2000_JD, t)
    return np.moveaxis(_pck_frame().rotation_at(times), -1, 0).reshape(t.size, 3, 3)


def initial_state(t_tdb_d, core=False):
    """DE421's Moon at ``t_tdb_d``: [q (body -> ICRF), w_m (body axes, rad/d)] and, with ``core``, the core's w_c."""
    from ..rotations import quat_from_euler313

    y0 = np.concatenate([quat_from_euler313(*librations([t_tdb_d])[0][0]), orientation([t_tdb_d])[1][0]])
    return np.concatenate([y0, core_angular_velocity(t_tdb_d)]) if core else y0


def core_angular_velocity(t_tdb_d, step_d=0.25):
    """DE421's fluid-core angular velocity at TDB day ``t``, mantle axes, rad/day.

    The header gives it at JDEPOC only (OMGCX/Y/Z).  Carried from JDEPOC to t by the
    core's equation (Folkner et al. 2014) driven by DE421's own mantle, in inertial
    axes: d(I_c w_c)/dt = -k_v (w_c - w_m) - (C_c - A_c) (z.w_c) (z x w_c), with
    I_c = A_c 1 + (C_c - A_c) z z^T about the mantle pole z, A_c = C_c (1 - COBLAT);
    k_v/C_c = KVC/IFAC (128 yr), free core precession (C_c - A_c)/C_c w ~ 200 yr.
    Classical RK4 on a ``step_d`` grid of DE421 samples (steps of 2 step_d).
    """
    c = moon_constants()
    t0 = c.epoch_tdb_d
    m0, _ = orientation([t0])
    wc = m0[0].T @ c.omega_core0_rad_d                           # ICRF
    if t_tdb_d != t0:
        n = 2 * max(1, int(np.ceil(abs(t_tdb_d - t0) / (2 * step_d)))) + 1
        s = np.linspace(t0, t_tdb_d, n)
        mats, omega = orientation(s)
        w_inertial = np.einsum("nji,nj->ni", mats, omega)       # M^T w
        wc = _carry_core(wc, s[1] - s[0], np.ascontiguousarray(mats[:, 2, :]), w_inertial,
                         c.kv_over_c_per_d, c.core_c_over_c, c.core_flattening)
    m_t, _ = orientation([t_tdb_d])
    return m_t[0] @ wc


@njit(cache=True)
def _core_rate(L, z, wm, kv, c_c, a_c):
    """d(I_c w_c)/dt and w_c for the core's angular momentum L about mantle pole z (inertial)."""
    w = L / a_c - (c_c - a_c) / (a_c * c_c) * dot3(z, L) * z
    return -kv * (w - wm) - (c_c - a_c) * dot3(z, w) * cross3(z, w), w


@njit(cache=True)
def _carry_core(wc, h, pole, w_mantle, kv, c_c, f_c):
    """RK4 of the core's angular momentum L = I_c w_c (units of C) over samples h apart."""
    a_c = c_c * (1.0 - f_c)
    L = a_c * wc + (c_c - a_c) * dot3(pole[0], wc) * pole[0]
    for k in range(0, pole.shape[0] - 2, 2):
        k1 = _core_rate(L, pole[k], w_mantle[k], kv, c_c, a_c)[0]
        k2 = _core_rate(L + h * k1, pole[k + 1], w_mantle[k + 1], kv, c_c, a_c)[0]
        k3 = _core_rate(L + h * k2, pole[k + 1], w_mantle[k + 1], kv, c_c, a_c)[0]
        k4 = _core_rate(L + 2 * h * k3, pole[k + 2], w_mantle[k + 2], kv, c_c, a_c)[0]
        L = L + (2 * h / 6.0) * (k1 + 2 * k2 + 2 * k3 + k4)
    return _core_rate(L, pole[-1], w_mantle[-1], kv, c_c, a_c)[1]


def earth_pole(t_start, t_end, step_d=50.0):
    """The Earth's mean pole of date in ICRF (IAU 1976 precession, ERFA pmat76) sampled
    every ``step_d`` days over [t_start, t_end] TDB days: (grid [t0, h], (m, 3)) for
    spinorbit.moon.interpolate_pole.  DE421 turned the Earth with IAU 1976 precession
    (plus nutation, whose 9" is far below what the J2 torque on the Moon can feel)."""
    import erfa

    m = max(2, int(np.ceil((t_end - t_start) / step_d)) + 1)
    t = t_start + step_d * np.arange(m)
    pole = np.array([erfa.pmat76(J2000_JD, ti)[2] for ti in t])
    return np.array([t_start, step_d]), pole
