"""The precession constant and the Milankovitch periods of an Earth-Moon state.

The precession constant (the luni-solar precession rate of the equator; Laskar et al. 2004, A&A 428, 261,
sect. 3) is alpha cos(eps), alpha = (3/2) (E_d / Omega) [n_sun^2 (1 - e_sun^2)^(-3/2) + (G m_moon / a^3)
(1 - e^2)^(-3/2) (1 - 3/2 sin^2 i)] (the Moon's term averaged over its orbit and its node, Kinoshita 1977),
with the dynamical ellipticity E_d following the rotation hydrostatically, E_d ~ Omega^2 (as spinorbit's
deep time does), so alpha ~ Omega.  It is scaled to La2004's p = 50.475838"/yr today.  The obliquity's main
period is 2 pi / (p + s3) and the climatic precession's 2 pi / (p + g5), with the planetary frequencies
today's (s3 = -18.85"/yr, g5 = 4.257"/yr; Laskar et al. 2004, Table 3 and 4, to 4 digits): their drift over
Gyr (chaotic, ~0.1"/yr for s3; Laskar et al. 2004 sect. 10) is not modelled.
"""
import numpy as np

PRECESSION_TODAY_ARCSEC_YR = 50.475838
S3_ARCSEC_YR = -18.85
G5_ARCSEC_YR = 4.257
TURN_ARCSEC = 1_296_000.0


def luni_solar_factor(semi_major_axis_km, eccentricity, inclination, gm_moon, n_sun, sun_e2):
    """The bracket of alpha (rad^2/day^2)."""
    moon = (gm_moon / semi_major_axis_km**3 * (1 - eccentricity**2) ** -1.5
            * (1 - 1.5 * np.sin(inclination) ** 2))
    return n_sun**2 * (1 - sun_e2) ** -1.5 + moon


def precession_constant(rotation, obliquity, factor, today):
    """p ("/yr) of states with rotation rates, obliquities and luni-solar factors, given ``today`` =
    (rotation, obliquity, factor) at which p is La2004's."""
    rotation0, obliquity0, factor0 = today
    return (PRECESSION_TODAY_ARCSEC_YR * rotation / rotation0 * factor / factor0
            * np.cos(obliquity) / np.cos(obliquity0))


def periods_kyr(precession_arcsec_yr):
    """{obliquity_period, precession_period} in kyr: 2 pi / (p + s3) and 2 pi / (p + g5)."""
    p = np.asarray(precession_arcsec_yr, dtype=float)
    return {"obliquity_period": TURN_ARCSEC / (p + S3_ARCSEC_YR) / 1000.0,
            "precession_period": TURN_ARCSEC / (p + G5_ARCSEC_YR) / 1000.0}
