"""The Earth's answer layer on a stored rigid solution: the non-rigid pole (or the rigid one), the model's mean pole
and nutation about it, and IAU 2006/2000A's CIP beside them, as a Solution of their own.

Each of these is the Earth scene's own (the tides' secular turn, starts.earth_tides; the transfer function
applied term by term to the rigid nutation fitted on the luni-solar arguments, comparisons.earth_nonrigid;
the mean pole fitted with IAU 2000A's terms, comparisons.earth_iau.precession_nutation), a fit over a run.  The
fits are made over fixed windows, so that an answer at a date never depends on how far the store reaches
elsewhere: the scene's own span (the validated century) and its repeats either side (:func:`windows`), each
window fitted on the scene's output grid shifted onto it and answering for the dates between its edges rounded
to the solution's segments (so that a segment takes one window's fit); the layer spans the windows the stored
rigid solution covers whole, evaluated at the solution's Chebyshev points and fitted there like the rigid run;
its provenance lists the windows (``fit_windows_tdb_d``).  It is stored beside the rigid solution and computed
again when that is extended.  IAU's CIP is fitted too (ERFA takes ~0.2 ms a date): the fit's error, measured at
every tenth segment's in-between points, is in ``fit_error``.
"""
import math
from dataclasses import dataclass

import numpy as np

from ..base.errors import InputError
from ..base.layout import Layout
from . import store, stretches
from .chebyshev import Segments, interpolating
from .solution import Solution

LAYOUT = Layout([("earth.pole", 3, "vector", ""), ("iau.cip", 2, "vector", "rad"),
                 ("nutation.mean", 2, "vector", "rad"), ("nutation.offset", 2, "vector", "rad")])
CHECKED_EVERY = 10          # segments (those whose index on the grid is a multiple), at their inner extrema
FITS = "fixed windows: the scene's span and its repeats"      # in the record: layers fitted otherwise are not read


@dataclass(frozen=True)
class Window:
    """A fit window: the fits are made on ``grid`` (the scene's output times shifted by whole spans) and answer
    for the dates in [lo, hi] (its edges on the segment grid)."""

    grid: np.ndarray
    lo: float
    hi: float

    @property
    def reach(self):
        """(first, last) TDB days the rigid solution must cover for this window."""
        return min(self.lo, self.grid[0]), max(self.hi, self.grid[-1])


def windows(scenario, t_first, t_last):
    """The fit windows answering for the dates in [t_first, t_last] (TDB days), in time order."""
    times = np.sort(scenario.output_times())
    origin, length = times[0], times[-1] - times[0]
    grid = stretches.grid(stretches.stored(scenario))

    def edge(k):
        return grid.origin_d + round((origin + k * length - grid.origin_d) / grid.length_d) * grid.length_d

    def index(t):
        k = math.floor((t - origin) / length)
        return k - 1 if t < edge(k) else k + 1 if t >= edge(k + 1) else k

    return [Window(times + k * length, edge(k), edge(k + 1))
            for k in range(index(t_first), index(t_last) + 1)]


def reach(scenario, t_first, t_last):
    """(first, last) TDB days the rigid solution must cover to answer for [t_first, t_last]."""
    found = windows(scenario, t_first, t_last)
    return found[0].reach[0], found[-1].reach[1]


def covered(scenario, span):
    """The windows a rigid solution over ``span`` covers whole (none: InputError)."""
    found = [w for w in windows(scenario, *span) if span[0] <= w.reach[0] and w.reach[1] <= span[1]]
    if not found:
        raise InputError("span", f"{span[0]:.6g}..{span[1]:.6g} TDB days",
                         "a rigid Earth solution covering at least one fit window (the scene's whole span)")
    return found


def layer(rigid, scenario, nonrigid):
    """The layer (a Solution over the fit windows ``rigid`` covers whole) of the Earth scene ``scenario``,
    non-rigid or not."""
    from ..comparisons import earth_nonrigid as nr
    from ..starts import earth_tides as tides

    fits = covered(scenario, rigid.span)

    def computed(_, lo, hi):
        rates = tides.rates(scenario.params.earth.tides, scenario.params.orbit.source)
        return _computed(rigid, nr.settings(scenario.params) if nonrigid else None, rates, fits)

    return store.solve(_record(scenario, nonrigid), fits[0].lo, fits[-1].hi, computed)


def stored(scenario, nonrigid, t_start, t_end):
    """The stored layer when it covers [t_start, t_end], else None."""
    rec = _record(scenario, nonrigid)
    try:
        found = store.read(store.path_of(rec), rec)
    except store.Unreadable:
        return None
    return found if found is not None and found.covers(t_start, t_end) else None


def _record(scenario, nonrigid):
    return {**store.record(scenario), "scene": "earth_layer", "nonrigid": nonrigid, "fits": FITS,
            "transfer_function": scenario.params.earth.transfer_function if nonrigid else None}


def _basis(times):
    from ..analysis import nonrigid
    from ..references import arguments

    phases, _ = arguments.phases(times, nonrigid.LUNISOLAR_ARGUMENTS)
    return np.hstack([np.exp(1j * phases).T, np.exp(-1j * phases).T])


def _offsets(times, poles):
    from ..references import erfa_pole

    return np.array(erfa_pole.about_mean_pole(times, poles)), np.sin(erfa_pole.mean_angles(times)[3])


def _nonrigid_terms(grid, pole_at, settings):
    """The non-rigid layer's change to the nutation over a window's ``grid`` (``pole_at(times)``: the rigid
    poles): the scene's layer (comparisons.earth_nonrigid.nonrigid_pole) applied there, less MHB2000's nonlinear
    precession it adds, fitted as a sum of circular terms on the luni-solar arguments -- what the transfer
    function and MHB2000's add-on terms make of the fitted ones."""
    from ..analysis import nonrigid
    from ..comparisons import earth_nonrigid as nr

    z_grid = pole_at(grid)
    changed = nr.nonrigid_pole(grid, z_grid, **settings)
    (before, sin_grid), (after, _) = _offsets(grid, z_grid), _offsets(grid, changed)
    precession = nonrigid.nonlinear_precession(grid - grid[0])
    dz = (after[0] - before[0] - precession) * sin_grid + 1j * (after[1] - before[1])
    return np.linalg.lstsq(_basis(grid), dz, rcond=None)[0]


def _nonrigid(t, z, terms, start):
    """The non-rigid poles at ``t`` (n, 3) from the rigid ones ``z``: the fitted ``terms`` added to the
    nutation, MHB2000's nonlinear precession counted from ``start``."""
    from ..analysis import nonrigid
    from ..references import erfa_pole

    (dpsi, deps), sin_t = _offsets(t, z)
    dz_t = _basis(t) @ terms
    return erfa_pole.from_mean_pole(t, dpsi + dz_t.real / sin_t + nonrigid.nonlinear_precession(t - start),
                                    deps + dz_t.imag)


def _computed(rigid, settings, tide_rates, fits):
    """The layer over the windows ``fits``; the tides' secular turn (``tide_rates``, "/cy) and MHB2000's
    nonlinear precession accumulate from the solution's start, as the scene's from its span's; the non-rigid
    layer and the mean pole are fitted window by window."""
    from ..comparisons import earth_iau as vs
    from ..references import erfa_pole
    from ..starts import earth_tides as tides
    from .fit import errors

    segments = rigid.segments.window(fits[0].lo, fits[-1].hi)
    count = len(segments.coefficients)
    nodes, checks = segments.nodes(segments.first, count)
    checked = (np.arange(segments.first, segments.first + count) % CHECKED_EVERY) == 0
    t = np.concatenate([nodes.ravel(), checks[checked, 1:-1].ravel()])      # none on a window's edge
    order = np.argsort(t, kind="stable")
    start = rigid.provenance["runs"][0]["start_tdb_d"]

    def tilted(times):
        counted = np.concatenate([[start], times])                 # the turn counts from the start
        return tides.tilted(counted, rigid.part("earth.pole", counted), *tide_rates)[1:]

    ts = t[order]
    z, iau = tilted(ts), erfa_pole.IauPole()(ts)
    columns = np.empty((ts.size, LAYOUT.size))
    for window in fits:
        inside = (ts >= window.lo) & (ts < window.hi)
        zw, iau_w = z[inside], {key: value[inside] for key, value in iau.values.items()}
        if settings is not None:
            zw = _nonrigid(ts[inside], zw, _nonrigid_terms(window.grid, tilted, settings), start)
        _, _, nutation = vs.precession_nutation(ts[inside], zw, iau_w)
        columns[inside] = np.column_stack([zw, iau_w["cip_x_rad"], iau_w["cip_y_rad"], nutation["psi_mean"],
                                           nutation["eps_mean"], nutation["dpsi"], nutation["deps"]])
    values = np.empty_like(columns)
    values[order] = columns
    n = nodes.size
    at_nodes = values[:n].reshape(count, segments.degree + 1, -1).transpose(0, 2, 1)
    fitted = Segments(segments.origin_d, segments.length_d, segments.first, interpolating(at_nodes))
    provenance = {"scene": "earth_layer", "layer": "non-rigid" if settings else "rigid",
                  "nonrigid": settings, "fit_windows_tdb_d": [[w.grid[0], w.grid[-1]] for w in fits],
                  "rigid": rigid.provenance,
                  "fit_error": errors(LAYOUT, LAYOUT.normalise(fitted.evaluate(t[n:])), values[n:]),
                  "state_size": 0, "integrator": rigid.provenance["integrator"]}
    return Solution(fitted, LAYOUT, provenance, {"start": (fitted.span[0], np.zeros(0)),
                                                 "end": (fitted.span[1], np.zeros(0))})


def table(solution, t):
    """The Earth scene's columns (compare.table) at TDB days ``t`` from a layer."""
    import astropy.units as u
    from astropy.table import QTable

    from ..base.constants import MAS
    from ..scene.schema import tdb_days_to_time

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
