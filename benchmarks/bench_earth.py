"""Error against run time for the Earth's precession-nutation: gyroscopic and full models.

    python benchmarks/bench_earth.py            # writes benchmarks/earth_error_vs_time.{csv,png}

Compiled rk8 (one core) at several steps, the structure-preserving splittings
(full model only: a rigid body under an external torque; symmetric-exact free
flow, geodesic precession as an exact frame rotation), and scipy solve_ivp DOP853
with a NumPy right-hand side at several tolerances; error = max |figure axis - a
converged run| in mas; wall time excludes compilation and is scaled to a
simulated century.  DE421 Moon + Sun (quintic Hermite, 0.25 d), geodesic
precession and J2 rate on.  Prints the rows and, per model, the fastest run of
each method reaching each error level with scipy + NumPy's time over it.
"""
import csv
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from spinorbit.base.constants import MAS
from spinorbit.bodies.earth import ERA_RATE_RAD_D
from spinorbit.edge.bench import fastest_at
from spinorbit.integrators import simulate
from spinorbit.models.assemblies.earth import rigid_earth
from spinorbit.models.start import on_pole
from spinorbit.orbits.sources import sample_orbits
from spinorbit.references import erfa_pole

OUT = Path(__file__).parent
T0 = 0.0                                   # J2000
SPANS = {"gyroscopic": 36525.0, "full": 3652.5}
SPLITTINGS = {"strang": [0.5, 0.25, 0.125, 0.0625, 0.03125], "yoshida4": [0.5, 0.25, 0.125, 0.0625, 0.03125],
              "suzuki4": [0.5, 0.25, 0.125, 0.0625, 0.03125]}
LEVELS_MAS = (200.0, 2.0, 0.02, 2e-4)          # ~1e-6, 1e-8, 1e-10, 1e-12 rad


def setup(model, span):
    """The rigid Earth System (``model``), started on the IAU pole at T0, and its orbits."""
    orbits = sample_orbits("de421", "earth", ("moon", "sun"), T0 - 1, T0 + span + 1, 0.25, measure=False)
    system = rigid_earth(orbits, model, ecliptic_pole=erfa_pole.ecliptic_pole_j2000(), t0=T0)
    z0 = erfa_pole.cip_vector(T0)
    system.y0 = system.layout.pack(on_pole(system, "earth", T0, z0, ERA_RATE_RAD_D, erfa_pole.terrestrial_x_axis(T0)))
    return system, orbits


def numpy_rhs(model, system, orbits):
    """The same right-hand sides in plain NumPy (positions from the interpolant, one call per evaluation)."""
    figure, gm = system.bodies["earth"].figure, np.asarray(orbits.gm)
    moments, k = figure.moments, figure.anisotropy_rate_per_d
    c_minus_a, frame_rate = moments[2] - moments[0], system.interactions[-1].rate_rad_d

    def tensor(t):
        r = orbits.positions(np.array([t]))[0]
        s = np.linalg.norm(r, axis=1)
        return np.einsum("i,ij,ik->jk", 3 * gm / s**5, r, r) * (1 + k * t)

    def quat_matrix(q):
        w, x, y, z = q
        return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])

    def quat_rate(q, w_inertial):
        w, x, y, z = q
        a, b, c = w_inertial
        return 0.5 * np.array([-a * x - b * y - c * z, a * w + b * z - c * y,
                               b * w + c * x - a * z, c * w + a * y - b * x])

    if model == "gyroscopic":
        def rhs(t, spin):
            norm = np.linalg.norm(spin)
            ell, lam = spin / norm, norm / moments[0]
            t_0 = tensor(t)
            z = ell - np.cross(ell, c_minus_a * np.cross(t_0 @ ell, ell) / (norm * lam))    # Oppolzer, first order
            z /= np.linalg.norm(z)
            return c_minus_a * np.cross(t_0 @ z, z) + np.cross(frame_rate, spin)
    else:
        def rhs(t, y):
            rot = quat_matrix(y[:4])
            omega = y[4:7]
            torque_inertial = c_minus_a * np.cross(tensor(t) @ rot[:, 2], rot[:, 2])   # axisymmetric
            torque = rot.T @ torque_inertial
            omega_dot = (torque - np.cross(omega, moments * omega)) / moments
            return np.concatenate([quat_rate(y[:4], rot @ omega + frame_rate), omega_dot])
    return rhs


def main():
    rows = []
    for model, steps, tolerances in (("gyroscopic", [16.0, 8.0, 4.0, 2.0, 1.0], [1e-7, 1e-8, 1e-10, 1e-12]),
                                     ("full", [0.4, 0.2, 0.1, 0.05], [1e-9, 1e-11, 1e-13])):
        span = SPANS[model]
        system, orbits = setup(model, span)
        t = T0 + np.arange(0.0, span + 1e-9, 8.0)
        converged, _ = simulate(system, t, "rk8", {"step": steps[-1] / 4}, estimate_error=False)
        reference = system.figure_axes("earth", t, converged.y)
        scale = 36525.0 / span
        runs = [("rk8", "rk8 (numba)", step) for step in steps]
        if model == "full":
            runs += [(name, f"{name} (numba)", step) for name, hs in SPLITTINGS.items() for step in hs]
        for method, label, step in runs:
            sol = simulate(system, t, method, {"step": step}, estimate_error=False)[0]
            err = np.linalg.norm(system.figure_axes("earth", t, sol.y) - reference, axis=1).max() / MAS
            rows.append({"model": model, "method": label, "setting": f"step {step} d",
                         "wall_s_per_century": sol.wall_s * scale, "error_mas": err})
            print(rows[-1])
        # scipy DOP853 + NumPy rhs over a tenth of the span (it is slow), error on that part.
        short = t[t <= T0 + span / 10]
        rhs = numpy_rhs(model, system, orbits)
        for rtol in tolerances:
            start = time.perf_counter()
            sol = solve_ivp(rhs, (T0, short[-1]), system.y0, method="DOP853", t_eval=short, rtol=rtol, atol=rtol * 1e-3)
            wall = time.perf_counter() - start
            y = system.layout.normalise(sol.y.T)
            err = np.linalg.norm(system.figure_axes("earth", short, y) - reference[:len(short)], axis=1).max() / MAS
            rows.append({"model": model, "method": "scipy DOP853 + NumPy rhs", "setting": f"rtol {rtol:g}",
                         "wall_s_per_century": wall * scale * 10, "error_mas": err})
            print(rows[-1])
    with open(OUT / "earth_error_vs_time.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    plot(rows)
    print()
    print(tables(rows))


def tables(rows):
    """Markdown: every run, then the fastest run per method reaching each error level (ratio = scipy / it)."""
    lines = ["| model | method | setting | s / century | error mas |", "|---|---|---|---|---|"]
    lines += [f"| {r['model']} | {r['method']} | {r['setting']} | {r['wall_s_per_century']:.3g} | "
              f"{r['error_mas']:.2g} |" for r in rows]
    for model in SPANS:
        sel = [r for r in rows if r["model"] == model]
        names = list(dict.fromkeys(r["method"] for r in sel))
        lines += ["", f"{model}: fastest s / century reaching each error (x = scipy DOP853 + NumPy rhs / it)", "",
                  "| error <= | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
        for level in LEVELS_MAS:
            best = fastest_at(sel, level, error="error_mas", wall="wall_s_per_century")
            base = best.get("scipy DOP853 + NumPy rhs")
            cells = ["-" if m not in best else f"{best[m]:.3g}" + (f" (x{base / best[m]:.0f})" if base else "")
                     for m in names]
            lines.append(f"| {level:g} mas ({level * MAS:.0e} rad) | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plot(rows):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for model in ("gyroscopic", "full"):
        for method in dict.fromkeys(r["method"] for r in rows if r["model"] == model):
            pts = [(r["wall_s_per_century"], max(r["error_mas"], 1e-7)) for r in rows
                   if r["model"] == model and r["method"] == method]
            splitting = model == "full" and "rk8" not in method
            marker = "s--" if method.startswith("scipy") else ("^-" if splitting else "o-")
            ax.loglog(*zip(*pts), marker, label=f"{model}, {method}")
    ax.set_xlabel("wall time per simulated century [s] (one core)")
    ax.set_ylabel("max figure-axis error [mas]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "earth_error_vs_time.png", dpi=110)


if __name__ == "__main__":
    main()
