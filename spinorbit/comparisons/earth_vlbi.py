"""An Earth run's pole against VLBI's observed pole, beside IAU 2006/2000A's.

Edge module.  The observed CIP is IAU 2006/2000A + (dX, dY) (IERS EOP 20 C04, references.vlbi_pole), so
model - observed = (model - IAU) - (dX, dY) and IAU - observed = -(dX, dY), at the run's output times within
the table's span (the daily offsets interpolated linearly), over it and per decade.  The C04 table runs from
1962; its dX, dY are VLBI's, from 1984 (the rows before hold zeros and are left out).  The free core
nutation, a free mode no forced model holds, is in the observed offsets: the comparison is given as it is
and with S. Lambert's empirical FCN (references.fcn_lambert) taken out of the observations over that model's
span, beside the same span with it left in.
"""
import numpy as np

from ..base.constants import JULIAN_YEAR_D, MAS
from ..references import fcn_lambert, vlbi_pole


def vlbi_summary(t, dx_mas, dy_mas):
    """{span: {rms and counts}} of model - observed and IAU - observed (mas) in X and Y over the span the run
    and
    the C04 table share, and over the FCN model's span with and without the FCN; None if they share none.
    ``dx_mas``, ``dy_mas``: the run's model - IAU 2006/2000A at its times ``t`` (TDB days)."""
    observed = vlbi_pole.offsets()
    inside = (t >= max(t[0], observed.t_tdb_d[0])) & (t <= min(t[-1], observed.t_tdb_d[-1]))
    if not inside.any():
        return None
    t_in = t[inside]
    dx_obs, dy_obs = (np.interp(t_in, observed.t_tdb_d, v) / MAS for v in (observed.dx, observed.dy))
    rows = {"c04": _rms_pair(t_in, dx_mas[inside], dy_mas[inside], dx_obs, dy_obs),
            "per_decade": per_decade(t_in, dx_mas[inside], dy_mas[inside], dx_obs, dy_obs)}
    fcn_span = (t_in >= fcn_lambert.SPAN_TDB_D[0]) & (t_in <= fcn_lambert.SPAN_TDB_D[1])
    if fcn_span.any():
        tf = t_in[fcn_span]
        fx, fy = (v / MAS for v in fcn_lambert.fcn_pole(tf))
        model = (dx_mas[inside][fcn_span], dy_mas[inside][fcn_span])
        rows["fcn_span_with_fcn"] = _rms_pair(tf, *model, dx_obs[fcn_span], dy_obs[fcn_span])
        rows["fcn_span_fcn_removed"] = _rms_pair(tf, *model, dx_obs[fcn_span] - fx, dy_obs[fcn_span] - fy)
        rows["fcn_size_mas"] = {"x_rms": _rms(fx), "y_rms": _rms(fy),
                                "max": float(np.abs(fx + 1j * fy).max())}
    return {"comparison": rows, "reference": vlbi_pole.provenance(), "fcn_model": fcn_lambert.provenance()}


def per_decade(t, dx_model, dy_model, dx_obs, dy_obs):
    """{"1990s": _rms_pair, ...} over each calendar decade the times reach (Julian years from J2000)."""
    years = 2000.0 + t / JULIAN_YEAR_D
    rows = {}
    for decade in range(int(years[0] // 10) * 10, int(years[-1]) + 1, 10):
        k = (years >= decade) & (years < decade + 10)
        if k.any():
            rows[f"{decade}s"] = _rms_pair(t[k], dx_model[k], dy_model[k], dx_obs[k], dy_obs[k])
    return rows


def _rms_pair(t, dx_model, dy_model, dx_obs, dy_obs):
    return {"start_tdb_d": float(t[0]), "end_tdb_d": float(t[-1]), "n": int(t.size),
            "model_minus_observed_x_rms_mas": _rms(dx_model - dx_obs),
            "model_minus_observed_y_rms_mas": _rms(dy_model - dy_obs),
            "iau_minus_observed_x_rms_mas": _rms(-dx_obs), "iau_minus_observed_y_rms_mas": _rms(-dy_obs)}


def _rms(x):
    return float(np.sqrt(np.mean(np.square(x))))
