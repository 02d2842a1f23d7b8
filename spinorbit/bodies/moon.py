"""The Moon of DE421: figure, fluid core, tides and rotation state, from the DE421 header.

Folkner, Williams & Boggs 2008 (IOM 343R-08-003) and Williams, Boggs & Folkner 2008
(DE421 lunar ephemeris, IOM 335-JW,DB,WF-20080314-001); header names in the comments.
Moments (units of M R^2, R = ``radius_km``) follow from the undistorted J2 and
beta = (C - A)/B, gamma = (B - A)/C (Folkner et al. 2014, IPN PR 42-196):
C = 2 J2 (1 + beta)/(2 beta - gamma + beta gamma), B = C (1 + gamma)/(1 + beta),
A = C (1 - beta gamma)/(1 + beta).
"""
from dataclasses import dataclass
from functools import cache

import numpy as np

from ..base.constants import J2000_JD
from .de421_header import header
from .table import gm_km3_d2


@dataclass(frozen=True)
class Moon:
    """The DE421 lunar constants, named with their units."""

    gm_km3_d2: float              # GMB / (1 + EMRAT)
    radius_km: float              # AM, reference radius of the gravity field
    beta: float                   # LBET = (C - A)/B
    gamma: float                  # LGAM = (B - A)/C
    j2: float                     # J2M, undistorted
    c22: float                    # C22M
    c_nm: np.ndarray              # unnormalised C_nm (5, 5), degrees 3-4 (C_n0 = -J_n): J3M, J4M, CnmM
    s_nm: np.ndarray              # unnormalised S_nm (5, 5): SnmM
    k2: float                     # K2M, potential Love number
    tau_d: float                  # TAUM, time delay of the tide, days
    kv_over_c_per_d: float        # KVC = k_nu / C, core-mantle friction, 1/day
    core_c_over_c: float          # IFAC = C_core / C
    core_flattening: float        # COBLAT = (C_c - A_c)/C_c
    epoch_tdb_d: float            # JDEPOC - J2000: epoch of the rotation state
    angles0_rad: np.ndarray       # PHI, THT, PSI at the epoch (3-1-3, ICRF -> body)
    omega0_rad_d: np.ndarray      # OMEGAX/Y/Z, mantle angular velocity, body axes
    omega_core0_rad_d: np.ndarray  # OMGCX/Y/Z, core angular velocity, mantle axes

    @property
    def c_mr2(self):
        """C/(M R^2) of the whole undistorted Moon."""
        b, g = self.beta, self.gamma
        return 2 * self.j2 * (1 + b) / (2 * b - g + b * g)

    @property
    def moments(self):
        """(A, B, C) of the whole undistorted Moon, units of M R^2."""
        b, g, c = self.beta, self.gamma, self.c_mr2
        return np.array([c * (1 - b * g) / (1 + b), c * (1 + g) / (1 + b), c])


@cache
def de421():
    """The Moon of DE421."""
    h = header()
    c_nm, s_nm = np.zeros((5, 5)), np.zeros((5, 5))
    c_nm[3, 0], c_nm[4, 0] = -h["J3M"], -h["J4M"]
    for n in (3, 4):
        for m in range(1, n + 1):
            c_nm[n, m], s_nm[n, m] = h[f"C{n}{m}M"], h[f"S{n}{m}M"]
    return Moon(gm_km3_d2=gm_km3_d2("moon"), radius_km=h["AM"], beta=h["LBET"], gamma=h["LGAM"], j2=h["J2M"],
                c22=h["C22M"], c_nm=c_nm, s_nm=s_nm, k2=h["K2M"], tau_d=h["TAUM"], kv_over_c_per_d=h["KVC"],
                core_c_over_c=h["IFAC"], core_flattening=h["COBLAT"], epoch_tdb_d=h["JDEPOC"] - J2000_JD,
                angles0_rad=np.array([h["PHI"], h["THT"], h["PSI"]]),
                omega0_rad_d=np.array([h["OMEGAX"], h["OMEGAY"], h["OMEGAZ"]]),
                omega_core0_rad_d=np.array([h["OMGCX"], h["OMGCY"], h["OMGCZ"]]))


# The Moon's mean orbit about the Earth, for orbit-averaged torques and the Earth-Moon pair's quadrupole:
# semi-major axis, eccentricity and inclination to the ecliptic (standard mean values; the averaged
# torque factor below, 0.99242, is Kinoshita's 1977 (Celest. Mech. 15, 277) 0.9925194 to 1e-4).
MEAN_DISTANCE_KM = 384399.0
MEAN_ECCENTRICITY = 0.0549
MEAN_INCLINATION_DEG = 5.145
# Tidal recession of the Moon today, lunar laser ranging (Williams & Boggs 2016, Celest. Mech. Dyn. Astr.
# 126, 89): 38.30 +- 0.09 mm/yr.
RECESSION_KM_PER_YR = 38.30e-6


def orbit_average_factor():
    """(1 - e^2)^(-3/2) (1 - 3/2 sin^2 i) of the mean lunar orbit: the Moon's torque on an oblate body,
    averaged over the orbit and its 18.6-yr nodal regression about the ecliptic (Kinoshita 1977)."""
    e, i = MEAN_ECCENTRICITY, np.radians(MEAN_INCLINATION_DEG)
    return (1 - e * e) ** -1.5 * (1 - 1.5 * np.sin(i) ** 2)
