"""The IAU 2006/2000A celestial intermediate pole from ERFA (pyerfa), and angles of any pole.

Times are TDB days from J2000.0; ERFA wants TT, which differs from TDB by at
most 1.7 ms (the pole moves < 1e-9 mas in that time), so TDB is passed as TT.
Angles in rad.  Fukushima-Williams angles (ERFA pfw06): gamma_bar, phi_bar
place the IAU 2006 ecliptic of date in GCRS; psi (precession + nutation in
longitude) and eps (obliquity) place an equator on it (P03, Capitaine et al. 2003).
"""
import numpy as np

from ..base.constants import J2000_JD
from .base import Comparable

PSI_A_RATE_ARCSEC_CY = 5038.481507       # IAU 2006 precession in longitude psi_A, fixed J2000 ecliptic
EPS0_ARCSEC = 84381.406                  # IAU 2006 obliquity at J2000

# Main IAU 2000A luni-solar nutation terms (IERS Conventions 2010, Table 5.3a): name -> (dpsi sin, deps cos),
# arcsec at J2000.
IAU2000A_MAIN_ARCSEC = {"18.6 yr": (-17.2064161, 9.2052331), "0.5 yr": (-1.3170906, 0.5730336),
                        "13.66 d": (-0.2276413, 0.0978459)}

# Arguments fitted to a nutation series, in order of precedence: name -> multipliers of the Delaunay
# arguments (l, l', F, D, Om) of references.arguments.
NUTATION_ARGUMENTS = {
    "18.6 yr": (0, 0, 0, 0, 1), "9.3 yr": (0, 0, 0, 0, 2), "1 yr": (0, 1, 0, 0, 0),
    "0.5 yr": (0, 0, 2, -2, 2), "121.7 d": (0, 1, 2, -2, 2), "365.2 d": (0, -1, 2, -2, 2),
    "177.8 d": (0, 0, 2, -2, 1), "27.55 d": (1, 0, 0, 0, 0), "13.66 d": (0, 0, 2, 0, 2),
    "13.63 d": (0, 0, 2, 0, 1), "9.13 d": (1, 0, 2, 0, 2), "31.8 d": (-1, 0, 0, 2, 0),
    "27.09 d": (-1, 0, 2, 0, 2), "14.77 d": (0, 0, 0, 2, 0),
}


class IauPole:
    """The IAU 2006/2000A pole as a ``references.base.Reference``, values in rad: the CIP ``cip_x_rad``,
    ``cip_y_rad`` in GCRS, the mean pole's Fukushima-Williams angles ``psi_bar_rad``, ``eps_a_rad`` and
    the nutation ``dpsi_rad``, ``deps_rad`` (psi = psi_bar + dpsi, eps = eps_A + deps)."""

    name = "IAU 2006/2000A (ERFA)"

    def __call__(self, t_tdb_d):
        import erfa

        t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
        gamma_bar, phi_bar, psi_bar, eps_a = mean_angles(t)
        dpsi, deps = nutation(t)
        x, y = erfa.fw2xy(gamma_bar, phi_bar, psi_bar + dpsi, eps_a + deps)     # = bpn2xy(pnm06a(t)), one nut06a
        return Comparable(t, {"cip_x_rad": x, "cip_y_rad": y, "psi_bar_rad": psi_bar, "eps_a_rad": eps_a,
                              "dpsi_rad": dpsi, "deps_rad": deps}, provenance())


def provenance():
    """Where the IAU 2006/2000A pole comes from: library and version, citations, span."""
    import erfa

    return {"name": "IAU 2006 precession + IAU 2000A nutation: CIP X, Y = bpn2xy(pnm06a)",
            "data": f"pyerfa {erfa.__version__} (ERFA {erfa.version.erfa_version})",
            "citation": "IERS Conventions (2010), ch. 5 (Petit & Luzum, IERS TN 36); Capitaine, Wallace & "
                        "Chapront (2003), A&A 412, 567 (P03); Mathews, Herring & Buffett (2002), JGR 107 (MHB2000)",
            "span": "series in time from J2000: no hard limit"}


def _jd(t_tdb_d):
    return J2000_JD, np.asarray(t_tdb_d, dtype=float)


def npb_matrix(t_tdb_d):
    """IAU 2006/2000A bias-precession-nutation matrices GCRS -> true equator of date, (n, 3, 3)."""
    import erfa

    return erfa.pnm06a(*_jd(t_tdb_d))


def cip_xy(t_tdb_d):
    """CIP X, Y in GCRS (rad): ERFA ``bpn2xy(pnm06a(t))``."""
    import erfa

    return erfa.bpn2xy(npb_matrix(t_tdb_d))


def cip_vector(t_tdb_d):
    """Unit CIP vector(s) in GCRS: third row of the NPB matrix."""
    return npb_matrix(t_tdb_d)[..., 2, :]


def terrestrial_x_axis(t_tdb_d):
    """x axis of the terrestrial intermediate frame (TIRS) in GCRS, with UT1 taken as TDB.

    Only the phase of the daily spin depends on it (a triaxial Earth's A axis);
    UT1 = TDB misplaces that phase by Delta T (about a minute, 0.3 deg).
    """
    import erfa

    jd = _jd(t_tdb_d)
    x, y = cip_xy(t_tdb_d)
    c2t = erfa.c2tcio(erfa.c2ixys(x, y, erfa.s06(*jd, x, y)), erfa.era00(*jd), np.eye(3))
    return c2t[..., 0, :]


def ecliptic_pole_j2000():
    """Unit pole of the IAU 2006 ecliptic of J2000 in GCRS (ERFA ecm06 at J2000)."""
    import erfa

    return erfa.ecm06(J2000_JD, 0.0)[2]


def mean_angles(t_tdb_d):
    """IAU 2006 Fukushima-Williams angles (gamma_bar, phi_bar, psi_bar, eps_A), rad (ERFA pfw06)."""
    import erfa

    return erfa.pfw06(*_jd(t_tdb_d))


def nutation(t_tdb_d):
    """IAU 2000A nutation (dpsi, deps), rad, as used with IAU 2006 precession (ERFA nut06a)."""
    import erfa

    return erfa.nut06a(*_jd(t_tdb_d))


def pole_angles(t_tdb_d, pole_gcrs):
    """Fukushima-Williams (psi, eps) of pole directions (n, 3) on the IAU 2006 ecliptic of date.

    With gamma_bar, phi_bar from pfw06, the pole in ecliptic-of-date axes
    R1(phi_bar) R3(gamma_bar) z is (sin eps sin psi, sin eps cos psi, cos eps)
    (the third row of ERFA's fw2m).  For the IAU pole psi = psi_bar + dpsi,
    eps = eps_A + deps.
    """
    gamb, phib, _, _ = mean_angles(t_tdb_d)
    z = np.asarray(pole_gcrs, dtype=float)
    x1 = np.cos(gamb) * z[:, 0] + np.sin(gamb) * z[:, 1]
    y1 = -np.sin(gamb) * z[:, 0] + np.cos(gamb) * z[:, 1]
    y2 = np.cos(phib) * y1 + np.sin(phib) * z[:, 2]
    z2 = -np.sin(phib) * y1 + np.cos(phib) * z[:, 2]
    psi = np.unwrap(np.arctan2(x1, y2))
    eps = np.arctan2(np.hypot(x1, y2), z2)
    return psi, eps


def pole_from_angles(t_tdb_d, psi, eps):
    """Unit pole(s) in GCRS, (3,) or (n, 3), with Fukushima-Williams angles (psi, eps) (inverse of pole_angles)."""
    gamb, phib, _, _ = mean_angles(t_tdb_d)
    x1, y2, z2 = np.sin(eps) * np.sin(psi), np.sin(eps) * np.cos(psi), np.cos(eps)
    y1 = np.cos(phib) * y2 - np.sin(phib) * z2
    z = np.sin(phib) * y2 + np.cos(phib) * z2
    return np.stack([np.cos(gamb) * x1 - np.sin(gamb) * y1, np.sin(gamb) * x1 + np.cos(gamb) * y1, z], axis=-1)


def about_mean_pole(t_tdb_d, pole_gcrs):
    """(psi - psi_bar, eps - eps_A), rad: Fukushima-Williams angles of poles (n, 3) about the IAU 2006 mean
    pole (for the IAU pole, the nutation dpsi, deps)."""
    psi, eps = pole_angles(t_tdb_d, pole_gcrs)
    _, _, psi_bar, eps_a = mean_angles(t_tdb_d)
    return psi - psi_bar, eps - eps_a


def from_mean_pole(t_tdb_d, dpsi, deps):
    """Unit poles in GCRS at angles (dpsi, deps) rad from the IAU 2006 mean pole (inverse of about_mean_pole)."""
    _, _, psi_bar, eps_a = mean_angles(t_tdb_d)
    return pole_from_angles(t_tdb_d, psi_bar + dpsi, eps_a + deps)
