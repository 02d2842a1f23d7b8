"""Scenario files (TOML): loading, ``--set`` overrides, and validation with clear errors.

A scenario is a TOML file with a ``[scene]`` table naming its ``kind`` (one of
``spinorbit.scenes.SCENES``), a ``[span]`` table, an ``[integrator]`` table, and
the tables its kind declares in its ``SCHEMA``.  Every key is checked: an
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
a step over the span must not ask for more output rows, orbit samples or
integrator steps than ``LIMITS`` allows, nor a rate for more than ``MAX_CYCLES``
cycles: the run is refused up front with the estimate, instead of hanging or
filling the memory.  Files must be UTF-8 and nest at most ``MAX_DEPTH`` levels.
"""
import datetime
import math
import tomllib
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .errors import InputError, ScenarioError
from .schema import (
    INTEGRATOR_OPTIONS,
    MAX_TEXT,
    REQUIRED,
    Key,
    checked_float,
    dotted_items,
    finite_float,
    parse_tdb_days,
)

MAX_DEPTH = 8                  # nesting of tables and arrays in a scenario
# What a step over the span may ask for: count limit and bytes per item (estimate).
# Compiled fixed-step methods take ~1-10 us a step; scipy's adaptive ones ~100 us (Python per stage).
LIMITS = {"output rows": (1_000_000, 200), "orbit samples": (10_000_000, 150),
          "integrator steps": (100_000_000, 0), "adaptive steps (at max_step)": (1_000_000, 0)}


COMMON_SCHEMA = {
    "scene.kind": Key(type=str),
    "scene.title": Key(type=str, default=""),
    "scene.description": Key(type=str, default=""),
    "span.start": Key(type=str, help="ISO time, TDB"),
    "span.end": Key(type=str, help="ISO time (TDB) or a duration such as '100 yr'"),
    "span.step": Key(unit="d", positive=True, count="output rows", help="output cadence"),
    "integrator.method": Key(type=str, default="dop853"),
    "integrator.estimate_error": Key(type=bool, default=True),
    "output.plots": Key(type=bool, default=True),
}
OPEN_TABLES = ("integrator",)     # [integrator] options go to the method, which checks their names
MIN_SPAN_D = 1e-6              # shortest span, days (0.0864 s)
# Cycles a run may have to follow: any rate key (rad/d) times the span, and the torque's own
# time-scale sqrt(3 GM/s^3) when a scene has orbit.gm and a distance.  The fast-spin stress
# scene follows 1e5 spin cycles (a compiled splitting method); dop853 costs ~10 ms per cycle
# (p93 at orbit.rate = 1000 rad/d: 3200 cycles in 45 s), so 2e5 cycles is about half an hour.
MAX_CYCLES = 2e5
DISTANCE_KEYS = ("orbit.radius", "orbit.f", "orbit.a")


class Scenario:
    """A validated scenario: ``scenario["body.moments"]`` gives the converted value."""

    def __init__(self, data, path=None):
        self.data = data
        self.path = Path(path) if path else None
        self.name = self.path.stem if self.path else "scenario"
        self.checkpoint = None          # a checkpoint.Checkpoint when the command line runs it (--resume)
        self.extra_times = None         # TDB days the Python API asks for, besides the span's grid
        from .scenes import scene_module  # the scene registry (lazy imports)

        check_depth(data, str(self.path) if self.path else "scenario")
        kind = _lookup(data, "scene.kind", Key(type=str))
        if not isinstance(kind, str):
            raise ScenarioError("scene.kind", kind, "a string naming a scene kind")
        self.module = scene_module(kind)
        method = data.get("integrator", {}).get("method") if isinstance(data.get("integrator"), dict) else None
        if method == "taylor" and not getattr(self.module, "TAYLOR", False):
            raise ScenarioError("integrator.method", "taylor", f"a method other than 'taylor' for scene kind "
                                f"'{kind}', which reads an ephemeris (taylor runs: {', '.join(taylor_kinds())})")
        self.schema = {**COMMON_SCHEMA, **self.module.SCHEMA}
        self._check_keys()
        self.values = {key: self._convert(key, spec) for key, spec in self.schema.items()}
        self.kind = kind
        self._options = self._integrator_options()
        self.t_start, self.t_end = self._span()
        self._check_counts()
        self._check_cycles()
        from .integrators import get_method

        with scenario_errors(self):
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
        return dict(self._options)

    def output_times(self):
        """Output times in TDB days from J2000: start to end at span.step (end included), descending
        when the span runs backward (end before start); with the API's ``extra_times`` among them."""
        step = self["span.step"] * (1.0 if self.t_end > self.t_start else -1.0)
        n = int(np.floor((self.t_end - self.t_start) / step + 1e-9))
        times = self.t_start + step * np.arange(n + 1)
        if not np.isclose(times[-1], self.t_end, rtol=0, atol=1e-9 * abs(step)):
            times = np.append(times, self.t_end)
        if self.extra_times is not None:
            times = np.union1d(times, self.extra_times)[::1 if step > 0 else -1]
        return times

    @property
    def bounds(self):
        """(earliest, latest) TDB days of the span, whichever way it runs."""
        return min(self.t_start, self.t_end), max(self.t_start, self.t_end)

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
                    raise ScenarioError(name, _lookup(self.data, name, Key(type=object)),
                                        f"one of the keys {accepted}{_nearest(name, accepted)}")
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
                raise ScenarioError(key, value, f"a string of at most {MAX_TEXT} characters ({len(value)} given)")
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                spec.check_range(key, finite_float(key, value), value)
            return value
        if spec.size:
            if not isinstance(value, list) or len(value) != spec.size:
                raise ScenarioError(key, value, spec.accepted())
            vector = np.array([checked_float(key, v, spec) for v in value])
            with np.errstate(over="ignore"):
                length = np.linalg.norm(vector)
            if spec.direction and not 0 < length < math.inf:
                raise ScenarioError(key, value, f"a direction: {spec.size} numbers, not all zero, with a finite length")
            return vector
        return checked_float(key, value, spec)

    def _check_options(self, content):
        """[integrator] names: the method's options (its class says which), method and estimate_error."""
        from .integrators import METHODS, get_method

        method = content.get("method", COMMON_SCHEMA["integrator.method"].default)
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

    def _span(self):
        start = parse_tdb_days("span.start", self["span.start"])
        end_text = self["span.end"]
        try:
            end = parse_tdb_days("span.end", end_text)
        except ScenarioError:
            end = start + checked_float("span.end", end_text, Key(unit="d"))
        if end < start and not getattr(self.module, "BACKWARD", False):
            raise ScenarioError("span.end", end_text, f"a time after span.start ({self['span.start']}); scene kind "
                                f"'{self.kind}' runs forward only (backward runs: {', '.join(backward_kinds())})")
        if abs(end - start) < MIN_SPAN_D:
            raise ScenarioError("span.end", end_text, f"a span of at least {MIN_SPAN_D:g} d from span.start")
        return start, end

    def _check_counts(self):
        """Refuse a step that would ask for too many rows, samples or steps over the span."""
        span = abs(self.t_end - self.t_start)
        steps = [(key, spec, self.values[key]) for key, spec in self.schema.items() if spec.count]
        steps += [(f"integrator.{name}", INTEGRATOR_OPTIONS[name], value) for name, value in self._options.items()
                  if name in INTEGRATOR_OPTIONS and INTEGRATOR_OPTIONS[name].count]
        for key, spec, step in steps:
            limit, item_bytes = LIMITS[spec.count]
            n = span / step + 1
            if n > limit:
                count = f"{n:,.0f}" if n < 1e15 else f"{n:.3g}"
                memory = f", ~{_bytes(n * item_bytes)} in memory" if item_bytes else ""
                raise ScenarioError(key, _lookup(self.data, key, spec) if _has(self.data, key) else step,
                                    f"a step giving at most {limit:,} {spec.count} over the {span:.6g} d span "
                                    f"(this one gives {count}{memory}); lengthen {key} or shorten the span")


    def _check_cycles(self):
        """Refuse rates (and GM over distance^3) that would make the run follow more than MAX_CYCLES cycles."""
        span = abs(self.t_end - self.t_start)
        rates = [(key, float(np.linalg.norm(self.values[key])), "") for key, spec in self.schema.items()
                 if spec.unit == "rad/d" and self.values[key] is not None]
        distance = next((key for key in DISTANCE_KEYS if key in self.values), None)
        if "orbit.gm" in self.values and distance:
            torque_rate = math.sqrt(3 * self.values["orbit.gm"] / self.values[distance] ** 3)
            rates.append((distance, torque_rate, f" (sqrt(3 orbit.gm/{distance}^3) = {torque_rate:.3g} rad/d)"))
        for key, rate, how in rates:
            cycles = rate * span / (2 * math.pi)
            if cycles > MAX_CYCLES:
                raise ScenarioError(key, _lookup(self.data, key, Key()) if _has(self.data, key) else rate,
                                    f"a value giving at most {MAX_CYCLES:.0e} cycles over the {span:.6g} d span "
                                    f"(this one gives {cycles:.3g}{how}); change {key} or shorten the span")


# The library names an argument it cannot use (errors.InputError); the scenario key that sets it:
ARGUMENT_KEYS = {"method": "integrator.method", "step": "integrator.step", "free_flow": "integrator.free_flow",
                 "source": "orbit.source", "bodies": "orbit.bodies", "radius": "orbit.radius", "a": "orbit.a",
                 "e": "orbit.e", "f": "orbit.f", "beta": "orbit.beta", "t_out": "span"}


@contextmanager
def scenario_errors(scenario):
    """Turn a library InputError raised inside into a ScenarioError on the scenario key that set the argument
    (an ``[integrator]`` option by its own name, else ARGUMENT_KEYS)."""
    try:
        yield
    except InputError as exc:
        options = scenario.data.get("integrator", {})
        key = f"integrator.{exc.name}" if exc.name in options else ARGUMENT_KEYS.get(exc.name, exc.name)
        raise ScenarioError(key, exc.given, exc.accepted) from None


def check_depth(data, where, limit=MAX_DEPTH):
    """Raise ScenarioError if tables and arrays nest deeper than ``limit`` (checked without recursion)."""
    stack = [(data, 0, "")]
    while stack:
        node, depth, name = stack.pop()
        if depth > limit:
            raise ScenarioError(name or where, "(nested deeper)", f"tables and arrays nested at most {limit} deep")
        if isinstance(node, dict):
            stack.extend((v, depth + 1, f"{name}.{k}" if name else str(k)) for k, v in node.items())
        elif isinstance(node, list):
            stack.extend((v, depth + 1, name) for v in node)


def _bytes(n):
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000


def backward_kinds():
    """Scene kinds that run a span backward (their module sets BACKWARD = True)."""
    from .scenes import SCENES, scene_module

    return sorted(kind for kind in SCENES if getattr(scene_module(kind), "BACKWARD", False))


def taylor_kinds():
    """Scene kinds whose every term is a function of the state and the time (their module sets TAYLOR = True):
    heyoka's Taylor integrator takes them."""
    from .scenes import SCENES, scene_module

    return sorted(kind for kind in SCENES if getattr(scene_module(kind), "TAYLOR", False))


def _toml_datetime_text(key, value):
    """An unquoted TOML date/datetime as ISO text; a time zone makes no sense for TDB."""
    if getattr(value, "tzinfo", None) is not None:
        raise ScenarioError(key, value.isoformat(), "a TDB time without a time-zone offset, e.g. 2000-01-01T12:00:00")
    return value.isoformat()


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
    node = data
    parts = key.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ScenarioError(key, assignment, "a dotted path into the scenario's tables")
    node[parts[-1]] = value


def load_scenario(path, overrides=()):
    """Read and validate a scenario file (a path, or a built-in scene's name: spinorbit.catalogue); ``overrides``
    are ``key=value`` strings."""
    from .catalogue import resolve

    path = resolve(path)
    if not path.is_file() or not _is_utf8(str(path)):
        raise ScenarioError("scenario", str(path), "an existing .toml file with a UTF-8 name, or the name of a "
                                                   "built-in scene (see `spinorbit list`)")
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
    for assignment in overrides:
        apply_override(data, assignment)
    return Scenario(data, path)


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


def key_table(scene):
    """Markdown-like lines: every key of ``scene``'s kind (its file's value, the default, unit, range, meaning),
    the [integrator] options, and the kind's docstring's first line; what ``spinorbit show`` prints."""
    import math
    import tomllib

    from .catalogue import resolve
    from .integrators import METHODS, get_method
    from .scenes import scene_module

    path = resolve(scene)
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    kind = data.get("scene", {}).get("kind")
    module = scene_module(kind)
    given = dict(dotted_items(data))
    method = given.get("integrator.method", COMMON_SCHEMA["integrator.method"].default)
    options = get_method(method).options if method in METHODS else {}
    lines = [f"{path.stem} (kind {kind}): {(module.__doc__ or '').strip().splitlines()[0]}", "",
             f"{'key':34} {'value in the file':24} {'default':22} {'unit':8} {'range':18} meaning"]
    for key, spec in {**COMMON_SCHEMA, **module.SCHEMA, **{f"integrator.{name}": spec for name, spec in
                                                           INTEGRATOR_OPTIONS.items() if name in options}}.items():
        name = key.removeprefix("integrator.")
        default = repr(options[name]) if key.startswith("integrator.") and name in options else \
            "(required)" if spec.default is REQUIRED else repr(spec.default)
        if spec.choices:
            span = "|".join(map(str, spec.choices))
        elif math.isfinite(spec.min) or math.isfinite(spec.max) or spec.positive:
            span = f"{'>0' if spec.positive else f'{spec.min:g}'} .. {spec.max:g}"
        else:
            span = ""
        value = repr(given[key]) if key in given else ""
        lines.append(f"{key:34} {value[:24]:24} {default[:22]:22} {spec.unit or '':8} {span[:18]:18} {spec.help}")
    return lines
