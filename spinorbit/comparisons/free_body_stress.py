"""The torque-free body's stress cases (scenes/stress_free_body): each runs its methods through
analysis.ladder.work_precision and returns (comparison, details)."""
import math

import numpy as np

from ..analysis.invariants import invariant_drift, kinetic_energy
from ..analysis.ladder import settings, work_precision
from ..analysis.theory import FreeRigidBody, axisymmetric_attitude
from ..base.rotations import quat_angle, quat_from_rotation_vector
from ..models.assemblies.idealised import free_body, under_point_masses

Q0 = np.array([1.0, 0.0, 0.0, 0.0])
# |L| after N rounded rotations random-walks by ~ eps sqrt(N): suzuki4, 1e7 steps = 2e8 rotations
# -> 3e-12.
PASSED = "passed"          # the metric the verdict judges: the case's criteria met
L_ROUNDING = 1e-11


def ok(rows):
    return [r for r in rows if "failed" not in r]     # the rows that ran (a failed run fails its case)


def attitude_error(exact):
    return lambda solution: {"attitude_error_max_rad": float(quat_angle(solution.quaternion, exact).max())}


def flip(p):
    moments, omega0 = p.body.moments, p.body.omega0
    period = FreeRigidBody(moments, omega0, Q0).period
    t = np.arange(0.0, (p.stress.flips + 1.5) * period / 2, 0.005)

    def measured(sol):
        wy = sol.omega[:, 1]
        i = np.nonzero(np.sign(wy[:-1]) != np.sign(wy[1:]))[0]
        crossing = t[i] - wy[i] * (t[i + 1] - t[i]) / (wy[i + 1] - wy[i])
        flips = crossing.size - 1
        period_d = float(2 * (crossing[-1] - crossing[0]) / flips)
        return {"flips": int(flips), "period_measured_d": period_d,
                "period_rel_error_vs_closed_form": period_d / period - 1}

    rows = work_precision(free_body(moments, Q0, omega0), t, settings(p.stress.methods, step=5e-3),
                          measured)
    worst = max(abs(r["period_rel_error_vs_closed_form"]) for r in ok(rows))
    passed = (len(ok(rows)) == len(rows) and worst < 1e-3
              and min(r["flips"] for r in rows) >= p.stress.flips)
    comparison = {"period_closed_form_d": period, "period_design_reference_d": 12.335,
                  "period_rel_error_max": worst, PASSED: bool(passed)}
    return comparison, {"methods": {r["method"]: r for r in rows}}


def degenerate(p):
    from ..orbits.analytic import CircularOrbits
    orbit = CircularOrbits(("F",), [1.0], [1.0], [0.7], inclination=[0.4])
    omega0 = np.array([0.3, -0.2, 2.0])
    t = np.linspace(0.0, 100.0, 201)
    sphere = under_point_masses(np.ones(3), orbit, Q0, omega0)
    torque_max = float(np.abs([sphere.torque(ti, sphere.y0, sphere.params) for ti in t]).max())
    cases = (("sphere", sphere, quat_from_rotation_vector(omega0 * t[:, None])),     # uniform rotation
             ("a_eq_b_1e-12", free_body(np.array([1.0, 1.0 + 1e-12, 1.3]), Q0, omega0),
              axisymmetric_attitude(np.array([1.0, 1.0, 1.3]), omega0, Q0, t, 2)))
    rows = {}
    for label, system, exact in cases:
        for r in work_precision(system, t, settings(p.stress.methods, step=0.01),
                                attitude_error(exact)):
            rows[f"{label}/{r['method']}"] = {**r, "finite": "failed" not in r}
    worst = max(r["attitude_error_max_rad"] for r in ok(rows.values()))
    passed = bool(torque_max == 0.0 and worst < 1e-9 and all(r["finite"] for r in rows.values()))
    comparison = {"sphere_torque_max": torque_max, "attitude_error_max_rad": worst, PASSED: passed}
    return comparison, {"methods": rows}


def shapes(p):
    t = np.linspace(0.0, 100.0, 201)
    rows = {}
    for f in p.stress.flattenings:
        for shape, moments, omega0, s in (("oblate", [1 - f, 1 - f, 1.0], [0.3, 0.2, 2.0], 2),
                                          ("prolate", [1 - f, 1.0, 1.0], [2.0, 0.3, 0.2], 0)):
            moments, omega0 = np.array(moments), np.array(omega0)
            exact = axisymmetric_attitude(moments, omega0, Q0, t, s)
            for r in work_precision(free_body(moments, Q0, omega0), t,
                                    settings(p.stress.methods, step=0.01), attitude_error(exact)):
                rows[f"{shape}/{f:g}/{r['method']}"] = r.get("attitude_error_max_rad", math.inf)
    worst = max(rows.values())
    return {"attitude_error_max_rad": worst, PASSED: bool(worst < 1e-9)}, {"attitude_error_max_rad": rows}


def long_run(p):
    moments = np.array([2 / 3, 1.0, 2.0])
    omega0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / moments
    h, steps = 0.1, p.stress.steps
    t = np.linspace(0.0, h * steps, 10001)
    tenth = t.size // 10

    def drift(sol):
        energy = kinetic_energy(moments, sol.omega)
        de = np.abs(energy / energy[0] - 1)
        return {**invariant_drift(moments, sol.quaternion, sol.omega),
                "energy_error_first_tenth": float(de[:tenth].max()),
                "energy_error_last_tenth": float(de[-tenth:].max())}

    # never 1e7 steps of scipy
    fixed_step = [(m, o) for m, o in settings(p.stress.methods, step=h) if o]
    rows = {r["method"]: r for r in work_precision(free_body(moments, Q0, omega0), t, fixed_step, drift)}
    split = [r for m, r in rows.items() if m in ("strang", "yoshida4", "suzuki4")]
    passed = bool(split) and len(ok(split)) == len(split) and all(
        r["L_norm_rel_drift"] < L_ROUNDING
        and r["energy_error_last_tenth"] < 2 * r["energy_error_first_tenth"] for r in split)
    return {"steps": steps, "L_norm_rel_drift_max_splitting": max(r["L_norm_rel_drift"] for r in ok(split)),
            PASSED: passed}, {"methods": rows}
