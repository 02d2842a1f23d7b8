"""The non-rigid Earth's nutation: a transfer function applied term by term to the rigid nutation.

Layer 2 (numpy).  The rigid Earth's forced nutation, decomposed into circular
terms on the luni-solar arguments, is multiplied term by term by the ratio T of
the non-rigid to the rigid response at each term's frequency (the route of the
IERS 1996 series and of MHB2000: Mathews, Herring & Buffett 2002, JGR 107(B4) 2068;
IERS Conventions 2010, TN36 §5.5.1).  Time dependence exp(i sigma Omega t),
sigma in cycles per sidereal day (cpsd) in the terrestrial frame: a circular
nutation of celestial frequency nu (cpsd, prograde > 0) is a wobble of
sigma = nu - 1, and its amplitude ratio is T(sigma).

Two transfer functions, one checking the other:

- ``IERS1996`` (the default): the published resonance form
      T(sigma) = R + R' (1 + sigma) + A_CW / (sigma - s_CW) + A_FCN / (sigma - s_FCN)
  with T. Herring's resonance factors of the KSV_1996_3 series (the IERS
  Conventions 1996 nutation series: KSRE95 rigid Earth times this transfer
  function; constants below).  Its free modes are the Chandler wobble s_CW and
  the free core nutation s_FCN.  MHB2000's own resonance strengths (with the free
  inner-core nutation) were not found in any reachable source; see RESULTS.md.
- ``MHB2000``: the two-layer Earth (elastic mantle and fluid core) of Sasao, Okubo
  & Saito (1980) in the form of Mathews, Buffett, Herring & Shapiro (1991, JGR 96,
  8219): the angular momentum of the whole Earth and of the fluid core in the
  terrestrial frame, linearised; m = mantle wobble, m_f = the core's differential
  wobble, phi = the tidal forcing (the rigid Earth's wobble is e phi / (e - sigma)):

    [sigma - e + (1 + sigma) kappa] m + (1 + sigma)(A_f/A + xi) m_f = [(1 + sigma) kappa - e] phi
    sigma (1 + gamma) m + [1 + sigma (1 + beta) + e_f + K_CMB] m_f = sigma gamma phi

  (kappa, xi, gamma, beta: the mantle's and the core's deformation compliances,
  c/A = kappa (m - phi) + xi m_f, c_f/A_f = gamma (m - phi) + beta m_f; K_CMB the
  core-mantle coupling constant).  Its normal modes (Chandler wobble and free core
  nutation) are the roots of the determinant.

MHB2000's nonlinear terms enter only through their published contribution to the
precession rate (``nonlinear_precession``).  Left out: the free inner-core
nutation, and what the transfer functions do not hold (the nonlinear terms'
nutations, the S1 atmospheric tide's prograde annual term).
"""
from dataclasses import dataclass

import numpy as np

from .analysis.spans import resolvable
from .bodies.earth import ERA_RATE_RAD_D, H_D
from .constants import ARCSEC, JULIAN_CENTURY_D


@dataclass(frozen=True)
class EarthParameters:
    """Basic Earth parameters of the two-layer model (dimensionless)."""

    e: float              # dynamical ellipticity (C - A)/A of the whole Earth
    e_f: float            # dynamical ellipticity of the fluid core
    a_f: float            # A_f / A, fluid core over whole Earth
    kappa: float          # mantle compliances (elastic)
    xi: float
    gamma: float          # core compliances (elastic)
    beta: float
    k_cmb: complex        # core-mantle boundary coupling constant

    def transfer(self, sigma):
        """Non-rigid / rigid nutation amplitude at terrestrial frequencies sigma (cpsd), complex, shape of sigma."""
        m, rhs = _matrices(sigma, self)
        if self.a_f == 0.0:                    # no core: the mantle equation alone
            wobble = rhs[..., 0] / m[..., 0, 0]
        else:
            wobble = np.linalg.solve(m, rhs[..., None])[..., 0, 0]
        s = np.atleast_1d(np.asarray(sigma, dtype=complex))
        return (wobble * (self.e - s) / self.e).reshape(np.shape(sigma))

    def normal_modes(self):
        """(Chandler wobble, free core nutation) terrestrial frequencies, cpsd: the roots of det M(sigma)."""
        mantle = np.poly1d([1 + self.kappa, self.kappa - self.e])
        core = np.poly1d([1 + self.beta, 1 + self.e_f + self.k_cmb])
        det = mantle * core - np.poly1d([1.0, 1.0]) * (self.a_f + self.xi) * np.poly1d([1 + self.gamma, 0.0])
        roots = sorted(det.roots, key=lambda r: r.real)
        return complex(roots[1]), complex(roots[0])


@dataclass(frozen=True)
class ResonanceExpansion:
    """A transfer function in resonance form: T(sigma) = R + R' (1 + sigma) + sum over free modes of A / (sigma - s)."""

    r: complex
    r_prime: complex
    chandler: complex             # s_CW, cpsd, terrestrial frame
    chandler_strength: complex    # A_CW
    fcn: complex                  # s_FCN
    fcn_strength: complex         # A_FCN

    def transfer(self, sigma):
        """Non-rigid / rigid nutation amplitude at terrestrial frequencies sigma (cpsd), complex, shape of sigma."""
        s = np.asarray(sigma, dtype=complex)
        return (self.r + self.r_prime * (1 + s) + self.chandler_strength / (s - self.chandler)
                + self.fcn_strength / (s - self.fcn))

    def normal_modes(self):
        """(Chandler wobble, free core nutation) terrestrial frequencies, cpsd: the poles of T."""
        return self.chandler, self.fcn


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
#   = 0.0026456.  What checks them is indirect: the free core nutation and the
#   main terms they give (tests/test_nonrigid.py, benchmarks/RESULTS.md).
MHB2000 = EarthParameters(e=H_D / (1.0 - H_D), e_f=0.0026456, a_f=0.1132,
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
#     R and R'  1.04901828112 -.00150732471    -.25517427386   .03965769073   (R; then R' in the frequency slot)
# The routine writes its complex numbers with the opposite sign of i to this module's exp(i sigma Omega t):
# its FCN grows (Im s < 0).  Every value is therefore taken conjugated, which makes the FCN decay, as the
# two-layer model's FCN does (Im K_CMB < 0); the out-of-phase terms it then gives have IAU 2000A's signs.
# FCN period in space -430.06 d, Chandler wobble 393.9 d (no ocean: MHB2000's is 383.4 d).
IERS1996 = ResonanceExpansion(r=1.04901828112 + 0.00150732471j, r_prime=-0.25517427386 - 0.03965769073j,
                              chandler=0.0025317 + 0j, chandler_strength=-0.00057992 + 0j,
                              fcn=-1.00231888314 + 0.00002920327j,
                              fcn_strength=-0.00011489752 - 0.00000214130j)
DEFAULT = IERS1996                # the layer's model wherever p is None

# MHB2000 normal modes, cpsd, terrestrial frame, in this module's convention: IERS Conventions 2010
# Tables 6.4 and 7.1 list them for tidal frequencies (-0.0026010 - 0.0001361i, 1.0023181 + 0.000025i,
# and the free inner-core nutation 0.999026 + 0.000780i), i.e. as -conj(sigma); read in copies of those
# tables in public code (e.g. L. Petrov's, "taken from the IERS Conventions 2000").  FCN period in
# space: -1/(0.0023181 * 1.0027379) = -430.21 solar days, the "conventional -431.39 sidereal days" of
# Krasna et al. 2013 (A&A 555, A29); Q = 1.0023181 / (2 Im) = 20 000, beside VLBI's 15 400-19 500 (the
# compilation in Table 1 of "Parameters of the Earth's Free Core Nutation from Diurnal Strain Tides",
# Sci. Rep. 10, 2020, doi:10.1038/s41598-020-66426-7).
PUBLISHED_CHANDLER_CPSD = 0.0026010 + 0.0001361j
PUBLISHED_FCN_CPSD = -1.0023181 + 0.000025j
SIDEREAL_PER_SOLAR_DAY = ERA_RATE_RAD_D / (2.0 * np.pi)

# MHB2000's nonlinear terms (products of the nutation amplitudes in the non-rigid Earth's equations):
# their contribution to the precession rate in longitude, -21 050 uas/cy (0 in obliquity), as listed
# among the contributions to the IAU 2006 (P03) rate: Capitaine, Wallace & Chapront 2003, A&A 412, 567,
# Table 3 ("Non-linear effect").
NONLINEAR_PRECESSION_ARCSEC_CY = -0.021050


def _matrices(sigma, p):
    """(M, rhs) of the two-layer equations at terrestrial frequencies sigma (cpsd): shapes (..., 2, 2), (..., 2)."""
    s = np.atleast_1d(np.asarray(sigma, dtype=complex))
    m = np.empty(s.shape + (2, 2), dtype=complex)
    m[..., 0, 0] = s - p.e + (1 + s) * p.kappa
    m[..., 0, 1] = (1 + s) * (p.a_f + p.xi)
    m[..., 1, 0] = s * (1 + p.gamma)
    m[..., 1, 1] = 1 + s * (1 + p.beta) + p.e_f + p.k_cmb
    rhs = np.stack([(1 + s) * p.kappa - p.e, s * p.gamma], axis=-1)
    return m, rhs


def transfer(sigma, p=None):
    """Non-rigid / rigid nutation amplitude at terrestrial frequency sigma (cpsd) for the model p (None: DEFAULT).

    The two-layer model equals 1 at sigma = -1 (precession) and for the RIGID parameters.
    """
    return (p or DEFAULT).transfer(sigma)


def normal_modes(p=None):
    """(Chandler wobble, free core nutation) terrestrial frequencies (cpsd) of the model p (None: DEFAULT)."""
    return (p or DEFAULT).normal_modes()


def celestial_period_days(sigma):
    """Period (solar days) in space of a wobble of terrestrial frequency sigma (cpsd); < 0 retrograde."""
    return 1.0 / ((1.0 + sigma.real) * SIDEREAL_PER_SOLAR_DAY)


def wobble_period_days(sigma):
    """Period (solar days) in the terrestrial frame of a wobble of frequency sigma (cpsd)."""
    return 1.0 / (sigma.real * SIDEREAL_PER_SOLAR_DAY)


# Luni-solar arguments (multipliers of l, l', F, D, Om) of the nutation terms above ~1 mas, ordered as
# in IERS TN36 Table 5.3a; the terms the non-rigid response is applied to.
LUNISOLAR_ARGUMENTS = (
    (0, 0, 0, 0, 1), (0, 0, 2, -2, 2), (0, 0, 2, 0, 2), (0, 0, 0, 0, 2), (0, 1, 0, 0, 0),
    (0, 1, 2, -2, 2), (1, 0, 0, 0, 0), (0, 0, 2, 0, 1), (1, 0, 2, 0, 2), (0, -1, 2, -2, 2),
    (0, 0, 2, -2, 1), (-1, 0, 2, 0, 2), (-1, 0, 0, 2, 0), (1, 0, 0, 0, 1), (-1, 0, 0, 0, 1),
    (-1, 0, 2, 2, 2), (1, 0, 2, 0, 1), (-2, 0, 2, 0, 1), (0, 0, 0, 2, 0), (0, 0, 2, 2, 2),
    (-2, 0, 0, 2, 0), (2, 0, 2, 0, 2), (1, 0, 2, -2, 2), (-1, 0, 2, 0, 1), (2, 0, 0, 0, 0),
    (0, 0, 2, 0, 0), (0, 1, 0, 0, 1), (-1, 0, 0, 2, 1), (0, 2, 2, -2, 2), (0, 0, -2, 2, 0),
    (1, 0, 0, -2, 1), (0, -1, 0, 0, 1), (-1, 0, 2, 2, 1), (0, 2, 0, 0, 0), (1, 0, 2, 2, 2),
    (-2, 0, 2, 0, 0), (0, 1, 2, 0, 2), (0, 0, 2, 2, 1), (0, -1, 2, 0, 2), (0, 0, 0, 2, 1),
    (1, 0, 2, -2, 1), (2, 0, 2, -2, 2), (-2, 0, 0, 2, 1), (2, 0, 2, 0, 1), (0, -1, 2, -2, 1),
)


def nonlinear_precession(dt_d):
    """Longitude offset (rad) accumulated over dt_d (days) by MHB2000's nonlinear precession rate."""
    return NONLINEAR_PRECESSION_ARCSEC_CY * ARCSEC * np.asarray(dt_d) / JULIAN_CENTURY_D


def circular_terms(t_d, x, y, phases, rates):
    """Least-squares decomposition of z = x + i y on exp(+-i phase_k) plus a quadratic in time.

    ``t_d`` (n,) days; ``x, y`` (n,) rad; ``phases`` (K, n) rad; ``rates`` (K,) rad/d.
    Returns (amplitudes (2K,) complex, celestial frequencies (2K,) cpsd, basis (n, 2K)):
    z ~ poly + basis @ amplitudes.  In the plane (x, y) = (dpsi sin eps, deps) a positive
    rotation is prograde, so exp(i phase) turns at +rate and exp(-i phase) at -rate.
    """
    centuries = (t_d - t_d.mean()) / 36525.0
    basis = np.hstack([np.exp(1j * phases).T, np.exp(-1j * phases).T])
    design = np.column_stack([np.ones_like(centuries), centuries, centuries**2, basis])
    coef = np.linalg.lstsq(design, x + 1j * y, rcond=None)[0]
    nu = np.concatenate([rates, -rates]) / ERA_RATE_RAD_D
    return coef[3:], nu, basis


def nonrigid_nutation(t_d, x, y, phases, rates, p=None):
    """Non-rigid (x, y) from the rigid (x, y) = (dpsi sin eps, deps), rad, term by term.

    Each circular term c exp(+-i phase) of the arguments the span resolves becomes
    T(nu - 1) c exp(+-i phase); what the terms do not capture (the quadratic, the
    smaller terms) is kept as it is (T = 1).
    """
    keep = resolvable(rates, t_d[-1] - t_d[0])
    amplitudes, nu, basis = circular_terms(t_d, x, y, phases[keep], rates[keep])
    dz = basis @ ((transfer(nu - 1.0, p) - 1.0) * amplitudes)
    return x + dz.real, y + dz.imag
