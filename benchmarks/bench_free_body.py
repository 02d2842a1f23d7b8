"""Work-precision on the free rigid body (Hairer-Lubich-Wanner case), t <= 1000 d, error vs closed form.

Run: ``python benchmarks/bench_free_body.py``.  I = (2/3, 1, 2) (HLW's (2, 1, 2/3)
in spinorbit's A <= B <= C order), L0 = (sin 1.1, 0, cos 1.1); outputs every
day; error = max attitude error (rad) against spinorbit.analysis.theory.FreeRigidBody
(Jacobi elliptic functions).  Wall times exclude compilation (numba, heyoka).
"""
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).parent))
import models  # noqa: E402

from spinorbit.analysis.ladder import work_precision  # noqa: E402
from spinorbit.analysis.theory import FreeRigidBody  # noqa: E402
from spinorbit.base.rotations import quat_angle  # noqa: E402
from spinorbit.edge.bench import fastest_at  # noqa: E402
from spinorbit.models.assemblies.idealised import free_body  # noqa: E402

MOMENTS = np.array([2 / 3, 1.0, 2.0])
OMEGA0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / MOMENTS
Q0 = np.array([1.0, 0.0, 0.0, 0.0])
T_OUT = np.linspace(0.0, 1000.0, 1001)
LEVELS = (1e-6, 1e-8, 1e-10, 1e-12)


def main():
    q_exact = FreeRigidBody(MOMENTS, OMEGA0, Q0).attitude(T_OUT)
    error = lambda q: float(quat_angle(q / np.linalg.norm(q, axis=1, keepdims=True), q_exact).max())
    system = free_body(MOMENTS, Q0, OMEGA0)
    y0 = system.y0
    ladder = [(method, {"step": h}) for method, steps in [("rk8", [0.5 / 2**k for k in range(6)]),
                                                          ("suzuki4", [0.1 / 2**k for k in range(8)]),
                                                          ("strang", [0.01 / 2**k for k in range(5)])] for h in steps]
    ladder += [("dop853", {"rtol": 10.0**-k, "atol": 10.0**-k * 1e-3}) for k in range(6, 14)]
    rows = [("dop853 + numba rhs" if r["method"] == "dop853" else r["method"],
             f"step={r['step']:.3g}" if "step" in r else f"rtol=1e-{round(-math.log10(r['rtol']))}",
             r["wall_s"], r["rhs_evaluations"], r["error_rad"])
            for r in work_precision(system, T_OUT, ladder, lambda s: {"error_rad": error(s.quaternion)})
            if "failed" not in r]
    for k in range(6, 14):
        rtol = 10.0**-k
        nfev = [0]

        def fun(t, y):
            nfev[0] += 1
            return models.numpy_free_rhs(t, y, MOMENTS)

        start = time.perf_counter()
        sol = solve_ivp(fun, (0, T_OUT[-1]), y0, "DOP853", t_eval=T_OUT, rtol=rtol, atol=rtol * 1e-3)
        rows.append(("scipy DOP853 + NumPy rhs", f"rtol=1e-{k}", time.perf_counter() - start, nfev[0],
                     error(sol.y.T[:, :4])))
    try:
        import heyoka as hy

        for k in range(6, 16, 1):
            ta = hy.taylor_adaptive(models.heyoka_free_equations(MOMENTS), y0, tol=10.0**-k)   # compiles here
            start = time.perf_counter()
            out = ta.propagate_grid(T_OUT)
            rows.append(("heyoka (Taylor)", f"tol=1e-{k}", time.perf_counter() - start, -1, error(out[-1][:, :4])))
    except ImportError:
        pass

    print("| method | setting | wall_s | rhs evaluations | max attitude error [rad] |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]:.3g} | {r[3] if r[3] >= 0 else '-'} | {r[4]:.2e} |")
    table = [{"method": r[0], "wall_s": r[2], "error_rad": r[4]} for r in rows]
    names = list(dict.fromkeys(r[0] for r in rows))
    print("\nFastest run reaching each error level, wall s (ratio = scipy DOP853 + NumPy / this method):\n")
    print("| error <= | " + " | ".join(names) + " |")
    print("|---|" + "---|" * len(names))
    for level in LEVELS:
        best = fastest_at(table, level)
        base = best.get("scipy DOP853 + NumPy rhs")
        cells = [("-" if m not in best else f"{best[m]:.3g}" + (f" (x{base / best[m]:.0f})" if base else ""))
                 for m in names]
        print(f"| {level:.0e} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
