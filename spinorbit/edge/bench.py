"""Work-precision of the integrators on one scene: ``spinorbit bench SCENE.toml``.

A scene that can be benchmarked declares ``bench`` (spinorbit.scene.declaration.Scene): on the model its ``build``
makes for the output times, ``error(solution)``, the maximum attitude error in rad against the scene's
closed form or a converged run (:func:`spinorbit.analysis.ladder.converged_error`).

Every registered method that ``supports`` the system is run on a ladder of
settings: fixed-step and splitting methods at steps halving from a quarter of
the shortest time scale (capped at the output spacing for methods that land on
every output; rk8 is not, it interpolates with its continuous extension),
adaptive methods at rtol = 1e-3 ... 1e-13 (atol = rtol/1000), the Taylor integrator at tolerance = 1e-6 ...
1e-17.  The rows come from
:func:`spinorbit.analysis.ladder.work_precision`; a method's ladder stops when a run takes longer
than ``budget_s`` or reaches the rounding floor (a setting too coarse to finish is left out).
Wall times exclude one-off compilation (each integrator warms up first).
"""
import csv
import math
import shlex
import sys
from pathlib import Path

import numpy as np

from ..analysis.ladder import cheapest, work_precision
from ..base.errors import ScenarioError
from ..integrators import METHODS, get_method

COLUMNS = ("method", "kind", "order", "setting", "wall_s", "rhs_evaluations", "steps", "error_rad")
LEVELS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
MAX_BUDGET_S = 3600.0           # --budget: the longest run a method's ladder may take


def time_scale(system):
    """Shortest time scale of the motion (time units): ``system.meta["time_scale"]`` where the
    scene gives one (e.g. a gyroscopic model, whose state holds no spin), else 2 pi / |omega0|."""
    if "time_scale" in system.meta:
        return float(system.meta["time_scale"])
    omega = [part.index for part in system.layout.slices if part.name.endswith(".omega")]
    rate = float(np.linalg.norm(system.y0[omega[0]])) if omega else 0.0
    return 2 * math.pi / rate if rate > 0 else 1.0


def ladder(cls, system, t_out):
    """Settings for one method, coarse to fine, as its class declares them (Integrator.ladder) for the motion's
    time scale and the output spacing."""
    spacing = np.diff(t_out)
    return cls.ladder(time_scale(system), float(np.median(spacing)) if spacing.size else None)


def run_method(name, system, t_out, error, budget_s=10.0, floor=1e-14):
    """Rows of the work-precision table for one method (a setting too coarse to finish is left out)."""
    cls = get_method(name)
    settings = ladder(cls, system, t_out)
    previous = [math.inf]

    def enough(row):
        if "failed" in row:
            return False                  # too coarse to finish: try the next, finer setting
        err = row["error_rad"]
        done = row["wall_s"] > budget_s or err < floor or (err > 0.5 * previous[0] and err < 1e-10)
        previous[0] = err
        return done

    rows = work_precision(system, t_out, [(cls, s) for s in settings],
                          lambda solution: {"error_rad": error(solution)}, until=enough)
    return [{"method": cls.name, "kind": cls.kind, "order": cls.order,
             "setting": ", ".join(f"{k}={v:.3g}" for k, v in setting.items()),
             **{k: row[k] for k in COLUMNS[4:]}}
            for setting, row in zip(settings, rows) if "failed" not in row]


def bench_system(system, t_out, error, methods=None, budget_s=10.0, rows=None):
    """Work-precision rows for every requested (default: every suitable) method, appended to ``rows`` (a new
    list by default) as each method finishes, so that an interrupted bench still has the finished ones."""
    names = methods or [m for m in METHODS if get_method(m)().supports(system)]
    for name in names:
        if name not in METHODS:
            raise ScenarioError("--methods", name, f"method names, of {sorted(METHODS)}")
    rows = [] if rows is None else rows
    for name in names:
        rows.extend(run_method(name, system, t_out, error, budget_s))
    return rows


def fastest_at(rows, level, error="error_rad", wall="wall_s"):
    """{method: least ``wall`` over rows whose ``error`` is <= level}."""
    best = {m: cheapest([r for r in rows if r["method"] == m], error, level, wall)
            for m in {r["method"] for r in rows}}
    return {m: row[wall] for m, row in best.items() if row is not None}


def markdown(rows, title, command, note=""):
    lines = [f"# Work-precision: {title}", "", f"Command: `{command}`. Wall times exclude compilation; "
             "error = max attitude error over the outputs, rad." + (f" {note}" if note else ""), "",
             "| method | order | setting | wall_s | rhs evaluations | error [rad] |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['method']} | {r['order'] or '-'} | {r['setting']} | {r['wall_s']:.3g} | "
                     f"{r['rhs_evaluations']} | {r['error_rad']:.2e} |")
    lines += ["", "Fastest run reaching each error level (wall s):", "",
              "| error <= | " + " | ".join(sorted({r["method"] for r in rows})) + " |",
              "|---|" + "---|" * len({r["method"] for r in rows})]
    for level in LEVELS:
        best = fastest_at(rows, level)
        cells = [f"{best[m]:.3g}" if m in best else "-" for m in sorted({r["method"] for r in rows})]
        lines.append(f"| {level:.0e} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(rows, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for name in dict.fromkeys(r["method"] for r in rows):
        pts = [(r["wall_s"], max(r["error_rad"], 1e-17)) for r in rows if r["method"] == name]
        ax.loglog(*zip(*pts), "o-", ms=3, label=name)
    ax.set_xlabel("wall time [s] (compilation excluded)")
    ax.set_ylabel("max attitude error [rad]")
    ax.set_title(title)
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write(rows, out, title, command, note=""):
    """work_precision.csv, .md and .png in ``out``; returns the paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "work_precision.csv", out / "work_precision.md", out / "work_precision.png"]
    with open(paths[0], "w", newline="") as f:
        writer = csv.DictWriter(f, COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    paths[1].write_text(markdown(rows, title, command, note))
    plot(rows, paths[2], title)
    return paths


def bench_scenario(path, methods=None, out=None, budget_s=10.0, overrides=(), force=False):
    """Load a scenario, build its system and write the work-precision table into the run directory ``out``
    (spinorbit.edge.rundir: a previous table replaced whole, files spinorbit did not write refused unless
    ``force``); returns (rows, paths)."""
    from ..scene.declaration import scenario_errors
    from .rundir import RunDirectory
    from .scenarios import load_scenario

    if not isinstance(budget_s, (int, float)) or not 0 < budget_s <= MAX_BUDGET_S:
        raise ScenarioError("--budget", budget_s, f"seconds in (0, {MAX_BUDGET_S:g}]")
    scenario = load_scenario(path, overrides)
    if scenario.scene.bench is None:
        raise ScenarioError("scene.kind", scenario.kind, "a scene kind that declares how to bench it "
                            f"(bench: {', '.join(bench_kinds())})")
    target = Path(out or Path("runs") / f"{scenario.name}-bench")
    with RunDirectory(target, force=force) as run_dir:     # refuses a bad --out before the ladder runs
        with scenario_errors(scenario):
            t_out = scenario.output_times()
            model = scenario.scene.build(scenario.params, t_out)
            system = model.system if model.system is not None else model.bench_system
            error = scenario.scene.bench(scenario.params, model, t_out)
        command = " ".join(["spinorbit bench", str(path), *(f"--set {shlex.quote(o)}" for o in overrides),
                            *([f"--methods {','.join(methods)}"] if methods else [])])
        title = scenario.params.scene.title or scenario.name
        agreement = system.meta.get("reference_agreement_rad")
        note = "" if agreement is None else (f"Reference: a converged run (agrees with one at half its step "
                                             f"to {agreement:.1e} rad).")
        rows, names = [], []
        try:
            bench_system(system, t_out, error, methods, budget_s, rows)
        except KeyboardInterrupt:                      # Ctrl-C or SIGTERM: keep the methods that finished
            if rows:
                where = run_dir.fail(lambda d: write(rows, d, f"{title} (interrupted)", command, note))
                print(f"the methods that finished are written to {where}/", file=sys.stderr)
            raise
        run_dir.commit(lambda d: names.extend(p.name for p in write(rows, d, title, command, note)))
    return rows, [run_dir.out / name for name in names]


def bench_kinds():
    """The scene kinds ``spinorbit bench`` takes: their Scene declares ``bench``."""
    from ..scenes import SCENES, scene_of

    return sorted(kind for kind in SCENES if scene_of(kind).bench is not None)
