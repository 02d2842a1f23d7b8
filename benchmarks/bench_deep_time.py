"""Deep time (issue 24): what the orbit's and the spin's pieces do, their cost, and the chaos, measured.

    python benchmarks/bench_deep_time.py moon      # the Moon as a body (IAS15) against the EMB's quadrupole
    python benchmarks/bench_deep_time.py factors   # each piece's part in the 1-Myr distance from La2004
    python benchmarks/bench_deep_time.py ladder    # error against run time: the N-body's and the spin's steps
    python benchmarks/bench_deep_time.py cost      # 1 Myr end to end, first (empty cache) and cached
    python benchmarks/bench_deep_time.py chaos [--myr 20]   # two solutions 1e-10 apart: their divergence
    python benchmarks/bench_deep_time.py mars [--myr 1]     # Mars against La2004 Mars: the rate, the tides
    python benchmarks/bench_deep_time.py mars_band --sweep runs/mars_sweep   # a Mars sweep's divergence
    python benchmarks/bench_deep_time.py mars_asteroids      # Mars on an orbit with Ceres, Vesta, Pallas
    python benchmarks/bench_deep_time.py mars_no_asteroids   # the same start and integration, without them

Each prints Markdown for benchmarks/results_deep_time.md.  The N-body runs take minutes of CPU: run them with
``nice -n 10``; solutions go to spinorbit's cache (``SPINORBIT_CACHE_DIR``) and are reused.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
KYR_D = 365250.0
ARCSEC = math.pi / 648000


def moon(years=3000.0, every_d=1460.0):
    """The EMB's perihelion drift with the Moon as a body (IAS15, Earth and Moon from DE421, the Sun's GR;
    with and without the Earth's J2) against WHFast with the EMB a point mass, the static ring, the ring."""
    from spinorbit.bodies import moon as luna
    from spinorbit.orbits import solution

    t = -np.arange(0.0, years * 365.25 + 1, every_d)
    print(f"EMB perihelion drift against the Moon as a body over {years:g} yr\n\n| Moon on the EMB | "
          "Earth's J2 on the Moon | drift ″/kyr | share of the body's effect |\n|---|---|---|---|")
    for j2 in (False, True):
        started = time.perf_counter()
        body = _moon_as_body(t, j2)
        wall = time.perf_counter() - started
        drifts = {}
        for kind in ("none", "static_ring", "ring"):
            orbit = solution.solve(solution.Settings(output_d=every_d, moon=kind), t[-1], 0.0)
            index = np.searchsorted(orbit.t_d, t)
            n, ev = orbit.normal[index], orbit.eccentricity_vector[index]
            angle = np.arctan2(np.sum(np.cross(body[1], ev) * n, axis=1), np.sum(body[1] * ev, axis=1))
            drifts[kind] = np.polyfit(-t / KYR_D, angle / ARCSEC, 1)[0]
        for kind, drift in drifts.items():
            share = (drifts["none"] - drift) / drifts["none"]
            print(f"| {kind} | {'yes' if j2 else 'no'} | {drift:+.2f} | {share:.3f} |")
        print(f"| (IAS15: {wall:.0f} s) | | | |")
    ratio = _static_average() / luna.MEAN_DISTANCE_KM**2 / solution.lunar_ring_j2()
    print(f"\nDE421's Moon 1901-2049, nu <rho^2 P2(cos gamma)> seen from the Sun: {ratio:.4f} of the static "
          "ring")


def _static_average():
    """2 nu <rho^2 P2(cos gamma)> over DE421's Moon (rho) and Sun (gamma: the angle between them), km^2."""
    from spinorbit.orbits import solution
    from spinorbit.orbits.kernel import JPLKernel

    k = JPLKernel()
    t = np.arange(-36000.0, 18000.0, 0.0625)
    rho = k.relative_states("moon", "earth", t)[0]
    sun = k.relative_states("sun", "earth_moon_barycenter", t)[0]
    cos = np.sum(rho * sun, axis=1) / np.linalg.norm(rho, axis=1) / np.linalg.norm(sun, axis=1)
    gm_e, gm_m = solution.gm_km3_d2("earth"), solution.gm_km3_d2("moon")
    return 2 * gm_e * gm_m / (gm_e + gm_m) ** 2 * np.mean(np.sum(rho**2, axis=1) * (1.5 * cos**2 - 0.5))


def _moon_as_body(t, earth_j2):
    """(normals, eccentricity vectors) of the EMB's heliocentric orbit at times t from IAS15 with the Moon."""
    import rebound
    import reboundx

    from spinorbit.bodies.de421_header import header
    from spinorbit.bodies.table import gm_km3_d2
    from spinorbit.orbits.kernel import JPLKernel

    names = ("sun", "mercury", "venus", "earth", "moon", "mars", "jupiter", "saturn", "uranus", "neptune",
             "pluto")
    k = JPLKernel()
    sim = rebound.Simulation()
    sim.G = 1.0
    for name in names:
        p, v = k.relative_states(name, "solar_system_barycenter", [0.0])
        sim.add(m=gm_km3_d2(name), x=p[0, 0], y=p[0, 1], z=p[0, 2], vx=v[0, 0], vy=v[0, 1], vz=v[0, 2])
    sim.integrator = "ias15"
    extras = reboundx.Extras(sim)
    gr = extras.load_force("gr_potential")
    extras.add_force(gr)
    gr.params["c"] = header()["CLIGHT"] * 86400.0
    if earth_j2:
        harmonics = extras.load_force("gravitational_harmonics")
        extras.add_force(harmonics)
        sim.particles[3].params["J2"], sim.particles[3].params["R_eq"] = header()["J2E"], header()["RE"]
    normals, eccentricity = [], []
    for time_d in t:
        sim.integrate(time_d, exact_finish_time=1)
        sun, earth, luna = (sim.particles[i] for i in (0, 3, 4))
        w = np.array([earth.m, luna.m]) / (earth.m + luna.m)
        state = [w[0] * getattr(earth, c) + w[1] * getattr(luna, c) - getattr(sun, c)
                 for c in ("x", "y", "z", "vx", "vy", "vz")]
        r, v = np.array(state[:3]), np.array(state[3:])
        h = np.cross(r, v)
        normals.append(h / np.linalg.norm(h))
        eccentricity.append(np.cross(v, h) / (sun.m + earth.m + luna.m) - r / np.linalg.norm(r))
    return np.array(normals), np.array(eccentricity)


FACTORS = [("nominal: ring, GR, tidal tilt, IAU 2006 rate", []),
           ("no tidal tilt", ["model.tidal_tilt=false"]),
           ("precession constant from IAU 2006's H_d", ['model.precession="iau2006_hd"']),
           ("Td = 0 (no tides)", ["model.Td=0"]),
           ("Moon: static ring", ['orbit.moon="static_ring"']),
           ("Moon: none (the EMB a point mass)", ['orbit.moon="none"']),
           ("no GR", ["orbit.relativity=false"])]


def factors():
    """The scene over 1 Myr with each piece changed, against La2004 (La93's spreads beside it)."""
    from spinorbit import run_scenario

    print("| 0 to -1 Myr | obliquity max ° | e e^(iϖ̄) max | e max | ϖ̄ at -1 Myr ° |\n|---|---|---|---|---|")
    names = ("obliquity_max_deg", "climatic_precession_vector_max", "eccentricity_max",
             "perihelion_longitude_end_deg")
    formats = ("{:.4f}", "{:.1e}", "{:.1e}", "{:+.2f}")

    def row(label, c, prefix):
        cells = [f.format(c[f"{prefix}_{n}_1myr"]) for n, f in zip(names, formats)]
        print(f"| {label} | {' | '.join(cells)} |")

    for label, overrides in FACTORS:
        c = run_scenario(ROOT / "scenarios/earth_deep_time.toml", overrides).summary["comparison"]
        row(label, c, "la2004")
    row("La93 with tides - without (Laskar et al. 1993)", c, "la93_tides")
    row("La2004 - La93 with tides", c, "la2004_minus_la93")


def ladder(span_kyr=200.0):
    """Error against run time: WHFast steps against a 1-d run over ``span_kyr``, and RK8 steps of the spin
    against a 10-yr run over 1 Myr (both on the nominal model)."""
    from spinorbit.comparisons import earth_deep_time_table as table
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.integrators import simulate
    from spinorbit.orbits import solution
    from spinorbit.starts import earth_deep_time as deep_time_model

    nominal = load_scenario("earth_deep_time").params      # IAU 2006's rate, the tidal tilt, Td = Ed = 1, the ring

    def spin(orbit, t, step):
        p = replace(nominal, orbit=replace(nominal.orbit, output=orbit.t_d[1] - orbit.t_d[0]))
        model = deep_time_model.spin_model(p, orbit)
        solution_, point = simulate(model.system, t, "rk8", {"step": step}, estimate_error=False)
        return table.quantities(t, solution_.y, model), point["wall_s"]

    t = -np.arange(0.0, span_kyr * KYR_D + 1, KYR_D)
    print(f"WHFast step against 1 d, over {span_kyr:g} kyr (the spin run at 100 yr on each)\n\n"
          "| step d | N-body s/Myr | e vector max | obliquity max ″ | e e^(iϖ̄) max |\n|---|---|---|---|---|")
    runs = {}
    with tempfile.TemporaryDirectory() as folder:
        for step in (1.0, 2.5, 5.0, 8.0, 10.0):
            settings = solution.Settings(step_d=step, output_d=36500.0 if step != 8.0 else 36400.0)
            started = time.perf_counter()
            orbit = solution.solve(settings, t[-1], 0.0, path=Path(folder) / f"{step}.npz")
            runs[step] = (spin(orbit, t, 36500.0)[0], (time.perf_counter() - started) / span_kyr * 1000)
    ref = runs.pop(1.0)[0]
    for step, (q, cost) in runs.items():
        vector = np.abs(q["eccentricity"] * np.exp(1j * q["perihelion_longitude"])
                        - ref["eccentricity"] * np.exp(1j * ref["perihelion_longitude"]))
        print(f"| {step:g} | {cost:.0f} | {np.abs(q['eccentricity'] - ref['eccentricity']).max():.1e} | "
              f"{np.abs(q['obliquity'] - ref['obliquity']).max() / ARCSEC:.3f} | {vector.max():.1e} |")
    orbit = solution.solve(solution.Settings(), -1000 * KYR_D, 0.0)
    t = -np.arange(0.0, 1000 * KYR_D + 1, KYR_D)
    ref, _ = spin(orbit, t, 3652.5)
    print("\nRK8 step of the spin against 10 yr, over 1 Myr\n\n"
          "| step yr | spin s/Myr | obliquity max ″ | ϖ̄ max ″ |\n|---|---|---|---|")
    for years in (2000, 1000, 500, 200, 100, 50):
        q, wall = spin(orbit, t, years * 365.25)
        dvarpi = np.angle(np.exp(1j * (q["perihelion_longitude"] - ref["perihelion_longitude"])))
        print(f"| {years} | {wall:.3f} | {np.abs(q['obliquity'] - ref['obliquity']).max() / ARCSEC:.2e} | "
              f"{np.abs(dvarpi).max() / ARCSEC:.2e} |")


def cost():
    """``spinorbit run scenarios/earth_deep_time.toml`` with an empty cache (the N-body and the compilation
    included), then again (the solution and the kernels read from the cache)."""
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        env = {**os.environ, "SPINORBIT_CACHE_DIR": cache, "NUMBA_CACHE_DIR": str(Path(cache) / "numba")}
        command = [sys.executable, "-m", "spinorbit.edge.cli", "run", "scenarios/earth_deep_time.toml", "--out",
                   str(Path(out) / "run")]
        print("| 1 Myr | whole command | N-body | spin |\n|---|---|---|---|")
        for label in ("first (empty cache)", "cached"):
            started = time.perf_counter()
            subprocess.run(command, cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL)
            wall = time.perf_counter() - started
            summary = json.loads((Path(out) / "run" / "summary.json").read_text())
            print(f"| {label} | {wall:.1f} s | {summary['orbital_solution']['wall_s_this_run']:.1f} s | "
                  f"{summary['run']['wall_s']:.3f} s |")


def chaos(myr=20.0, displacement=1e-10, window_kyr=10.0):
    """Two solutions, the second's EMB displaced by ``displacement`` of its heliocentric distance at J2000:
    their distance in the EMB's eccentricity vector and orbit normal, raw (osculating) and averaged over
    ``window_kyr`` (the short periods out: the mean longitudes drift apart linearly, 1.5 x 1e-10 of the mean
    motion, and dephase them), and the e-folding time of the averaged distance's growth."""
    from spinorbit.orbits import solution

    runs = [solution.solve(solution.Settings(displacement=d), -myr * 1000 * KYR_D, 0.0)
            for d in (0.0, displacement)]
    t = runs[0].t_d[::-1]
    vectors = [np.column_stack([r.eccentricity_vector, r.normal])[::-1] for r in runs]
    size = round(window_kyr * KYR_D / abs(t[1] - t[0]))
    blocks = len(t) // size
    mean = [v[:blocks * size].reshape(blocks, size, 6).mean(axis=1) for v in vectors]
    averaged = np.linalg.norm(mean[1] - mean[0], axis=1)
    raw = np.linalg.norm(vectors[1] - vectors[0], axis=1)[:blocks * size].reshape(blocks, size).max(axis=1)
    mid = t[:blocks * size].reshape(blocks, size).mean(axis=1) / KYR_D / 1000
    print(f"| Myr | distance, {window_kyr:g}-kyr means | osculating, max over the window |\n|---|---|---|")
    for k in np.linspace(0, blocks - 1, 21).astype(int):
        print(f"| {mid[k]:.1f} | {averaged[k]:.2e} | {raw[k]:.2e} |")
    late = np.abs(mid) >= myr / 2
    slope = np.polyfit(np.abs(mid[late]), np.log(averaged[late]), 1)[0]
    print(f"\ngrowth of the averaged distance over the last half: e-folding {1 / slope:.2f} Myr "
          "(Laskar 1989: a Lyapunov time of ~5 Myr)")


MARS = (("La2004's parameters (p -7.597\"/yr, k2 0.149, Q 92)", []),
        ("p -7.590: La2004's p without the geodesic 0.0068\"/yr", ["mars.precession_rate=-7.59025 arcsec/yr"]),
        ("p -7.5833 (0.18 % below La2004's)", ["mars.precession_rate=-7.5833 arcsec/yr"]),
        ("p -7.6083 (Konopliv et al. 2016)", ["mars.precession_rate=-7.6083 arcsec/yr"]),
        ("p -7.576 (La2003's, Folkner et al. 1997)", ["mars.precession_rate=-7.576 arcsec/yr"]),
        ("k2 0.169 (Konopliv et al. 2016)", ["tides.k2=0.169"]),
        ("Q 50 (La2003's)", ["tides.Q=50"]),
        ("no tides (k2 0)", ["tides.k2=0"]))


def mars(myr=1.0):
    """The Mars scene over ``myr`` with the rate and the tides changed, against La2004 Mars (La2003 beside)."""
    from spinorbit import run_scenario

    windows = [w for w in ("1myr", "5myr", "20myr") if float(w.removesuffix("myr")) <= myr + 1e-9]
    windows += [] if f"{myr:g}myr" in windows else ["span"]
    print("| 0 to -%g Myr | " % myr + " | ".join(f"obliquity max ° ({w})" for w in windows)
          + " | ϖ̄ at the end ° | e max |\n|---" * 1 + "|---" * (len(windows) + 2) + "|")
    for label, overrides in MARS:
        c = run_scenario(ROOT / "scenarios/mars_deep_time.toml",
                         [f'span.end="-{myr:g} Myr"', "output.plots=false", *overrides]).summary["comparison"]
        cells = [f"{c[f'la2004_obliquity_max_deg_{w}']:.3f}" for w in windows]
        print(f"| {label} | {' | '.join(cells)} | {c['la2004_perihelion_longitude_end_deg_span']:+.2f} | "
              f"{c['la2004_eccentricity_max_span']:.1e} |")
    cells = [f"{c[f'la2003_minus_la2004_obliquity_max_deg_{w}']:.3f}" for w in windows]
    print(f"| La2003 Mars - La2004 Mars | {' | '.join(cells)} | "
          f"{c['la2003_minus_la2004_perihelion_longitude_end_deg_span']:+.2f} | 0 |")


def mars_band(sweep, block_kyr=50):
    """A Mars sweep's (``spinorbit sweep``) obliquity spread (max - min over the members) against time: its
    envelope (the spread's max over ``block_kyr``), the e-folding time of the envelope's growth where it is
    between 10x its first block and 5 deg (before it fills the chaotic band), and its power-law index there
    (1: the members dephase linearly, a regular motion; growing: exponential)."""
    from astropy.table import QTable

    from spinorbit.comparisons.mars_deep_time import band

    tables = [QTable.read(p, format="ascii.ecsv") for p in sorted(Path(sweep).glob("*/timeseries.ecsv"))]
    t_kyr, low, high, _ = band(tables)
    blocks = len(t_kyr) // block_kyr
    envelope = (high - low)[1:blocks * block_kyr + 1].reshape(blocks, block_kyr).max(axis=1)
    mid = np.abs(t_kyr[1:blocks * block_kyr + 1].reshape(blocks, block_kyr).mean(axis=1)) / 1000
    print(f"{len(tables)} members, envelope over {block_kyr} kyr\n\n| Myr | obliquity spread ° |\n|---|---|")
    for k in np.unique(np.linspace(0, blocks - 1, 21).astype(int)):
        print(f"| {mid[k]:.2f} | {envelope[k]:.3g} |")
    window = (envelope > 10 * envelope[0]) & (envelope < 5.0)
    if window.sum() < 3:
        print("\nthe envelope never grows between 10x its start and 5 deg: no e-folding measured")
        return
    slope = np.polyfit(mid[window], np.log(envelope[window]), 1)[0]
    index = np.polyfit(np.log(mid[window]), np.log(envelope[window]), 1)[0]
    print(f"\nover {mid[window].min():.2f}-{mid[window].max():.2f} Myr: e-folding {1 / slope:.2f} Myr, "
          f"power-law index {index:.2f}")


def mars_asteroids(myr=1.0, with_asteroids=True):
    """Mars against La2004 Mars on an orbit with Ceres, Vesta and Pallas (La2004 carries five asteroids; DE421's
    masses, DE430's states at 1969-06-28 as benchmarks/asteroid_share.py takes them) or without them, both
    started from DE421 at 1969-06-28 (IAS15 to J2000), then WHFast 5 d back ``myr`` as the orbital solution
    (the Sun's GR, the Moon's ring on the EMB)."""
    import rebound
    import reboundx
    from asteroid_share import STATES

    from spinorbit.base.constants import DAY_S, J2000_JD
    from spinorbit.bodies import moon
    from spinorbit.bodies.de421_header import header
    from spinorbit.bodies.table import gm_km3_d2
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.integrators import simulate
    from spinorbit.orbits import solution
    from spinorbit.orbits.kernel import open_ephemeris
    from spinorbit.references import laskar
    from spinorbit.starts import mars_deep_time

    h = header()
    t0 = h["JDEPOC"] - J2000_JD
    kernel = open_ephemeris("de421", t0, t0)
    sim = rebound.Simulation()
    sim.G = 1.0
    for body in solution.BODIES:
        gm = gm_km3_d2("earth") + gm_km3_d2("moon") if body == solution.BODIES[solution.EMB] else gm_km3_d2(body)
        p, v = kernel.relative_states(body, "solar_system_barycenter", [t0])
        sim.add(m=gm, x=p[0, 0], y=p[0, 1], z=p[0, 2], vx=v[0, 0], vy=v[0, 1], vz=v[0, 2])
    for state, key in (STATES.values() if with_asteroids else ()):
        x = np.array(state) * h["AU"]
        sim.add(m=h[key] * h["AU"] ** 3, x=x[0], y=x[1], z=x[2], vx=x[3], vy=x[4], vz=x[5])
    sim.t = t0
    extras = reboundx.Extras(sim)
    gr = extras.load_force("gr_potential")
    extras.add_force(gr)
    gr.params["c"] = h["CLIGHT"] * DAY_S
    ring = extras.load_force("gravitational_harmonics")
    extras.add_force(ring)
    emb, sun, mars = (sim.particles[solution.BODIES.index(b)] for b in (solution.BODIES[solution.EMB], "sun",
                                                                        "mars"))
    emb.params["J2"] = solution.MOON["ring"] * solution.lunar_ring_j2()
    emb.params["R_eq"] = moon.MEAN_DISTANCE_KM

    def orbit(body):
        r = np.array([body.x - sun.x, body.y - sun.y, body.z - sun.z])
        v = np.array([body.vx - sun.vx, body.vy - sun.vy, body.vz - sun.vz])
        n = np.cross(r, v)
        return n / np.linalg.norm(n), np.cross(v, n) / (sun.m + body.m) - r / np.linalg.norm(r)

    sim.integrator = "ias15"
    for t in np.linspace(t0, 0.0, 32)[1:]:
        emb.params["Omega"] = rebound.Vec3d(*orbit(emb)[0])
        sim.integrate(t, exact_finish_time=1)
    sim.integrator = "whfast"
    sim.integrator.corrector = 11
    sim.dt = -5.0
    rows = []
    for t in -np.arange(0.0, myr * 1000 * KYR_D + 1.0, 36525.0):
        if t < 0:                                    # as the solution's _ReboundBranch: a safe first step, then fast
            sim.integrator.safe_mode = 1
            sim.steps(1)
            sim.integrator.safe_mode = 0
            sim.integrate(t, exact_finish_time=0)
            sim.synchronize()
        emb.params["Omega"] = rebound.Vec3d(*orbit(emb)[0])
        rows.append([sim.t, *orbit(mars)[0], *orbit(mars)[1]])
    rows = np.array(rows[::-1])
    path = solution.HeliocentricOrbit(rows[:, 1:4], rows[:, 4:7], np.full(len(rows), 2.279e8))
    held = solution.OrbitalSolution(rows[:, 0], {"mars": path, solution.BODIES[solution.EMB]: path}, {}, {}, {})
    out = -np.arange(0.0, myr * 1000 * KYR_D + 1.0, KYR_D)
    reference = laskar.Insolation("La2004_Mars")(out)["obliquity_rad"]
    label = "with Ceres, Vesta, Pallas" if with_asteroids else "without asteroids"
    nominal = load_scenario("mars_deep_time").params
    for rate in (-7.597, -7.5833):
        params = replace(nominal, mars=replace(nominal.mars, precession_rate=rate),
                         tides=replace(nominal.tides, k2=0.149, Q=92.0), orbit=replace(nominal.orbit, output=36525.0))
        model = mars_deep_time.spin_model(params, held)
        y = simulate(model.system, out, "rk8", {"step": 36525.0}, estimate_error=False)[0].y
        normal = model.system.orbit(out)[0]
        obliquity = np.arccos(np.clip(np.sum(y[:, :3] * normal, axis=1), -1, 1))
        print(f"| {label}, p {rate} | {np.degrees(np.abs(obliquity - reference)).max():.3f} |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("part", choices=("moon", "factors", "ladder", "cost", "chaos", "mars", "mars_band",
                                         "mars_asteroids", "mars_no_asteroids"))
    parser.add_argument("--myr", type=float, default=None)
    parser.add_argument("--sweep", default="runs/mars_sweep")
    args = parser.parse_args()
    parts = {"moon": moon, "factors": factors, "ladder": ladder, "cost": cost,
             "chaos": lambda: chaos(args.myr or 20.0), "mars": lambda: mars(args.myr or 1.0),
             "mars_band": lambda: mars_band(args.sweep),
             "mars_asteroids": lambda: mars_asteroids(args.myr or 1.0),
             "mars_no_asteroids": lambda: mars_asteroids(args.myr or 1.0, with_asteroids=False)}
    parts[args.part]()
