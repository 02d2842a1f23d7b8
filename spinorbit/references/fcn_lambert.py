"""The free core nutation as observed: S. Lambert's empirical model, IERS Conventions (2010) §5.5.5.

The FCN is a free mode: no forced model predicts its amplitude or phase, which VLBI follows as they drift.
The model (IERS TN36 §5.5.5, software FCNNUT, table of 2013-12-19; read in two public copies of that
routine, which agree) writes the CIP's FCN offset as a retrograde circle of fixed period -430.21 d with
amplitudes fitted to VLBI year by year:

    X + i Y = (X_C + i X_S) exp(i phi),   phi = 2 pi (MJD - 51544.5) / (-430.21 d)

(its Y_C = X_S, Y_S = -X_C), X_C, X_S interpolated linearly between the yearly values (uas) of
1984.0-2013.0.  Outside that span the routine holds the last values; here it is refused.
"""
import numpy as np

from ..base.constants import MAS
from ..base.errors import InputError

PERIOD_D = -430.21
MJD_J2000 = 51544.5
# MJD (TT), X_C, X_S (uas), their uncertainty (uas)
TABLE = (
    (45700.0, 4.55, -36.58, 19.72), (46066.0, -141.82, -105.35, 11.12), (46431.0, -246.56, -170.21, 9.47),
    (46796.0, -281.89, -159.24, 8.65), (47161.0, -255.05, -43.58, 8.11), (47527.0, -210.46, -88.56, 7.31),
    (47892.0, -187.79, -57.35, 6.41), (48257.0, -163.01, 26.26, 5.52), (48622.0, -145.53, 44.65, 4.80),
    (48988.0, -145.12, 51.49, 5.95), (49353.0, -109.93, 16.87, 9.45), (49718.0, -87.30, 5.36, 8.25),
    (50083.0, -90.61, 1.52, 7.67), (50449.0, -94.73, 35.35, 4.40), (50814.0, -67.52, 27.57, 3.40),
    (51179.0, -44.11, -14.31, 3.45), (51544.0, 5.21, -74.87, 3.26), (51910.0, 70.37, -129.66, 2.86),
    (52275.0, 86.47, -127.84, 2.75), (52640.0, 110.44, -42.73, 2.59), (53005.0, 114.78, -0.13, 2.53),
    (53371.0, 132.96, -4.78, 2.72), (53736.0, 157.36, 28.63, 2.19), (54101.0, 160.40, 58.87, 1.87),
    (54466.0, 156.76, 101.24, 1.74), (54832.0, 142.99, 143.01, 1.89), (55197.0, 33.70, 184.46, 1.95),
    (55562.0, 0.76, 253.70, 1.14), (55927.0, 25.47, 271.66, 1.07), (56293.0, 113.42, 256.50, 1.86),
)
SPAN_TDB_D = (TABLE[0][0] - MJD_J2000, TABLE[-1][0] - MJD_J2000)


def fcn_pole(t_tdb_d):
    """(X, Y), rad, of the free core nutation at TDB days from J2000 within SPAN_TDB_D."""
    t = np.asarray(t_tdb_d, dtype=float)
    if t.size and (t.min() < SPAN_TDB_D[0] or t.max() > SPAN_TDB_D[1]):
        raise InputError("t_tdb_d", (float(t.min()), float(t.max())),
                         f"times within the FCN table's span {SPAN_TDB_D} (1984.0-2013.0)")
    mjd, xc, xs, _ = np.array(TABLE).T
    amplitude = np.interp(t + MJD_J2000, mjd, xc) + 1j * np.interp(t + MJD_J2000, mjd, xs)
    z = amplitude * np.exp(2j * np.pi * t / PERIOD_D) * MAS / 1000.0
    return z.real, z.imag


def provenance():
    return {"name": "free core nutation, S. Lambert's empirical model",
            "citation": "IERS Conventions (2010), TN36 §5.5.5, routine FCNNUT (table of 2013-12-19)",
            "span": "1984.0-2013.0"}
