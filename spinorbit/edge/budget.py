"""What a run asks for, and whether it fits, decided before it starts: the rows, orbit samples, integrator steps
and N-body stage a scenario's span asks for at its step keys; the time and memory they cost (measured per
item for its scene kind: its Scene's ``cost``, spinorbit.scene.declaration.NBODY_COSTS); the cycles its rates make it
follow.  A step over ``LIMITS``, an estimate over ``limits.time`` or ``limits.memory``, or over ``MAX_CYCLES``
cycles is refused on the key that sets it, with the estimate, instead of hanging or filling the memory.

Edge module, below ``scenarios`` (which calls ``check`` on every scenario it loads).
"""
import math
import os

import numpy as np

from ..base.errors import ScenarioError
from ..orbits.sources import OrbitSource
from ..scene.params import values_of
from ..scene.schema import INTEGRATOR_OPTIONS, Key, has_key, lookup

# The most a step over the span may ask for, whatever the time and memory limits.
LIMITS = {"output rows": 1_000_000, "orbit samples": 10_000_000, "integrator steps": 1_000_000_000,
          "adaptive steps (at max_step)": 1_000_000}


ADAPTIVE_STEP_S = 2e-4         # scipy's adaptive methods: Python between the stages of each step
# The key an N-body stage's refusal names, and what would shorten it.
NBODY_KEYS = {"WHFast steps": ("span.end", "a shorter span (an orbital solution once computed is kept in the "
                                           "cache: a later run reads it)"),
              "IAS15 days": ("orbit.source", "a span nearer DE421's (1899-2200: REBOUND starts from DE421's state "
                                             "there and integrates out to the span), or an ephemeris that covers "
                                             "it (orbit.source = 'de440')"),
              "Taylor days (solar system)": ("span.end", "a shorter span")}
# Cycles a run may have to follow: any rate key (rad/d) times the span, and the time-scales its scene declares
# (a torque's sqrt(3 GM/s^3), Euler's equations' body-frame rates).  The fast-spin stress
# scene follows 1e5 spin cycles (a compiled splitting method); dop853 costs ~10 ms per cycle
# (p93 at orbit.rate = 1000 rad/d: 3200 cycles in 45 s), so 2e5 cycles is about half an hour.
MAX_CYCLES = 2e5


def check(scenario):
    """Refuse a scenario whose counts, estimate or cycles are over their limits (see the module docstring)."""
    _check_counts(scenario)
    _check_cycles(scenario)


def counts(scenario):
    """{count: items} the span asks for at each step key (output rows, orbit samples, integrator
    steps ...), the largest where two keys count the same."""
    counts = {}
    for _, kind, step in count_keys(scenario):
        counts[kind] = max(counts.get(kind, 0), scenario.params.span.length / step + 1)
    return {**counts, **nbody_counts(scenario)}


def nbody_counts(scenario):
    """{N-body count: items} the run integrates before its own: the scene's (``Scene.nbody_counts``: the
    deep-time orbital solution's WHFast steps not yet in the cache) and the IAS15 days of orbit.source =
    'rebound' (out from DE421's nearest epoch, then over the span)."""
    counts = dict(scenario.scene.nbody_counts(scenario.params)) if scenario.scene.nbody_counts else {}
    source = values_of(scenario.params).get("orbit.source")
    span = scenario.params.span
    days = source.integration_days(span.start, span.end) if isinstance(source, OrbitSource) else 0.0
    if days:
        counts["IAS15 days"] = days
    return counts


def estimate(scenario):
    """{"time_s", "memory_bytes"} of the run, from its counts and the kind's measured costs."""
    items, cost = counts(scenario), scenario.cost()
    memory = cost.base_bytes + sum(items.get(kind, 0) * size for kind, size in cost.bytes_per.items())
    time = sum(n * step_cost(scenario, kind) for kind, n in items.items())
    return {"time_s": time, "memory_bytes": memory}


def step_cost(scenario, kind):
    """Seconds per item of a count (0 for those that cost memory only)."""
    from ..scene.declaration import NBODY_COSTS

    return {"integrator steps": scenario.cost().step_s, "adaptive steps (at max_step)": ADAPTIVE_STEP_S,
            **NBODY_COSTS}.get(kind, 0.0)


def count_keys(scenario):
    """(key, count, step) of every step key that sets a count."""
    values = values_of(scenario.params)
    steps = [(key, spec.count, values[key]) for key, spec in scenario.schema.items()
             if spec.count and values[key] is not None]
    steps += [(f"integrator.{name}", INTEGRATOR_OPTIONS[name].count, value)
              for name, value in scenario.params.integrator.options().items()
              if name in INTEGRATOR_OPTIONS and INTEGRATOR_OPTIONS[name].count]
    return steps


def _check_counts(scenario):
    """Refuse a step that would ask for more rows, samples or steps than LIMITS, or a run the estimate
    says takes longer than limits.time or more memory than limits.memory."""
    span = scenario.params.span.length
    for key, kind, step in count_keys(scenario):
        n = span / step + 1
        if n > LIMITS[kind]:
            size = scenario.cost().bytes_per.get(kind, 0) * n
            memory = f", ~{_bytes(size)} in memory" if size else ""
            refuse(scenario, key, step, f"a step giving at most {LIMITS[kind]:,} {kind} over the {span:.6g} d "
                                        f"span (this one gives {_count(n)}{memory}); lengthen {key} or shorten "
                                        "the span")
    culprits = {kind: (key, step) for key, kind, step in count_keys(scenario)}
    _check_time(scenario, culprits)
    _check_memory(scenario, culprits)


def _check_time(scenario, culprits):
    limit, total, items = scenario.params.limits.time, estimate(scenario)["time_s"], counts(scenario)
    if total <= limit:
        return
    kind = max(items, key=lambda k: items[k] * step_cost(scenario, k))
    each = step_cost(scenario, kind)
    if kind in NBODY_KEYS:
        key, remedy = NBODY_KEYS[kind]
        refuse(scenario, key, values_of(scenario.params).get(key), f"a run the estimate finishes within limits.time = "
                                                        f"{_duration(limit)}: its N-body work, "
                                                        f"{_count(items[kind])} {kind} at ~{each * 1e6:.3g} us "
                                                        f"each (measured), is ~{_duration(items[kind] * each)} "
                                                        f"(the whole run ~{_duration(total)}); {remedy}, or "
                                                        "raise limits.time")
    key, step = culprits[kind]
    refuse(scenario, key, step, f"a run the estimate finishes within limits.time = {_duration(limit)}: "
                                f"{_count(items[kind])} {kind} at ~{each * 1e6:.3g} us each (measured for "
                                f"{scenario.kind}) is ~{_duration(total)}; lengthen {key}, shorten the span, "
                                "or raise limits.time")


def _check_memory(scenario, culprits):
    limit, total = scenario.params.limits.memory or physical_memory() / 2, estimate(scenario)["memory_bytes"]
    if total <= limit:
        return
    cost, items = scenario.cost(), counts(scenario)
    kind = max(cost.bytes_per, key=lambda k: items.get(k, 0) * cost.bytes_per[k])
    if kind not in culprits or items[kind] * cost.bytes_per[kind] < cost.base_bytes:
        refuse(scenario, "limits.memory", limit, f"at least the ~{_bytes(cost.base_bytes)} any run of "
                                                 f"{scenario.kind} takes (measured)")
    key, step = culprits[kind]
    refuse(scenario, key, step, f"a run the estimate holds within limits.memory = {_bytes(limit)}: "
                                f"{_count(items[kind])} {kind} at ~{_bytes(cost.bytes_per[kind])} each "
                                f"(measured for {scenario.kind}) is ~{_bytes(total)}; lengthen {key}, shorten "
                                "the span, or raise limits.memory")


def refuse(scenario, key, value, accepted):
    raise ScenarioError(key, lookup(scenario.data, key, Key()) if has_key(scenario.data, key) else value,
                        accepted)


def _check_cycles(scenario):
    """Refuse rate keys, and the time-scales the scene declares, that would make the run follow over
    MAX_CYCLES cycles."""
    span = scenario.params.span.length
    values = values_of(scenario.params)
    rates = [(key, float(np.linalg.norm(values[key])), "") for key, spec in scenario.schema.items()
             if spec.unit == "rad/d" and values[key] is not None]
    if scenario.scene.time_scales is not None:
        rates += [(s.key, s.rate, s.how) for s in scenario.scene.time_scales(scenario.params)]
    for key, rate, how in rates:
        cycles = rate * span / (2 * math.pi)
        if cycles > MAX_CYCLES:
            refuse(scenario, key, rate, f"a value giving at most {MAX_CYCLES:.0e} cycles over the {span:.6g} "
                                        f"d span (this one gives {cycles:.3g}{how}); change {key} or shorten "
                                        "the span")


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
