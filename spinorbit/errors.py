"""Exceptions, each named after what went wrong and saying what to do next."""


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
        super().__init__(f"{_short(str(key))}: got {_short(repr(given))}; expected {' '.join(str(accepted).split())}")


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
        super().__init__(f"{_short(str(name))}: got {_short(repr(given))}; expected {' '.join(str(accepted).split())}")


class PhysicsError(SpinorbitError, ValueError):
    """Parameters that do not describe a physical system (e.g. a non-rigid inertia)."""


class EphemerisRangeError(SpinorbitError, ValueError):
    """A time outside the span an orbit source covers; never extrapolated."""

    def __init__(self, source, requested, span, unit="TDB days from J2000", note=""):
        self.source, self.requested, self.span, self.note = source, requested, span, note
        asked = f"{requested[0]:.6g} to {requested[1]:.6g}" if isinstance(requested, tuple) else requested
        super().__init__(
            f"{source} covers {span[0]:.6g} to {span[1]:.6g} {unit} ({_epochs(span)}{note}); "
            f"asked for {asked}. Shorten [span], or choose a source that covers it "
            "(a larger .bsp in ephemerides/, or orbit.source = 'rebound')."
        )


def _epochs(span_days):
    """Julian epochs of a span in TDB days from J2000, e.g. 'J1899.92 to J2200.08'."""
    return " to ".join(f"J{2000.0 + t / 365.25:.2f}" for t in span_days)


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
