"""The tides' secular rates of the Earth's axis (P03 Table 3's "tides" rows), which a rigid Earth lacks.

A rigid Earth driven by an ephemeris feels no tidal torque.  The real Earth's tides, raised by the Moon and
the Sun and answering late, are pulled on by both, and the torque turns the axis.  Two sources:

* ``"de421"``: DE421's own tidal model (models.interactions.tides: per band a Love number and a time delay
  from the DE421 header, the delayed tide of Folkner et al. 2014, eq. 32), its torque on the Earth from the
  Moon and the Sun pulling on the tides both raise (DE421's eq. 32 keeps the Moon's pull only; the Sun's
  pull on the Moon's tide and the Moon's on the Sun's do not average out: both raise the K1 tide, at the
  same frequency), the axis held on the IAU 2006/2000A pole, averaged over the 18.6-yr node cycle centred on
  J2000: the rates of the Fukushima-Williams angles, less those of the same tides answering at once.  That
  elastic part (+1.97 mas/cy in longitude, 0 in obliquity: the tidal deformation's own precession, which P03
  leaves inside its fitted H_d, Lambert & Capitaine 2004) belongs to the H_d fitted to the rate; the delays
  give +0.08 mas/cy in longitude and +0.42 in obliquity, the semi-diurnal band tilting the axis away from the
  ecliptic pole, the diurnal and zonal bands toward it;
* ``"williams1994"``: Williams' (1994, AJ 108, 711) obliquity rate from tidal dissipation, +2.4 mas/cy (P03
  Table 3, tides (c); in longitude its tides rows are in t^2 only).

Edge module (ERFA through references.erfa_pole); the sum is cached in memory per ephemeris.
"""
import functools

import numpy as np

from ..base.constants import ARCSEC, JULIAN_CENTURY_D, JULIAN_YEAR_D
from ..base.progress import stage
from ..bodies import earth
from ..bodies.table import gm_km3_d2
from ..references import erfa_pole

CHOICES = ("none", "de421", "williams1994")
NODE_CYCLE_D = 18.6 * JULIAN_YEAR_D
STEP_D = 0.3                 # the Moon moves 4 deg: the average is converged to 1e-4 (0.1 d gives the same)


def rates(choice, source):
    """(dpsi/dt, deps/dt) of the axis, "/cy, from the tides: ``choice`` one of CHOICES; ``source`` the orbit
    source (spinorbit.orbits.sources) whose ephemeris the DE421 model is averaged on (DE421 for a source that
    is not a kernel)."""
    if choice == "none":
        return 0.0, 0.0
    if choice == "williams1994":
        return 0.0, earth.TIDAL_OBLIQUITY_RATE_ARCSEC_CY
    from ..orbits.sources import DE421

    love = earth.de421_tides()
    ephemeris = source if source.jpl_kernel else DE421()       # averaged on a kernel
    with stage("the tides' rates (DE421's model averaged over 18.6 yr)"):
        delayed = model_rates(ephemeris, tuple(love[band] for band in (0, 1, 2)))
        elastic = model_rates(ephemeris, tuple((love[band][0], 0.0) for band in (0, 1, 2)))
    return tuple(d - e for d, e in zip(delayed, elastic))


@functools.lru_cache(maxsize=4)
def model_rates(source, love, sun=True):
    """The delayed-tide model's rates, "/cy (see the module docstring), on the ephemeris ``source``: ``love``
    = ((k2, tau d) of the zonal, diurnal, semi-diurnal band); ``sun``: the Sun raises tides and pulls on them
    (else the Moon alone); ``source`` a JPL kernel's OrbitSource (spinorbit.orbits.sources)."""
    from ..models.interactions import tides

    t = np.arange(-NODE_CYCLE_D / 2, NODE_CYCLE_D / 2, STEP_D)
    ephemeris = source.open(t[0], t[-1])
    (r_moon, v_moon), (r_sun, v_sun) = (ephemeris.relative_states(b, "earth", t) for b in ("moon", "sun"))
    gm_e, gm_m, gm_s = (gm_km3_d2(b) for b in ("earth", "moon", "sun"))
    p = np.array([gm_e, gm_m, gm_s if sun else 0.0, earth.EQUATORIAL_RADIUS_KM, *(k for k, _ in love),
                  *(tau for _, tau in love)])
    poles = erfa_pole.cip_vector(t)
    moment = earth.C_MR2 * gm_e * earth.EQUATORIAL_RADIUS_KM ** 2        # C, G-scaled like the torque
    zdot = np.empty_like(poles)
    for i, pole in enumerate(poles):
        spin = earth.ERA_RATE_RAD_D * pole
        moon_pull = tides.torque_on_earth(r_moon[i], v_moon[i], r_sun[i], v_sun[i], spin, p)
        # the Sun's pull on both bulges: -GM_S r_sun x grad U (raised_by gives (1 + GM_M/GM_E) grad U)
        grad = (tides.raised_by(r_sun[i], r_moon[i], v_moon[i], gm_m, gm_e + gm_m, spin, p)
                + tides.raised_by(r_sun[i], r_sun[i], v_sun[i], gm_s, gm_s + gm_e + gm_m, spin, p))
        sun_pull = -gm_s * np.cross(r_sun[i], grad / (1.0 + gm_m / gm_e))
        torque = moon_pull + sun_pull if sun else moon_pull
        zdot[i] = (torque - np.dot(torque, pole) * pole) / (moment * earth.ERA_RATE_RAD_D)
    plus, minus = erfa_pole.pole_angles(t, poles + zdot), erfa_pole.pole_angles(t, poles - zdot)
    return tuple(float(np.mean(a - b) / 2.0 * JULIAN_CENTURY_D / ARCSEC) for a, b in zip(plus, minus))


def tilted(t, z, psi_rate, eps_rate):
    """The axes ``z`` (n, 3, GCRS) turned from the first time on at the rates ("/cy) in the Fukushima-Williams
    angles about the IAU 2006 mean pole."""
    if not (psi_rate or eps_rate):
        return z
    dpsi, deps = erfa_pole.about_mean_pole(t, z)
    elapsed = (t - t[0]) * ARCSEC / JULIAN_CENTURY_D
    return erfa_pole.from_mean_pole(t, dpsi + psi_rate * elapsed, deps + eps_rate * elapsed)
