"""A stored scene's model over a stretch of time: what its Scene keeps (``Scene.stored``, a scene.Stored), its
grid, the scenario of a stretch, the System it integrates, where its first run starts, and the ephemeris its fit
reads.

A stored solution starts once, at the scene's anchor (the state the scene starts from there), and is extended
from its ends: each later stretch is the same model started at the state where the last run stopped.
"""
from .chebyshev import Grid


def stored(scenario):
    """What ``scenario``'s scene keeps as a solution (its Stored); InputError for a scene that keeps none."""
    declared = scenario.scene.stored
    if declared is None:
        from ..base.errors import InputError
        from ..scenes import stored_kinds

        raise InputError("scene", scenario.kind, f"a scene kept as a solution: {sorted(stored_kinds())}")
    return declared


def grid(declared):
    """The Grid of a Stored's segments: ``segment_d`` days of ``degree`` from J2000."""
    return Grid(0.0, declared.segment_d, declared.degree)


def own_start(scenario):
    """Where ``scenario`` asks its model to start when a key says so (TDB days: its Stored's ``own_start``), or
    None (the stored solution's anchor)."""
    declared = stored(scenario)
    return None if declared.own_start is None else declared.own_start(scenario.params)


def stretch(scenario, lo, hi, t0):
    """``scenario`` over [lo, hi] TDB days, its model started at t0 (its Stored's ``started``: the Moon reads its
    start from a key): a copy holding those parameters (``Params.with_span``), without the run's checkpoint or
    extra output times."""
    import copy

    p = scenario.params.with_span(lo, hi)
    started = stored(scenario).started
    plain = copy.copy(scenario)
    plain.checkpoint, plain.extra_times = None, None
    return plain.with_params(p if started is None else started(p, t0))


def first_start(scenario):
    """(t0, state) where the scene's first run starts: the scene's start at the anchor (the Earth: at its own
    span.start, with the start its own span gives it; the solar system: at DE421's epoch, where the scene starts
    by default, from DE421's initial conditions, or with ``start.epoch = "span"`` from DE421's states there)."""
    anchor = stored(scenario).anchor
    built = system(scenario if anchor is None else stretch(scenario, anchor, anchor + 4.0, anchor), None)
    return float(built.t0), built.y0.copy()


def ephemeris(scenario, built, lo, hi):
    """The JPL ephemeris reader of ``scenario``'s orbit source over [lo, hi] TDB days where ``built`` (its System)
    sees a body from another (fit.seen: that position is fitted from it, fit.components), or None (nothing seen,
    or a source that is not a JPL kernel)."""
    from .fit import seen

    if not seen(built):
        return None
    source = scenario.params.orbit.source
    return source.open(lo, hi) if source.jpl_kernel else None


def system(scenario, start):
    """The scene's System over the scenario's span, started at ``start`` = (t0, state) (its Scene's
    ``restart``), or at the scene's own start (``start`` None: its ``build``)."""
    scene, p = scenario.scene, scenario.params
    if start is None:
        return scene.build(p, scenario.output_times()).system
    return scene.restart(p, start)
