"""The Cassini state of a body in the 3:2 spin-orbit resonance on a precessing orbit (Mercury), and how a run's
spin is measured against it.

Peale's equation (Peale 1969, AJ 74, 483; in the form of Baland et al. 2017, Icarus 291, 136, §2, for a rigid
planet whose core follows the mantle): the orbit-averaged torque of the Sun on the degree-2 figure (J2, C22
unnormalised, C/(M R^2)) of a body turning at 3n/2 makes its spin axis s precess about the orbit normal k,

    ds/dt = -alpha k x s,   alpha = n / (C/(M R^2)) [J2 G210(e) cos eps + C22 G201(e) (1 + cos eps)],

with the eccentricity functions G210 = (1 - e^2)^(-3/2) and G201 = <(a/r)^3 cos(2f - 3M)> = 7e/2 - 123e^3/16
+ ... (taken here by quadrature, spinorbit.analysis.planar_spin_orbit.forcing_coefficients).  The orbit normal
precesses about the Laplace pole at the node rate Omega' < 0 with inclination i; the spin stays fixed in the
precessing frame (Cassini state 1) where s, k and the Laplace pole are coplanar and

    alpha(eps) sin eps = -Omega' sin(eps + i).

Only the orbit normal's speed |dk/dt| = -Omega' sin i enters at first order; i enters through cot i (0.4 % of
eps for Mercury).  The state lies on the far side of k from the Laplace pole: along k x dk/dt.

A spin started off the state circles it at alpha (the free precession, ~1300 yr for Mercury): from its
velocity v in the precessing frame, the centre it circles is s - k x v / alpha (``settled_axis``, with the
frame's turning about k, Omega' cos i, taken out), so a run much shorter than the free period still finds the
state the spin settles to.
"""
import math

import numpy as np

from .planar_spin_orbit import forcing_coefficients


def eccentricity_functions(e):
    """(G210, G201) of eccentricity e: (1 - e^2)^(-3/2) and the 3:2 resonant mean of (a/r)^3 cos(2f - 3M)."""
    return (1.0 - e * e) ** -1.5, forcing_coefficients(e, 1)[1]


def precession_constant(n, e, j2, c22, c_mr2, obliquity=0.0):
    """alpha (rad per unit of n) of Peale's equation: the spin axis's precession rate about the orbit normal of a
    body turning at 3n/2 with obliquity ``obliquity`` (rad)."""
    g210, g201 = eccentricity_functions(e)
    c = math.cos(obliquity)
    return n / c_mr2 * (j2 * g210 * c + c22 * g201 * (1.0 + c))


def peale_obliquity(n, e, j2, c22, c_mr2, normal_speed, inclination):
    """eps (rad) of Cassini state 1 from Peale's equation, the orbit normal moving at ``normal_speed`` =
    |dk/dt| (rad per unit of n) on a cone of half-angle ``inclination`` (rad) about the Laplace pole."""
    if normal_speed == 0.0:
        return 0.0
    node_rate = normal_speed / math.sin(inclination)
    eps = 0.0
    for _ in range(50):                      # a contraction: alpha >> |Omega'|
        eps = math.asin(node_rate * math.sin(eps + inclination) / precession_constant(n, e, j2, c22, c_mr2, eps))
    return eps


def cassini_axis(normal, normal_rate, obliquity):
    """The unit spin axis of Cassini state 1: ``obliquity`` from the orbit normal toward normal x d(normal)/dt."""
    normal = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    away = np.cross(normal, normal_rate)
    size = np.linalg.norm(away)
    if size == 0.0:
        return normal
    return math.cos(obliquity) * normal + math.sin(obliquity) * away / size


def osculating(r, v, gm):
    """Osculating elements of states r, v (n, 3) about a mass GM: {normal (n, 3), perihelion (n, 3) unit vectors,
    a, e, mean_anomaly (unwrapped), true_anomaly} (km, km/d, km^3/d^2, rad)."""
    h = np.cross(r, v)
    normal = h / np.linalg.norm(h, axis=1)[:, None]
    distance = np.linalg.norm(r, axis=1)
    e_vec = np.cross(v, h) / gm - r / distance[:, None]
    e = np.linalg.norm(e_vec, axis=1)
    perihelion = e_vec / e[:, None]
    a = 1.0 / (2.0 / distance - np.einsum("ij,ij->i", v, v) / gm)
    f = np.arctan2(np.einsum("ij,ij->i", np.cross(perihelion, r), normal), np.einsum("ij,ij->i", perihelion, r))
    big_e = 2.0 * np.arctan(np.sqrt((1 - e) / (1 + e)) * np.tan(f / 2))
    return {"normal": normal, "perihelion": perihelion, "a": a, "e": e, "true_anomaly": f,
            "mean_anomaly": np.unwrap(big_e - e * np.sin(big_e))}


def linear_fit(t, values, t_ref):
    """(value at t_ref, rate) of a least-squares line through values (n, ...) at times t."""
    columns = np.column_stack([np.ones_like(t), t - t_ref])
    coef = np.linalg.lstsq(columns, values.reshape(t.size, -1), rcond=None)[0]
    return coef[0].reshape(values.shape[1:]), coef[1].reshape(values.shape[1:])


def mean_normal(t, normals, t_ref):
    """(unit orbit normal at t_ref, its rate perpendicular to it) fitted to the osculating normals (n, 3)."""
    value, rate = linear_fit(t, normals, t_ref)
    value /= np.linalg.norm(value)
    return value, rate - value * (value @ rate)


def settled_axis(t, axes, normal, normal_rate, t_ref, alpha, inclination):
    """(the centre the spin axis circles at t_ref, the spin's free-precession offset from it (rad), the spin's
    mean axis at t_ref): the axes (n, 3) seen from the normal moving linearly as fitted, their mean offset and
    velocity fitted; in the frame precessing with the orbit (turning at Omega' cos i about the normal, Omega' =
    -|dk/dt|/sin i) the offset moves at v' = v + |dk/dt| cot i k x offset and circles the state at alpha -
    |dk/dt| cot i; the centre is the offset less k x v' / (alpha - |dk/dt| cot i) (module docstring)."""
    moving = normal + np.outer(t - t_ref, normal_rate)
    moving /= np.linalg.norm(moving, axis=1)[:, None]
    offset, velocity = linear_fit(t, axes - moving, t_ref)
    turning = float(np.linalg.norm(normal_rate)) / math.tan(inclination)
    free = np.cross(normal, velocity + turning * np.cross(normal, offset)) / (alpha - turning)
    centre = normal + offset - free
    return centre / np.linalg.norm(centre), float(np.linalg.norm(free)), (normal + offset) / np.linalg.norm(
        normal + offset)


def angle(a, b):
    """The angle (rad) between vectors a and b."""
    return math.atan2(np.linalg.norm(np.cross(a, b)), float(np.dot(a, b)))
