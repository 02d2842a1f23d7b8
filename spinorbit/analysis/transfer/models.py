"""The published transfer functions: MHB2000's own (the default), the IERS 1996 factors, the two-layer Earth.

* ``MHB2000``: MHB2000's transfer function (Mathews, Herring & Buffett 2002, JGR 107(B4) 2068) at the
  nutation frequencies of ``mhb2000_table`` (there, its value; with MHB2000's add-on terms), relative to
  REN-2000's rigid amplitudes (H = ``mhb2000_table.RIGID_H``); between them the resonance form fitted to
  those values (``fit_resonance``, weighted by REN-2000's amplitudes, since a tabulated T carries the
  files' 0.05-prad rounding over it) with MHB2000's own free modes held at their published frequencies:
  the Chandler wobble, the free core nutation and the free inner-core nutation.
* ``IERS1996``: T. Herring's resonance factors of the KSV_1996_3 series (the IERS Conventions 1996 series:
  KSRE95 rigid Earth times this function).
* ``TWO_LAYER``: the two-layer Earth (forms.EarthParameters) with MHB2000's parameters.
"""
import numpy as np

from ...bodies.earth import H_D
from . import mhb2000_table
from .forms import EarthParameters, Mode, ResonanceExpansion, Tabulated, fit_resonance

# MHB2000 normal modes, cpsd, terrestrial frame, in this package's convention: IERS Conventions 2010
# Tables 6.4 and 7.1 list them for tidal frequencies (-0.0026010 - 0.0001361i, 1.0023181 + 0.000025i and
# the free inner-core nutation 0.999026 + 0.000780i), i.e. as -conj(sigma); read in copies of those tables
# in public code (e.g. L. Petrov's love_numbers.i, "taken from the IERS Conventions 2000", whose FICN reads
# 0.99026, a dropped digit: 0.999026 in Mathews 2001's set beside it, 0.998935).  FCN period in space:
# -1/(0.0023181 * 1.0027379) = -430.21 solar days, the "conventional -431.39 sidereal days" of Krasna et
# al. 2013 (A&A 555, A29); Q = 1.0023181 / (2 Im) = 20 000, beside VLBI's 15 400-19 500 (the compilation
# in Table 1 of "Parameters of the Earth's Free Core Nutation from Diurnal Strain Tides", Sci. Rep. 10,
# 2020, doi:10.1038/s41598-020-66426-7).  FICN: +1024 d (prograde) in space.
PUBLISHED_CHANDLER_CPSD = 0.0026010 + 0.0001361j
PUBLISHED_FCN_CPSD = -1.0023181 + 0.000025j
PUBLISHED_FICN_CPSD = -0.999026 + 0.000780j
MHB2000_MODES = {"CW": PUBLISHED_CHANDLER_CPSD, "FCN": PUBLISHED_FCN_CPSD, "FICN": PUBLISHED_FICN_CPSD}


PRAD = 1e-12


def mhb2000_transfer(rows=mhb2000_table.ROWS, rigid_h=mhb2000_table.RIGID_H):
    """The Tabulated transfer function of ``rows`` (mhb2000_table's layout), resonance form fitted between."""
    table = np.array([row[2:] for row in rows])
    sigma, values, weights = table[:, 0] - 1.0, table[:, 1] + 1j * table[:, 2], table[:, 5]
    between = fit_resonance(sigma, values, weights, MHB2000_MODES, rigid_h)
    return Tabulated(sigma, values, (table[:, 3] + 1j * table[:, 4]) * PRAD, between, rigid_h)


MHB2000 = mhb2000_transfer()

# e: the rigid model's H_d = (C - A)/C (P03: Capitaine, Wallace & Chapront 2003, A&A 412, 567) as
#   (C - A)/A, 0.0032845474; MHB 2002's e = 0.0032845479 gives H_d = 0.0032737950 (rate effect 7e-4"/cy).
# A_f/A: PREM's fluid outer core (Dziewonski & Anderson 1981, PEPI 25, 297: outer-core density
#   12.5815 - 1.2638 x - 3.6426 x^2 - 5.5281 x^3 g/cm^3, x = r / 6371 km, 1221.5-3480 km, integrated in
#   spherical shells: 9.066e36 kg m^2) over the Earth's A = C (1 - H_d), with C/(M a^2) = 0.3307,
#   GM = 398600.4418 km^3/s^2, G = 6.67430e-11, a = 6378.1366 km: 8.008e37 kg m^2.  Recomputed: 0.11321.
# e_f = 0.0026456 and K_CMB = 2.23e-5 - 1.85e-5 i (MHB 2002's estimates from VLBI: e_f above its
#   hydrostatic value, Im K_CMB the electromagnetic dissipation at the core-mantle boundary) and the
#   elastic PREM compliances kappa, xi, gamma, beta (Mathews et al. 1991, JGR 96, 8219, as used by MHB
#   2002) are the values as recalled from those papers: NOT checked against their tables, which were
#   out of reach when this was written.  e_f has a secondary source: the IERS EOP Product Center's
#   constants page lists core moments A_f = 9.1152379e36, C_f = 9.1393530e36 kg m^2, (C_f - A_f)/A_f
#   = 0.0026456.  What checks them is indirect: the free core nutation and the main terms they give.
TWO_LAYER = EarthParameters(e=H_D / (1.0 - H_D), e_f=0.0026456, a_f=0.1132,
                            kappa=1.0340e-3, xi=2.2204e-4, gamma=1.9662e-3, beta=6.1600e-4,
                            k_cmb=2.23e-5 - 1.85e-5j)
RIGID = EarthParameters(e=H_D / (1.0 - H_D), e_f=0.0, a_f=0.0, kappa=0.0, xi=0.0, gamma=0.0, beta=0.0,
                        k_cmb=0.0)

# T. Herring's resonance factors of the KSV_1996_3 nutation series (the IERS Conventions 1996 series,
# McCarthy 1996, IERS TN 21, ch. 5), as printed in the header of his public Fortran routine KSV_1996_3
# ("The resonance factors used are: Type / Amplitude / Frequency (cpsd)"), from "the Mathews et al.
# nutation formulation (full complex estimates, and scaling parameter R from the same theory)" (Mathews,
# Buffett, Herring & Shapiro 1991, JGR 96, 8219):
#     RFCN      -.00011489752  .00000214130   -1.00231888314  -.00002920327
#     CW        -.00057992000  .00000000000     .00253170000   .00000000000
#     R and R'  1.04901828112 -.00150732471    -.25517427386   .03965769073   (R; R' in the frequency slot)
# The routine writes its complex numbers with the opposite sign of i to this package's exp(i sigma Omega t):
# its FCN grows (Im s < 0).  Every value is therefore taken conjugated, which makes the FCN decay, as the
# two-layer model's FCN does (Im K_CMB < 0); the out-of-phase terms it then gives have IAU 2000A's signs.
# FCN period in space -430.06 d, Chandler wobble 393.9 d (no ocean: MHB2000's is 383.4 d).
IERS1996 = ResonanceExpansion(r=1.04901828112 + 0.00150732471j, r_prime=-0.25517427386 - 0.03965769073j,
                              modes=(Mode("CW", 0.0025317 + 0j, -0.00057992 + 0j),
                                     Mode("FCN", -1.00231888314 + 0.00002920327j,
                                          -0.00011489752 - 0.00000214130j)))

MODELS = {"mhb2000": MHB2000, "iers1996": IERS1996, "two_layer": TWO_LAYER}
