"""Pieces scene modules share: a rigid body from its moments, its time-scales, plots (spinorbit.plots)."""
import math

import numpy as np

from ..bodies import RigidBody
from ..errors import PhysicsError, ScenarioError
from ..plots import plot_series  # scenes call common.plot_series
from ..scene import TimeScale


def u():
    """astropy.units, imported on first use."""
    import astropy.units as units

    return units


def rigid_body(scenario, key="body.moments"):
    """RigidBody from principal moments at ``key``; a non-physical body is a ScenarioError on that key."""
    moments = scenario[key]
    try:
        return RigidBody.from_principal(*moments, name=key)
    except PhysicsError as exc:
        raise ScenarioError(key, moments.tolist(), f"a rigid body ({exc})") from None


DISTANCE_KEYS = ("orbit.radius", "orbit.f", "orbit.a")


def rigid_body_time_scales(schema):
    """``time_scales`` of a rigid body's scene with these keys: the body-frame rates Euler's equations make of
    its spin keys (|rate| x the largest |B - C|/A of its moments, when over 1), and a centre of forces' torque
    time-scale sqrt(3 GM/s^3)."""
    spins = [key for key, spec in schema.items() if key.startswith("body.") and spec.unit == "rad/d"]
    distance = next((key for key in DISTANCE_KEYS if key in schema), None)

    def time_scales(p):
        scales = []
        moments = p["body.moments"] if "body.moments" in schema else None
        if moments is not None and np.all(np.abs(moments) > 0):
            a, b, c = (float(m) for m in moments)
            euler = max(abs(b - c) / abs(a), abs(c - a) / abs(b), abs(a - b) / abs(c))
            scales += [TimeScale("body.moments", float(np.linalg.norm(p[key])) * euler,
                                 f" (the body-frame rate |{key}| x {euler:.3g}, Euler's equations)")
                       for key in spins if p[key] is not None and euler > 1]
        if "orbit.gm" in schema and distance:
            rate = math.sqrt(3 * p["orbit.gm"] / p[distance] ** 3)
            scales.append(TimeScale(distance, rate, f" (sqrt(3 orbit.gm/{distance}^3) = {rate:.3g} rad/d)"))
        return scales

    return time_scales


def decimal_year(t):
    """TDB days from J2000 -> Julian epoch (decimal year), for time axes."""
    return 2000.0 + np.asarray(t) / 365.25


def plot_omega(solution):
    return plot_series(solution.t - solution.t[0], solution.omega.T, "days from start",
                       "body angular velocity [rad/d]", ["x", "y", "z"])
