"""A scene's typed parameters: frozen dataclasses written in code, one per scenario table, each field declared
with its scenario key (``key(...)``: a schema.Key, its unit, range and help).

A scene declares ``class <Kind>Params(Params)`` with a field per table of its own (``model: ModelTable``) beside
the tables every scene has (:class:`Params`: ``scene``, ``span``, ``integrator``, ``output``, ``limits``).  A TOML
file, ``--set``, the API's values and a sweep's members are all parsed into it by ``scenarios.Scenario``; code
reads it by attribute (``p.model.level``, ``p.span.end``) and makes a variant with ``dataclasses.replace`` (the
API and the solution store: ``p.with_span(start, end)``).  What a value holds once loaded is the field's
annotation: a quantity in its key's internal unit, a time in TDB days from J2000.0, an orbit source as its
``OrbitSource`` object (:func:`source_key`): what a key's text names is made once, at load (``Key.parse``).  The
keys a scene accepts are read off its class (:func:`keys_of`), never written twice.

Edge module, below ``scenarios`` and ``scenes``.
"""
from dataclasses import MISSING, dataclass, field, fields, replace

import numpy as np

from ..integrators.options import OPTIONS
from ..orbits.sources import orbit_source
from .schema import REQUIRED, Key, checked_float, parse_tdb_days

_table = dataclass(frozen=True, kw_only=True, eq=False)


def table(cls):
    """A scenario table's class: a frozen dataclass with keyword fields (``@table``)."""
    return _table(cls)


def key(**spec):
    """A field of a table: its scenario key (``schema.Key(**spec)``) in the field's metadata; its default the
    key's (a copy for a list or an array), required where the key has none."""
    declared = Key(**spec)
    metadata = {"key": declared}
    if declared.default is REQUIRED:
        return field(metadata=metadata)
    if declared.parse is not None:
        return field(default_factory=lambda: declared.parse(declared.default), metadata=metadata)
    if isinstance(declared.default, (list, dict, np.ndarray)):
        return field(default_factory=lambda: _copy(declared.default), metadata=metadata)
    return field(default=declared.default, metadata=metadata)


def source_key(help, default="de421", choices=()):
    """A field holding an orbit source: the file names it ('de421', 'rebound', a kernel; one of ``choices`` where
    given), the field holds its ``OrbitSource`` (spinorbit.orbits.sources), made at load, where a kernel whose
    file is not there is refused; with ``default=""`` the key is optional and "" holds None."""
    return key(type=str, default=default, choices=choices, parse=_source if default else _optional_source,
               help=help)


def time_key(help, default=""):
    """A field holding a time: the file gives ISO text in TDB (schema.ISO_TDB), the field holds TDB days from
    J2000.0, made at load; with ``default=""`` the key is optional and "" holds None."""
    return key(type=str, default=default, parse=_tdb_days if default else _optional_tdb_days, help=help)


def _tdb_days(text):
    return parse_tdb_days("time", text)


def _optional_tdb_days(text):
    return _tdb_days(text) if text else None


def _source(name):
    return orbit_source(name).checked()


def _optional_source(name):
    return _source(name) if name else None


def _copy(value):
    return value.copy() if hasattr(value, "copy") else list(value)


def keys_of(params_type):
    """{dotted key: Key} of a Params class: every field of every table, in declaration order (the
    [integrator] options excepted: the chosen method says which it accepts, schema.INTEGRATOR_OPTIONS)."""
    keys = {}
    for table_field in fields(params_type):
        for leaf in fields(table_field.type):
            if "key" in leaf.metadata:
                keys[f"{table_field.name}.{leaf.name}"] = leaf.metadata["key"]
    return keys


def converted(params_type, dotted, value):
    """``value`` (an astropy Quantity, a text with its unit, or a number for a key without one) as the field of
    key ``dotted`` of ``params_type`` holds it: in the key's unit, checked in its range (schema.checked_float with
    the field's key: the conversion loading makes); ScenarioError naming the key otherwise.  For Python building
    parameters with ``dataclasses.replace`` from values with units."""
    return checked_float(dotted, value, keys_of(params_type)[dotted])


def tables_of(params_type):
    """{table name: its class} of a Params class."""
    return {table_field.name: table_field.type for table_field in fields(params_type)}


# ---- the tables every scene has ----------------------------------------------------------------------------

@table
class SceneTable:
    kind: str = key(type=str, help="what the scene runs (a module of spinorbit/scenes: spinorbit.scenes.SCENES)")
    title: str = key(type=str, default="", help="one line for reports and `spinorbit list`")
    description: str = key(type=str, default="", help="free text, copied to the report")


@table
class SpanTable:
    """The span, loaded: ``start`` and ``end`` in TDB days from J2000.0 (a file gives ISO text, ``end`` also a
    duration from the start), ``step`` the output cadence in days."""

    start: float = key(type=str, help="ISO time, TDB")
    end: float = key(type=str, help="ISO time (TDB) or a duration such as '100 yr'")
    step: float = key(unit="d", positive=True, count="output rows", help="output cadence")

    @property
    def bounds(self):
        """(earliest, latest) TDB days, whichever way the span runs."""
        return min(self.start, self.end), max(self.start, self.end)

    @property
    def length(self):
        """|end - start|, days."""
        return abs(self.end - self.start)

    @property
    def backward(self):
        return self.end < self.start

    def times(self, extra=None):
        """Output times in TDB days: start to end at ``step`` (end included), descending when the span runs
        backward; with ``extra`` TDB days among them."""
        step = self.step * (-1.0 if self.backward else 1.0)
        n = int(np.floor((self.end - self.start) / step + 1e-9))
        times = self.start + step * np.arange(n + 1)
        if not np.isclose(times[-1], self.end, rtol=0, atol=1e-9 * abs(step)):
            times = np.append(times, self.end)
        if extra is not None:
            times = np.union1d(times, extra)[::-1 if self.backward else 1]
        return times


def _option():
    return field(default=None)


@table
class IntegratorTable:
    """The integrator: its method, whether its error is estimated, and its options (None: the method's own
    default; spinorbit.integrators.options declares each option's meaning, unit and range)."""

    method: str = key(type=str, default="dop853", help="spinorbit.integrators.METHODS")
    estimate_error: bool = key(type=bool, default=True, help="rerun at half the step (or a tenth the "
                                                             "tolerance) and report the difference")
    step: float | None = _option()
    max_steps: float | None = _option()
    rtol: float | None = _option()
    atol: float | None = _option()
    max_step: float | None = _option()
    tolerance: float | None = _option()
    free_flow: str | None = _option()
    compact_mode: object = _option()
    opt_level: float | None = _option()

    def options(self):
        """{option: value} the scenario gives the method (units in days)."""
        return {name: getattr(self, name) for name in OPTIONS if getattr(self, name) is not None}


@table
class OutputTable:
    plots: bool = key(type=bool, default=True, help="draw the scene's figures (PNG)")


@table
class LimitsTable:
    time: float = key(unit="s", positive=True, default=3600.0, max=3.2e7,
                      help="longest run the up-front estimate lets through (e.g. '10 h')")
    memory: float | None = key(unit="byte", positive=True, default=None, max=1e15,
                               help="largest memory the estimate lets through (default: half the machine's)")


@_table
class Params:
    """What every scene's parameters hold; a scene's class adds its own tables."""

    scene: SceneTable
    span: SpanTable
    integrator: IntegratorTable
    output: OutputTable = field(default_factory=OutputTable)
    limits: LimitsTable = field(default_factory=LimitsTable)

    def with_span(self, start=None, end=None):
        """These parameters over [start, end] TDB days from J2000.0 (``dataclasses.replace``; either left out: its
        own)."""
        start = self.span.start if start is None else start
        end = self.span.end if end is None else end
        return replace(self, span=replace(self.span, start=float(start), end=float(end)))


def filled(params_type, values, span, options):
    """An instance of ``params_type`` from the loaded ``values`` (dotted key -> converted value), the ``span``
    (SpanTable) and the [integrator] ``options`` ({name: value})."""
    by_table = {}
    for dotted, value in values.items():
        name, leaf = dotted.split(".", 1)
        by_table.setdefault(name, {})[leaf] = value
    made = {name: cls(**by_table.get(name, {})) for name, cls in tables_of(params_type).items()
            if name not in ("span", "integrator")}
    integrator = IntegratorTable(**by_table["integrator"], **options)
    return params_type(**made, span=span, integrator=integrator)


def check_values(params):
    """Raise ScenarioError naming the key unless each number of ``params`` (each element of a vector, each
    [integrator] option) is finite and inside its key's range and each choice one its key accepts: what loading
    checks of a file's values, for parameters made by ``dataclasses.replace`` (Scenario.with_params)."""
    from ..base.errors import ScenarioError
    from .schema import INTEGRATOR_OPTIONS

    specs = {**keys_of(type(params)), **{f"integrator.{name}": spec for name, spec in INTEGRATOR_OPTIONS.items()}}
    values = {**values_of(params), **{f"integrator.{name}": v for name, v in params.integrator.options().items()}}
    for dotted, value in values.items():
        spec = specs.get(dotted)
        if spec is None or spec.parse is not None or value is None or isinstance(value, bool):
            continue                            # an object made from its text (an orbit source): made checked
        if spec.choices and value not in spec.choices:
            raise ScenarioError(dotted, value, spec.accepted())
        numbers = np.ravel(value) if isinstance(value, np.ndarray) else [value] if isinstance(value, (int, float)) \
            else []
        for number in numbers:
            spec.check_range(dotted, float(number), value.tolist() if isinstance(value, np.ndarray) else value)


def values_of(params):
    """{dotted key: value} of every keyed field (the span's start and end in TDB days): what the solution store
    records, the budget counts and an export writes in its comments, generically."""
    return {f"{table_field.name}.{leaf.name}": getattr(getattr(params, table_field.name), leaf.name)
            for table_field in fields(params) for leaf in fields(table_field.type) if "key" in leaf.metadata}


def at_defaults(table, *names):
    """Whether the keyed fields of a table instance (those ``names``, or all) hold their declared defaults: the
    model a scene declares as its reference's, e.g. La2004's physics.  A default is the field's (what its key's
    default text names, for a key that names an object)."""
    chosen = [f for f in fields(table) if "key" in f.metadata and (not names or f.name in names)]
    return all(np.array_equal(getattr(table, f.name), f.default_factory() if f.default is MISSING else f.default)
               for f in chosen)
