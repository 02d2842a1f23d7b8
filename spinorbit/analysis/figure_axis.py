"""The figure axis of a P96 run (ZA, XZA) and the least-squares fit of Euler's terms to them (§846-849)."""
import numpy as np

from ..base.rotations import matrices_from_quats


def figure_axis(solution):
    """Unit vectors (n, 3) of the body's z axis in inertial axes."""
    return matrices_from_quats(solution.quaternion)[:, :, 2]


def figure_axis_angles(solution):
    """ZA = p and unwrapped XZA = lambda (rad) of the body's z axis."""
    axis = figure_axis(solution)
    return np.arccos(np.clip(axis[:, 2], -1, 1)), np.unwrap(np.arctan2(axis[:, 1], axis[:, 0]))


def fit_angles(solution, t0, delta, eps_f, resonant=False):
    """(dt, ZA, XZA, XZA's and ZA's least-squares coefficients), angles in rad, dt in days from t0,
    phi = XZA - delta dt: XZA on [1, dt, sin 2phi, cos 2phi, *more], ZA on [1, cos 2phi, sin 2phi,
    *more], more = the free nutation (cos eps_f dt, sin eps_f dt) or, ``resonant``, §849's growth
    (dt cos 2phi, dt sin 2phi)."""
    dt = solution.t - t0
    p, lam = figure_axis_angles(solution)
    phi = lam - delta * dt
    c2, s2, one = np.cos(2 * phi), np.sin(2 * phi), np.ones_like(dt)
    more = [dt * c2, dt * s2] if resonant else [np.cos(eps_f * dt), np.sin(eps_f * dt)]
    fit = [np.linalg.lstsq(np.column_stack(cols), y, rcond=None)[0]
           for y, cols in ((lam, [one, dt, s2, c2, *more]), (p, [one, c2, s2, *more]))]
    return dt, p, lam, *fit
