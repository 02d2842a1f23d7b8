"""Nutation series in L. Petrov's harmonic-expansion ("heo") files, and the tables derived from them.

Public data files of NASA's sgdass (L. Petrov's VLBI software, github.com/nasa/sgdass, ``vtd/include/``,
commit 3e3cad5; written by his ``nut_out`` v4.2, 2003-12-27): ``ren2000_heo.i`` (REN-2000, the rigid
Earth: Souchay, Loysel, Kinoshita & Folgueira 1999, A&AS 135, 111), ``mhb2000_transf_heo.i`` (the same
constituents times MHB2000's transfer function: Mathews, Herring & Buffett 2002, JGR 107(B4) 2068),
``mhb2000_addon_heo.i`` (that, plus MHB2000's add-on terms) and ``mhb2000_heo.i`` (MHB2000 as in
T. Herring's code: the IAU 2000A nutation).  The files are not shipped; what is derived from them is
(``references.ren2000``, ``analysis.transfer.mhb2000_table``), their rows printed by

    python -m spinorbit.references.sgdass_heo DIRECTORY

Conventions, from the files' headers and ``nut_const.i``, checked against ERFA's nut00a
(tests/analysis/test_transfer.py): a constituent k has phase PHAS at J2000 (rad), rate FREQ in the
terrestrial frame, which turns at OM_NM + OM_PRC against space (rad/s), acceleration ACCL (rad/s^2), and
amplitudes PMC, PMS (prad; rates in 1e-24 rad/s).  In the plane (dpsi sin eps0, deps),
eps0 = EPSILON_0_NUT, the nutation is

    dpsi sin eps0 + i deps = sum_k i (PMC_k - i PMS_k) exp(i phi_k),
    phi_k(t) = PHAS_k + (FREQ_k + OM_NM + OM_PRC) t + ACCL_k t^2 / 2,    t in s from J2000 (TDB).

Times here are TDB days from J2000, amplitudes complex in rad (``i (PMC - i PMS)``: the coefficient of
exp(+i phi) in that plane).
"""
import itertools
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..base.constants import ARCSEC, DAY_S
from . import arguments

OM_NM = 7.292115146706979e-05            # rad/s, nut_const.i: nominal Earth angular velocity
OM_PRC = 7.08618327e-12                  # rad/s, nut_const.i: precession rate (L. Petrov 2002)
PRAD = 1e-12                             # rad per picoradian
RATE_UNIT = 1e-24                        # rad/s, the files' unit of amplitude rates
FILES = {"ren2000": "ren2000_heo.i", "mhb2000_transf": "mhb2000_transf_heo.i",
         "mhb2000_addon": "mhb2000_addon_heo.i", "mhb2000": "mhb2000_heo.i"}

_NUMBER = r"([-+]?\d*\.\d+D[-+]?\d+)"
_ARGUMENT = re.compile(r"^\s*&\s*" + r",\s*".join([_NUMBER] * 3) + r",\s*(\d+),\s*'([RP])'")
_AMPLITUDES = re.compile(r"^\s*&\s*" + r",\s*".join([_NUMBER] * 4))
_EPSILON = re.compile(r"Epsilon_o\s*=\s*([\d.]+)\s*rad")


@dataclass(frozen=True, eq=False)
class HeoSeries:
    """A nutation series: per constituent its phase at J2000 (rad), celestial rate (rad/s), acceleration
    (rad/s^2), complex amplitude (rad) and its rate (rad/s); ``eps0`` the obliquity of the plane (rad)."""

    phase: np.ndarray
    rate: np.ndarray
    accel: np.ndarray
    amplitude: np.ndarray
    amplitude_rate: np.ndarray
    eps0: float


def read(path):
    """The series of one heo file."""
    lines = Path(path).read_text().splitlines()
    eps0 = next(float(m[1]) for m in map(_EPSILON.search, lines) if m)
    rows = []
    for head, tail in itertools.pairwise(lines):
        if (arg := _ARGUMENT.match(head)) and (amp := _AMPLITUDES.match(tail)):
            rows.append([float(v.replace("D", "e")) for v in (*arg.groups()[:3], *amp.groups())])
    phase, freq, accel, pmc, pms, pmc_rate, pms_rate = np.array(rows).T
    return HeoSeries(phase, freq + OM_NM + OM_PRC, accel, 1j * (pmc - 1j * pms) * PRAD,
                     1j * (pmc_rate - 1j * pms_rate) * RATE_UNIT, eps0)


def nutation(series, t_tdb_d, chunk=256):
    """(dpsi, deps), rad, of the whole series at TDB days from J2000."""
    t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float)) * DAY_S
    z = np.empty(t.shape, dtype=complex)
    for start in range(0, t.size, chunk):
        ts = t[start:start + chunk, None]
        phi = series.phase + series.rate * ts + 0.5 * series.accel * ts**2
        terms = (series.amplitude + series.amplitude_rate * ts) * np.exp(1j * phi)
        z[start:start + chunk] = terms.sum(axis=1)
    return z.real / np.sin(series.eps0), z.imag


def constituent(series, multipliers, direction):
    """(amplitude rad, its rate rad/s), complex, of exp(direction i sum m_j F_j) (F_j Delaunay's arguments,
    ``multipliers`` m), summed over the series' entries at that phase and rate (REN-2000 lists some
    contributions to one argument apart); (0, 0) if the series has none."""
    phase, rate_d = arguments.phases(np.array([0.0]), [multipliers])
    rate = direction * rate_d[0] / DAY_S
    d_phase = np.angle(np.exp(1j * (series.phase - direction * phase[0, 0])))
    rows = (np.abs(series.rate - rate) < 1e-14) & (np.abs(d_phase) < 1e-6)
    return complex(series.amplitude[rows].sum()), complex(series.amplitude_rate[rows].sum())


def long_period_table(series, min_amplitude_rad, min_period_d=2.0):
    """references.ren2000.ROWS: the constituents of ``series`` with periods in space over ``min_period_d``
    (the CIP's nutation) and amplitudes from ``min_amplitude_rad``, in the files' units and order: PHAS,
    FREQ, ACCL, PMC, PMS (prad), PMC_RATE, PMS_RATE (1e-24 rad/s), rounded as the files write them."""
    long_period = np.abs(series.rate) * DAY_S < 2 * np.pi / min_period_d
    keep = long_period & (np.abs(series.amplitude) >= min_amplitude_rad)
    rows = []
    for k in np.flatnonzero(keep):
        a, r = series.amplitude[k] / PRAD, series.amplitude_rate[k] / RATE_UNIT
        amplitudes = (round(float(v), 1) for v in (a.imag, a.real, r.imag, r.real))
        rows.append((round(float(series.phase[k]), 10), float(f"{series.rate[k] - OM_NM - OM_PRC:.12e}"),
                     float(f"{series.accel[k]:.4e}"), *amplitudes))
    return rows


def transfer_table(directory, multipliers):
    """analysis.transfer.mhb2000_table.ROWS for the arguments ``multipliers`` (both directions, where REN-2000
    has the constituent): multipliers, direction, celestial frequency (cpsd, ERFA's arguments at J2000),
    T = MHB2000-transfer / REN-2000 (real, imaginary), the add-on term (prad: real, imaginary) and
    REN-2000's amplitude (prad)."""
    from ..bodies.earth import ERA_RATE_RAD_D

    series = [read(Path(directory) / FILES[key]) for key in ("ren2000", "mhb2000_transf", "mhb2000_addon")]
    rows = []
    for m in multipliers:
        for direction in (1, -1):
            ren, transf, addon = (constituent(s, m, direction)[0] for s in series)
            if ren == 0:
                continue
            t = transf / ren
            extra = (addon - transf) / PRAD if addon != 0 else 0j   # the add-on file: periods over 3.3 d
            nu = direction * arguments.phases(np.array([0.0]), [m])[1][0] / ERA_RATE_RAD_D
            rows.append((tuple(int(v) for v in m), direction, float(f"{nu:.12e}"), round(t.real, 12),
                         round(t.imag, 12), round(extra.real, 1), round(extra.imag, 1),
                         round(abs(ren) / PRAD, 1)))
    return rows


REN2000_MIN_AMPLITUDE_RAD = 1e-6 * ARCSEC     # 1 uas: the main terms' fitted parts move < 0.005 mas below it


def main(directory):
    """Print the rows of references.ren2000.ROWS and analysis.transfer.mhb2000_table.ROWS."""
    from ..analysis.nonrigid import LUNISOLAR_ARGUMENTS

    ren = long_period_table(read(Path(directory) / FILES["ren2000"]), REN2000_MIN_AMPLITUDE_RAD)
    print("# references/ren2000.py ROWS\n" + "\n".join(f"    {row!r}," for row in ren))
    transfer = transfer_table(directory, LUNISOLAR_ARGUMENTS)
    print("# analysis/transfer/mhb2000_table.py ROWS\n" + "\n".join(f"    {row!r}," for row in transfer))


if __name__ == "__main__":
    main(sys.argv[1])
