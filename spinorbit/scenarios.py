"""Scenario files (TOML): loading, ``--set`` overrides, and validation with clear errors.

A scenario is a TOML file with a ``[scene]`` table naming its ``kind`` (one of
``spinorbit.scenes.SCENES``), a ``[span]`` table, an ``[integrator]`` table, and
the tables its kind declares in its ``SCHEMA``.  Every key is checked: an
unknown key, a missing table, a wrong unit or an impossible value raises
:class:`ScenarioError` naming the dotted key path, what was given and what is
accepted.

Quantities are strings with units, parsed by astropy (``"384400 km"``,
``"13.18 deg/d"``); bare numbers are accepted only for dimensionless keys.
Times are ISO strings in TDB; ``span.end`` may also be a duration from
``span.start`` (``"100 yr"``, ``"1073.15 d"``).
"""
import datetime
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .constants import J2000_JD
from .errors import ScenarioError

REQUIRED = object()


@dataclass(frozen=True)
class Key:
    """One accepted scenario key.

    ``unit``: internal unit a quantity is converted to (None: not a quantity,
    "" : dimensionless); ``size``: vector length (0 for a scalar);
    ``choices``: accepted strings; ``type``: python type for non-quantities.
    """

    unit: str | None = None
    default: object = REQUIRED
    size: int = 0
    choices: tuple = ()
    type: type = float
    help: str = ""

    def accepted(self):
        if self.choices:
            return f"one of {list(self.choices)}"
        if self.unit:
            what = f"a list of {self.size} quantities" if self.size else "a quantity"
            return f"{what} in units convertible to '{self.unit}', e.g. \"1.0 {self.unit}\""
        if self.unit == "":
            return f"a list of {self.size} numbers" if self.size else "a number"
        return f"a value of type {self.type.__name__}"


COMMON_SCHEMA = {
    "scene.kind": Key(type=str),
    "scene.title": Key(type=str, default=""),
    "scene.description": Key(type=str, default=""),
    "span.start": Key(type=str, help="ISO time, TDB"),
    "span.end": Key(type=str, help="ISO time (TDB) or a duration such as '100 yr'"),
    "span.step": Key(unit="d", help="output cadence"),
    "integrator.method": Key(type=str, default="dop853"),
    "integrator.estimate_error": Key(type=bool, default=True),
    "output.plots": Key(type=bool, default=True),
}
# integrator.<option> keys are passed to the chosen method, which checks their names.
OPEN_TABLES = ("integrator",)


class Scenario:
    """A validated scenario: ``scenario["body.moments"]`` gives the converted value."""

    def __init__(self, data, path=None):
        self.data = data
        self.path = Path(path) if path else None
        self.name = self.path.stem if self.path else "scenario"
        from .scenes import scene_module            # the scene registry (lazy imports)

        kind = _lookup(data, "scene.kind", Key(type=str))
        self.module = scene_module(kind)
        self.schema = {**COMMON_SCHEMA, **self.module.SCHEMA}
        self._check_keys()
        self.values = {key: self._convert(key, spec) for key, spec in self.schema.items()}
        self.kind = kind
        self.t_start, self.t_end = self._span()
        from .integrators import get_method

        get_method(self["integrator.method"])(**self.integrator_options())   # checks method and options now

    def __getitem__(self, key):
        if key not in self.values:
            raise KeyError(f"{key} is not a key of scene kind '{self.kind}'")
        return self.values[key]

    def get(self, key, default=None):
        value = self.values.get(key)
        return default if value is None else value

    def integrator_options(self):
        """Options for the integrator (all of [integrator] but method/estimate_error), units -> days."""
        options = {}
        for key, value in self.data.get("integrator", {}).items():
            if key in ("method", "estimate_error"):
                continue
            options[key] = _to_float(f"integrator.{key}", value, "d" if key == "step" else "")
        return options

    def output_times(self):
        """Output times in TDB days from J2000: start to end at span.step (end included)."""
        step = self["span.step"]
        n = int(np.floor((self.t_end - self.t_start) / step + 1e-9))
        times = self.t_start + step * np.arange(n + 1)
        return times if np.isclose(times[-1], self.t_end, rtol=0, atol=1e-9 * step) else np.append(times, self.t_end)

    # --- validation -------------------------------------------------------
    def _check_keys(self):
        tables = {key.split(".")[0] for key in self.schema}
        for table, content in self.data.items():
            if table not in tables:
                raise ScenarioError(table, "(table)", f"one of the tables {sorted(tables)}")
            if not isinstance(content, dict):
                raise ScenarioError(table, content, "a table")
            if table in OPEN_TABLES:
                continue
            for name in _flatten(content, table):
                if name not in self.schema:
                    accepted = sorted(k for k in self.schema if k.startswith(table + "."))
                    raise ScenarioError(name, _lookup(self.data, name, Key(type=object)), f"one of the keys {accepted}")
        for key, spec in self.schema.items():
            if spec.default is REQUIRED and not _has(self.data, key):
                table = key.split(".")[0]
                given = "(missing table)" if table not in self.data else "(missing)"
                raise ScenarioError(key, given, spec.accepted())

    def _convert(self, key, spec):
        if not _has(self.data, key):
            return spec.default
        value = _lookup(self.data, key, spec)
        if spec.choices:
            if value not in spec.choices:
                raise ScenarioError(key, value, spec.accepted())
            return value
        if spec.unit is None:
            if spec.type is str and isinstance(value, (datetime.date, datetime.time)):
                value = _toml_datetime_text(key, value)
            if spec.type is float and isinstance(value, int) and not isinstance(value, bool):
                return float(value)
            if not isinstance(value, spec.type) or (spec.type is not bool and isinstance(value, bool)):
                raise ScenarioError(key, value, spec.accepted())
            return value
        if spec.size:
            if not isinstance(value, list) or len(value) != spec.size:
                raise ScenarioError(key, value, spec.accepted())
            return np.array([_to_float(key, v, spec.unit) for v in value])
        return _to_float(key, value, spec.unit)

    def _span(self):
        start = parse_tdb_days("span.start", self["span.start"])
        end_text = self["span.end"]
        try:
            end = parse_tdb_days("span.end", end_text)
        except ScenarioError:
            end = start + _to_float("span.end", end_text, "d")
        if not end > start:
            raise ScenarioError("span.end", end_text, f"a time after span.start ({self['span.start']})")
        if not self["span.step"] > 0:
            raise ScenarioError("span.step", self.data["span"]["step"], "a positive duration")
        return start, end


def _toml_datetime_text(key, value):
    """An unquoted TOML date/datetime as ISO text; a time zone makes no sense for TDB."""
    if getattr(value, "tzinfo", None) is not None:
        raise ScenarioError(key, value.isoformat(), "a TDB time without a time-zone offset, e.g. 2000-01-01T12:00:00")
    return value.isoformat()


def parse_tdb_days(key, text):
    """ISO time string (TDB) -> days from J2000.0 TDB."""
    from astropy.time import Time

    if not isinstance(text, str) or not text[:1].isdigit() or "-" not in text[1:]:
        raise ScenarioError(key, text, "an ISO time in TDB, e.g. '2000-01-01T12:00:00'")
    try:
        t = Time(text, scale="tdb")
    except ValueError:
        raise ScenarioError(key, text, "an ISO time in TDB, e.g. '2000-01-01T12:00:00'") from None
    return (t.jd1 - J2000_JD) + t.jd2


def tdb_days_to_time(t_days):
    """TDB days from J2000.0 -> astropy Time (scale TDB)."""
    from astropy.time import Time

    return Time(J2000_JD, np.asarray(t_days), format="jd", scale="tdb")


def _to_float(key, value, unit):
    """A TOML value (number or quantity string) as a float in ``unit``."""
    import astropy.units as u

    if isinstance(value, bool):
        raise ScenarioError(key, value, f"a quantity in '{unit}'")
    if isinstance(value, (int, float)):
        if unit:
            raise ScenarioError(key, value, f"a quantity with a unit convertible to '{unit}', e.g. \"{value} {unit}\"")
        return float(value)
    try:
        quantity = u.Quantity(value)
    except (TypeError, ValueError):
        raise ScenarioError(key, value, f"a quantity such as \"1.0 {unit or ''}\"".replace(' "', ' "')) from None
    try:
        return float(quantity.to_value(unit or u.dimensionless_unscaled, equivalencies=u.dimensionless_angles() if unit and "rad" in unit else []))
    except u.UnitConversionError:
        raise ScenarioError(key, value, f"units convertible to '{unit or 'dimensionless'}'") from None


def _flatten(table, prefix):
    for name, value in table.items():
        key = f"{prefix}.{name}"
        if isinstance(value, dict):
            yield from _flatten(value, key)
        else:
            yield key


def _has(data, key):
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return False
        node = node[part]
    return True


def _lookup(data, key, spec):
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            raise ScenarioError(key, "(missing)", spec.accepted())
        node = node[part]
    return node


def apply_override(data, assignment):
    """Apply one ``--set dotted.key=value`` (value parsed as TOML, else taken as a string)."""
    if "=" not in assignment:
        raise ScenarioError("--set", assignment, "key=value, e.g. span.end=2030-01-01")
    key, text = (s.strip() for s in assignment.split("=", 1))
    try:
        value = tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        value = text
    node = data
    parts = key.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ScenarioError(key, assignment, "a dotted path into the scenario's tables")
    node[parts[-1]] = value


def load_scenario(path, overrides=()):
    """Read and validate a scenario file; ``overrides`` are ``key=value`` strings."""
    path = Path(path)
    if not path.is_file():
        raise ScenarioError("scenario", str(path), "an existing .toml file (see `spinorbit list`)")
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(str(path), f"invalid TOML ({exc})", "a TOML file") from None
    for assignment in overrides:
        apply_override(data, assignment)
    return Scenario(data, path)
