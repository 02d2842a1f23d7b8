"""The Moon's orientation analysed: differences of two attitudes (pole, longitude), the physical
librations about the Cassini state, and the sub-Earth point.

Layer 2 (numpy).  The frame and the arguments are inputs (``references.arguments``):
the body angles are taken against the mean ecliptic and equinox of date, node phi_e,
inclination theta_e, and phi_e + psi_e the prime meridian's longitude; then
tau = phi_e + psi_e - (L + 180 deg), rho = theta_e - I, sigma = phi_e - (Om + 180 deg).
"""
import numpy as np

from ..base.constants import ARCSEC
from ..base.rotations import euler313_from_matrix, matrices_from_quats, vector_angle

INCLINATION_RAD = np.radians(1.54242)       # mean inclination of the lunar equator to the ecliptic (Meeus ch. 53)
# The metrics residual_metrics computes (the summary's comparison keys, read by verdicts and the API)
POLE_ERROR_MAX_ARCSEC, POLE_ERROR_RMS_ARCSEC = "pole_error_max_arcsec", "pole_error_rms_arcsec"
LONGITUDE_ERROR_MAX_ARCSEC, LONGITUDE_ERROR_RMS_ARCSEC = "longitude_error_max_arcsec", "longitude_error_rms_arcsec"


def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


def physical_librations(icrf_to_body, icrf_to_ecliptic, mean_longitude, node, earth_from_moon):
    """tau, rho, sigma (rad) and the sub-Earth longitude and latitude (rad) of a series of orientations.

    ``icrf_to_body``, ``icrf_to_ecliptic``: (n, 3, 3) matrices (the mean ecliptic of date);
    ``mean_longitude`` L and ``node`` Om of the Moon (n,) rad; ``earth_from_moon`` (n, 3) ICRF, any unit.
    """
    ecl = euler313_from_matrix(np.einsum("nij,nkj->nik", icrf_to_body, icrf_to_ecliptic))
    lon, lat = sub_point(icrf_to_body, earth_from_moon)
    return {"tau": _wrap(ecl[:, 0] + ecl[:, 2] - mean_longitude - np.pi), "rho": ecl[:, 1] - INCLINATION_RAD,
            "sigma": _wrap(ecl[:, 0] - node - np.pi), "sub_earth_lon": lon, "sub_earth_lat": lat}


def sub_point(icrf_to_frame, direction):
    """(longitude, latitude) rad of the directions (n, 3) ICRF, any length, in the body frames ``icrf_to_frame``
    (n, 3, 3): the sub-Earth (sub-observer) point of the direction from the body to the Earth (the observer)."""
    u = np.einsum("nij,nj->ni", icrf_to_frame, direction / np.linalg.norm(direction, axis=1, keepdims=True))
    return np.arctan2(u[:, 1], u[:, 0]), np.arcsin(np.clip(u[:, 2], -1.0, 1.0))


def optical_librations(icrf_to_ecliptic, mean_longitude, node, earth_from_moon):
    """The optical libration in longitude and latitude (rad): the sub-Earth point of the Cassini state (the
    lunar equator at inclination I to the mean ecliptic of date, its node Om + 180 deg, the prime meridian at
    L + 180 deg: tau = rho = sigma = 0).  Arguments as :func:`physical_librations`."""
    from ..base.rotations import matrix_from_euler313

    cassini = matrix_from_euler313(node + np.pi, np.full_like(node, INCLINATION_RAD), mean_longitude - node)
    mats = np.einsum("nij,njk->nik", cassini, icrf_to_ecliptic)
    u = np.einsum("nij,nj->ni", mats, earth_from_moon / np.linalg.norm(earth_from_moon, axis=1, keepdims=True))
    return np.arctan2(u[:, 1], u[:, 0]), np.arcsin(u[:, 2])


def icrf_to_body(quaternions):
    """ICRF-to-body matrices (n, 3, 3) of body-to-ICRF quaternions (n, 4) (an integrated attitude)."""
    return np.ascontiguousarray(np.swapaxes(matrices_from_quats(quaternions), -1, -2))


def pole_and_longitude_difference(m_a, m_b):
    """Differences of two series of ICRF-to-body matrices (n, 3, 3), rad: (pole, longitude).

    pole: angle between the two body z axes (tilt of the spin axis);
    longitude: signed rotation about z of frame a relative to frame b
    (from the relative matrix m_a m_b^T; positive when a leads b).
    """
    m_a, m_b = np.asarray(m_a), np.asarray(m_b)
    z_a, z_b = m_a[:, 2, :], m_b[:, 2, :]
    pole = vector_angle(z_a, z_b)
    rel = np.einsum("nij,nkj->nik", m_a, m_b)
    longitude = np.arctan2(rel[:, 0, 1] - rel[:, 1, 0], rel[:, 0, 0] + rel[:, 1, 1])
    return pole, longitude


def residual_metrics(mats, reference_mats):
    """Max and rms pole and longitude differences of two series of ICRF-to-body matrices, arcsec."""
    out = {}
    names = ((POLE_ERROR_MAX_ARCSEC, POLE_ERROR_RMS_ARCSEC), (LONGITUDE_ERROR_MAX_ARCSEC, LONGITUDE_ERROR_RMS_ARCSEC))
    for (largest, rms), x in zip(names, pole_and_longitude_difference(mats, reference_mats)):
        out[largest] = float(np.abs(x).max() / ARCSEC)
        out[rms] = float(np.sqrt(np.mean(x**2)) / ARCSEC)
    return out


def attitude_error(reference_mats):
    """An error function for analysis.ladder: the max pole or longitude difference (rad) of a solution's
    attitude from ICRF-to-body matrices (n, 3, 3) at its output times."""
    def error(solution):
        return float(max(np.abs(x).max() for x in pole_and_longitude_difference(icrf_to_body(solution.quaternion),
                                                                                reference_mats)))

    return error
