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
cycles; and the run's time and memory, estimated from the counts and the costs
measured per item for its scene kind (its Scene's ``cost``: seconds per integrator step,
bytes per row and per orbit sample), must fit ``limits.time`` (default 1 h) and
``limits.memory`` (default half the machine's): the run is refused up front with
the estimate, instead of hanging or filling the memory.  Files must be UTF-8, at
most ``MAX_FILE_BYTES``, and nest at most ``MAX_DEPTH`` levels.
"""
import datetime
import math
import os
import tomllib
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .errors import EphemerisRangeError, InputError, ScenarioError
from .schema import (
    INTEGRATOR_OPTIONS,
    MAX_TEXT,
    REQUIRED,
    Key,
    checked_float,
    dotted_items,
    filled,
    finite_float,
    parse_tdb_days,
    record,
)

MAX_DEPTH = 8                  # nesting of tables and arrays in a scenario
MAX_FILE_BYTES = 1 << 20       # a scenario file (a few kB; every string in it is at most schema.MAX_TEXT)
# The most a step over the span may ask for, whatever the time and memory limits.
LIMITS = {"output rows": 1_000_000, "orbit samples": 10_000_000, "integrator steps": 1_000_000_000,
          "adaptive steps (at max_step)": 1_000_000}


ADAPTIVE_STEP_S = 2e-4         # scipy's adaptive methods: Python between the stages of each step
# The key an N-body stage's refusal names, and what would shorten it.
NBODY_KEYS = {"WHFast steps": ("span.end", "a shorter span (an orbital solution once computed is kept in the "
                                           "cache: a later run reads it)"),
              "IAS15 days": ("orbit.source", "a span nearer DE421's (1899-2200: REBOUND starts from DE421's state "
                                             "there and integrates out to the span), or an ephemeris that covers "
                                             "it (orbit.source = 'de440')")}
COMMON_SCHEMA = {
    "scene.kind": Key(type=str, help="what the scene runs (spinorbit.scenes.SCENES)"),
    "scene.title": Key(type=str, default="", help="one line for reports and `spinorbit list`"),
    "scene.description": Key(type=str, default="", help="free text, copied to the report"),
    "span.start": Key(type=str, help="ISO time, TDB"),
    "span.end": Key(type=str, help="ISO time (TDB) or a duration such as '100 yr'"),
    "span.step": Key(unit="d", positive=True, count="output rows", help="output cadence"),
    "integrator.method": Key(type=str, default="dop853", help="spinorbit.integrators.METHODS"),
    "integrator.estimate_error": Key(type=bool, default=True, help="rerun at half the step (or a tenth the "
                                                                   "tolerance) and report the difference"),
    "output.plots": Key(type=bool, default=True, help="draw the scene's figures (PNG)"),
    "limits.time": Key(unit="s", positive=True, default=3600.0, max=3.2e7,
                       help="longest run the up-front estimate lets through (e.g. '10 h')"),
    "limits.memory": Key(unit="byte", positive=True, default=None, max=1e15,
                         help="largest memory the estimate lets through (default: half the machine's)"),
}
OPEN_TABLES = ("integrator",)     # [integrator] options go to the method, which checks their names
MIN_SPAN_D = 1e-6              # shortest span, days (0.0864 s)
# Cycles a run may have to follow: any rate key (rad/d) times the span, and the time-scales its scene declares
# (a torque's sqrt(3 GM/s^3), Euler's equations' body-frame rates).  The fast-spin stress
# scene follows 1e5 spin cycles (a compiled splitting method); dop853 costs ~10 ms per cycle
# (p93 at orbit.rate = 1000 rad/d: 3200 cycles in 45 s), so 2e5 cycles is about half an hour.
MAX_CYCLES = 2e5
SPAN_END_ACCEPTED = ("an ISO date in TDB without a time zone (e.g. '2030-01-01' or '2030-01-01T12:00:00'), or a "
                     "finite duration from span.start (e.g. '100 yr', '2 d', '2 days', '-1 Myr')")


class Scenario:
    """A validated scenario: ``scenario["body.moments"]`` gives the converted value."""

    def __init__(self, data, path=None):
        self.data = data
        self.path = Path(path) if path else None
        self.name = self.path.stem if self.path else "scenario"
        self.checkpoint = None          # a checkpoint.Checkpoint when the command line runs it (--resume)
        self.extra_times = None         # TDB days the Python API asks for, besides the span's grid
        self.notes = []                 # what loading changed and says (method_switch)
        from .scenes import scene_of  # the scene registry (lazy imports)

        check_depth(data, str(self.path) if self.path else "scenario")
        kind = _lookup(data, "scene.kind", Key(type=str))
        if not isinstance(kind, str):
            raise ScenarioError("scene.kind", kind, "a string naming a scene kind")
        self.scene = scene_of(kind)
        method = data.get("integrator", {}).get("method") if isinstance(data.get("integrator"), dict) else None
        if method == "taylor" and not self.scene.taylor:
            raise ScenarioError("integrator.method", "taylor", f"a method other than 'taylor' for scene kind "
                                f"'{kind}', which reads an ephemeris (taylor runs: {', '.join(taylor_kinds())})")
        self.schema = {**COMMON_SCHEMA, **self.scene.schema}
        self._check_keys()
        self.values = {key: self._convert(key, spec) for key, spec in self.schema.items()}
        self.kind = kind
        self._options = self._integrator_options()
        self.t_start, self.t_end = self._span()
        options = {f"integrator.{name}": spec for name, spec in INTEGRATOR_OPTIONS.items()}
        values = {**self.values, **{key: self._options.get(key.split(".")[1]) for key in options}}
        self.params = filled(_record_type(kind, {**self.schema, **options}), values, self.t_start, self.t_end)
        self._check_counts()
        self._check_cycles()
        from .integrators import get_method

        with scenario_errors(self):
            get_method(self["integrator.method"])(**self.integrator_options())   # checks method and options

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
            try:
                end = start + checked_float("span.end", end_text, Key(unit="d"))
            except ScenarioError:
                raise ScenarioError("span.end", end_text, SPAN_END_ACCEPTED) from None
        if end < start and not self.scene.backward:
            raise ScenarioError("span.end", end_text, f"a time after span.start ({self['span.start']}); "
                                f"scene kind '{self.kind}' runs forward only (backward runs: "
                                f"{', '.join(backward_kinds())})")
        if abs(end - start) < MIN_SPAN_D:
            raise ScenarioError("span.end", end_text, f"a span of at least {MIN_SPAN_D:g} d from span.start")
        return start, end

    def counts(self):
        """{count: items} the span asks for at each step key (output rows, orbit samples, integrator
        steps ...), the largest where two keys count the same."""
        counts = {}
        for _, kind, step in self._count_keys():
            counts[kind] = max(counts.get(kind, 0), abs(self.t_end - self.t_start) / step + 1)
        return {**counts, **self.nbody_counts()}

    def nbody_counts(self):
        """{N-body count: items} the run integrates before its own: the scene's (``Scene.nbody_counts``: the
        deep-time orbital solution's WHFast steps not yet in the cache) and the IAS15 days of orbit.source =
        'rebound' (out from DE421's nearest epoch, then over the span)."""
        from .orbits.sources import rebound_days

        counts = dict(self.scene.nbody_counts(self.params)) if self.scene.nbody_counts else {}
        if self.values.get("orbit.source") == "rebound":
            counts["IAS15 days"] = rebound_days(self.t_start, self.t_end)
        return counts

    def cost(self):
        """The measured per-item costs of this scene kind (its Scene's cost)."""
        return self.scene.cost

    def estimate(self):
        """{"time_s", "memory_bytes"} of the run, from its counts and the kind's measured costs."""
        counts, cost = self.counts(), self.cost()
        memory = cost.base_bytes + sum(counts.get(kind, 0) * size for kind, size in cost.bytes_per.items())
        time = sum(n * self._step_cost(kind) for kind, n in counts.items())
        return {"time_s": time, "memory_bytes": memory}

    def _step_cost(self, kind):
        """Seconds per item of a count (0 for those that cost memory only)."""
        from .scene import NBODY_COSTS

        return {"integrator steps": self.cost().step_s, "adaptive steps (at max_step)": ADAPTIVE_STEP_S,
                **NBODY_COSTS}.get(kind, 0.0)

    def _count_keys(self):
        """(key, count, step) of every step key that sets a count."""
        steps = [(key, spec.count, self.values[key]) for key, spec in self.schema.items()
                 if spec.count and self.values[key] is not None]
        steps += [(f"integrator.{name}", INTEGRATOR_OPTIONS[name].count, value)
                  for name, value in self._options.items()
                  if name in INTEGRATOR_OPTIONS and INTEGRATOR_OPTIONS[name].count]
        return steps

    def _check_counts(self):
        """Refuse a step that would ask for more rows, samples or steps than LIMITS, or a run the estimate
        says takes longer than limits.time or more memory than limits.memory."""
        span = abs(self.t_end - self.t_start)
        for key, kind, step in self._count_keys():
            n = span / step + 1
            if n > LIMITS[kind]:
                size = self.cost().bytes_per.get(kind, 0) * n
                memory = f", ~{_bytes(size)} in memory" if size else ""
                self._refuse(key, step, f"a step giving at most {LIMITS[kind]:,} {kind} over the "
                                        f"{span:.6g} d span (this one gives {_count(n)}{memory}); lengthen "
                                        f"{key} or shorten the span")
        culprits = {kind: (key, step) for key, kind, step in self._count_keys()}
        self._check_time(culprits)
        self._check_memory(culprits)

    def _check_time(self, culprits):
        limit, estimate, counts = self["limits.time"], self.estimate()["time_s"], self.counts()
        if estimate <= limit:
            return
        kind = max(counts, key=lambda k: counts[k] * self._step_cost(k))
        if kind in NBODY_KEYS:
            key, remedy = NBODY_KEYS[kind]
            self._refuse(key, self.values.get(key), f"a run the estimate finishes within limits.time = "
                                                    f"{_duration(limit)}: its N-body stage, {_count(counts[kind])} "
                                                    f"{kind} at ~{self._step_cost(kind) * 1e6:.3g} us each "
                                                    f"(measured), is ~{_duration(counts[kind] * self._step_cost(kind))}"
                                                    f" (the whole run ~{_duration(estimate)}); {remedy}, or raise "
                                                    "limits.time")
        key, step = culprits[kind]
        self._refuse(key, step, f"a run the estimate finishes within limits.time = {_duration(limit)}: "
                                f"{_count(counts[kind])} {kind} at ~{self._step_cost(kind) * 1e6:.3g} us "
                                f"each (measured for {self.kind}) is ~{_duration(estimate)}; lengthen {key}, "
                                "shorten the span, or raise limits.time")

    def _check_memory(self, culprits):
        limit, estimate = self["limits.memory"] or physical_memory() / 2, self.estimate()["memory_bytes"]
        if estimate <= limit:
            return
        cost, counts = self.cost(), self.counts()
        kind = max(cost.bytes_per, key=lambda k: counts.get(k, 0) * cost.bytes_per[k])
        if kind not in culprits or counts[kind] * cost.bytes_per[kind] < cost.base_bytes:
            self._refuse("limits.memory", limit, f"at least the ~{_bytes(cost.base_bytes)} any run of "
                                                 f"{self.kind} takes (measured)")
        key, step = culprits[kind]
        self._refuse(key, step, f"a run the estimate holds within limits.memory = {_bytes(limit)}: "
                                f"{_count(counts[kind])} {kind} at ~{_bytes(cost.bytes_per[kind])} each "
                                f"(measured for {self.kind}) is ~{_bytes(estimate)}; lengthen {key}, shorten "
                                "the span, or raise limits.memory")

    def _refuse(self, key, value, accepted):
        raise ScenarioError(key, _lookup(self.data, key, Key()) if _has(self.data, key) else value, accepted)

    def _check_cycles(self):
        """Refuse rate keys, and the time-scales the scene declares, that would make the run follow over
        MAX_CYCLES cycles."""
        span = abs(self.t_end - self.t_start)
        rates = [(key, float(np.linalg.norm(self.values[key])), "") for key, spec in self.schema.items()
                 if spec.unit == "rad/d" and self.values[key] is not None]
        if self.scene.time_scales is not None:
            rates += [(s.key, s.rate, s.how) for s in self.scene.time_scales(self.params)]
        for key, rate, how in rates:
            cycles = rate * span / (2 * math.pi)
            if cycles > MAX_CYCLES:
                self._refuse(key, rate, f"a value giving at most {MAX_CYCLES:.0e} cycles over the {span:.6g} "
                                        f"d span (this one gives {cycles:.3g}{how}); change {key} or shorten "
                                        "the span")


_RECORDS = {}


def _record_type(kind, keys):
    """The typed record of a scene kind's values (schema.record), made once per kind."""
    if kind not in _RECORDS:
        _RECORDS[kind] = record(f"{kind}_params", keys)
    return _RECORDS[kind]


# The library names an argument it cannot use (errors.InputError); the scenario key that sets it:
ARGUMENT_KEYS = {"method": "integrator.method", "step": "integrator.step",
                 "free_flow": "integrator.free_flow",
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
    except EphemerisRangeError as exc:
        (first, last) = scenario.bounds
        asked_first, asked_last = exc.requested if isinstance(exc.requested, tuple) else (first, last)
        before, after = max(first - asked_first, 0.0), max(asked_last - last, 0.0)
        low, high = exc.span[0] + before, exc.span[1] - after
        fits = (f"a span from {_iso(low)} to {_iso(high)} TDB fits" if high > low else "no span fits")
        around = (f"the run samples the orbit {before:.3g} d before its span and {after:.3g} d after it, so "
                  if before or after else "")
        raise EphemerisRangeError(exc.source, exc.requested, exc.span,
                                  note=f"{exc.note}; {around}{fits}") from None


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


def _iso(t_tdb_d):
    """TDB days from J2000 as an ISO date and time to the minute."""
    from .schema import tdb_days_to_time

    return tdb_days_to_time(t_tdb_d).isot[:16]


def _bytes(n):
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000


def _count(n):
    return f"{n:,.0f}" if n < 1e15 else f"{n:.3g}"


def _duration(seconds):
    for unit, size in (("d", 86400), ("h", 3600), ("min", 60)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


def physical_memory():
    """Bytes of memory the machine has (POSIX sysconf)."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def backward_kinds():
    """Scene kinds that run a span backward (their Scene says ``backward``)."""
    from .scenes import SCENES, scene_of

    return sorted(kind for kind in SCENES if scene_of(kind).backward)


def taylor_kinds():
    """Scene kinds whose every term is a function of the state and the time (their Scene says ``taylor``):
    heyoka's Taylor integrator takes them."""
    from .scenes import SCENES, scene_of

    return sorted(kind for kind in SCENES if scene_of(kind).taylor)


def _toml_datetime_text(key, value):
    """An unquoted TOML date/datetime as ISO text; a time zone makes no sense for TDB."""
    if getattr(value, "tzinfo", None) is not None:
        raise ScenarioError(key, value.isoformat(),
                            "a TDB time without a time-zone offset, e.g. 2000-01-01T12:00:00")
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
    """Read and validate a scenario file (a path, or a built-in scene's name: spinorbit.catalogue); ``overrides``
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


def key_table(scene):
    """(heading, rows): the kind's docstring's first paragraph, and every key of ``scene``'s kind as a row of
    texts, nothing cut (key, its file's value, the default, unit, range, meaning), the [integrator] options
    among them; what ``spinorbit show`` prints."""
    import math

    from .integrators import METHODS, get_method
    from .scenes import scene_module

    scenario = load_scenario(scene)
    path, kind = scenario.path, scenario["scene.kind"]
    module = scene_module(kind)
    given = dict(dotted_items(scenario.data))
    method = given.get("integrator.method", COMMON_SCHEMA["integrator.method"].default)
    options = get_method(method).options if method in METHODS else {}
    summary = " ".join((module.__doc__ or "").strip().split("\n\n")[0].split())
    rows = [("key", "value in the file", "default", "unit", "range", "meaning")]
    options_keys = {f"integrator.{name}": spec for name, spec in INTEGRATOR_OPTIONS.items() if name in options}
    for key, spec in {**COMMON_SCHEMA, **scenario.scene.schema, **options_keys}.items():
        name = key.removeprefix("integrator.")
        default = repr(options[name]) if key.startswith("integrator.") and name in options else \
            "(required)" if spec.default is REQUIRED else repr(spec.default)
        if spec.choices:
            span = "|".join(map(str, spec.choices))
        elif math.isfinite(spec.min) or math.isfinite(spec.max) or spec.positive:
            span = f"{'>0' if spec.positive else f'{spec.min:g}'} .. {spec.max:g}"
        else:
            span = ""
        rows.append((key, repr(given[key]) if key in given else "", default, spec.unit or "", span, spec.help))
    return f"{path.stem} (kind {kind}): {summary}", rows
