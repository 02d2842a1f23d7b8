"""Hyperion's Lyapunov exponents measured (scenes/stress_hyperion): the regular orbit, the nominal start's
ensembles over two run lengths and two integrators, the 3-D body, and the map of the planar exponent over
initial (theta - f, theta'/n) at periapsis."""
import math

import numpy as np

from ..analysis.lyapunov import ensemble_mean
from ..analysis.planar_spin_orbit import kepler_orbit, planar_lyapunov, planar_vs_rigid_body, rigid_body_lyapunov
from ..models.planar import planar_params
from ..scene.declaration import Outcome

# The metrics the verdict judges (the summary's comparison keys)
LYAPUNOV_REGULAR_PER_T, PASSED = "lyapunov_regular_per_T", "passed"
ENSEMBLE_PAIRS = ("rk8_T_vs_rk8_2T", "rk8_T_vs_dop853_T")       # the ensemble means compared: run length, method


def nominal_sigmas(pair):
    """The summary's key of the ensemble means' difference of ``pair`` (one of ENSEMBLE_PAIRS), in their
    standard errors."""
    return f"lyapunov_nominal_{pair}_sigmas"


def lyapunov_map(p, planar, period):
    """(theta grid, rate/n grid, exponent (n_rate, n_theta) in 1/T) at periapsis after map.orbits periods."""
    n_theta, n_rate = (int(v) for v in p.map.grid)
    theta = (np.arange(n_theta) + 0.5) * math.pi / n_theta
    lo, hi = p.map.rate_range
    rate = lo + (np.arange(n_rate) + 0.5) * (hi - lo) / n_rate
    th, rt = np.meshgrid(theta, rate)
    running = planar_lyapunov(planar, th.ravel(), rt.ravel() * planar[0], p.span.start, period,
                              p.map.orbits, p.lyapunov.steps_per_orbit // 2,
                              p.lyapunov.d0)
    return theta, rate, running[-1].reshape(th.shape)


def compare_run(p, run):
    from ..plots.common import plot_series
    from ..plots.lyapunov import plot_lyapunov_map

    moments = p.body.moments
    gamma = (moments[1] - moments[0]) / moments[2]
    gm, a, e = p.orbit.gm, p.orbit.a, p.orbit.e
    t0, n, start = p.span.start, math.sqrt(gm / a**3), p.lyapunov.start
    period, orbit, planar = 2 * math.pi / n, kepler_orbit(gm, a, e, t0), planar_params(n, e, t0, gamma)
    orbits, steps = p.lyapunov.orbits, p.lyapunov.steps_per_orbit
    d0 = p.lyapunov.d0

    planar_error, system = planar_vs_rigid_body(moments, orbit, planar, t0, period, start)
    regular_orbits = p.lyapunov.regular_orbits
    regular = planar_lyapunov(planar_params(n, e, t0, p.lyapunov.regular_gamma), 0.0, n, t0, period,
                              regular_orbits, steps, d0)[:, 0]
    thetas = start[0] + 1e-3 * np.arange(p.lyapunov.ensemble)
    long_run = planar_lyapunov(planar, thetas, start[1] * n, t0, period, 2 * orbits, steps, d0)
    dop853 = planar_lyapunov(planar, thetas, start[1] * n, t0, period, orbits, steps, d0, "dop853")
    tilted = rigid_body_lyapunov(system, period, p.lyapunov.orbits_3d, steps, d0)
    theta, rate, exponent = lyapunov_map(p, planar, period)

    nominal = {"rk8_T": ensemble_mean(long_run[orbits - 1]), "rk8_2T": ensemble_mean(long_run[-1]),
               "dop853_T": ensemble_mean(dop853[-1])}
    sigmas = {f"{a}_vs_{b}": abs(nominal[a][0] - nominal[b][0]) / math.hypot(nominal[a][1], nominal[b][1])
              for a, b in (("rk8_T", "rk8_2T"), ("rk8_T", "dop853_T"))}
    decay = float(regular[-1] / regular[regular_orbits // 2 - 1])     # ln(t)/t: ~0.5 from T to 2T; chaos: ~1
    chaotic_min = p.lyapunov.chaotic_min
    chaotic = exponent > chaotic_min
    comparison = {
        "checks": "maximal Lyapunov exponent (Benettin two-trajectory renormalisation every orbit, 1/T): "
                  "regular orbit below lyapunov.regular_max and decaying; the ensemble mean around the "
                  "nominal Hyperion start positive and equal within lyapunov.max_sigma standard errors over "
                  "T and 2T (rk8) and with dop853; 3-D exponent; planar model vs 3-D body",
        "b_minus_a_over_c": gamma,
        "orbital_period_d": period,
        LYAPUNOV_REGULAR_PER_T: float(regular[-1]),
        "lyapunov_regular_ln_t_over_t_per_T": float(math.log(regular.size) / regular.size),
        "lyapunov_regular_ratio_2T_over_T": decay,
        **{f"lyapunov_nominal_{k}_per_T": v[0] for k, v in nominal.items()},
        **{f"lyapunov_nominal_{k}_stderr_per_T": v[1] for k, v in nominal.items()},
        **{nominal_sigmas(k): v for k, v in sigmas.items()},
        "lyapunov_time_nominal_T": 1 / nominal["rk8_2T"][0],
        "lyapunov_3d_per_T": float(tilted[-1]),
        "lyapunov_3d_half_run_per_T": float(tilted[tilted.size // 2 - 1]),
        "chaotic_fraction_of_map": float(chaotic.mean()),
        "chaotic_fraction_above_half_threshold": float(np.mean(exponent > chaotic_min / 2)),
        "chaotic_fraction_above_twice_threshold": float(np.mean(exponent > 2 * chaotic_min)),
        "map_exponent_median_regular_per_T":
            float(np.median(exponent[~chaotic])) if (~chaotic).any() else math.nan,
        "map_exponent_median_chaotic_per_T":
            float(np.median(exponent[chaotic])) if chaotic.any() else math.nan,
        "planar_vs_3d_theta_max_rad_5_orbits": planar_error,
        PASSED: bool(regular[-1] < p.lyapunov.regular_max and decay < 0.75
                       and min(v[0] for v in nominal.values()) > chaotic_min
                       and max(sigmas.values()) < p.lyapunov.max_sigma and planar_error < 1e-8),
    }
    details = {"map": {"theta_minus_f_rad": theta, "rate_over_n": rate, "exponent_per_T": exponent},
               "method": "Benettin et al. (1980): two trajectories, renormalised to d0 every orbital period"}
    shown = min(regular.size, long_run.shape[0])
    figures = {"lyapunov_map": plot_lyapunov_map(theta, rate, exponent, chaotic_min),
               "lyapunov_running": plot_series(
                   np.arange(1, shown + 1), [regular[:shown], long_run[:shown, 0]], "orbital periods",
                   "running exponent [1/T]", ["regular (small (B-A)/C)", "Hyperion nominal"], logy=True)}
    sections = {"details": details, "run": {"method": "rk8,dop853"}}
    return Outcome(comparison, figures=figures, sections=sections)
