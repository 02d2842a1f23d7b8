"""Scenario files (TOML): loading, ``--set`` overrides, and validation with clear errors.

A scenario is a TOML file with a ``[scene]`` table naming its ``kind`` (one of
``spinorbit.scenes.SCENES``), a ``[span]`` table, an ``[integrator]`` table, and
the tables its kind's Scene declares in its ``schema``.  Every key is checked: an
unknown key, a missing table, a wrong unit or an impossible value raises
:class:`ScenarioError` naming the dotted key path, what was given and what is
accepted.

Quantities are strings with units, parsed by astropy (``"384400 km"``,
``"13.18 deg/d"``); bare numbers are accepted only for dimensionless keys
(``schema.py``: the keys, their ranges and the conversions).
Times are ISO strings in TDB; ``span.end`` may also be a duration from
``span.start`` (``"100 yr"``, ``"1073.15 d"``).

Beyond types and units, every number must be finite and inside its key's
plausible range (``Key.min``/``Key.max``), tolerances inside [100 eps, 1e-3];
what the run asks for (rows, samples, steps, cycles, time, memory) must fit its
limits (spinorbit.edge.budget).  Files must be UTF-8, at most ``MAX_FILE_BYTES``, and
nest at most ``MAX_DEPTH`` levels.  Python's values (the API's) go in through
``load_scenario(values=...)``, validated alike; a valid scenario carries them as
its scene's typed parameters, ``scenario.params`` (an instance of the scene's ``params`` class,
spinorbit.scene.params: ``scenario.params.orbit.source``).
"""
import datetime
import math
import os
import tomllib
from pathlib import Path

import numpy as np

from ..base.errors import ScenarioError
from ..scene.declaration import scenario_errors
from ..scene.params import SpanTable, filled
from ..scene.schema import (
    INTEGRATOR_OPTIONS,
    MAX_TEXT,
    REQUIRED,
    Key,
    checked_float,
    dotted_items,
    finite_float,
    has_key,
    lookup,
    parse_tdb_days,
)
from . import budget

MAX_DEPTH = 8                  # nesting of tables and arrays in a scenario
MAX_FILE_BYTES = 1 << 20       # a scenario file (a few kB; every string in it is at most schema.MAX_TEXT)
OPEN_TABLES = ("integrator",)     # [integrator] options go to the method, which checks their names
MIN_SPAN_D = 1e-6              # shortest span, days (0.0864 s)
SPAN_END_ACCEPTED = ("an ISO date in TDB without a time zone (e.g. '2030-01-01' or '2030-01-01T12:00:00'), or a "
                     "finite duration from span.start (e.g. '100 yr', '2 d', '2 days', '-1 Myr')")


class Scenario:
    """A validated scenario: ``params``, its scene's typed parameters (``scenario.params.body.moments``: the
    converted value), beside what running it needs (its ``scene`` and ``kind``, its file's ``name`` and ``path``,
    the raw ``data``, a checkpoint, the API's extra output times)."""

    def __init__(self, data, path=None):
        self.data = data
        self.path = Path(path) if path else None
        self.name = self.path.stem if self.path else "scenario"
        self.checkpoint = None          # a checkpoint.Checkpoint when the command line runs it (--resume)
        self.extra_times = None         # TDB days the Python API asks for, besides the span's grid
        self.notes = []                 # what loading changed and says (method_switch)
        from ..scenes import scene_of  # the scene registry (lazy imports)

        check_depth(data, str(self.path) if self.path else "scenario")
        kind = lookup(data, "scene.kind", Key(type=str))
        if not isinstance(kind, str):
            raise ScenarioError("scene.kind", kind, "a string naming a scene kind")
        self.scene = scene_of(kind)
        self.kind = kind
        method = data.get("integrator", {}).get("method") if isinstance(data.get("integrator"), dict) else None
        if method == "taylor" and not self.scene.taylor:
            raise ScenarioError("integrator.method", "taylor", f"a method other than 'taylor' for scene kind "
                                f"'{kind}', which reads an ephemeris (taylor runs: {', '.join(taylor_kinds())})")
        self.schema = self.scene.schema
        self._check_keys()
        values = {key: self._convert(key, spec) for key, spec in self.schema.items()}
        self.params = filled(self.scene.params, values, self._span(values), self._integrator_options())
        self.validate()

    def validate(self):
        """Check what the parameters ask for against the limits and the method (budget.check; the method's
        options), as a scenario is checked when it is loaded: after ``params`` is replaced, e.g. by
        ``with_params``."""
        budget.check(self)
        from ..integrators import get_method

        with scenario_errors(self):
            get_method(self.params.integrator.method)(**self.params.integrator.options())

    def with_params(self, params):
        """This scenario with ``params`` (a ``dataclasses.replace`` of its own), validated alike: each value in
        its key's range (params.check_values), the span the scene can run, then the budget and the method's
        options."""
        import copy

        from ..scene.params import check_values

        check_values(params)
        span = params.span
        self._check_span(span, f"{span.start:.9g} TDB days from J2000", f"{span.end:.9g} TDB days from J2000")
        other = copy.copy(self)
        other.params = params
        other.validate()
        return other

    def output_times(self):
        """Output times in TDB days from J2000 (the span's, spinorbit.scene.params.SpanTable.times), with the API's
        ``extra_times`` among them."""
        return self.params.span.times(self.extra_times)

    # --- validation -------------------------------------------------------
    def _check_keys(self):
        tables = {key.split(".")[0] for key in self.schema}
        for table, content in self.data.items():
            if table not in tables:
                raise ScenarioError(table, "(table)", f"one of the tables {sorted(tables)}{_nearest(table, tables)}")
            if not isinstance(content, dict):
                raise ScenarioError(table, content, "a table")
            if table in OPEN_TABLES:
                self._check_options(content)
                continue
            for name, _ in dotted_items(content, table + "."):
                if name not in self.schema:
                    accepted = sorted(k for k in self.schema if k.startswith(table + "."))
                    raise ScenarioError(name, lookup(self.data, name, Key(type=object)),
                                        f"one of the keys {accepted}{_nearest(name, accepted)}")
        for key, spec in self.schema.items():
            if spec.default is REQUIRED and not has_key(self.data, key):
                table = key.split(".")[0]
                given = "(missing table)" if table not in self.data else "(missing)"
                raise ScenarioError(key, given, spec.accepted())

    def _convert(self, key, spec):
        """The value of ``key`` once loaded: checked (type, unit, range), then what it names (``spec.parse``)."""
        value = self._checked(key, spec) if has_key(self.data, key) else spec.default
        return spec.parsed(key, value)

    def _checked(self, key, spec):
        value = lookup(self.data, key, spec)
        if spec.choices:
            if not isinstance(value, str) or value not in spec.choices:
                raise ScenarioError(key, value, spec.accepted())
            return value
        if spec.unit is None:
            if spec.type is str and isinstance(value, (datetime.date, datetime.time)):
                value = _toml_datetime_text(key, value)
            if spec.type is float and isinstance(value, int) and not isinstance(value, bool):
                value = float(finite_float(key, value))
            if not isinstance(value, spec.type) or (spec.type is not bool and isinstance(value, bool)):
                raise ScenarioError(key, value, spec.accepted())
            if isinstance(value, str) and len(value) > MAX_TEXT:
                raise ScenarioError(key, value, f"a string of at most {MAX_TEXT} characters "
                                                f"({len(value)} given)")
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                spec.check_range(key, finite_float(key, value), value)
            return value
        if spec.size:
            if getattr(value, "isscalar", True) is False:      # an astropy Quantity array from the API
                value = list(value)
            if not isinstance(value, list) or len(value) != spec.size:
                raise ScenarioError(key, value, spec.accepted())
            vector = np.array([checked_float(key, v, spec) for v in value])
            with np.errstate(over="ignore"):
                length = np.linalg.norm(vector)
            if spec.direction and not 0 < length < math.inf:
                raise ScenarioError(key, value, f"a direction: {spec.size} numbers, not all zero, with a "
                                                "finite length")
            return vector
        return checked_float(key, value, spec)

    def _check_options(self, content):
        """[integrator] names: the method's options (its class says which), method and estimate_error."""
        from ..integrators import METHODS, get_method

        method = content.get("method", self.schema["integrator.method"].default)
        known = set(get_method(method).options) if isinstance(method, str) and method in METHODS else \
            set(INTEGRATOR_OPTIONS)
        accepted = sorted(known | {"method", "estimate_error"})
        for name in content:
            if name not in accepted:
                raise ScenarioError(f"integrator.{name}", content[name],
                                    f"one of the keys {accepted} for method {method!r}{_nearest(name, accepted)}")

    def _integrator_options(self):
        options = {}
        for key, value in self.data.get("integrator", {}).items():
            if key in ("method", "estimate_error"):
                continue
            spec = INTEGRATOR_OPTIONS.get(key, Key(unit=""))
            options[key] = checked_float(f"integrator.{key}", value, spec)
        return options

    def _span(self, values):
        """The span's table: start and end in TDB days, the cadence in days."""
        start_text, end_text = values["span.start"], values["span.end"]
        start = parse_tdb_days("span.start", start_text)
        try:
            end = parse_tdb_days("span.end", end_text)
        except ScenarioError:
            try:
                end = start + checked_float("span.end", end_text, Key(unit="d"))
            except ScenarioError:
                raise ScenarioError("span.end", end_text, SPAN_END_ACCEPTED) from None
        span = SpanTable(start=start, end=end, step=values["span.step"])
        self._check_span(span, start_text, end_text)
        return span

    def _check_span(self, span, start_given, end_given):
        """Refuse a span the scene cannot run: backward for a scene that runs forward only, or shorter than
        MIN_SPAN_D; the file's text (or the replaced days) named as given."""
        if span.backward and not self.scene.backward:
            raise ScenarioError("span.end", end_given, f"a time after span.start ({start_given}); "
                                f"scene kind '{self.kind}' runs forward only (backward runs: "
                                f"{', '.join(backward_kinds())})")
        if span.length < MIN_SPAN_D:
            raise ScenarioError("span.end", end_given, f"a span of at least {MIN_SPAN_D:g} d from span.start")

    def cost(self):
        """The measured per-item costs of this scene kind (its Scene's cost)."""
        return self.scene.cost

    def counts(self):
        """{count: items} the span asks for (spinorbit.edge.budget.counts)."""
        return budget.counts(self)

    def estimate(self):
        """{"time_s", "memory_bytes"} of the run (spinorbit.edge.budget.estimate)."""
        return budget.estimate(self)

def check_depth(data, where, limit=MAX_DEPTH):
    """Raise ScenarioError if tables and arrays nest deeper than ``limit`` (checked without recursion)."""
    stack = [(data, 0, "")]
    while stack:
        node, depth, name = stack.pop()
        if depth > limit:
            raise ScenarioError(name or where, "(nested deeper)",
                                f"tables and arrays nested at most {limit} deep")
        if isinstance(node, dict):
            stack.extend((v, depth + 1, f"{name}.{k}" if name else str(k)) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((v, depth + 1, name) for v in node)


def backward_kinds():
    """Scene kinds that run a span backward (their Scene says ``backward``)."""
    from ..scenes import SCENES, scene_of

    return sorted(kind for kind in SCENES if scene_of(kind).backward)


def taylor_kinds():
    """Scene kinds whose every term is a function of the state and the time (their Scene says ``taylor``):
    heyoka's Taylor integrator takes them."""
    from ..scenes import SCENES, scene_of

    return sorted(kind for kind in SCENES if scene_of(kind).taylor)


def _toml_datetime_text(key, value):
    """An unquoted TOML date/datetime as ISO text; a time zone makes no sense for TDB."""
    if getattr(value, "tzinfo", None) is not None:
        raise ScenarioError(key, value.isoformat(),
                            "a TDB time without a time-zone offset, e.g. 2000-01-01T12:00:00")
    return value.isoformat()


def _is_utf8(text):
    """False for command-line text holding undecodable bytes (surrogate escapes)."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return False
    return True


def apply_override(data, assignment):
    """Apply one ``--set dotted.key=value`` (value parsed as TOML, else taken as a string)."""
    if not _is_utf8(assignment):
        offset = next(i for i, c in enumerate(assignment) if not _is_utf8(c))
        raise ScenarioError("--set", assignment, f"UTF-8 text (a byte that is not UTF-8 at offset {offset})")
    if "=" not in assignment:
        raise ScenarioError("--set", assignment, "key=value, e.g. span.end=2030-01-01")
    key, text = (s.strip() for s in assignment.split("=", 1))
    try:
        value = tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        value = text
    except (ValueError, RecursionError) as exc:   # e.g. an integer over Python's digit limit, deep nesting
        raise ScenarioError(key, text, f"a TOML value Python can read ({_reason(exc)})") from None
    set_value(data, key, value, assignment)


def set_value(data, key, value, given=None):
    """Put ``value`` (a TOML value, or a number, string, list or astropy Quantity from Python) at dotted ``key``
    of a scenario's tables; the scenario's validation then checks it as it checks the file's."""
    if not isinstance(key, str) or not key:
        raise ScenarioError("values", key, "dotted scenario keys, e.g. 'orbit.source'")
    node = data
    parts = key.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ScenarioError(key, given if given is not None else value, "a dotted path into the scenario's "
                                                                            "tables")
    node[parts[-1]] = value


def load_scenario(path, overrides=(), values=None):
    """Read and validate a scenario file (a path, or a built-in scene's name: spinorbit.edge.catalogue); ``overrides``
    are ``key=value`` strings (the command line's ``--set``), ``values`` a dict of dotted key -> value (Python's
    values, e.g. the API's: no text to parse), applied after them."""
    from .catalogue import resolve

    if isinstance(path, bytes) or not isinstance(path, (str, os.PathLike)):
        raise ScenarioError("scenario", path, "a path to a scenario .toml file (a str or os.PathLike) or a "
                                              "built-in scene's name")
    if isinstance(overrides, (str, bytes)) or not isinstance(overrides, (list, tuple)) or not all(
            isinstance(item, str) for item in overrides):
        raise ScenarioError("--set", overrides, "a list of 'key=value' strings, e.g. ['span.end=10 d']")
    path = resolve(path)
    if not _is_utf8(str(path)) or not path.is_file():
        raise ScenarioError("scenario", str(path), "an existing .toml file with a UTF-8 name, or the name of a "
                                                   "built-in scene (see `spinorbit list`)")
    if path.stat().st_size > MAX_FILE_BYTES:
        raise ScenarioError("scenario", str(path), f"a scenario file of at most {MAX_FILE_BYTES:,} bytes "
                                                   f"({path.stat().st_size:,} given)")
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ScenarioError(str(path), f"byte 0x{raw[exc.start]:02x} at offset {exc.start}",
                            "a UTF-8 text file (re-save it as UTF-8)") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(str(path), f"invalid TOML ({exc})", "a TOML file") from None
    except (ValueError, RecursionError) as exc:
        raise ScenarioError(str(path), _reason(exc), "a TOML file Python can read") from None
    from .method_switch import option_names, switch_method

    in_file = dict(data.get("integrator", {})) if isinstance(data.get("integrator"), dict) else {}
    for assignment in overrides:
        apply_override(data, assignment)
    for key, value in (values or {}).items():
        set_value(data, key, value)
    notes = switch_method(data["integrator"], in_file, option_names(overrides)) \
        if isinstance(data.get("integrator"), dict) else []
    scenario = Scenario(data, path)
    scenario.notes = notes
    return scenario


def _nearest(name, names):
    """" (did you mean 'x'?)" for the accepted name closest to a misspelt one, or ""."""
    import difflib

    close = difflib.get_close_matches(str(name), [str(n) for n in names], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _reason(exc):
    """The first line of an exception's message, or its type for a RecursionError."""
    if isinstance(exc, RecursionError):
        return "nesting too deep to parse"
    return str(exc).splitlines()[0] if str(exc) else type(exc).__name__
