"""The Earth: figure, its secular change, rotation and tides.

IAU 2006 precession (Capitaine, Wallace & Chapront 2003, "P03"): H_d = (C - A)/C and J2 with
its rate.  The DE421 header (bodies.de421_header) has J2E at RE, which DE421 lets act on the
Moon's figure (terms.figure_figure), and the Earth's tides (``de421_tides``).  Triaxiality:
EGM2008 C22 with C/(M a^2) = 0.3307.
Rotation: the Earth rotation angle rate (IERS Conventions 2010, eq. 5.15); geodesic
precession (de Sitter) of the dynamical frame against the GCRS (IERS Conventions 2010, §5.6.4).
"""
import math

from .de421_header import header

H_D = 3.27379448e-3                      # (C - A)/C, IAU 2006 (P03)
J2 = 1.0826359e-3                        # IAU 2006 (P03)
J2_RATE_PER_CY = -3.001e-9               # dJ2/dt, P03
J4 = -3.0 * 5.39965866638991e-7          # -C40 = -3 C40_bar, EGM2008 (Pavlis et al. 2012, JGR 117, B04406)
C_MR2 = 0.3307                           # C/(M a^2) (IERS Conventions 2010, ch. 1; Groten 2004: 0.3307007)
EQUATORIAL_RADIUS_KM = 6378.1366         # a, IERS Conventions 2010 Table 1.1
B_MINUS_A_OVER_C = 1.904e-5              # 4 C22 / (C/MR^2), EGM2008 C22 = 1.5745e-6, C/MR^2 = 0.3307
A_AXIS_LONGITUDE_DEG = -14.93            # longitude of the axis of least moment (EGM2008 C22, S22)
ERA_RATE_RAD_D = 2 * math.pi * 1.00273781191135448   # Earth rotation angle rate, rad per UT1 day
GEODESIC_PRECESSION_ARCSEC_CY = 1.919883  # rate of the dynamical frame w.r.t. GCRS, prograde
# Tidal dissipation's own rate of the obliquity, ~ sin(eps) cos(eps): +2.4 mas/cy (Williams 1994, AJ 108,
# 711; Capitaine et al. 2003, A&A 412, 567, Table 3 "tides (c)"): the tides tilt the axis away from the
# ecliptic pole.
TIDAL_OBLIQUITY_RATE_ARCSEC_CY = 0.0024


def de421_tides():
    """The Earth's tides of DE421, per band (0 zonal, 1 diurnal, 2 semi-diurnal): {band: (k2, time delay d)}
    from the header's K2E0/1/2 and TAUE0/1/2 (Folkner et al. 2014, IPN PR 42-196, the tidal acceleration)."""
    h = header()
    return {band: (h[f"K2E{band}"], h[f"TAUE{band}"]) for band in (0, 1, 2)}
