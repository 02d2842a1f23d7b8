"""Stress cases of the torque-free rigid body (Euler ch. 15 §808), each passing or failing on a number.

``stress.case``:

* ``flip`` — intermediate-axis flips (I = 0.3, 0.35, 0.4; omega0 = 0.1, 15, 0.1 rad/d):
  the flip period measured over ``stress.flips`` flips (zero crossings of w_y)
  against the closed-form period 4 K(k^2)/... of theory.FreeRigidBody (12.335 d).
* ``degenerate`` — A = B = C exactly under a point-mass torque (the torque must be
  exactly zero, no NaN: uniform rotation) and A = B (1 + 1e-12) torque-free
  against the axisymmetric closed form.
* ``shapes`` — prolate (A < B = C) and oblate (A = B < C) bodies with (C - A)/C
  from 1e-8 to 0.9 against the axisymmetric closed form (below).
* ``long_run`` — ``stress.steps`` steps of the HLW body per method: drift of |L|
  and of the energy (first and last tenth of the run), bounded for the splitting.

Axisymmetric closed form (symmetry axis s, other moment I_p): with body L0,
q(t) = q0 * E(L0 t / I_p) * E((1/I_s - 1/I_p) L_s t e_s), E(w) the unit
quaternion of rotation vector w, and body L rotating about e_s by
-(1/I_s - 1/I_p) L_s t.  Written with I_p - I_s so that it stays exact for a
flattening of 1e-8 (the general elliptic form loses digits there).
"""
import math

import numpy as np

from ..dynamics import invariant_drift, kinetic_energy, point_mass_system, torque_free_system
from ..errors import ScenarioError
from ..integrators import integrate
from ..rotations import quat_angle, quat_multiply
from ..scenarios import Key
from ..verdict import Check, Verdict
from . import common

CASES = ("flip", "degenerate", "shapes", "long_run")
VERDICT = Verdict("the case's closed form or invariant", (Check("its criteria", "passed", source="the case's criteria (module docstring; benchmarks/RESULTS.md, stress scenes)"),))

SCHEMA = {
    "stress.case": Key(type=str, choices=CASES),
    "body.moments": Key(unit="", size=3, default=np.array([0.3, 0.35, 0.4]), help="A <= B <= C (flip, long_run)"),
    "body.omega0": Key(unit="rad/d", size=3, default=np.array([0.1, 15.0, 0.1]), help="initial body omega"),
    "stress.flips": Key(type=int, default=1000, help="flip: number of flips measured"),
    "stress.flattenings": Key(type=list, default=[1e-8, 1e-6, 1e-4, 1e-2, 0.3, 0.9], help="shapes: (C - A)/C"),
    "stress.methods": Key(type=list, default=["rk8", "strang", "suzuki4", "dop853"], help="methods compared"),
    "stress.steps": Key(type=int, default=10**7, help="long_run: steps per method"),
}
Q0 = np.array([1.0, 0.0, 0.0, 0.0])
# |L| after N rounded rotations random-walks by ~ eps sqrt(N): suzuki4, 1e7 steps = 2e8 rotations -> 3e-12.
L_ROUNDING = 1e-11
CHECKS = {
    "flip": "intermediate-axis flip period over many flips vs closed form; passes within 1e-3 relative",
    "degenerate": "A = B = C: torque exactly 0, no NaN, uniform rotation; A = B(1 + 1e-12): attitude vs "
                  "axisymmetric closed form; passes below 1e-9 rad",
    "shapes": "prolate/oblate, (C - A)/C = 1e-8 ... 0.9: attitude vs axisymmetric closed form; passes below 1e-9 rad",
    "long_run": "|L| and energy drift over many steps; passes if the splitting keeps |L| to 1e-11 and its energy "
                "error in the last tenth is below twice that of the first tenth (no secular growth)",
}


def _exp(w):
    """Unit quaternion of the rotation vector w (..., 3)."""
    angle = np.linalg.norm(w, axis=-1, keepdims=True)
    axis = np.divide(w, angle, out=np.zeros_like(w), where=angle > 0)
    return np.concatenate([np.cos(angle / 2), np.sin(angle / 2) * axis], axis=-1)


def axisymmetric_attitude(moments, omega0, q0, t, s):
    """Closed-form attitude (n, 4) of a body symmetric about axis s (the other two moments equal)."""
    i_s = moments[s]
    i_p = moments[(s + 1) % 3]
    l0 = moments * omega0
    e_s = np.eye(3)[s]
    t = np.asarray(t)[:, None]
    first = _exp(l0 / i_p * t)
    second = _exp((i_p - i_s) / (i_s * i_p) * l0[s] * e_s * t)
    return np.array([quat_multiply(quat_multiply(q0, a), b) for a, b in zip(first, second)])


def _options(method, step):
    return {} if method in ("dop853", "radau", "rk45") else {"step": step}


def flip(scenario):
    from ..theory import FreeRigidBody

    moments, omega0 = scenario["body.moments"], scenario["body.omega0"]
    period = FreeRigidBody(moments, omega0, Q0).period
    t = np.arange(0.0, (scenario["stress.flips"] + 1.5) * period / 2, 0.005)
    system = torque_free_system(moments, Q0, omega0)
    rows = {}
    for method in scenario["stress.methods"]:
        sol = integrate(system, t, method, **_options(method, 0.005))
        wy = sol.omega[:, 1]
        i = np.nonzero(np.sign(wy[:-1]) != np.sign(wy[1:]))[0]
        crossing = t[i] - wy[i] * (t[i + 1] - t[i]) / (wy[i + 1] - wy[i])
        flips = crossing.size - 1
        measured = 2 * (crossing[-1] - crossing[0]) / flips
        rows[method] = {"flips": int(flips), "period_measured_d": float(measured),
                        "period_rel_error_vs_closed_form": float(measured / period - 1), "wall_s": sol.wall_s}
    worst = max(abs(r["period_rel_error_vs_closed_form"]) for r in rows.values())
    comparison = {"period_closed_form_d": period, "period_design_reference_d": 12.335,
                  "period_rel_error_max": worst, "passed": bool(worst < 1e-3 and
                                                                 min(r["flips"] for r in rows.values()) >= scenario["stress.flips"])}
    return comparison, {"methods": rows}, system, t


def degenerate(scenario):
    from ..orbits.analytic import CircularOrbits

    orbit = CircularOrbits(("F",), [1.0], [1.0], [0.7], inclination=[0.4])
    omega0 = np.array([0.3, -0.2, 2.0])
    t = np.linspace(0.0, 100.0, 201)
    rows = {}
    for label, moments in (("sphere", np.ones(3)), ("a_eq_b_1e-12", np.array([1.0, 1.0 + 1e-12, 1.3]))):
        if label == "sphere":
            system = point_mass_system(moments, orbit, Q0, omega0)
            exact = _exp(omega0 * t[:, None])              # uniform rotation about a fixed axis
            torque_max = float(np.abs([system.torque(ti, system.y0, system.params) for ti in t]).max())
        else:
            system = torque_free_system(moments, Q0, omega0)
            exact = axisymmetric_attitude(np.array([1.0, 1.0, 1.3]), omega0, Q0, t, 2)
        for method in scenario["stress.methods"]:
            sol = integrate(system, t, method, **_options(method, 0.01))
            rows[f"{label}/{method}"] = {"attitude_error_max_rad": float(quat_angle(sol.quaternion, exact).max()),
                                         "finite": bool(np.all(np.isfinite(sol.y)))}
    worst = max(r["attitude_error_max_rad"] for r in rows.values())
    comparison = {"sphere_torque_max": torque_max, "attitude_error_max_rad": worst,
                  "passed": bool(torque_max == 0.0 and worst < 1e-9 and all(r["finite"] for r in rows.values()))}
    return comparison, {"methods": rows}, system, t


def shapes(scenario):
    t = np.linspace(0.0, 100.0, 201)
    rows, worst = {}, 0.0
    for f in scenario["stress.flattenings"]:
        for shape, moments, omega0, s in (("oblate", [1 - f, 1 - f, 1.0], [0.3, 0.2, 2.0], 2),
                                          ("prolate", [1 - f, 1.0, 1.0], [2.0, 0.3, 0.2], 0)):
            moments, omega0 = np.array(moments), np.array(omega0)
            system = torque_free_system(moments, Q0, omega0)
            exact = axisymmetric_attitude(moments, omega0, Q0, t, s)
            for method in scenario["stress.methods"]:
                sol = integrate(system, t, method, **_options(method, 0.01))
                err = float(quat_angle(sol.quaternion, exact).max())
                rows[f"{shape}/{f:g}/{method}"] = err
                worst = max(worst, err)
    return {"attitude_error_max_rad": worst, "passed": bool(worst < 1e-9)}, {"attitude_error_max_rad": rows}, system, t


def long_run(scenario):
    moments = np.array([2 / 3, 1.0, 2.0])
    omega0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / moments
    system = torque_free_system(moments, Q0, omega0)
    h, steps = 0.1, scenario["stress.steps"]
    t = np.linspace(0.0, h * steps, 10001)
    rows = {}
    for method in scenario["stress.methods"]:
        if method in ("dop853", "radau", "rk45"):
            continue                                   # never 1e7 steps of scipy
        sol = integrate(system, t, method, step=h)
        energy = kinetic_energy(moments, sol.omega)
        de = np.abs(energy / energy[0] - 1)
        tenth = t.size // 10
        rows[method] = {"steps": sol.nsteps, "wall_s": sol.wall_s, **invariant_drift(moments, sol.y),
                        "energy_error_first_tenth": float(de[:tenth].max()),
                        "energy_error_last_tenth": float(de[-tenth:].max())}
    split = [r for m, r in rows.items() if m in ("strang", "yoshida4", "suzuki4")]
    passed = bool(split) and all(r["L_norm_rel_drift"] < L_ROUNDING and
                                 r["energy_error_last_tenth"] < 2 * r["energy_error_first_tenth"] for r in split)
    comparison = {"steps": steps, "L_norm_rel_drift_max_splitting": max(r["L_norm_rel_drift"] for r in split),
                  "passed": passed}
    return comparison, {"methods": rows}, system, t


def build(scenario):
    """For ``spinorbit bench``: the case's torque-free system (flip: closed-form period reference)."""
    from ..theory import FreeRigidBody

    moments, omega0 = scenario["body.moments"], scenario["body.omega0"]
    system = torque_free_system(moments, Q0, omega0)
    t = scenario.output_times()
    q_exact = FreeRigidBody(moments, omega0, Q0).attitude(t - scenario.t_start)
    return system, t, lambda solution: float(quat_angle(solution.quaternion, q_exact).max())


def run(scenario):
    case = scenario["stress.case"]
    for method in scenario["stress.methods"]:
        if not isinstance(method, str):
            raise ScenarioError("stress.methods", method, "method names, e.g. ['rk8', 'strang']")
    comparison, details, system, t = {"flip": flip, "degenerate": degenerate, "shapes": shapes,
                                      "long_run": long_run}[case](scenario)
    comparison = {"checks": CHECKS[case], **comparison}
    summary = {"comparison": comparison, "details": details, "run": {"method": ",".join(scenario["stress.methods"])}}
    return common.result(scenario, None, summary, {}, None)
