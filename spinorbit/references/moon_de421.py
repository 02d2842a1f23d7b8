"""JPL DE421 lunar orientation as a reference (edge module); the series are read by spinorbit.bodies.de421_orientation,
the lunar constants are spinorbit.bodies.moon's, DE421's initial states spinorbit.models.start's.

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

import numpy as np

from ..base.constants import J2000_JD
from ..base.errors import EphemerisRangeError
from ..base.rotations import matrix_from_euler313, omega_body_from_euler313_rates
from ..bodies import de421_orientation
from .base import Comparable

FREE_LIBRATION_LONGITUDE_PERIOD_D = 1056.16     # DE421's free libration in longitude (Yang et al. 2017)
# DE421's mean-Earth/polar-axis frame from its principal axes (MOON_ME_DE421 from MOON_PA_DE421): NAIF's
# moon_080317.tf, frame 31007, TKFRAME angles (67.92, 78.56, 0.30) arcsec about the axes (3, 2, 1), from
# Williams, Boggs & Folkner (2008) (the IOM below)
MEAN_EARTH_TK_ANGLES = ((3, 67.92), (2, 78.56), (1, 0.30))     # (axis, arcsec), as the frame kernel lists them


def principal_to_mean_earth():
    """The matrix taking vectors from DE421's principal-axis frame to its mean-Earth/polar-axis frame:
    [-0.30"]_1 [-78.56"]_2 [-67.92"]_3 (frame rotations), what SPICE makes of the TK frame's angles."""
    from ..base.constants import ARCSEC
    from ..base.rotations import frame_rotation

    m = np.eye(3)
    for axis, angle in MEAN_EARTH_TK_ANGLES:
        m = frame_rotation(axis, -angle * ARCSEC) @ m
    return m


def libration_span():
    """(start, end) TDB days from J2000 covered by the de421 libration arrays."""
    return de421_orientation.span()


def librations(t_tdb_d):
    """DE421 mantle angles (n, 3) rad and their rates (n, 3) rad/day at TDB days ``t`` (psi continuous)."""
    return de421_orientation.angles_and_rates(t_tdb_d)


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
        raise EphemerisRangeError("moon_pa_de421 PCK", (t.min(), t.max()), (start, end))
    times = load.timescale().tdb_jd(J2000_JD, t)
    return np.moveaxis(_pck_frame().rotation_at(times), -1, 0).reshape(t.size, 3, 3)


def earth_pole(t_start, t_end, step_d=50.0):
    """The Earth's mean pole of date in ICRF (IAU 1976 precession, ERFA pmat76) sampled
    every ``step_d`` days over [t_start, t_end] TDB days: (grid [t0, h], (m, 3)), the pole table of the
    Earth's J2 acting on the Moon (spinorbit.models.assemblies.moon).  DE421 turned the Earth with IAU 1976 precession
    (plus nutation, whose 9" is far below what the J2 torque on the Moon can feel)."""
    import erfa

    m = max(2, int(np.ceil((t_end - t_start) / step_d)) + 1)
    t = t_start + step_d * np.arange(m)
    pole = np.array([erfa.pmat76(J2000_JD, ti)[2] for ti in t])
    return np.array([t_start, step_d]), pole
