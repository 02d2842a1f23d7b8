"""Stress: Hyperion's chaotic tumbling, its maximal Lyapunov exponent measured, not assumed.

Planar spin-orbit on a Kepler ellipse (e = 0.1, (B - A)/C = 0.26; Wisdom, Peale
& Mignard 1984) and the full 3-D rigid body (Euler ch. 15 §808 + ch. 16 P91).

Method: analysis.lyapunov (Benettin et al. 1980), a reference and a neighbour d0 apart in the scaled phase
space (theta, theta'/n) -- in 3-D (2 q, omega/n) -- renormalised every orbital period T; lambda in 1/T.

The scene checks (a) a regular orbit (small (B - A)/C, synchronous start) whose lambda falls like
ln t/t (halves from T to 2T) below ``lyapunov.regular_max``; (b) the nominal Hyperion start: lambda
clearly positive and the same over two integration lengths (rk8) and with scipy's DOP853; (c) the 3-D
exponent of the same start.  It maps lambda over a grid of initial (theta - f, theta'/n) at periapsis
(PNG) with the chaotic fraction, and checks the planar model against the 3-D body in the plane once.

A finite-time exponent of a chaotic orbit is a random variable: rounding (another machine, library or
integrator) changes the trajectory after a few Lyapunov times, and the estimate with it.  So (b) takes
an ensemble of ``lyapunov.ensemble`` starts 1e-3 rad apart around the nominal one (decorrelated within
~50 periods) and compares ensemble means within ``lyapunov.max_sigma`` of their own standard errors.
"""
import math

import numpy as np

from ...analysis.lyapunov import ensemble_mean
from ...analysis.planar_spin_orbit import (
    kepler_orbit,
    planar_lyapunov,
    planar_vs_rigid_body,
    rigid_body_lyapunov,
)
from ...models.planar import planar_params
from ...scene import Model, Outcome, Scene
from ...schema import DISTANCE, GM, Key
from ...verdict import Check, Verdict
from .. import common
from .maps import lyapunov_map


def verdict(p, comparison):
    """The exponents' agreement between integrators and run lengths, the regular orbit, and all criteria."""
    return Verdict("Benettin exponents, rk8 and dop853", (
        Check("regular exponent", "lyapunov_regular_per_T", p["lyapunov.regular_max"], "/T",
              "a regular orbit's exponent falls like ln t/t (lyapunov.regular_max)"),
        *(Check(f"ensemble means, {pair.replace('_vs_', ' vs ').replace('_', ' ')}",
                f"lyapunov_nominal_{pair}_sigmas", p["lyapunov.max_sigma"], " sigma",
                "two integrators and two run lengths must give one mean exponent, within the ensemble's own "
                "standard errors (lyapunov.max_sigma)") for pair in ("rk8_T_vs_rk8_2T", "rk8_T_vs_dop853_T")),
        Check("all criteria", "passed", source="module docstring: (a)-(d)")))


SCHEMA = {
    "body.moments": Key(unit="", size=3, help="principal moments A < B < C (3-D runs); (B - A)/C for planar"),
    "orbit.gm": Key(**GM, help="GM of Saturn"),
    "orbit.a": Key(**DISTANCE, help="semi-major axis"),
    "orbit.e": Key(unit="", min=0.0, max=0.99, help="eccentricity"),
    "lyapunov.start": Key(unit="", size=2, help="nominal start at periapsis: theta - f (rad), theta'/n"),
    "lyapunov.orbits": Key(type=int, default=1000, help="length of the shorter nominal run, orbital periods"),
    "lyapunov.regular_orbits": Key(type=int, default=2000,
                                   help="length of the regular check run, orbital periods"),
    "lyapunov.orbits_3d": Key(type=int, default=300, help="length of the 3-D run, orbital periods"),
    "lyapunov.steps_per_orbit": Key(type=int, default=128, help="rk8 steps per orbital period"),
    "lyapunov.d0": Key(unit="", default=1e-8, help="separation after each renormalisation"),
    "lyapunov.ensemble": Key(type=int, default=16,
                             help="starts around the nominal one (1e-3 rad apart in theta)"),
    "lyapunov.max_sigma": Key(unit="", default=4.0,
                              help="pass: ensemble means agree within this many standard errors"),
    "lyapunov.regular_gamma": Key(unit="", default=0.01, help="(B - A)/C of the regular check orbit"),
    "lyapunov.regular_max": Key(unit="", default=0.01,
                                help="pass: regular exponent after regular_orbits below this, 1/T"),
    "lyapunov.chaotic_min": Key(unit="", default=0.2,
                                help="chaotic above this, 1/T (map; nominal must exceed it)"),
    "map.grid": Key(unit="", size=2, default=np.array([36.0, 36.0]), help="points in theta - f and theta'/n"),
    "map.rate_range": Key(unit="", size=2, default=np.array([0.0, 3.0]), help="theta'/n range"),
    "map.orbits": Key(type=int, default=200, help="length of each map run, orbital periods"),
}


def build(p, times):
    """No main run: the Lyapunov pairs, ensembles and map are integrations of their own (compare)."""
    return Model(None)


def compare_run(p, run):
    from ... import plots

    moments = p["body.moments"]
    gamma = (moments[1] - moments[0]) / moments[2]
    gm, a, e = p["orbit.gm"], p["orbit.a"], p["orbit.e"]
    t0, n, start = p.t_start, math.sqrt(gm / a**3), p["lyapunov.start"]
    period, orbit, planar = 2 * math.pi / n, kepler_orbit(gm, a, e, t0), planar_params(n, e, t0, gamma)
    orbits, steps = p["lyapunov.orbits"], p["lyapunov.steps_per_orbit"]
    d0 = p["lyapunov.d0"]

    planar_error, system = planar_vs_rigid_body(moments, orbit, planar, t0, period, start)
    regular_orbits = p["lyapunov.regular_orbits"]
    regular = planar_lyapunov(planar_params(n, e, t0, p["lyapunov.regular_gamma"]), 0.0, n, t0, period,
                              regular_orbits, steps, d0)[:, 0]
    thetas = start[0] + 1e-3 * np.arange(p["lyapunov.ensemble"])
    long_run = planar_lyapunov(planar, thetas, start[1] * n, t0, period, 2 * orbits, steps, d0)
    dop853 = planar_lyapunov(planar, thetas, start[1] * n, t0, period, orbits, steps, d0, "dop853")
    tilted = rigid_body_lyapunov(system, period, p["lyapunov.orbits_3d"], steps, d0)
    theta, rate, exponent = lyapunov_map(p, planar, period)

    nominal = {"rk8_T": ensemble_mean(long_run[orbits - 1]), "rk8_2T": ensemble_mean(long_run[-1]),
               "dop853_T": ensemble_mean(dop853[-1])}
    sigmas = {f"{a}_vs_{b}": abs(nominal[a][0] - nominal[b][0]) / math.hypot(nominal[a][1], nominal[b][1])
              for a, b in (("rk8_T", "rk8_2T"), ("rk8_T", "dop853_T"))}
    decay = float(regular[-1] / regular[regular_orbits // 2 - 1])     # ln(t)/t: ~0.5 from T to 2T; chaos: ~1
    chaotic_min = p["lyapunov.chaotic_min"]
    chaotic = exponent > chaotic_min
    comparison = {
        "checks": "maximal Lyapunov exponent (Benettin two-trajectory renormalisation every orbit, 1/T): "
                  "regular orbit below lyapunov.regular_max and decaying; the ensemble mean around the "
                  "nominal Hyperion start positive and equal within lyapunov.max_sigma standard errors over "
                  "T and 2T (rk8) and with dop853; 3-D exponent; planar model vs 3-D body",
        "b_minus_a_over_c": gamma,
        "orbital_period_d": period,
        "lyapunov_regular_per_T": float(regular[-1]),
        "lyapunov_regular_ln_t_over_t_per_T": float(math.log(regular.size) / regular.size),
        "lyapunov_regular_ratio_2T_over_T": decay,
        **{f"lyapunov_nominal_{k}_per_T": v[0] for k, v in nominal.items()},
        **{f"lyapunov_nominal_{k}_stderr_per_T": v[1] for k, v in nominal.items()},
        **{f"lyapunov_nominal_{k}_sigmas": v for k, v in sigmas.items()},
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
        "passed": bool(regular[-1] < p["lyapunov.regular_max"] and decay < 0.75
                       and min(v[0] for v in nominal.values()) > chaotic_min
                       and max(sigmas.values()) < p["lyapunov.max_sigma"] and planar_error < 1e-8),
    }
    details = {"map": {"theta_minus_f_rad": theta, "rate_over_n": rate, "exponent_per_T": exponent},
               "method": "Benettin et al. (1980): two trajectories, renormalised to d0 every orbital period"}
    shown = min(regular.size, long_run.shape[0])
    figures = {"lyapunov_map": plots.plot_lyapunov_map(theta, rate, exponent, chaotic_min),
               "lyapunov_running": common.plot_series(
                   np.arange(1, shown + 1), [regular[:shown], long_run[:shown, 0]], "orbital periods",
                   "running exponent [1/T]", ["regular (small (B-A)/C)", "Hyperion nominal"], logy=True)}
    sections = {"details": details, "run": {"method": "rk8,dop853"}}
    return Outcome(comparison, figures=figures, sections=sections)


SCENE = Scene(SCHEMA, build, compare_run, verdict, time_scales=common.rigid_body_time_scales(SCHEMA))
