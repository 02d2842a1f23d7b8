"""Mars: mass, degree-2 figure, moment, rotation, mean orbit and satellites, from the published measurements.

GM: the DE421 header's GM4 (Mars's system, Phobos and Deimos included: they add 1.9e-8 of it;
``table.gm_km3_d2("mars")``).  Degree-2 gravity: MRO120D (Konopliv et al. 2016, Icarus 274, 253; PDS
MRO-M-RSS-5-SDP-V1, jgmro_120d_sha.tab), fully normalised C20 = -8.750220925e-4, C22 = -8.458e-5,
S22 = 4.894e-5 at 3396.0 km, here unnormalised: J2 = -sqrt(5) C20, C22 = sqrt(5/12) |C22 + i S22| (the
sectoral term's size, about the A axis).  Polar moment C/(M R^2) = 0.36367 +- 0.00010 (Baland et al. 2020,
CMDA 132, 47, doi:10.1007/s10569-020-09986-0: their rigid-Mars model BMAN20 fitted to Konopliv et al. 2016's
rate with MRO120D's J2, giving H_D = (C - (A+B)/2)/C = 0.00538017 +- 0.00000148).  It is normalised at the same
R = 3396 km as J2 here: J2 / H_D = 0.363670.  The moment is thus itself derived from the measured rate by an
independent rigid model; the rate this package predicts from it tests the torques against theirs, not against an
observation.  Konopliv et al. 2011 (Icarus 211, 401) found 0.3644 +- 0.0005 at 3396 km from their rate -7594 +-
10 mas/yr (C_MR2_KONOPLIV_2011; ``mars.c_mr2`` takes any).  Measured precession rate -7608.3 +- 2.1 mas/yr and
k2 = 0.169 +- 0.006 (Konopliv et al. 2016).  Rotation: IAU 2015
(Archinal et al. 2018, CMDA 130:22, from Kuchynka et al. 2014, Icarus 229, 340): W = 176.049863 deg +
350.891982443297 deg/d at J2000; the pole, a series (spinorbit.references.mars_iau2015), is at (317.6809,
52.8864) deg at J2000.  The mean orbit of J2000 the precession angles refer to (node on the ICRF
equator N, inclination J) and Mars's mean anomaly: Konopliv et al. 2006 (Icarus 182, 23, §6).
Satellites (their mean orbits about Mars's equator): GM Phobos 7.087e-4, Deimos 9.62e-5 km^3/s^2 (Jacobson &
Lainey 2014, Planet. Space Sci. 102, 35), semi-major axes 9376 and 23458 km (Jacobson 2010, AJ 139, 668).
"""
import math

from ..base.constants import DAY_S

RADIUS_KM = 3396.0                        # reference radius of MRO120D
J2 = math.sqrt(5.0) * 8.750220925e-4       # MRO120D
C22 = math.sqrt(5.0 / 12.0) * math.hypot(8.458e-5, 4.894e-5)   # MRO120D, unnormalised sectoral size
A_AXIS_LONGITUDE_DEG = 0.5 * math.degrees(math.atan2(4.894e-5, -8.458e-5))   # least moment's axis, 75 deg E
C_MR2 = 0.36367                           # C/(M R^2) at 3396 km, Baland et al. 2020 (from Konopliv 2016's rate)
C_MR2_SIGMA = 0.00010
H_D_BALAND_2020 = 0.00538017              # Baland et al. 2020's dynamical flattening (C - (A+B)/2)/C
C_MR2_KONOPLIV_2011 = 0.3644              # +- 0.0005, Konopliv et al. 2011 (from their rate -7594 mas/yr)
K2 = 0.169                                # potential Love number, Konopliv et al. 2016
PRECESSION_RATE_MAS_YR = (-7608.3, 2.1)   # Konopliv et al. 2016, about the J2000 mean orbit's pole

W0_DEG = 176.049863                       # prime meridian at J2000, IAU 2015
ROTATION_RATE_DEG_D = 350.891982443297    # IAU 2015 (Kuchynka et al. 2014)
ROTATION_RATE_RAD_D = math.radians(ROTATION_RATE_DEG_D)

MEAN_ORBIT_NODE_DEG = 3.37919183          # N: the J2000 mean orbit's node on the ICRF equator, Konopliv 2006
MEAN_ORBIT_INCLINATION_DEG = 24.67682669  # J: its inclination to the ICRF equator, Konopliv 2006
MEAN_ANOMALY_J2000_DEG = 19.3564          # Konopliv 2006
MEAN_MOTION_DEG_D = 0.52403958828         # Konopliv 2006
MEAN_ECCENTRICITY = 0.0934                # J2000 mean orbit (Simon et al. 1994, A&A 282, 663: 0.09340065)
MEAN_SEMI_MAJOR_AXIS_KM = 1.52367934 * 149597870.7   # Simon et al. 1994

# (name, GM km^3/d^2, semi-major axis km): the satellites whose orbits stay on Mars's equator.
SATELLITES = (("phobos", 7.087e-4 * DAY_S ** 2, 9376.0), ("deimos", 9.62e-5 * DAY_S ** 2, 23458.0))


def moments():
    """(A, B, C) in units of M R^2 from J2, C22 and C/(M R^2) (J2 = (C - (A + B)/2)/(M R^2), C22 =
    (B - A)/(4 M R^2))."""
    return (C_MR2 - J2 - 2.0 * C22, C_MR2 - J2 + 2.0 * C22, C_MR2)


def dynamical_ellipticity(c_mr2=C_MR2):
    """(C - (A + B)/2)/C = J2 / (C/(M R^2))."""
    return J2 / c_mr2
