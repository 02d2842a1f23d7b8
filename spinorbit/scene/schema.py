"""What a scenario key may hold, and how a TOML value becomes a number in internal units.

Edge module (imports astropy), below ``scenarios`` and ``scenes``: a scene declares its keys
with :class:`Key` and the shared plausible ranges here; ``scenarios`` reads the file and checks
it against the scene's keys.  Quantities are strings with units, parsed by astropy
(``"384400 km"``, ``"13.18 deg/d"``); bare numbers only for dimensionless keys; times are
ISO strings in TDB, TDB days from J2000.0 inside.
"""
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..base.constants import J2000_JD
from ..base.errors import InputError, ScenarioError
from ..integrators.options import OPTIONS

REQUIRED = object()
MAX_TEXT = 10_000              # characters in a string value
EPS = float(np.finfo(float).eps)
# Plausible ranges scenes share, in internal units: Key(**GM, help=...).
GM = {"unit": "km3/d2", "positive": True, "max": 1e22}   # up to ~10 solar masses
DISTANCE = {"unit": "km", "min": 1.0, "max": 1e12}       # 1 km to ~7000 au
RATE = {"unit": "rad/d", "min": -1e3, "max": 1e3}        # orbital rates (Phobos: 20 rad/d)
SPIN = {"unit": "rad/d", "min": -1e6, "max": 1e6}        # spin rates, up to ~160 000 turns a day
ANGLE = {"unit": "rad", "min": -2 * math.pi, "max": 2 * math.pi}
SAMPLE_STEP = {"unit": "d", "positive": True, "max": 10.0, "count": "orbit samples"}


@dataclass(frozen=True)
class Key:
    """One accepted scenario key.

    ``unit``: internal unit a quantity is converted to (None: not a quantity,
    "" : dimensionless); ``size``: vector length (0 for a scalar);
    ``choices``: accepted strings; ``type``: python type for non-quantities.
    ``min``/``max``: plausible range of a number (in ``unit``), inclusive;
    ``positive``: must be > 0; ``count``: a step whose number over the span is
    limited (a key of ``LIMITS``); ``direction``: a vector the scene normalises
    (non-zero, with a finite length); ``parse``: what the checked value names, made
    at load (a name -> its OrbitSource, ISO text -> TDB days), raising InputError or
    ScenarioError (the key's refusal, in one line) when it names nothing.
    """

    unit: str | None = None
    default: object = REQUIRED
    size: int = 0
    choices: tuple = ()
    type: type = float
    help: str = ""
    min: float = -math.inf
    max: float = math.inf
    positive: bool = False
    count: str = ""
    direction: bool = False
    parse: Callable | None = None

    def accepted(self):
        if self.choices:
            return f"one of {list(self.choices)}"
        if self.unit:
            what = f"a list of {self.size} quantities" if self.size else "a quantity"
            return f"{what} in units convertible to '{self.unit}', e.g. \"1.0 {self.unit}\""
        if self.unit == "":
            return f"a list of {self.size} numbers" if self.size else "a number"
        if self.type is str and self.help:
            return f"a string: {self.help}"
        return f"a value of type {self.type.__name__}"

    def check_range(self, key, value, given):
        """Raise ScenarioError unless ``value`` (in ``unit``) is finite and inside the range."""
        inside = self.min <= value <= self.max and (value > 0 or not self.positive)
        if math.isfinite(value) and inside:
            return
        what = "a finite quantity" if self.unit else "a finite number"
        if self.positive or math.isfinite(self.min) or math.isfinite(self.max):
            low = "(0" if self.positive and self.min <= 0 else \
                "(-inf" if math.isinf(self.min) else f"[{self.min:g}"
            high = f"{self.max:g}]" if math.isfinite(self.max) else "inf)"
            what += f" in {low}, {high}" + (f" {self.unit}" if self.unit else "")
        raise ScenarioError(key, given, what)

    def parsed(self, key, value):
        """``value`` (checked) as the object it names (``parse``), or as it is; a refusal is a ScenarioError on
        ``key`` with what was given and what the parser accepts."""
        if self.parse is None:
            return value
        try:
            return self.parse(value)
        except (InputError, ScenarioError) as exc:
            raise ScenarioError(key, value, exc.accepted) from None


# integrator.<option> keys: the chosen method's class says which it accepts; their meaning, unit and range are
# declared once, with the integrators (spinorbit.integrators.options).
INTEGRATOR_OPTIONS = {name: Key(unit=option.unit, min=option.min, max=option.max, positive=option.positive,
                                count=option.count, help=option.help)
                      for name, option in OPTIONS.items() if option.numeric}


ISO_TDB = "an ISO date in TDB without a time zone, e.g. '2000-01-01' or '2000-01-01T12:00:00'"


def parse_tdb_days(key, text):
    """ISO time string (TDB) -> days from J2000.0 TDB."""
    from astropy.time import Time

    if not isinstance(text, str) or not text[:1].isdigit() or "-" not in text[1:]:
        raise ScenarioError(key, text, ISO_TDB)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")          # e.g. ERFA's "dubious year": refuse, do not print
            t = Time(text, scale="tdb")
            days = (t.jd1 - J2000_JD) + t.jd2
    except (ValueError, TypeError, ArithmeticError, Warning):
        raise ScenarioError(key, text, ISO_TDB) from None
    if not math.isfinite(days):
        raise ScenarioError(key, text, ISO_TDB)
    return days


def tdb_days_to_time(t_days):
    """TDB days from J2000.0 -> astropy Time (scale TDB)."""
    from astropy.time import Time

    return Time(J2000_JD, np.asarray(t_days), format="jd", scale="tdb")


def to_float(key, value, unit):
    """A TOML value (number or quantity string), or an astropy Quantity, as a float in ``unit``."""
    import astropy.units as u

    if isinstance(value, u.Quantity):
        return _quantity_value(key, value, unit)
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ScenarioError(key, value, f"a quantity in '{unit}'" if unit else "a number")
    if isinstance(value, (int, float)):
        if unit:
            example = value if len(str(value)) <= 20 else 1.0
            raise ScenarioError(key, value,
                                f"a quantity with a unit convertible to '{unit}', e.g. \"{example} {unit}\"")
        return finite_float(key, value)
    example = f'"1.0 {unit}"' if unit else "1.0"
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # astropy's unit and overflow warnings: refuse, do not print
        try:
            quantity = _quantity(value)
        except (TypeError, ValueError, ArithmeticError, LookupError, RecursionError, Warning):
            raise ScenarioError(key, value, f"a quantity such as {example}") from None
        if not quantity.isscalar:
            raise ScenarioError(key, value, f"a single quantity such as {example}")
        try:
            angles = u.dimensionless_angles() if unit and "rad" in unit else []
            return float(quantity.to_value(unit or u.dimensionless_unscaled, equivalencies=angles))
        except (u.UnitsError, TypeError, ValueError):
            raise ScenarioError(key, value, f"units convertible to '{unit or 'dimensionless'}'") from None
        except (ArithmeticError, Warning):
            raise ScenarioError(key, value, "a finite quantity (this one overflows)") from None


def _quantity(text):
    """astropy's Quantity of ``text``, a plural unit read as its singular ("2 days" is "2 day")."""
    import re

    import astropy.units as u

    try:
        return u.Quantity(text)
    except ValueError:
        singular = re.sub(r"\b([A-Za-z]{2,})s\b", r"\1", text)
        if singular == text:
            raise
        return u.Quantity(singular)


def _quantity_value(key, quantity, unit):
    """An astropy Quantity (the API's values) as a float in ``unit``: converted, never written as text."""
    import astropy.units as u

    if not quantity.isscalar:
        raise ScenarioError(key, str(quantity), f"a single quantity in '{unit}'")
    angles = u.dimensionless_angles() if unit and "rad" in unit else []
    try:
        number = float(quantity.to_value(unit or u.dimensionless_unscaled, equivalencies=angles))
    except (u.UnitsError, TypeError, ValueError):
        raise ScenarioError(key, str(quantity), f"units convertible to '{unit or 'dimensionless'}'") from None
    if not math.isfinite(number):
        raise ScenarioError(key, str(quantity), "a finite quantity")
    return number


def finite_float(key, value):
    """float(value), refusing integers too large for a float."""
    try:
        return float(value)
    except OverflowError:
        raise ScenarioError(key, value, "a finite number (at most ~1.8e308)") from None


def checked_float(key, value, spec):
    """``value`` as a float in ``spec.unit``, finite and inside the key's range."""
    number = to_float(key, value, spec.unit)
    spec.check_range(key, number, value)
    return number




def has_key(data, key):
    """Whether dotted ``key`` is in the nested tables ``data``."""
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return False
        node = node[part]
    return True


def lookup(data, key, spec):
    """The value at dotted ``key`` of ``data``; ScenarioError (missing, what ``spec`` accepts) when absent."""
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            raise ScenarioError(key, "(missing)", spec.accepted())
        node = node[part]
    return node


def dotted_items(table, prefix="", is_table=None):
    """(dotted key, value) of every leaf of a nested dict (a TOML table, a summary):
    {"a": {"b": 1}} -> ("a.b", 1); a dict for which ``is_table(dict)`` is true is a leaf."""
    for name, value in table.items():
        key = f"{prefix}{name}"
        if isinstance(value, dict) and not (is_table and is_table(value)):
            yield from dotted_items(value, key + ".", is_table)
        else:
            yield key, value
