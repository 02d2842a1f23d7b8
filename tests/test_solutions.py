"""Continuous solutions: the fit against the integrator's dense output between its nodes, a solution extended
in pieces against one computed whole, the store's refusals, two processes extending one file."""
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from spinorbit import solutions
from spinorbit.base.rotations import quat_angle
from spinorbit.edge.scenarios import load_scenario
from spinorbit.integrators import simulate
from spinorbit.solutions import chebyshev, store, stretches
from tests.units import arcsec

uas = arcsec * 1e-6


@pytest.fixture
def place(tmp_path, monkeypatch):
    monkeypatch.setitem(store.PLACE, "directory", tmp_path)
    return tmp_path


def test_chebyshev_series_reproduce_a_polynomial_and_join():
    """A degree-5 polynomial is reproduced by any series of degree >= 5 to rounding (the closed form)."""
    def poly(t):
        return 1.0 + 0.3 * t - 0.02 * t**2 + 1e-4 * t**5

    grid = chebyshev.Segments(0.0, 2.0, -2, np.zeros((3, 1, 8)))
    nodes, checks = grid.nodes(-2, 3)
    segments = chebyshev.fitted(0.0, 2.0, -2, poly(nodes)[:, None, :])
    t = np.linspace(-4.0, 2.0, 101)
    assert np.abs(segments.evaluate(t)[:, 0] - poly(t)).max() < 1e-13
    later = chebyshev.fitted(0.0, 2.0, 1, poly(grid.nodes(1, 2)[0])[:, None, :])
    assert segments.joined(later).span == (-4.0, 6.0)
    with pytest.raises(Exception, match="span"):
        segments.evaluate([6.5])


def test_fit_matches_the_dense_output_between_nodes(place):
    """The Moon's series at random dates against the integrator run to those dates: within 1 uas (the
    integration's own error estimate is ~5 uas over a year: the fit adds a small part of it)."""
    solution = solutions.for_scenario(load_scenario("moon_libration"), -20.0, 60.0)
    t = np.sort(np.random.default_rng(3).uniform(*solution.span, 200))
    t0, y0 = stretches.first_start(load_scenario("moon_libration"))
    scenario = stretches.stretch(load_scenario("moon_libration"), *solution.span, t0)
    system = stretches.system(scenario, (t0, y0))
    direct, _ = simulate(system, t, scenario.params.integrator.method, scenario.params.integrator.options(),
                         estimate_error=False)
    fitted = solution.part("moon.q", t)
    assert quat_angle(fitted, direct.quaternion).max() < 1 * uas
    assert solution.fit_error["fit_error_attitude_arcsec"] < 1e-6


def test_the_stated_fit_error_bounds_the_series_between_its_check_points():
    """The Moon over 40 d (10 segments of 4 d, two rk8 steps each): the series against simulate()'s dense output
    at 101 evenly spaced points per segment differs by at most twice the stated fit error (measured at T_14's
    15 extrema, where interpolation's error f^(n+1) T_(n+1) / (2^n (n+1)!) peaks, the middle -- where two steps'
    dense outputs join -- among them; the factor 2 leaves room for f^(n+1)'s change across a segment)."""
    from spinorbit.solutions import fit

    scenario = load_scenario("moon_libration")
    t0, y0 = stretches.first_start(scenario)
    stretch = stretches.stretch(scenario, t0, t0 + 40.0, t0)
    system = stretches.system(stretch, (t0, y0))
    method, options = stretch.params.integrator.method, stretch.params.integrator.options()
    grid = fit.Grid(t0, 4.0, 13)
    piece = fit.integrate(system, grid, t0, t0 + 40.0, method, options, estimate_error=False)
    t = (t0 + 4.0 * (np.arange(10)[:, None] + 0.5 + 0.5 * np.linspace(-1.0, 1.0, 101))).ravel()
    direct, _ = simulate(system, t, method, options, estimate_error=False)
    between = fit.errors(piece.layout, piece.layout.normalise(piece.segments.evaluate(t)),
                         fit.components(system, t, direct.y))
    assert between.keys() == piece.fit_error.keys()
    for key, stated in piece.fit_error.items():
        assert between[key] <= 2.0 * stated, key


def test_the_earth_seen_from_the_moon_is_de421s_within_a_millimetre(place):
    """The Moon's solution over 80 d holds the Earth seen from the Moon fitted at DE421's own values: at 1000
    random dates within 1 mm of DE421 read by jplephem directly, and the physical librations and sub-Earth point
    from it within 1 uas of those from jplephem's Earth."""
    from jplephem.spk import SPK

    from spinorbit.analysis.librations import icrf_to_body
    from spinorbit.orbits.kernel import kernel_path
    from spinorbit.references import eckhardt

    solution = solutions.for_scenario(load_scenario("moon_libration"), -20.0, 60.0)
    t = np.random.default_rng(5).uniform(*solution.span, 1000)
    with SPK.open(str(kernel_path("de421"))) as kernel:
        de421 = (kernel[3, 399].compute(2451545.0, t) - kernel[3, 301].compute(2451545.0, t)).T
    fitted = solution.part("earth.from_moon", t)
    assert np.linalg.norm(fitted - de421, axis=1).max() <= 1e-6                     # km
    mats = icrf_to_body(solution.part("moon.q", t))
    ours, direct = eckhardt.physical_librations(t, mats, fitted), eckhardt.physical_librations(t, mats, de421)
    for name in ("tau", "rho", "sigma", "sub_earth_lon", "sub_earth_lat"):
        assert np.abs(ours[name] - direct[name]).max() <= 1 * uas, name


def test_extended_in_pieces_equals_one_computed_whole(place, tmp_path_factory):
    """[0, 40] d then extended backward and forward to [-40, 80] against [-40, 80] at once: within the
    integration's own error estimate."""
    solutions.for_scenario(load_scenario("moon_libration"), 0.0, 40.0)
    pieces = solutions.for_scenario(load_scenario("moon_libration"), -40.0, 80.0)
    assert len(pieces.provenance["runs"]) == 3
    store.PLACE["directory"] = tmp_path_factory.mktemp("whole")
    whole = solutions.for_scenario(load_scenario("moon_libration"), -40.0, 80.0)
    assert whole.span == pieces.span and len(whole.provenance["runs"]) == 1
    t = np.linspace(*whole.span, 301)
    tolerance = max(solutions.integration_error(whole)["integration_error_attitude_arcsec"], 1e-6) * arcsec
    assert quat_angle(pieces.part("moon.q", t), whole.part("moon.q", t)).max() < tolerance


@pytest.mark.parametrize("damage", ["tamper", "truncate"])
def test_a_damaged_store_file_is_refused_and_recomputed(place, capfd, damage):
    first = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 8.0)
    path = first.path
    if damage == "tamper":                        # a well-formed npz whose numbers were changed
        with np.load(path) as npz:
            arrays = {name: npz[name] for name in npz.files}
        arrays["coefficients"][0, 0, 0] += 1e-9
        with open(path, "wb") as f:
            np.savez(f, **arrays)
    else:
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    capfd.readouterr()
    again = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 8.0)
    said = [line for line in capfd.readouterr().err.splitlines() if "refused" in line]
    assert len(said) == 1 and str(path) in said[0]
    t = np.linspace(0.0, 8.0, 17)
    assert quat_angle(again.part("moon.q", t), first.part("moon.q", t)).max() < 1e-3 * uas
    assert store.load(path, store.record(load_scenario("moon_libration"))) is not None


def test_two_processes_extending_one_solution_leave_one_good_file(place):
    solutions.for_scenario(load_scenario("moon_libration"), 0.0, 8.0)
    script = textwrap.dedent(f"""
        from spinorbit import solutions
        from spinorbit.edge.scenarios import load_scenario
        from spinorbit.solutions import store
        store.PLACE["directory"] = __import__("pathlib").Path({str(place)!r})
        s = solutions.for_scenario(load_scenario("moon_libration"), -16.0, 40.0)
        print(s.span, len(s.provenance["runs"]))
    """)
    runs = [subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True) for _ in range(2)]
    outputs = [run.communicate(timeout=300) for run in runs]
    assert all(run.returncode == 0 for run in runs), outputs
    assert {out for out, _ in outputs} == {"(-16.0, 40.0) 3\n"}           # one extended, the other read it
    files = list(place.glob("*.npz"))
    assert len(files) == 1 and not list(place.glob(".*tmp*"))
    stored = store.load(files[0], store.record(load_scenario("moon_libration")))
    assert stored.span == (-16.0, 40.0)


def test_a_runs_solution_is_its_model_over_its_span_as_a_qtable(place, capsys):
    """run_scenario(...).solution: the Moon over the run's span; at Times a QTable in rad whose angles are the
    run's own outputs within 1 uas (the run and the solution start from DE421's state at different epochs:
    the run at span.start, the solution at J2000 -- both DE421's, which agree to its own fit)."""
    import astropy.units as u
    from astropy.time import Time

    from spinorbit.edge import cli
    from spinorbit.edge.runner import run_scenario

    result = run_scenario("moon_libration", ["span.start=2000-01-01T12:00:00", "span.end=2000-01-11T12:00:00",
                                             "span.step=1 d", "output.plots=false"])
    solution = result.solution
    assert solution.covers(0.0, 10.0)
    table = solution.at(Time(2451545.0 + np.arange(11.0), format="jd", scale="tdb"))
    assert table["moon_phi"].unit == u.rad and len(table) == 11
    assert np.abs((table["moon_psi"] - result.table["psi"]).to_value(u.rad)).max() < 1 * uas
    cli._cache("show")
    assert "solution moon_libration: 2000.00–2000.03" in capsys.readouterr().out
