"""analysis.ladder.work_precision: rows of cost and error, failures as rows, the stopping rule."""
import numpy as np

from spinorbit.analysis.ladder import work_precision
from spinorbit.analysis.theory import FreeRigidBody
from spinorbit.base.rotations import quat_angle
from spinorbit.models.assemblies.idealised import free_body

MOMENTS, OMEGA0, Q0 = np.array([0.3, 0.35, 0.4]), np.array([0.1, 1.5, 0.1]), np.array([1.0, 0.0, 0.0, 0.0])


def test_rows_show_rk4_fourth_order_against_euler_closed_form_and_failures_as_rows():
    """Torque-free body (§808): rk4's error falls by 2^4 per halved step; max_steps = 1 fails as a row."""
    system = free_body(MOMENTS, Q0, OMEGA0)
    t = np.linspace(0.0, 20.0, 11)
    exact = FreeRigidBody(MOMENTS, OMEGA0, Q0).attitude(t)

    def error(solution):
        return {"attitude_error_rad": float(quat_angle(solution.quaternion, exact).max())}

    settings = [("rk4", {"step": 0.1}), ("rk4", {"step": 0.05}), ("rk8", {"step": 0.1, "max_steps": 1}),
                ("rk8", {"step": 0.5}), ("rk8", {"step": 0.25})]
    rows = work_precision(system, t, settings, error, until=lambda row: row.get("attitude_error_rad", 1) < 1e-8)
    coarse, fine, failed, stop = rows
    assert len(rows) == 4                                       # stopped at the first row below 1e-8: rk8, h = 0.5
    assert 13 < coarse["attitude_error_rad"] / fine["attitude_error_rad"] < 19     # 2^4, asymptotic regime
    assert fine["steps"] == 400 and fine["rhs_evaluations"] == 4 * 400 and fine["step"] == 0.05
    assert failed["method"] == "rk8" and "max_steps" in failed["failed"] and "attitude_error_rad" not in failed
    assert stop["step"] == 0.5 and stop["attitude_error_rad"] < 1e-8 and stop["wall_s"] >= 0
