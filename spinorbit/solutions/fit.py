"""An integration made continuous: a System run through the integrator door to the Chebyshev points of each
segment (the integrator's dense output where they fall inside its steps), the series fitted there, and the
fit's error measured against the integrator at the points between them.

What is fitted: the whole state (every slice of the System's layout); for a body turned by its spin (a
Gyroscopic rotator), its figure axis ``<body>.pole`` (System.figure_axes: the spin's direction plus the
Oppolzer terms, a function of the state and the torque, so it is fitted, not rebuilt); for a System centred on
one body, the first body its orbit source gives (``earth.from_moon``): read from the JPL ephemeris itself at the
node times where the orbit source is one (its own Chebyshev series, which a series of the segments' degree
follows to ~0.1 mm), else as the run read it (the orbit source's interpolant).
"""
from dataclasses import dataclass

import numpy as np

from ..base.constants import ARCSEC
from ..base.layout import Layout
from ..base.rotations import quat_angle, vector_angle
from ..integrators import simulate
from .chebyshev import Grid, Segments, grid_indices, interpolating_at  # noqa: F401  (fit.Grid)


@dataclass
class Piece:
    """A fitted stretch: ``segments``; ``layout`` of their components; ``ends``: {"start", "end"}: (t, state)
    where the integration stopped at each end of the span; ``run``: simulate's point (wall time, rhs
    evaluations, integration error estimate); ``fit_error``: the fit's measured error by kind."""

    segments: Segments
    layout: Layout
    ends: dict
    run: dict
    fit_error: dict


def poles(system):
    """The bodies whose figure axis is fitted beside the state (those turned by a spin, no attitude)."""
    return [s.name.split(".")[0] for s in system.layout.slices if s.name.endswith(".spin")]


def seen(system):
    """(body, origin) of the first body a System centred on ``origin`` reads from its orbit source (the Earth
    for the Moon, the Moon for the Earth), or None: its position is fitted too, so that what the scene derives
    from it (the librations, the sub-Earth point) needs no ephemeris at the dates."""
    externals, origin = getattr(system.motion, "externals", None), getattr(system.motion, "origin", None)
    if externals is None or origin is None or not hasattr(externals, "positions") or not len(externals.names):
        return None
    return externals.names[0], origin


def fitted_layout(system):
    """The state's layout, a ``<body>.pole`` slice (unit vector, inertial) for each of :func:`poles`, and
    ``<body>.from_<origin>`` (km, the orbit source's) for :func:`seen`."""
    parts = [(s.name, s.stop - s.start, s.kind, s.unit) for s in system.layout.slices]
    parts += [(f"{body}.pole", 3, "vector", "") for body in poles(system)]
    if seen(system):
        body, origin = seen(system)
        parts.append((f"{body}.from_{origin}", 3, "vector", f"km, from {origin}, the orbit source's"))
    return Layout(parts)


def components(system, t, states, ephemeris=None):
    """The fitted components (n, fitted size) of ``states`` (n, state size) at TDB days ``t``; the seen body's
    position from ``ephemeris`` (a JPL reader, spinorbit.orbits.kernel: ``relative_states``) when given, else from
    the System's orbits."""
    extra = [system.figure_axes(body, t, states) for body in poles(system)]
    if seen(system) and ephemeris is not None:
        extra.append(ephemeris.relative_states(*seen(system), t)[0])
    elif seen(system):
        extra.append(np.asarray(system.motion.externals.positions(t))[:, 0])
    return np.hstack([states, *extra]) if extra else np.asarray(states)


def integrate(system, grid, t_start, t_end, method, options, label=None, estimate_error=True, ephemeris=None):
    """The Piece covering [t_start, t_end] (rounded out to the grid) of ``system`` integrated from its t0
    (inside the span, or at one of its ends) with ``method`` and ``options`` (its error estimated unless
    ``estimate_error`` is False); ``ephemeris``: the JPL reader the seen body is read from (``components``)."""
    first, count = grid_indices(grid.origin_d, grid.length_d, t_start, t_end)
    empty = Segments(grid.origin_d, grid.length_d, first, np.zeros((count, 0, grid.degree + 1)))
    nodes, checks = empty.nodes(first, count)
    t_out = np.concatenate([nodes.ravel(), checks.ravel()])
    times, rows = np.unique(t_out, return_inverse=True)     # the segments' shared ends once
    solution, run = simulate(system, times, method, options, estimate_error=estimate_error, label=label)
    states = solution.y[rows]
    values = components(system, t_out, states, ephemeris)
    layout, n = fitted_layout(system), nodes.size
    at_nodes = values[:n].reshape(count, grid.degree + 1, -1).transpose(0, 2, 1)
    coefficients = interpolating_at(at_nodes, empty.normalised(nodes, first))
    segments = Segments(grid.origin_d, grid.length_d, first, coefficients)
    at_checks = segments.at_normalised(empty.normalised(checks, first)).reshape(-1, layout.size)
    fit, truth = layout.normalise(at_checks), values[n:]
    lo, hi = n + int(np.argmin(t_out[n:])), n + int(np.argmax(t_out[n:]))
    ends = {"start": (float(t_out[lo]), states[lo].copy()), "end": (float(t_out[hi]), states[hi].copy())}
    return Piece(segments, layout, ends, run, errors(layout, fit, truth))


def errors(layout, fit, truth):
    """{fit_error_*: max difference} of fitted and integrated components by kind: attitudes (quaternions) and
    directions (spins, poles) in arcsec, positions (``*.r``) in km, angles (unit "rad") in arcsec, every other
    slice relative to its size."""
    out = {}
    for part in layout.slices:
        a, b = fit[:, part.index], truth[:, part.index]
        if part.kind == "quaternion":
            key, value = "fit_error_attitude_arcsec", quat_angle(a, b).max() / ARCSEC
        elif part.name.endswith((".spin", ".pole")):
            key, value = "fit_error_direction_arcsec", vector_angle(a, b).max() / ARCSEC
        elif part.name.endswith(".r"):
            key, value = "fit_error_position_km", np.linalg.norm(a - b, axis=1).max()
        elif part.unit == "rad":
            key, value = f"fit_error_{part.name.replace('.', '_')}_arcsec", np.abs(a - b).max() / ARCSEC
        else:
            key = f"fit_error_{part.name.replace('.', '_')}_rel"
            value = np.abs(a - b).max() / max(np.abs(b).max(), 1e-300)
        out[key] = max(out.get(key, 0.0), float(value))
    return out
