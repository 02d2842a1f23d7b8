"""The non-rigid Earth's nutation: a transfer function applied term by term to a rigid Earth's nutation.

Layer 2 (numpy).  The rigid Earth's forced nutation, (x, y) = (dpsi sin eps, deps) about a mean pole,
decomposed into circular terms on the luni-solar arguments, is multiplied term by term by the ratio T of
the non-rigid to the rigid response at each term's frequency (the route of the IERS 1996 series and of
MHB2000: Mathews, Herring & Buffett 2002, JGR 107(B4) 2068; IERS Conventions 2010, TN36 §5.5.1); the
transfer functions are in ``analysis.transfer``.  The arguments' phases and rates come in from the caller
(references.arguments).

MHB2000's nonlinear terms enter through their published contribution to the precession rate
(``nonlinear_precession``) and, for MHB2000's own model, its add-on terms at the arguments' frequencies.
"""
import numpy as np

from ..base.constants import ARCSEC, JULIAN_CENTURY_D
from ..bodies.earth import ERA_RATE_RAD_D
from .spans import resolvable

# MHB2000's nonlinear terms (products of the nutation amplitudes in the non-rigid Earth's equations):
# their contribution to the precession rate in longitude, -21 050 uas/cy (0 in obliquity), as listed
# among the contributions to the IAU 2006 (P03) rate: Capitaine, Wallace & Chapront 2003, A&A 412, 567,
# Table 3 ("Non-linear effect").
NONLINEAR_PRECESSION_ARCSEC_CY = -0.021050

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


def nonrigid_nutation(t_d, x, y, phases, rates, model, h_d, kinematic=(0.0, 0.0)):
    """Non-rigid (x, y) from the rigid (x, y) = (dpsi sin eps, deps), rad, term by term.

    Each circular term c exp(+-i phase) of the arguments the span resolves becomes
    T(nu - 1) (h / h_d) c exp(+-i phase), h the dynamical ellipticity of the rigid Earth the model's T
    is relative to (``model.rigid_h``; None: the run's own ``h_d``), since a rigid Earth's first-order
    nutation goes as its H; the model's additive terms at the frequencies of all the arguments are added;
    what the terms do not capture (the quadratic, the smaller terms) is kept as it is (T = 1).
    ``kinematic`` = (x, y): a part of the input that is a turn of the reference frame, not a response to
    the torque (the geodesic nutation), taken out before and put back after.
    """
    x0, y0 = x - kinematic[0], y - kinematic[1]
    keep = resolvable(rates, t_d[-1] - t_d[0])
    amplitudes, nu, basis = circular_terms(t_d, x0, y0, phases[keep], rates[keep])
    scale = 1.0 if model.rigid_h is None else model.rigid_h / h_d
    dz = basis @ ((scale * model.transfer(nu - 1.0) - 1.0) * amplitudes)
    nu_all = np.concatenate([rates, -rates]) / ERA_RATE_RAD_D
    dz += np.hstack([np.exp(1j * phases).T, np.exp(-1j * phases).T]) @ model.additive(nu_all - 1.0)
    return x + dz.real, y + dz.imag
