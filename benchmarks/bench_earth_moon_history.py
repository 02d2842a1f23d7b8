"""The Earth-Moon tidal history (issue 33): what each tidal model gives over the Moon's age, and the cost.

    python benchmarks/bench_earth_moon_history.py numbers   # per model: today's rates, the Moon's age, the
                                                            # angular momentum, every proxy's residual
    python benchmarks/bench_earth_moon_history.py cost      # the scene end to end: first (empty numba and
                                                            # kernel caches) and warm, the five models
    python benchmarks/bench_earth_moon_history.py resonances  # the default ocean's resonance crossings

Each prints Markdown for benchmarks/results_earth_moon_history.md.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
SCENE = ROOT / "scenarios" / "earth_moon_history.toml"


def numbers():
    from dataclasses import replace

    from spinorbit import load_scenario, run_scenario
    from spinorbit.models.tidal_history.tides import TIDES
    from spinorbit.references.lunar_proxies import PROXIES

    print("| tidal model | fitted parameter | recession today cm/yr | LOD rate today ms/cy | de/dt today /Gyr "
          "| Moon's age (where it stops) Gyr | max abs(dL/L) over the history | obliquity rate today mas/cy "
          "| integration error (a, rel) |\n|---|---|---|---|---|---|---|---|---|")
    residuals = {}
    scenario = load_scenario(str(SCENE))
    p = scenario.params
    for model in TIDES:
        alone = replace(p, tides=replace(p.tides, model=model), compare=replace(p.compare, models=False))
        summary = run_scenario(scenario.with_params(alone)).summary
        c, m, run = summary["comparison"], summary["model"], summary["run"]
        c = {**c, "moon_age_gyr": c["moon_age_gyr"] if c["moon_age_gyr"] is not None else float("nan")}
        if "ocean_depth_km" in m:
            fitted = (f"depth {m['ocean_depth_km']:.4f} km, drag {m['ocean_drag_per_s']:.4g}/s (solid k2/Q "
                      f"{m['solid_k2_over_q']:.5f})")
        elif "k2_time_lag_s" in m:
            fitted = f"k2 dt = {m['k2_time_lag_s']:.1f} s (dt = {m['time_lag_s_for_k2_0.30']:.0f} s at k2 = 0.30)"
        else:
            fitted = f"k2/Q = {m['k2_over_q']:.5f} (Q = {m['q_for_k2_0.30']:.1f} at k2 = 0.30)"
        print(f"| {model} | {fitted} | {c['recession_rate_today_cm_per_yr']:.4f} | "
              f"{c['length_of_day_rate_today_ms_per_cy']:.3f} | {c['eccentricity_rate_today_per_gyr']:.4f} | "
              f"{c['moon_age_gyr']:.4f} | {c['angular_momentum_relative_error_max']:.2g} | "
              f"{c['obliquity_rate_today_mas_per_cy']:.2f} | "
              f"{run['integration_error_moon_semi_major_axis_rel']:.2g} |")
        print(f"|  | stop: {summary['stop']['reason']} |" + " |" * 7)
        residuals[model] = c
    print("\n| proxy | age Gyr | value | " + " | ".join(f"{m} residual (sigma)" for m in residuals)
          + " |\n|---|---|---|" + "---|" * len(residuals))
    for p in PROXIES:
        cells = []
        for c in residuals.values():
            value, sigma = c.get(f"{p.name}_residual_{p.unit}"), c.get(f"{p.name}_residual_sigma")
            cells.append("history stopped before" if value is None else
                         f"{value:+.4g} ({'no sigma' if sigma is None else f'{sigma:+.1f}'})")
        print(f"| {p.name} | {p.age_gyr} | {p.value:g} | " + " | ".join(cells) + " |")


def resonances():
    from spinorbit import run_scenario

    summary = run_scenario(str(SCENE), ["compare.models=false"]).summary
    print("| resonance (the distance's fast step) age Gyr | full width at half prominence Myr | recession rate "
          "there cm/yr |\n|---|---|---|")
    for step in summary["resonances"]:
        print(f"| {step['age_gyr']:.3f} | {step['width_myr']:.0f} | {step['recession_rate_cm_per_yr']:.2f} |")


def cost():
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        env = {**os.environ, "NUMBA_CACHE_DIR": str(Path(cache) / "numba"),
               "SPINORBIT_CACHE_DIR": str(Path(cache) / "spinorbit"), "SPINORBIT_QUIET": "1"}
        print("| run | wall s (whole command) | the main history's integration s |\n|---|---|---|")
        for label in ("first (empty caches)", "warm"):
            started = time.perf_counter()
            subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "run", str(SCENE), "--out",
                            str(Path(out) / "run"), "--force"], check=True, env=env, cwd=ROOT,
                           stdout=subprocess.DEVNULL)
            wall = time.perf_counter() - started
            summary = json.loads((Path(out) / "run" / "summary.json").read_text())
            print(f"| {label} | {wall:.1f} | {summary['run']['wall_s']:.3f} |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("numbers", "cost", "resonances"))
    {"numbers": numbers, "cost": cost, "resonances": resonances}[parser.parse_args().what]()
