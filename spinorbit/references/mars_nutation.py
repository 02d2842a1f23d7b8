"""The rigid-Mars nutation series Konopliv et al. 2006 adopt (Icarus 182, 23, §6: after Reasenberg & King 1979,
JGR 84, 6231; Roosbeek 1999), about the mean orbit of J2000: in longitude psi (along the orbit, from its node
on the ICRF equator) and obliquity I,

    dpsi = sum_k psi_k sin(alpha_k t + theta_k),   dI = I_0 + sum_k I_k cos(alpha_k t + theta_k),

with the arguments k M (k = 1, 2, 3) and k M + q (k = 1..6), M = Mars's mean anomaly (19.3564 deg at J2000,
0.52403958828 deg/d) and q = 142 deg (twice the perihelion's longitude from Mars's equinox); amplitudes in mas
(as tabulated in NASA JEOD's RNPMars model, models/environment/RNP/RNPMars).  Two terms of a frequency k n do
not separate over any span: the model is compared on each frequency's in-phase (sin) and quadrature (cos)
parts, which the table's terms give in closed form (:func:`by_frequency`).

What the table does not say: the precession constant (H) its amplitudes were computed for (a rigid series' terms
go as H), and its arguments to better than 0.01 deg: with M0 and q as tabulated, M + q/2, the Sun's mean longitude
from Mars's equinox that the main term goes with (as 2 lambda), is 0.036 deg behind DE421's Sun at J2000
(comparisons.mars_orientation.solar_longitude_lead; Simon et al. 1994, A&A 282, 663, have M0 = 19.3728 deg).
Baland et al. 2020 (CMDA 132, 47) give BMAN20 and a recomputed Roosbeek 1999 series with both stated
(https://lara.oma.be/RigidNutations/BMAN20.html).
"""
import math

import numpy as np

from ..base.constants import MAS
from ..bodies import mars

Q_DEG = 142.0
# (k, with q, psi sin mas, I cos mas)
TERMS = ((1, False, -632.6, -0.4), (2, False, -44.2, 0.0), (3, False, -4.0, 0.0),
         (1, True, -104.5, -49.1), (2, True, 1097.0, 515.7), (3, True, 240.1, 112.8), (4, True, 40.9, 19.2),
         (5, True, 6.5, 3.0), (6, True, 1.0, 0.4))
CITATION = "Konopliv et al. 2006, Icarus 182, 23 (rigid Mars nutation after Reasenberg & King 1979)"
FREQUENCIES = tuple(range(1, 7))


def mean_anomaly(t_tdb_d):
    """Mars's mean anomaly M (rad) at TDB days, Konopliv et al. 2006's linear one."""
    return np.radians(mars.MEAN_ANOMALY_J2000_DEG + mars.MEAN_MOTION_DEG_D * np.asarray(t_tdb_d, dtype=float))


def arguments(t_tdb_d):
    """name -> (phase k M (n,), rate k n rad/d): the series' frequencies, as analysis.harmonics fits them."""
    m, n = mean_anomaly(t_tdb_d), math.radians(mars.MEAN_MOTION_DEG_D)
    return {f"{k}M": (k * m, k * n) for k in FREQUENCIES}


def by_frequency():
    """{"kM": (psi sin, psi cos, I cos, I sin)} rad: the series on sin kM and cos kM."""
    q, out = math.radians(Q_DEG), {}
    for k in FREQUENCIES:
        parts = np.zeros(4)
        for kk, with_q, psi, inc in TERMS:
            if kk != k:
                continue
            phase = q if with_q else 0.0
            parts += np.array([psi * math.cos(phase), psi * math.sin(phase), inc * math.cos(phase),
                               -inc * math.sin(phase)])
        out[f"{k}M"] = tuple(parts * MAS)
    return out


def nutation(t_tdb_d):
    """(dpsi, dI) rad at TDB days (the constant I_0 = -1.4 mas left out: it is the mean obliquity's)."""
    m, q = mean_anomaly(t_tdb_d), math.radians(Q_DEG)
    dpsi = sum(psi * np.sin(k * m + (q if with_q else 0.0)) for k, with_q, psi, _ in TERMS)
    deps = sum(inc * np.cos(k * m + (q if with_q else 0.0)) for k, with_q, _, inc in TERMS)
    return dpsi * MAS, deps * MAS
