"""The Earth's answer layer on a stored rigid solution: the non-rigid pole (or the rigid one), the model's mean pole
and nutation about it, and IAU 2006/2000A's CIP beside them, as a Solution of their own.

Each of these is the Earth scene's own (the tides' secular turn, starts.earth_tides; the transfer function
applied term by term to the rigid nutation fitted on the luni-solar arguments, comparisons.earth_nonrigid;
the mean pole fitted with IAU 2000A's terms, comparisons.earth_iau.precession_nutation), a fit over a run,
so the layer is computed once over the stored rigid solution's whole span -- the non-rigid fit on the scene's
own output grid, continued over the span (_grid, _nonrigid), the rest at the solution's Chebyshev points --
and fitted there like the rigid run; its provenance says over which span (``fit_over_tdb_d``).  It is stored
beside the rigid solution and computed again when that is extended.  IAU's CIP is fitted too (ERFA takes
~0.2 ms a date): the fit's error, measured at a tenth of the segments' in-between points, is in
``fit_error``.
"""
import numpy as np

from ..layout import Layout
from . import store
from .chebyshev import Segments, interpolating
from .fit import errors
from .solution import Solution

LAYOUT = Layout([("earth.pole", 3, "vector", ""), ("iau.cip", 2, "vector", "rad"),
                 ("nutation.mean", 2, "vector", "rad"), ("nutation.offset", 2, "vector", "rad")])
CHECKED_EVERY = 10          # segments


def layer(rigid, scenario, nonrigid):
    """The layer (a Solution over ``rigid``'s span) of the Earth scene ``scenario``, non-rigid or not."""
    from ..comparisons import earth_nonrigid as nr
    from ..starts import earth_tides as tides

    def computed(_, lo, hi):
        rates = tides.rates(scenario["earth.tides"], scenario["orbit.source"])
        return _computed(rigid, nr.settings(scenario) if nonrigid else None, rates, _grid(rigid, scenario))

    return store.solve(_record(scenario, nonrigid), *rigid.span, computed)


def stored(scenario, nonrigid, t_start, t_end):
    """The stored layer when it covers [t_start, t_end] and was fitted over the whole stored rigid solution
    (its span is the rigid one's: the solution is extended only at its ends), else None."""
    rec = _record(scenario, nonrigid)
    try:
        found = store.read(store.path_of(rec), rec)
    except store.Unreadable:
        return None
    rigid = store.entry_span(store.path_of(store.record(scenario)))
    if found is None or rigid is None or tuple(found.span) != tuple(rigid) or not found.covers(t_start, t_end):
        return None
    return found


def _record(scenario, nonrigid):
    return {**store.record(scenario), "scene": "earth_layer", "nonrigid": nonrigid,
            "transfer_function": scenario["earth.transfer_function"] if nonrigid else None}


def _grid(rigid, scenario):
    """The scene's own output times, continued at its step over the rest of the stored span: where the
    non-rigid layer's fit is made (as the scene makes it)."""
    t, step = np.sort(scenario.output_times()), scenario["span.step"]
    lo, hi = rigid.span
    before = np.arange(t[0] - step, lo - 1e-9, -step)[::-1]
    return np.concatenate([before, t[(t >= lo) & (t <= hi)], np.arange(t[-1] + step, hi + 1e-9, step)])


def _counted_from(start, t):
    """``t`` with ``start`` before it, unless it begins there: the scene's turns count from its first time."""
    return t if t[0] == start else np.concatenate([[start], t])


def _nonrigid(t, z, grid, pole_at, settings, start):
    """The non-rigid poles at ``t`` (n, 3) from the rigid ones ``z``: the scene's non-rigid layer
    (comparisons.earth_nonrigid.nonrigid_pole) applied on ``grid`` (``pole_at(times)``: the rigid poles), and
    its change to the nutation -- a sum of circular terms on the luni-solar arguments, what the transfer
    function and MHB2000's add-on terms make of the fitted ones -- refitted on those terms and evaluated at
    ``t``; MHB2000's nonlinear precession counted from ``start``."""
    from ..analysis import nonrigid
    from ..comparisons import earth_nonrigid as nr
    from ..references import arguments, erfa_pole

    fit_t = _counted_from(start, grid)
    z_grid = pole_at(grid)
    changed = nr.nonrigid_pole(fit_t, pole_at(fit_t), **settings)[fit_t.size - grid.size:]

    def basis(times):
        phases, _ = arguments.phases(times, nonrigid.LUNISOLAR_ARGUMENTS)
        return np.hstack([np.exp(1j * phases).T, np.exp(-1j * phases).T])

    def offsets(times, poles):
        return np.array(erfa_pole.about_mean_pole(times, poles)), np.sin(erfa_pole.mean_angles(times)[3])

    (before, sin_grid), (after, _) = offsets(grid, z_grid), offsets(grid, changed)
    precession = nonrigid.nonlinear_precession(grid - start)
    dz = (after[0] - before[0] - precession) * sin_grid + 1j * (after[1] - before[1])
    terms = np.linalg.lstsq(basis(grid), dz, rcond=None)[0]
    (dpsi, deps), sin_t = offsets(t, z)
    dz_t = basis(t) @ terms
    return erfa_pole.from_mean_pole(t, dpsi + dz_t.real / sin_t + nonrigid.nonlinear_precession(t - start),
                                    deps + dz_t.imag)


def _computed(rigid, settings, tide_rates, grid):
    """The layer over the rigid solution's span; the tides' secular turn (``tide_rates``, "/cy) and MHB2000's
    nonlinear precession accumulate from the solution's start, as the scene's from its span's; the non-rigid
    layer's fit is made on ``grid`` (_nonrigid)."""
    from ..comparisons import earth_iau as vs
    from ..references import erfa_pole
    from ..starts import earth_tides as tides

    segments = rigid.segments
    count = len(segments.coefficients)
    nodes, checks = segments.nodes(segments.first, count)
    t = np.concatenate([nodes.ravel(), checks[::CHECKED_EVERY].ravel()])
    order = np.argsort(t, kind="stable")
    start = rigid.provenance["runs"][0]["start_tdb_d"]

    def tilted(times):
        counted = np.concatenate([[start], times])                 # the turn counts from the start
        return tides.tilted(counted, rigid.part("earth.pole", counted), *tide_rates)[1:]

    ts = t[order]
    z = tilted(ts)
    if settings is not None:
        z = _nonrigid(ts, z, grid, tilted, settings, start)
    iau = erfa_pole.IauPole()(ts)
    _, _, nutation = vs.precession_nutation(ts, z, iau)
    values = np.empty((t.size, LAYOUT.size))
    values[order] = np.column_stack([z, iau["cip_x_rad"], iau["cip_y_rad"], nutation["psi_mean"],
                                     nutation["eps_mean"], nutation["dpsi"], nutation["deps"]])
    n = nodes.size
    at_nodes = values[:n].reshape(count, segments.degree + 1, -1).transpose(0, 2, 1)
    fitted = Segments(segments.origin_d, segments.length_d, segments.first, interpolating(at_nodes))
    provenance = {"scene": "earth_layer", "layer": "non-rigid" if settings else "rigid",
                  "nonrigid": settings, "fit_over_tdb_d": list(rigid.span), "rigid": rigid.provenance,
                  "fit_error": errors(LAYOUT, LAYOUT.normalise(fitted.evaluate(t[n:])), values[n:]),
                  "state_size": 0, "integrator": rigid.provenance["integrator"]}
    return Solution(fitted, LAYOUT, provenance, {"start": (rigid.span[0], np.zeros(0)),
                                                 "end": (rigid.span[1], np.zeros(0))})


def table(solution, t):
    """The Earth scene's columns (compare.table) at TDB days ``t`` from a layer."""
    import astropy.units as u
    from astropy.table import QTable

    from ..constants import MAS
    from ..schema import tdb_days_to_time

    values = solution.components(t)
    z, cip = values[:, LAYOUT["earth.pole"]], values[:, LAYOUT["iau.cip"]]
    mean, offset = values[:, LAYOUT["nutation.mean"]], values[:, LAYOUT["nutation.offset"]]
    arcsec = lambda x: (x * u.rad).to(u.arcsec)
    time = tdb_days_to_time(t)
    s, celestial_to_intermediate = intermediate_frame(time, z[:, 0], z[:, 1])
    return QTable({"time": time, "cip_x": arcsec(z[:, 0]), "cip_y": arcsec(z[:, 1]),
                   "cip_x_minus_erfa": (z[:, 0] - cip[:, 0]) / MAS * u.mas,
                   "cip_y_minus_erfa": (z[:, 1] - cip[:, 1]) / MAS * u.mas,
                   "precession_longitude": arcsec(mean[:, 0]), "obliquity": (mean[:, 1] * u.rad).to(u.deg),
                   "nutation_longitude": arcsec(offset[:, 0]), "nutation_obliquity": arcsec(offset[:, 1]),
                   "cio_locator_s": arcsec(s), "celestial_to_intermediate": celestial_to_intermediate})


def intermediate_frame(time, x, y):
    """(the CIO locator s (n,) rad, the GCRS-to-CIRS matrices (n, 3, 3)) of the CIP X, Y (rad) at ``time``
    (astropy Time): s from IAU 2006's series given X, Y (ERFA s06), the matrix from X, Y and s (ERFA c2ixys),
    as ERFA's c2i06a builds them from IAU 2006/2000A's own X, Y (IERS Conventions 2010, 5.4.4 and 5.5.6)."""
    import erfa

    tt = time.tt
    s = erfa.s06(tt.jd1, tt.jd2, x, y)
    return s, erfa.c2ixys(x, y, s)
