"""Mercury: mass, degree-2 figure, moments and spin state, from the published measurements.

GM: DE421 header (GM1; ``de421_header.gm_km3_d2("mercury")``).  Degree-2 gravity: Verma & Margot
2016 (JGR Planets 121, 1627), normalised C20 = -2.25100e-5, C22 = 1.24973e-5 (here unnormalised: J2 = -sqrt(5) C20,
C22 = sqrt(5/12) C22_bar).  Moments and spin: Margot et al. 2012 (JGR 117, E00L09):
C/(M R^2) = 0.346 +- 0.014 (from the obliquity, the Cassini state), C_m/C = 0.431 +- 0.025
(the librating shell, from the libration amplitude itself), forced libration amplitude
38.5 +- 1.6 arcsec, obliquity 2.04 +- 0.08 arcmin.  Radius: 2439.4 km (IAU WGCCRE 2015).
Stark et al. 2015 (GRL 42, 7881), laser altimetry: libration 38.9 +- 1.3 arcsec, obliquity 2.029 +- 0.085 arcmin.
The degree-2 field is Verma & Margot's reanalysis of MESSENGER's tracking, which confirms the HgM005 field of
Mazarico et al. 2014 (JGR Planets 119, 2417) to better than 0.4 %.
The orbit's Laplace plane: Mercury's orbit precesses about its pole at about 8.6 deg inclination in ~300 kyr
(Yseboodt & Margot 2006, Icarus 181, 327); the inclination enters Peale's equation only through cot i.
"""
import math

RADIUS_KM = 2439.4
J2 = math.sqrt(5.0) * 2.25100e-5
C22 = math.sqrt(5.0 / 12.0) * 1.24973e-5
C_MR2 = 0.346
C_MANTLE_OVER_C = 0.431
LIBRATION_AMPLITUDE_ARCSEC = (38.5, 1.6)
OBLIQUITY_ARCMIN = (2.04, 0.08)
STARK_2015 = {"libration_arcsec": (38.9, 1.3), "obliquity_arcmin": (2.029, 0.085)}
LAPLACE_INCLINATION_DEG = 8.6


def moments():
    """(A, B, C) in units of M R^2 from J2, C22 and C/(M R^2) (J2 = (C - (A + B)/2)/(M R^2), C22 =
    (B - A)/(4 M R^2))."""
    return (C_MR2 - J2 - 2.0 * C22, C_MR2 - J2 + 2.0 * C22, C_MR2)


def b_minus_a_over_c():
    """(B - A)/C of the whole planet from gravity and the obliquity's C/MR^2: 4 C22 / (C/MR^2)."""
    return 4.0 * C22 / C_MR2

