"""Pieces scene modules share: the orbit tables of Euler's idealised problems, a rigid body's
time-scales, plots (spinorbit.plots.common)."""
import math
from dataclasses import fields

import numpy as np

from ..plots.common import plot_series  # scenes call common.plot_series
from ..scene.declaration import TimeScale
from ..scene.params import key, table
from ..scene.schema import DISTANCE, GM, RATE


@table
class CentreOfForcesTable:
    """A centre of forces F at rest (Euler's P92, P95)."""

    gm: float = key(**GM, help="GM of the centre of forces")
    radius: float = key(**DISTANCE, help="distance s of F")


@table
class CircularCentreTable:
    """A centre of forces F on a circle about the body (Euler's P93, P96)."""

    gm: float = key(**GM, help="GM of the centre of forces")
    radius: float = key(**DISTANCE, help="distance s of F")
    rate: float = key(**RATE, help="angular speed delta of F")


@table
class KeplerOrbitTable:
    """The body on a Kepler orbit about a central mass."""

    gm: float = key(**GM, help="GM of the central mass")
    a: float = key(**DISTANCE, help="semi-major axis")
    e: float = key(unit="", min=0.0, max=0.99, help="eccentricity")


def u():
    """astropy.units, imported on first use."""
    import astropy.units as units

    return units


DISTANCES = ("radius", "f", "a")        # the orbit table's distance, by the name a scene gives it


def rigid_body_time_scales(p):
    """``time_scales`` of a rigid body's scene: the body-frame rates Euler's equations make of its spin keys
    (|rate| x the largest |B - C|/A of its moments, when over 1), and a centre of forces' torque time-scale
    sqrt(3 GM/s^3)."""
    scales = []
    body, orbit = getattr(p, "body", None), getattr(p, "orbit", None)
    moments = getattr(body, "moments", None)
    if moments is not None and np.all(np.abs(moments) > 0):
        a, b, c = (float(m) for m in moments)
        euler = max(abs(b - c) / abs(a), abs(c - a) / abs(b), abs(a - b) / abs(c))
        spins = [f.name for f in fields(body) if f.metadata["key"].unit == "rad/d"]
        scales += [TimeScale("body.moments", float(np.linalg.norm(getattr(body, name))) * euler,
                             f" (the body-frame rate |body.{name}| x {euler:.3g}, Euler's equations)")
                   for name in spins if getattr(body, name) is not None and euler > 1]
    distance = next((name for name in DISTANCES if hasattr(orbit, name)), None)
    if hasattr(orbit, "gm") and distance:
        rate = math.sqrt(3 * orbit.gm / getattr(orbit, distance) ** 3)
        scales.append(TimeScale(f"orbit.{distance}", rate,
                                f" (sqrt(3 orbit.gm/orbit.{distance}^3) = {rate:.3g} rad/d)"))
    return scales


def decimal_year(t):
    """TDB days from J2000 -> Julian epoch (decimal year), for time axes."""
    return 2000.0 + np.asarray(t) / 365.25


def plot_omega(solution):
    return plot_series(solution.t - solution.t[0], solution.omega.T, "days from start",
                       "body angular velocity [rad/d]", ["x", "y", "z"])
