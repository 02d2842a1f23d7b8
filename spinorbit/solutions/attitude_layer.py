"""A gyroscopic body's attitude from its stored spin: its figure axis and its prime meridian, as a Solution of
their own on the spin solution's grid -- what the API answers and ``spinorbit export`` writes for it.

The figure axis is the scene's (spinorbit.models' System.figure_axes: the spin angular momentum's direction with its
Oppolzer terms), as the spin solution holds it (``<body>.pole``, solutions.fit).  The prime meridian W is
measured along the body's equator from its node on the ICRF equator (the IAU's convention), its 3-1-3
kinematics w_z = dW/dt + sin(delta) d alpha/dt integrated from the solution's anchor, where W is the scene's
start's (``System.meta["prime_meridian_rad"]``), w_z = |L|/C (no torque turns an axisymmetric body about its
axis).  In each segment alpha and sin(delta) d alpha/dt are Chebyshev series through the axis at the segment's
nodes, the latter integrated in closed form (numpy.polynomial.chebyshev.chebint); W's uniform turn is taken
from the segment's middle, less its whole turns there (:func:`turned_part`: small values, the same rotation;
1e5 rad of turn in a century, rounded at each node, would be off by 2 uas).  The body's
frame: z its figure axis, x its prime meridian.
"""
import numpy as np
from numpy.polynomial import chebyshev as cheb

from ..base.layout import Layout
from . import store
from .chebyshev import Segments, extrema, first_kind, interpolating
from .fit import errors
from .solution import Solution


def layout(body):
    return Layout([(f"{body}.pole", 3, "vector", ""), (f"{body}.prime_meridian", 1, "vector", "rad")])


def layer(spin, scenario, body):
    """The attitude layer (a Solution over ``spin``'s span) of gyroscopic ``body`` of ``scenario``'s stored
    solution ``spin``; kept in the store beside it."""
    record = {**store.record(scenario), "scene": f"{scenario.kind}_attitude", "body": body}
    return store.solve(record, *spin.span, lambda _, lo, hi: _computed(spin, scenario, body))


def _computed(spin, scenario, body):
    from .stretches import stretch, system

    segments = spin.segments
    count = len(segments.coefficients)
    nodes, checks = segments.nodes(segments.first, count)
    t0 = float(spin.provenance["runs"][0]["start_tdb_d"])
    start = system(stretch(scenario, t0, t0 + 4.0, t0), None)
    spin_rate = float(np.linalg.norm(start.y0[start.layout[f"{body}.spin"]]) / start.bodies[body].figure.moments[2])
    at = {name: _axes(spin, body, times) for name, times in (("nodes", nodes), ("checks", checks))}
    integrand = at["nodes"][2] * _rates(at["nodes"][1], first_kind(segments.degree), segments.length_d)
    primitive = cheb.chebint(interpolating(integrand), lbnd=-1.0, axis=-1) * (segments.length_d / 2.0)
    totals = cheb.chebval(1.0, primitive.T)
    anchor = int(round((t0 - segments.span[0]) / segments.length_d))
    before = np.concatenate([[0.0], np.cumsum(totals)])
    before -= before[anchor]                              # the turn counted from the anchor
    mids = segments.origin_d + (np.arange(segments.first, segments.first + count) + 0.5) * segments.length_d
    at_mids = start.meta["prime_meridian_rad"] + turned_part(spin_rate, mids - t0)

    def meridian(x):
        turned = before[:count, None] + np.array([cheb.chebval(x[k], primitive[k]) for k in range(count)])
        return at_mids[:, None] + spin_rate * segments.length_d / 2.0 * x - turned

    points = {"nodes": np.broadcast_to(first_kind(segments.degree), nodes.shape),
              "checks": np.broadcast_to(extrema(segments.degree), checks.shape)}
    values = {name: np.concatenate([at[name][0], meridian(points[name])[..., None]], axis=-1)
              for name in ("nodes", "checks")}
    fitted = Segments(segments.origin_d, segments.length_d, segments.first,
                      interpolating(values["nodes"].transpose(0, 2, 1)))
    parts = layout(body)
    truth = values["checks"].reshape(-1, parts.size)
    provenance = {**{k: spin.provenance.get(k) for k in ("scene", "keys", "ephemeris", "code_version", "integrator",
                                                         "grid")},
                  "model_start_tdb_d": t0, "layer": f"{body} attitude", "fit_over_tdb_d": list(spin.span),
                  "spin": spin.provenance, "spin_rate_rad_d": spin_rate, "state_size": 0,
                  "fit_error": errors(parts, fitted.at_normalised(points["checks"]).reshape(-1, parts.size), truth)}
    return Solution(fitted, parts, provenance, {"start": (spin.span[0], np.zeros(0)),
                                                "end": (spin.span[1], np.zeros(0))})


# 2 pi in three parts, the first two of 26 bits: k times them is exact for k < 2^27 turns (Cody & Waite 1980)
TWO_PI_PARTS = (6.283185243606567, 6.357301884918343e-08, 2.4492935982947064e-16)


def turned_part(rate, days):
    """rate x days modulo 2 pi (rad), to the last bit of a few radians: ``rate`` split in two halves of 26 bits
    (Veltkamp), each product with ``days`` (whole numbers of at most 27 bits: segment middles) exact, and 2 pi
    taken off in TWO_PI_PARTS; a product rounded at 1e5 rad would be off by 1e-11 rad (2 uas)."""
    days = np.asarray(days, dtype=float)
    high = np.float64(rate) * 134217729.0
    high = high - (high - rate)
    low = rate - high
    big, small = high * days, low * days
    turns = np.round((big + small) / (2 * np.pi))
    return (((big - turns * TWO_PI_PARTS[0]) - turns * TWO_PI_PARTS[1]) + small) - turns * TWO_PI_PARTS[2]


def _axes(spin, body, times):
    """(figure axes (count, n, 3): the spin solution's own, fitted beside its state (solutions.fit), right
    ascensions unwrapped in each segment (count, n), sin(declination))."""
    axes = spin.part(f"{body}.pole", times.ravel()).reshape(*times.shape, 3)
    axes = axes / np.linalg.norm(axes, axis=-1)[..., None]
    return axes, np.unwrap(np.arctan2(axes[..., 1], axes[..., 0]), axis=1), axes[..., 2]


def _rates(ra, x, length_d):
    """d alpha/dt (rad/d) at the nodes (normalised: ``x``) from each segment's series through alpha there."""
    coefficients = interpolating(ra)
    return np.array([cheb.chebval(x, cheb.chebder(c)) for c in coefficients]) * 2.0 / length_d
