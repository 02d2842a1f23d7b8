"""Answers from stored solutions (spinorbit.solutions) against runs, side by side in one run.

    python benchmarks/bench_solutions.py [latency|agreement|extension|fit_points|export|grid|readme|read_path|all]
                                         [--busy N]

* latency: a process asks for 100 dates spread over 2021-2041, its ends included (the store then holds the
  span); a new process asks ``earth_pole`` and ``moon_librations`` for 10^4 other dates there: the call's wall
  time (its first and a second call; ``import spinorbit`` aside, and every module the calls import, found by
  calls in another process, loaded before them -- or imported in the first call), beside what the API did
  before it kept solutions -- a run of the validated scene per call with the dates among its outputs
  (``SCENE_PER_CALL``, on this code's scenes) -- each with warm caches; ``--busy N``: N busy-loop processes
  compete with the solutions' calls (a crowded machine, whatever else runs);
* agreement: the API's values against direct scene runs over the same span (the Moon 2000-2020 started at
  J2000, the non-rigid Earth 1950-2050): the largest difference, uas;
* extension: a stored Moon 2000-2050 extended to 2100, beside integrating 2050-2100 (simulate() of the same
  System to the scene's 2-d outputs, with its error estimate) and a scene run of 2050-2100;
* fit_points: the Moon's series (2000-2002) against the integrator at the second-kind points of each segment,
  at the extrema of T_(n+1) (what the stated fit error measures) and at 101 points per segment;
* export: each kind with SPICE kernels over its scene's span (``spinorbit export SCENE``: the Moon 1900-2050 as a
  binary PCK; the coupled Earth-Moon and the solar system 1950-2050 as an SPK and the Moon's PCK): solve and
  write times, sizes; read back by spiceypy and skyfield at 1000 dates against the solution (uas, mm) and
  against DE421 (mas, m, km);
* grid: the solar system's series against its integrator between the nodes, each body (mm): the kept grid
  over the scene's 1950-2050, other grids side by side over 1969-1970;
* read_path: a new process answering 10^4 dates from a warm store (``moon_librations``), beside one reading
  JPL's lunar PCK (moon_pa_de421_1900-2050.bpc, the copy the lunarsky package ships) with skyfield at the same
  dates, and beside a process that only takes astropy Time and returns a QTable (the floor of the API's types),
  interleaved; then what the spinorbit process imports, by package (python -X importtime);
* readme: the README's API example (ten dates of 2027, ``moon_librations`` and ``earth_pole``) from empty
  caches (a fresh SPINORBIT_CACHE_DIR and NUMBA_CACHE_DIR), beside a scene per call.
"""
import argparse
import contextlib
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SPAN_2021_2041 = (7670.5, 14975.5)      # TDB days from J2000


def python(code, tree, env=None, args=()):
    """Run ``code`` in a new interpreter with spinorbit from ``tree``; its last stdout line as JSON."""
    environment = {**os.environ, "PYTHONPATH": str(tree), "SPINORBIT_QUIET": "1", **(env or {})}
    done = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=environment,
                          cwd=tempfile.gettempdir())
    if done.returncode:
        raise RuntimeError(done.stderr[-3000:])
    return json.loads(done.stdout.strip().splitlines()[-1])


SCENE_PER_CALL = """
from dataclasses import replace

import numpy as np
from spinorbit.edge.runner import run_scenario
from spinorbit.edge.scenarios import load_scenario

def _run(scene, first, last, step, days):
    scenario = load_scenario(scene)
    p = scenario.params
    scenario = scenario.with_params(replace(p, span=replace(p.span, start=first, end=last, step=step)))
    scenario.extra_times = np.unique(days)
    return run_scenario(scenario).table

def _days(t):
    return np.asarray(t.tdb.jd1 - 2451545.0 + t.tdb.jd2)

class spinorbit:        # the API before solutions: the validated scene run with the dates among its outputs
    @staticmethod
    def moon_librations(t):
        days = _days(t)
        first, last = days.min() - 1.0, days.max() + 1.0
        return _run("moon_libration", first, last, max(0.5, (last - first) / 2000.0), days)

    @staticmethod
    def earth_pole(t):
        return _run("earth_precession_nutation_nonrigid", -18262.5, 18262.5, 2.0, _days(t))
"""


DATES = """
import numpy as np
from astropy.time import Time
def dates(n, seed):
    days = np.sort(np.random.default_rng(seed).uniform({lo}, {hi}, n))
    return Time(2451545.0, days, format="jd", scale="tdb")
""".format(lo=SPAN_2021_2041[0], hi=SPAN_2021_2041[1])

LATENCY = DATES + """
import importlib, json, sys, time
import spinorbit
{api}
if sys.argv[1:2] == ["imported"]:        # import aside: every module a call reads, loaded before it is timed
    for module in json.loads(sys.argv[2]):
        try:
            importlib.import_module(module)
        except ImportError:             # a helper an extension module registers, loaded with its parent
            pass
out = {{}}
for name in ("moon_librations", "earth_pole"):
    call, t = getattr(spinorbit, name), dates(10_000, 2)
    started = time.perf_counter(); call(t); first = time.perf_counter() - started
    started = time.perf_counter(); call(dates(10_000, 3)); second = time.perf_counter() - started
    out[name] = [first, second]
print(json.dumps(out))
"""
IMPORTED = DATES + """
import json, sys
import spinorbit
before = set(sys.modules)
spinorbit.moon_librations(dates(10, 5)); spinorbit.earth_pole(dates(10, 5))
print(json.dumps(sorted(set(sys.modules) - before)))
"""


PREPARE = """
import json, numpy as np, spinorbit
from astropy.time import Time
t = Time(2451545.0, np.linspace({lo}, {hi}, 100), format="jd", scale="tdb")       # spread over the span, ends too
spinorbit.moon_librations(t); spinorbit.earth_pole(t)
print(json.dumps({{}}))
""".format(lo=SPAN_2021_2041[0], hi=SPAN_2021_2041[1])


def latency(busy=0):
    rows = {}
    python(PREPARE, ROOT)
    modules = json.dumps(python(IMPORTED, ROOT))      # what the calls import, found by calls in another process
    for label, api in (("solutions", ""), ("a scene per call", SCENE_PER_CALL)):
        with crowded(busy if label == "solutions" else 0):
            for imports in ("", "imported"):
                rows[label, imports] = python(LATENCY.format(api=api), ROOT,
                                              args=("imported", modules) if imports else ())
    print("\n## latency: 10^4 dates in 2021-2041, a new process (first call / second call, s)\n")
    print("| code | imports | moon_librations | earth_pole |\n|---|---|---|---|")
    for (label, imports), row in rows.items():
        print(f"| {label} | {'loaded before the call' if imports else 'in the first call'} | "
              f"{row['moon_librations'][0]:.3f} / {row['moon_librations'][1]:.3f} | "
              f"{row['earth_pole'][0]:.3f} / {row['earth_pole'][1]:.3f} |")
    for name in ("moon_librations", "earth_pole"):
        ratio = rows["a scene per call", "imported"][name][0] / rows["solutions", "imported"][name][0]
        print(f"\n{name}: {ratio:.0f}x faster (first call, import aside)", end="")
    print()


@contextlib.contextmanager
def crowded(busy):
    """``busy`` busy-loop processes competing for the cores while the block runs (none: the machine as it is)."""
    loops = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(busy)]
    try:
        time.sleep(1.0 if busy else 0.0)
        yield
    finally:
        for loop in loops:
            loop.kill()
            loop.wait()


def agreement():
    import spinorbit
    from spinorbit.base.constants import ARCSEC
    from spinorbit.base.rotations import matrix_from_euler313
    from spinorbit.edge.runner import run_scenario

    moon = run_scenario("moon_libration", ["span.start=2000-01-01T12:00:00", "span.end=2020-01-01T12:00:00",
                                           "model.start=2000-01-01T12:00:00", "output.plots=false"])
    answer = spinorbit.moon_librations(moon.table["time"])
    mats = [matrix_from_euler313(*(table[c].to_value("rad") for c in ("phi", "theta", "psi")))
            for table in (moon.table, answer)]
    moon_uas = np.linalg.norm(mats[0] - mats[1], axis=(1, 2)).max() / np.sqrt(2) / ARCSEC * 1e6
    earth = {}
    for scene, nonrigid in (("earth_precession_nutation_nonrigid", True), ("earth_precession_nutation", False)):
        run = run_scenario(scene, ["output.plots=false"])
        pole = spinorbit.earth_pole(run.table["time"], nonrigid=nonrigid)
        earth[scene] = (len(run.table), max(np.abs((pole[c] - run.table[c]).to_value("arcsec")).max()
                                            for c in ("cip_x", "cip_y")) * 1e6)
    print("\n## agreement with direct scene runs (largest difference, uas)\n")
    print("| answer | scene run | difference |\n|---|---|---|")
    print(f"| moon_librations, {len(moon.table)} dates | moon_libration 2000-2020 from J2000 | {moon_uas:.3g} |")
    for scene, (count, difference) in earth.items():
        print(f"| earth_pole(nonrigid={scene.endswith('nonrigid')}), {count} dates | {scene} 1950-2050 | "
              f"{difference:.3g} |")
    print(f"\nfit errors stated: Moon {answer.meta['fit_error']}, Earth layer {pole.meta['fit_error']}")


def extension():
    from dataclasses import replace

    from spinorbit import solutions
    from spinorbit.edge.runner import run_scenario
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.integrators import simulate
    from spinorbit.solutions import store, stretches

    store.PLACE["directory"] = Path(tempfile.mkdtemp(prefix="solutions-"))
    year = 365.25
    solutions.for_scenario(load_scenario("moon_libration"), 0.0, 50 * year)
    started = time.perf_counter()
    extended = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 100 * year)
    extend_s = time.perf_counter() - started
    scenario = load_scenario("moon_libration")
    stretch = stretches.stretch(scenario, 50 * year, 100 * year, 50 * year)     # DE421's Moon at 2050, out to 2100
    t_out = stretch.output_times()
    simulate(stretches.system(stretch, None), t_out[:10], "rk8", stretch.params.integrator.options(),
             estimate_error=False)                                              # compiled
    started = time.perf_counter()
    system = stretches.system(stretch, None)                                      # the orbits sampled, the start
    built_s = time.perf_counter() - started
    _, bare = simulate(system, t_out, "rk8", stretch.params.integrator.options(), estimate_error=True)
    integrate_s = time.perf_counter() - started - built_s
    started = time.perf_counter()
    p = scenario.params
    run_scenario(scenario.with_params(replace(p.with_span(50 * year, 100 * year),
                                              output=replace(p.output, plots=False))))
    scene_s = time.perf_counter() - started
    run = extended.provenance["runs"][-1]
    print("\n## extending a stored Moon by 50 yr (2050-2100), s\n")
    print("| extension of the stored solution | the System built (orbits, start) + simulate() of those 50 yr "
          "(2-d outputs, error estimate) | scene run of 2050-2100 | extension / bare | extension / scene |")
    print("|---|---|---|---|---|")
    print(f"| {extend_s:.2f} | {built_s:.2f} + {integrate_s:.2f} = {built_s + integrate_s:.2f} | {scene_s:.2f} | "
          f"{extend_s / (built_s + integrate_s):.2f} | {extend_s / scene_s:.2f} |")
    print(f"\nrhs evaluations (main run; the error estimate's run aside): extension {run['rhs_evaluations']} in "
          f"{run['steps']} steps (its integration {run['wall_s']:.2f} s), bare {bare['rhs_evaluations']} in "
          f"{bare['steps']} steps ({bare['wall_s']:.2f} s)")
    print(f"fit error {extended.fit_error}; integration error "
          f"{ {k: v for k, v in run.items() if k.startswith('integration_error_')} }")


EXPORTED = ("moon_libration", "earth_moon_coupled", "solar_system")    # each scene's own span (1900/1950-2050)
DE421_BOUND = "2x what DE421's asteroids move it"


def fit_points():
    """The Moon's series (2000-2002, fitted as the store fits it) against the integrator at three sets of points
    per segment: the second kind, the extrema of T_(n+1) (the stated fit error; the segment's midpoint, an rk8
    step point, among them) and 101 evenly spaced; the integrator run once to all of them."""
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.integrators import simulate
    from spinorbit.solutions import fit, stretches

    scenario = load_scenario("moon_libration")
    t0, y0 = stretches.first_start(scenario)
    grid = stretches.grid(stretches.stored(scenario))
    lo, hi = grid.bounds(t0, t0 + 730.0)
    stretch = stretches.stretch(scenario, lo, hi, t0)
    system = stretches.system(stretch, (t0, y0))
    method, options = stretch.params.integrator.method, stretch.params.integrator.options()
    ephemeris = stretches.ephemeris(stretch, system, lo, hi)
    piece = fit.integrate(system, grid, lo, hi, method, options, estimate_error=False, ephemeris=ephemeris)
    count = len(piece.segments.coefficients)
    mids = lo + (np.arange(count) + 0.5) * grid.length_d
    sets = {"second kind": np.cos(np.pi * np.arange(grid.degree + 1) / grid.degree),
            "extrema of T_(n+1) (stated)": np.cos(np.pi * np.arange(grid.degree + 2) / (grid.degree + 1)),
            "101 evenly spaced": np.linspace(-1.0, 1.0, 101)}
    times = {name: (mids[:, None] + grid.length_d / 2 * x).ravel() for name, x in sets.items()}
    every = np.unique(np.concatenate(list(times.values())))
    direct, _ = simulate(system, every, method, options, estimate_error=False)
    print("\n## the Moon's series (2000-2002) against the integrator, by the points checked in each segment\n")
    print("| points per segment | attitude, uas | omega, rel | omega_core, rel | Earth from the Moon, rel |")
    print("|---|---|---|---|---|")
    for name, t in times.items():
        rows = np.searchsorted(every, t)
        truth = fit.components(system, t, direct.y[rows], ephemeris)
        e = fit.errors(piece.layout, piece.layout.normalise(piece.segments.evaluate(t)), truth)
        print(f"| {name} | {e['fit_error_attitude_arcsec'] * 1e6:.3g} | {e['fit_error_moon_omega_rel']:.2g} | "
              f"{e['fit_error_moon_omega_core_rel']:.2g} | {e['fit_error_earth_from_moon_rel']:.2g} |")


def export():
    """Each kind exported over its scene's span: solve (store or run), write, read back at 1000 dates."""
    for scene in EXPORTED:
        with tempfile.TemporaryDirectory(prefix=f"export-{scene}-") as out:
            exported(scene, Path(out))
        sys.stdout.flush()


def exported(scene, out):
    import spiceypy

    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.solutions import for_export

    started = time.perf_counter()
    solution = for_export(load_scenario(scene, []))
    solve_s = time.perf_counter() - started
    started = time.perf_counter()
    written = solution.export(out)
    write_s = time.perf_counter() - started
    sizes = ", ".join(f"{Path(f).name} {Path(f).stat().st_size / 1e6:.3g} MB" for f in written["files"])
    lo, hi = (2000.0 + d / 365.25 for d in solution.span)
    print(f"\n## {scene} {lo:.0f}-{hi:.0f} exported\n")
    fit = {"attitude": f"{solution.fit_error['fit_error_attitude_arcsec'] * 1e6:.3g} uas"}
    if "fit_error_position_km" in solution.fit_error:
        fit["positions"] = f"{solution.fit_error['fit_error_position_km'] * 1e6:.3g} mm"
    print(f"solve {solve_s:.1f} s (from the store, or integrated when it lacks the span); write {write_s:.2f} s;"
          f" {sizes}; angles refit {written['fit_error']['moon_angles_arcsec']:.2g}\"; the solution's fit "
          f"error: {', '.join(f'{k} {v}' for k, v in fit.items())}")
    t = exact_dates(solution.span, 1000, 8)
    for path in written["files"]:
        spiceypy.furnsh(path)
    try:
        orientation_rows(solution, written, t)
        if any(f.endswith(".bsp") for f in written["files"]):
            position_rows(solution, written, t)
    finally:
        spiceypy.kclear()


def exact_dates(span, count, seed):
    """TDB days in ``span`` whose seconds are exact doubles: SPICE, skyfield and the solution read the same
    instant (a day count rounded to its last bit moves Mercury by up to 4 mm far from J2000)."""
    t = np.round(np.random.default_rng(seed).uniform(*span, count) * 2 ** 20) / 2 ** 20
    return np.clip(t, *span)


def orientation_rows(solution, written, t):
    import spiceypy
    from skyfield.api import load
    from skyfield.functions import mxm, rot_x, rot_z
    from skyfield.planetarylib import PlanetaryConstants

    from spinorbit.analysis.librations import icrf_to_body, pole_and_longitude_difference
    from spinorbit.base.constants import ARCSEC, DAY_S
    from spinorbit.references.moon_de421 import Orientation

    pck, frame = (next(f for f in written["files"] if f.endswith(suffix)) for suffix in (".bpc", ".tf"))
    truth = icrf_to_body(solution.part("moon.q", t))
    by_spice = np.array([spiceypy.pxform("J2000", written["frames"]["moon"], ti * DAY_S) for ti in t])
    constants = PlanetaryConstants()
    constants.read_text(load.open(frame))
    constants.read_binary(load.open(pck))
    segment = constants.build_frame_named(written["frames"]["moon"])._segment
    by_skyfield = np.array([mxm(rot_z(-w), mxm(rot_x(-d), rot_z(-r)))
                            for r, d, w in (segment.compute(2451545.0, ti, False) for ti in t)])

    def uas(a):
        return np.linalg.norm(a - truth, axis=(1, 2)).max() / np.sqrt(2) / ARCSEC * 1e6

    pole, longitude = (np.abs(x).max() / ARCSEC for x in
                       pole_and_longitude_difference(by_spice, Orientation()(t)["icrf_to_body"]))
    print("\n| the Moon's orientation (PCK) read back by | vs the solution, uas | vs DE421: pole, longitude |")
    print("|---|---|---|")
    print(f"| spiceypy pxform | {uas(by_spice):.3g} | {pole * 1e3:.3g} mas, {longitude * 1e3:.3g} mas |")
    print(f"| skyfield (two-part TDB) | {uas(by_skyfield):.3g} | |")


def carried(solution, t):
    """{(name, NAIF code): (n, 3) km about the solar-system barycentre} of every body the SPK holds, from the
    solution (the Earth and the Moon from their barycentre by the body table's mass ratio; that barycentre, for a
    solution without barycentric bodies, from DE421, which the coupled Earth-Moon's run reads)."""
    from spinorbit.bodies.table import EMB, gm_km3_d2
    from spinorbit.orbits.kernel import open_ephemeris
    from spinorbit.solutions.tracks import tracks

    values = {part.name[:-2]: solution.part(part.name, t) for part in solution.layout.slices
              if part.name.endswith(".r") and "barycentric" in part.unit}
    if EMB not in values:
        values[EMB] = open_ephemeris("de421", *solution.span).relative_states(EMB, "solar_system_barycenter", t)[0]
    mu = gm_km3_d2("moon") / (gm_km3_d2("earth") + gm_km3_d2("moon"))
    moon = solution.part("moon.r", t)
    values.update(moon=values[EMB] + (1 - mu) * moon, earth=values[EMB] - mu * moon)
    return {(track.name, track.target): values[track.name] for track in tracks(solution)}


def position_rows(solution, written, t):
    from skyfield.api import load
    from skyfield.jpllib import SpiceKernel

    kernel = SpiceKernel(next(f for f in written["files"] if f.endswith(".bsp")))
    at = load.timescale().tdb_jd(2451545.0, t)
    print("\n| body (NAIF code about its centre) | records, degree | fit error, mm | spiceypy spkpos about 0 vs "
          "the solution, mm | skyfield vs the solution, mm | vs DE421 (heliocentric; the Sun about 0) | scene's "
          "bound |\n|---|---|---|---|---|---|---|")
    try:
        print_positions(solution, written, t, kernel, at)
    finally:
        kernel.close()


def print_positions(solution, written, t, kernel, at):
    """The rows of each body the SPK ``kernel`` holds, read about 0 at ``t`` (skyfield: ``at``)."""
    import spiceypy
    from jplephem.spk import SPK

    from spinorbit.base.constants import ARCSEC, DAY_S
    from spinorbit.comparisons import earth_moon_de421, solar_system_de421
    from spinorbit.orbits.kernel import open_ephemeris

    bsp = next(f for f in written["files"] if f.endswith(".bsp"))
    with SPK.open(bsp) as spk:
        records = {s.target: (s.load_array()[1], s.load_array()[2].shape) for s in spk.segments}
    de421 = open_ephemeris("de421", *solution.span)
    carried_at = carried(solution, t)
    sun = dict(carried_at).get(("sun", 10))
    for (name, code), truth in carried_at.items():
        by_spice = np.array([spiceypy.spkpos(str(code), ti * DAY_S, "J2000", "NONE", "0")[0] for ti in t])
        by_skyfield = kernel[code].at(at).position.km.T
        length, (_, count, coefficients) = records[code]
        fit = written["fit_error"][f"{name}_position_km"] * 1e6
        de421_km, bound = "", ""
        if name == "sun":
            drift = np.linalg.norm(by_spice - de421.relative_states("sun", "solar_system_barycenter", t)[0], axis=1)
            de421_km = f"{drift.max():.3g} km (the barycentre's drift; {drift[-1]:.3g} km at the end)"
        elif sun is not None and name not in ("moon", "earth_moon_barycenter"):
            heliocentric = by_spice - np.array([spiceypy.spkpos("10", ti * DAY_S, "J2000", "NONE", "0")[0]
                                                for ti in t])
            error = solar_system_de421.planet_errors(t, {name: heliocentric})[name].max()
            de421_km = f"{error:.3g} km"
            bound = f"{2 * solar_system_de421.ASTEROIDS_KM[name]:.3g} km ({DE421_BOUND})"
        print(f"| {name} ({code}) | {count} x {length:.4g} d, {coefficients - 1} | {fit:.2g} | "
              f"{mm(by_spice, truth):.3g} | {mm(by_skyfield, truth):.3g} | {de421_km} | {bound} |")
    moon = np.array([spiceypy.spkpos("MOON", ti * DAY_S, "J2000", "NONE", "EARTH")[0] for ti in t])
    moon_sky = (kernel["moon"] - kernel["earth"]).at(at).position.km.T
    direction, distance = earth_moon_de421.orbit_errors(t, moon)
    tolerance = "1 mas, 0.1 m" if sun is not None else "1\", 2 km"
    print(f"| the Moon from the Earth (301 - 399) | | | {mm(moon, solution.part('moon.r', t)):.3g} "
          f"| {mm(moon_sky, solution.part('moon.r', t)):.3g} "
          f"| {np.nanmax(direction) / ARCSEC * 1e3:.3g} mas, {np.nanmax(np.abs(distance)) * 1e3:.3g} m "
          f"| {tolerance} (the scene's) |")


def mm(read, truth):
    return np.linalg.norm(read - truth, axis=1).max() * 1e6


GRIDS = ((4.0, 13), (2.0, 13), (8.0, 13), (4.0, 8))     # (segment d, degree): the scene's own first


def grid():
    """The solar system's grid: each body's fit error against the integrator between the nodes, over the scene's
    whole span on the kept grid, and over its first year from DE421's epoch on other grids side by side."""
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.solutions import stretches
    from spinorbit.solutions.chebyshev import Grid

    scenario = load_scenario("solar_system", [])
    start = stretches.first_start(scenario)
    kept = stretches.grid(stretches.stored(scenario))
    rows = {f"{kept.length_d:g} d, degree {kept.degree}, 1950-2050": fit_errors(scenario, start, kept,
                                                                                  *scenario.params.span.bounds)}
    year = (start[0], start[0] + 365.25)
    for length, degree in GRIDS:
        rows[f"{length:g} d, degree {degree}, 1969-1970"] = fit_errors(scenario, start,
                                                                        Grid(0.0, length, degree), *year)
    bodies = list(next(iter(rows.values())))
    print("\n## the solar system's fit: each body's series against the integrator between the nodes, mm\n")
    print(f"| grid | {' | '.join(bodies)} |\n|---|{'---|' * len(bodies)}")
    for label, errors in rows.items():
        print(f"| {label} | {' | '.join(f'{errors[b]:.3g}' for b in bodies)} |")


def fit_errors(scenario, start, grid, lo, hi):
    """{body: largest |series - integrator| (mm)} at the points between the nodes of ``grid`` over [lo, hi]: one
    run to the nodes and those points, the series fitted as solutions.fit.integrate fits it (at the node times as
    rounded), each body's largest difference (integrate states only the largest of all)."""
    from spinorbit.integrators import simulate
    from spinorbit.solutions import stretches
    from spinorbit.solutions.chebyshev import Segments, grid_indices, interpolating_at
    from spinorbit.solutions.fit import components, fitted_layout

    stretch = stretches.stretch(scenario, lo, hi, start[0])
    system = stretches.system(stretch, start)
    first, count = grid_indices(grid.origin_d, grid.length_d, lo, hi)
    empty = Segments(grid.origin_d, grid.length_d, first, np.zeros((count, 0, grid.degree + 1)))
    nodes, checks = empty.nodes(first, count)
    t_out = np.concatenate([nodes.ravel(), checks.ravel()])
    times, rows = np.unique(t_out, return_inverse=True)
    settings = stretch.params.integrator
    run, _ = simulate(system, times, settings.method, settings.options(), estimate_error=False)
    values, n, layout = components(system, t_out, run.y[rows]), nodes.size, fitted_layout(system)
    at_nodes = values[:n].reshape(count, grid.degree + 1, -1).transpose(0, 2, 1)
    series = Segments(grid.origin_d, grid.length_d, first, interpolating_at(at_nodes, empty.normalised(nodes, first)))
    fitted = series.at_normalised(empty.normalised(checks, first)).reshape(-1, layout.size)
    return {part.name[:-2]: np.linalg.norm(fitted[:, part.index] - values[n:, part.index], axis=1).max() * 1e6
            for part in layout.slices if part.name.endswith(".r")}


README_EXAMPLE = """
import json, time
started = time.perf_counter()
import spinorbit
{api}
from astropy.time import Time
t = Time([f"2027-{{month:02d}}-15" for month in range(1, 11)])
moon, pole = spinorbit.moon_librations(t), spinorbit.earth_pole(t)
print(json.dumps({{"wall_s": time.perf_counter() - started}}))
"""


def readme():
    rows = {}
    for label, api in (("solutions", ""), ("a scene per call", SCENE_PER_CALL), ("main job", None)):
        empty = tempfile.mkdtemp(prefix="empty-cache-")
        caches = {"SPINORBIT_CACHE_DIR": f"{empty}/spinorbit", "NUMBA_CACHE_DIR": f"{empty}/numba"}
        if api is not None:
            rows[label] = python(README_EXAMPLE.format(api=api), ROOT, caches)["wall_s"]
            continue
        started = time.perf_counter()                 # the README's first command, its first run
        subprocess.run([sys.executable, "-m", "spinorbit", "--quiet", "run",
                        str(ROOT / "scenarios/moon_libration.toml"), "--out", f"{empty}/run"], check=True,
                       capture_output=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT), **caches})
        rows["main job: spinorbit run scenarios/moon_libration.toml"] = time.perf_counter() - started
    print("\n## the README's API example and its main job, each from empty caches (s, import included)\n")
    print("| code | wall |\n|---|---|")
    for label, wall in rows.items():
        print(f"| {label} | {wall:.1f} |")


READ_DAYS = "np.sort(np.random.default_rng(11).uniform(7670.5, 9862.0, 10_000))"     # 2021-2027, TDB days
READ_SPINORBIT = """import numpy as np
from astropy.time import Time
import spinorbit
t = Time(2451545.0, {days}, format="jd", scale="tdb")
table = spinorbit.moon_librations(t)
assert len(table) == 10_000
""".format(days=READ_DAYS)
READ_SKYFIELD = """import importlib.resources
import numpy as np
from skyfield.api import load
from skyfield.planetarylib import PlanetaryConstants
data = importlib.resources.files("lunarsky") / "data"
constants = PlanetaryConstants()
constants.read_text(load.open(str(data / "fk" / "satellites" / "moon_080317.tf")))
constants.read_binary(load.open(str(data / "pck" / "moon_pa_de421_1900-2050.bpc")))
frame = constants.build_frame_named("MOON_PA_DE421")
t = load.timescale().tdb_jd(2451545.0 + {days})
m = frame.rotation_at(t)                                   # ICRF -> body, (3, 3, n)
phi, theta = np.arctan2(m[2, 0], -m[2, 1]), np.arccos(m[2, 2])
psi = np.arctan2(m[0, 2], m[1, 2])
assert phi.size == 10_000
""".format(days=READ_DAYS)
READ_FLOOR = """import numpy as np
import astropy.units as u
from astropy.table import QTable
from astropy.time import Time
t = Time(2451545.0, {days}, format="jd", scale="tdb")
days = t.tdb.jd1 - 2451545.0 + t.tdb.jd2
table = QTable({{"time": t, **{{f"c{{i}}": np.sin(days * i) * u.arcsec for i in range(10)}}}})
""".format(days=READ_DAYS)


def read_path(repeats=5):
    """A new process answering 10^4 dates from a warm store, beside skyfield reading JPL's lunar PCK at the same
    dates, and beside the floor of an API that takes astropy Time and returns a QTable; interleaved, each the
    median of ``repeats`` processes timed from outside (interpreter start to exit); then what the spinorbit
    process imports (python -X importtime, exclusive microseconds summed by top-level package)."""
    python(READ_SPINORBIT + "print('{}')", ROOT)                      # the store warm, the kernels compiled
    codes = {"skyfield, JPL's moon_pa_de421 PCK (lunarsky's copy)": READ_SKYFIELD,
             "spinorbit.moon_librations, warm store": READ_SPINORBIT,
             "numpy + astropy Time in, QTable out (no computation)": READ_FLOOR}
    walls = {label: [] for label in codes}
    environment = {**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_QUIET": "1"}
    for _ in range(repeats):
        for label, code in codes.items():
            started = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True, env=environment, cwd=tempfile.gettempdir())
            walls[label].append(time.perf_counter() - started)
    skyfield = float(np.median(walls[next(iter(codes))]))
    print("\n## read path: a new process answering 10^4 dates of 2021-2027 (s, interpreter start to exit; "
          f"median of {repeats}, interleaved)\n")
    print("| process | wall | / skyfield |\n|---|---|---|")
    for label, values in walls.items():
        print(f"| {label} | {np.median(values):.2f} | {np.median(values) / skyfield:.1f} |")
    done = subprocess.run([sys.executable, "-X", "importtime", "-c", READ_SPINORBIT], env=environment,
                          cwd=tempfile.gettempdir(), capture_output=True, text=True, check=True)
    by_package = {}
    for line in done.stderr.splitlines():
        if line.startswith("import time:") and "|" in line and "self" not in line:
            own, _, name = line[len("import time:"):].split("|")
            top = name.strip().split(".")[0]
            by_package[top] = by_package.get(top, 0) + int(own)
    print("\nwhat the spinorbit process imports (s, exclusive, by top-level package, the largest):\n")
    print("| package | import |\n|---|---|")
    for top, micro in sorted(by_package.items(), key=lambda kv: -kv[1])[:8]:
        print(f"| {top} | {micro / 1e6:.2f} |")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("part", nargs="?", default="all",
                        choices=["latency", "agreement", "extension", "fit_points", "export", "grid", "readme",
                                 "read_path", "all"])
    parser.add_argument("--busy", type=int, default=0,
                        help="latency: busy-loop processes competing with the solutions' calls (a crowded machine)")
    args = parser.parse_args()
    parts = ["latency", "agreement", "extension", "fit_points", "export", "grid", "readme", "read_path"] \
        if args.part == "all" \
        else [args.part]
    for part in parts:
        globals()[part](**({"busy": args.busy} if part == "latency" else {}))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
