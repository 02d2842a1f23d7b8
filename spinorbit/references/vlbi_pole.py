"""VLBI's observed celestial pole: the offsets dX, dY of the CIP from the IAU 2006/2000A model.

IERS EOP 20 C04 (the IERS Earth Orientation Centre's combined series, consistent with ITRF 2020, daily at
0h UTC), as ``astropy-iers-data`` ships it offline and astropy reads it (``astropy.utils.iers.IERS_B``).
The IERS gives dX, dY with respect to IAU 2006/2000A (IERS Conventions 2010, TN36 §5.5.4; the file's
columns say "wrt IAU2000A Nutation", its header "IAU 2000"): the observed pole is IAU 2006/2000A + (dX, dY).
The rows before the first VLBI value (1984-01-01) hold zeros and are left out.  Times are TDB days from
J2000 (UTC + leap seconds + 32.184 s, then TDB - TT < 2 ms), offsets in rad.
"""
from dataclasses import dataclass

import numpy as np

from ..base.constants import J2000_JD


@dataclass(frozen=True, eq=False)
class PoleOffsets:
    """Observed CIP offsets from IAU 2006/2000A: times (TDB days), dX, dY and their errors (rad)."""

    t_tdb_d: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    dx_error: np.ndarray
    dy_error: np.ndarray


def offsets():
    """The C04 offsets from the first row with a VLBI value on."""
    from astropy.time import Time
    from astropy.utils import iers

    table = iers.IERS_B.open()
    dx, dy = (np.asarray(table[k].to_value("rad")) for k in ("dX_2000A", "dY_2000A"))
    first = int(np.argmax((dx != 0.0) | (dy != 0.0)))
    t = Time(np.asarray(table["MJD"].to_value("d"))[first:], format="mjd", scale="utc").tdb
    return PoleOffsets((t.jd1 - J2000_JD) + t.jd2, dx[first:], dy[first:],
                       *(np.asarray(table[k].to_value("rad"))[first:] for k in ("e_dX_2000A", "e_dY_2000A")))


def provenance():
    """Where the observed offsets come from."""
    from pathlib import Path

    import astropy_iers_data

    return {"name": "VLBI celestial pole offsets dX, dY from IAU 2006/2000A (IERS EOP 20 C04)",
            "data": f"astropy-iers-data {astropy_iers_data.__version__} "
                    f"({Path(astropy_iers_data.IERS_B_FILE).name})",
            "citation": "IERS Earth Orientation Centre, EOP 20 C04 (consistent with ITRF 2020); IERS "
                        "Conventions (2010), TN36 §5.5.4",
            "span": "from 1984-01-01 (the first VLBI value) to the table's last row"}
