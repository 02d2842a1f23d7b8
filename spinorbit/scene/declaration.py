"""What a scene declares, for the one runner (``runner.run_scenario``) to run.

A scene module defines ``SCENE = Scene(...)``: its keys, how it builds the System it integrates, what it
compares, its verdict, its cost and the time-scales its run follows.  The runner does the rest for every
scene: validate the scenario into the scene's typed parameters (its ``params`` class), build, simulate, compare,
table, figures, summary, verdict, result.  A scene that needs further integrations (a twin model, a run driven
by another orbit source, an ensemble of methods) asks the runner for them through ``Run.integrate``; a scene
with nothing of its own to integrate (an ensemble compared method by method) builds ``Model(None)``.

Edge module, below ``scenes`` (scenes import it) and ``scenarios`` (which reads what a scene declares).
"""
from contextlib import contextmanager
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Callable

from ..base.errors import EphemerisRangeError, InputError, ScenarioError


@dataclass(frozen=True)
class Cost:
    """What one item of a count costs a scene kind, measured (``python benchmarks/bench_costs.py``, peak
    resident memory and wall time of whole runs at two sizes; benchmarks/results_costs.md): wall
    seconds per integrator step of its fixed-step method, peak bytes per output row and per orbit
    sample, and the peak of a small run."""

    step_s: float = 3e-5             # a rigid body on an analytic orbit
    row_bytes: float = 1000
    sample_bytes: float = 1000
    base_bytes: float = 350e6

    @property
    def bytes_per(self):
        return {"output rows": self.row_bytes, "orbit samples": self.sample_bytes}


# The N-body stages a run may do before its own integration, per item (benchmarks/bench_costs.py --only nbody,
# benchmarks/results_costs.md): the deep-time orbital solution's WHFast steps (10 bodies, 5 d; 1.6 us of CPU a
# step, 1.5-2 us of wall time on a free core) and REBOUND's IAS15 run of orbit.source = 'rebound' per simulated
# day (11 bodies, GR; 0.37 ms of CPU a day); each about twice the quiet figure, as Cost's.
# The solar system's Taylor run at 1e-15 per simulated day (12 bodies, EIH, the Moon's and the Earth's spins:
# 4.8 s of wall time for 20 yr on the shared machine, load about 8; 2.3e-4 s quiet from 28.6 s a century).
NBODY_COSTS = {"WHFast steps": 4e-6, "IAS15 days": 8e-4, "Taylor days (solar system)": 6e-4}


@dataclass(frozen=True)
class TimeScale:
    """A rate (rad/d) a run follows, beside the scenario's rate keys: ``key`` the scenario key that sets it,
    ``how`` says how it follows from the keys (printed when the run is refused for too many cycles)."""

    key: str
    rate: float
    how: str = ""


class Model(SimpleNamespace):
    """What a scene builds: ``system``, the System the runner integrates over the output times (None: nothing),
    and, by name, whatever its comparison reads besides the solution (a closed form, the orbits, a start)."""

    def __init__(self, system, **context):
        super().__init__(system=system, **context)


@dataclass
class Run:
    """What the runner hands a scene's ``compare``: the parameters, the model, the output times, the main
    run's solution and its point (method, wall time, error estimate), ``fitted``: the main run's Solution
    (spinorbit.solutions; None when it was run to the outputs), and ``integrate(system, times, part,
    method=None, options=None, estimate_error=None) -> (solution, point)`` for a further run (``part`` names its
    checkpoint and progress bar; the scenario's [integrator] unless given)."""

    params: object
    model: Model
    times: object
    integrate: Callable
    solution: object = None
    point: dict = field(default_factory=dict)
    fitted: object = None


@dataclass
class Outcome:
    """What a scene's comparison returns.  ``comparison``: the metrics the verdict reads (summary["comparison"]);
    ``columns``: columns added to the attitude table of the main run (name -> Quantity array), or ``table`` in
    its place (None with no main run: no table); ``figures``: name -> function drawing one figure;
    ``sections``: further summary sections (model, reference, details, or ``run`` in place of the point);
    ``not_measured``: dotted summary key -> why it could not be measured."""

    comparison: dict
    columns: dict = field(default_factory=dict)
    figures: dict = field(default_factory=dict)
    sections: dict = field(default_factory=dict)
    not_measured: dict = field(default_factory=dict)
    table: object = None


@dataclass(frozen=True, eq=False)
class Answer:
    """What spinorbit.edge.api answers from a scene's stored solution and the accuracy it states there
    (``meta["expected_accuracy"]``, ``api.expected(name)``).  ``name``: the answer ("moon", "earth_rigid");
    ``scenario``: the validated built-in scenario it is answered from, whose verdict's tolerances it states;
    ``tolerances``: {stated name: the verdict's metric it is} (the name's last word its unit); ``stated``:
    further figures ({name: value}, e.g. the largest difference one date of the validated run showed);
    ``statistic`` and ``basis``: what the tolerances bound and what the validated run measured;
    ``beyond_de421``: what applies at dates where the reference has no data; ``bounds``: {difference column:
    the stated name bounding it at one date}; ``columns``: the table's columns; ``body``: the body
    ``spinorbit.orientation`` and ``spinorbit at`` answer for with it (None: none), ``about`` what they give
    for it; ``function``: the spinorbit function answering for the body (None: the attitude layer's pole and
    prime meridian, ``api.orientation``)."""

    name: str
    scenario: str
    tolerances: dict
    statistic: str
    basis: str
    columns: tuple
    stated: dict = field(default_factory=dict)
    beyond_de421: str | None = None
    bounds: dict = field(default_factory=dict)
    body: str | None = None
    about: str = ""
    function: str | None = None


@dataclass(frozen=True)
class Stored:
    """What a scene keeps as a continuous solution (spinorbit.solutions): Chebyshev segments of ``segment_d``
    days and ``degree`` from J2000 (their error below the integration's: tests/test_solutions.py,
    benchmarks/bench_solutions.py); ``anchor``: the TDB day its first run starts from (None: the scenario's own
    span.start); ``kernels``: SPICE kernels carry it (an attitude or integrated positions: ``spinorbit export``);
    ``attitude``: the gyroscopic body whose attitude layer (solutions.attitude_layer) it answers with, and
    ``attitude_table(t, poles, prime_meridian) -> QTable``: that layer's table at TDB days ``t`` (what its
    comparison says of it); ``own_start(p) -> TDB days | None``: where a key starts the model elsewhere than
    the anchor (None: at the anchor); ``started(p, t0) -> p``: the parameters of a stretch started at t0 (a
    model that reads its start from a key; None: ``p`` itself)."""

    segment_d: float
    degree: int
    anchor: float | None
    kernels: bool = True
    attitude: str | None = None
    attitude_table: Callable = None
    own_start: Callable = None
    started: Callable = None


@dataclass(frozen=True)
class Scene:
    """A scene's declarations.  ``params``: its parameter class (a spinorbit.scene.params.Params with a table per
    scenario table, each field declared with its key), which the scenario is loaded into and every function
    below receives as ``p``; ``schema``: the keys read off it; ``build(p, times) -> Model``;
    ``compare(p, run) -> Outcome`` (a scene module names it ``compare_run``: the ``compare`` submodule some
    scenes have would shadow it); ``verdict``: a Verdict, or ``verdict(p, comparison) -> Verdict`` when it
    depends on the settings or the outcome; ``cost``: measured per-item costs (the up-front estimate);
    ``time_scales(p) -> [TimeScale]``: rates the run follows beyond the rate keys (torques, Euler's equations);
    ``bench(p, model, times) -> error(solution) in rad`` for ``spinorbit bench`` on the model ``build`` made
    (its ``system``, or ``bench_system`` where it has no main run; it may set the System's
    ``meta["reference_agreement_rad"]``); ``backward``: the span may run backward;
    ``taylor``: every term a function of the state and the time, so heyoka's Taylor integrator takes it;
    ``restart(p, start) -> System``: the model started at a stored state ``start`` = (t0, y) instead of its own
    start (what a continuous solution is extended with, spinorbit.solutions);
    ``sweep_figures(tables) -> {name: draw}``: figures over a sweep's members (e.g. a band over their curves);
    ``nbody_counts(p) -> {count: items}``: N-body work its run does (NBODY_COSTS' counts: an orbital solution
    or a REBOUND run first, or its own run where its integrator chooses its steps), for the up-front estimate;
    ``stored``: what it keeps as a continuous solution (a Stored; None: it keeps none);
    ``answers``: what spinorbit.edge.api answers from its stored solution (:class:`Answer`), the accuracy it states
    and the body it answers for."""

    params: type
    build: Callable = None
    compare: Callable = None
    verdict: object = None
    cost: Cost = Cost()
    time_scales: Callable = None
    bench: Callable = None
    backward: bool = False
    taylor: bool = False
    restart: Callable = None
    sweep_figures: Callable = None
    nbody_counts: Callable = None
    stored: Stored = None
    answers: tuple[Answer, ...] = ()

    @property
    def schema(self):
        """{dotted key: schema.Key} the scene accepts, read off its parameter class (params.keys_of)."""
        from .params import keys_of

        return keys_of(self.params)

    def verdict_for(self, params, comparison):
        """The Verdict of a run with these parameters and this comparison (None: the scene declares none)."""
        return self.verdict(params, comparison or {}) if callable(self.verdict) else self.verdict


def integrate(scenario, system, times, part=None, method=None, options=None, estimate_error=None):
    """simulate() with the scenario's [integrator] table (or ``method`` and ``options``): the main run
    checkpointed when the command line gives a checkpoint, a further run ``part`` in a checkpoint of its own
    and a progress bar named for it; its error estimated as the scenario says (or as ``estimate_error``; a run
    with its own ``method``: not estimated, not checkpointed)."""
    from ..integrators import simulate

    label = scenario.name if part is None else f"{scenario.name} ({part})"
    if method is not None:
        return simulate(system, times, method, options or {}, bool(estimate_error), None, label)
    checkpoint = scenario.checkpoint
    if checkpoint is not None and part is not None:
        checkpoint = checkpoint.part(part)
    settings = scenario.params.integrator
    estimate = settings.estimate_error if estimate_error is None else estimate_error
    return simulate(system, times, settings.method, settings.options(), estimate,
                    checkpoint, label)


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
        (first, last) = scenario.params.span.bounds
        asked_first, asked_last = exc.requested if isinstance(exc.requested, tuple) else (first, last)
        before, after = max(first - asked_first, 0.0), max(asked_last - last, 0.0)
        low, high = exc.span[0] + before, exc.span[1] - after
        fits = (f"a span from {_iso(low)} to {_iso(high)} TDB fits" if high > low else "no span fits")
        around = (f"the run samples the orbit {before:.3g} d before its span and {after:.3g} d after it, so "
                  if before or after else "")
        raise EphemerisRangeError(exc.source, exc.requested, exc.span,
                                  note=f"{exc.note}; {around}{fits}") from None


def _iso(t_tdb_d):
    """TDB days from J2000 as an ISO date and time to the minute."""
    from .schema import tdb_days_to_time

    return tdb_days_to_time(t_tdb_d).isot[:16]
