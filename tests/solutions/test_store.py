"""The solution store as hostile input and under load (issue 42): keyed by the ephemeris file's content, its folder
private, a run's last output on its span, the kind's own grid, a lock never waited on without limit by a finished
run, a full disk that keeps the answer, `cache clear` that keeps what a live process holds, masked dates refused,
reverse dates matched at once, a read error that is not the file's, and a size bound.

References: hashlib's sha256 of the ephemeris file, the scene's own span and step (the run's output times), the
scene's grid (its Scene's ``stored``), the same call without the fault injected."""
import errno
import fcntl
import hashlib
import os
import shutil
import threading
import time

import numpy as np
import pytest

from spinorbit import solutions
from spinorbit.base import verified
from spinorbit.base.errors import InputError
from spinorbit.edge.runner import run_scenario
from spinorbit.edge.scenarios import load_scenario
from spinorbit.orbits.kernel import kernel_path
from spinorbit.solutions import store, stretches
from tests.units import arcsec

uas = arcsec * 1e-6
J2000 = "span.start=2000-01-01T12:00:00"


@pytest.fixture
def place(tmp_path, monkeypatch):
    folder = tmp_path / "solutions"
    folder.mkdir(mode=0o700)
    monkeypatch.setitem(store.PLACE, "directory", folder)
    monkeypatch.setattr(store, "VERIFIED", {})
    return folder


def moon(*sets):
    return load_scenario("moon_libration", list(sets))


def test_a_different_file_under_the_same_name_gets_its_own_solution(tmp_path, monkeypatch, place):
    """42.1: ``orbit.source = "k.bsp"`` in two folders holding two different files: two records, and the
    provenance names the file's sha256 and size (hashlib's, of the bytes)."""
    original = kernel_path("de421")
    for name, extra in (("a", b""), ("b", b"\0" * 1024)):        # DAF records are addressed: a tail is inert
        (tmp_path / name).mkdir()
        (tmp_path / name / "k.bsp").write_bytes(original.read_bytes() + extra)
    monkeypatch.chdir(tmp_path / "a")
    first = store.record(moon("orbit.source=k.bsp"))
    solution = solutions.for_scenario(moon("orbit.source=k.bsp"), 0.0, 4.0)
    monkeypatch.chdir(tmp_path / "b")
    second = store.record(moon("orbit.source=k.bsp"))
    assert store.path_of(first) != store.path_of(second)
    data = (tmp_path / "a" / "k.bsp").read_bytes()
    assert solution.provenance["ephemeris"]["sha256"] == hashlib.sha256(data).hexdigest()
    assert solution.provenance["ephemeris"]["bytes"] == len(data)


def test_a_solutions_folder_others_can_write_is_refused_in_one_line(place):
    """42.2: the store's folder under the rule of every other cache (spinorbit.base.private)."""
    place.chmod(0o777)
    with pytest.raises(InputError, match="writable by others") as info:
        store.directory()
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("sets", [[J2000, "span.end=3.3 d", "span.step=0.1 d"],
                                  ["span.start=2000-03-01T00:00:00", "span.end=-30 d", "span.step=10 min"],
                                  [J2000, "span.end=1 h", "span.step=10 min"]])
def test_a_run_whose_last_output_rounds_past_its_segments_finishes(place, sets):
    """42.4: the output times end at span.end within rounding; the run's table holds them all."""
    result = run_scenario("moon_libration", [*sets, "output.plots=false"])
    times = result.scenario.output_times()
    assert len(result.table) == len(times)
    assert abs(times[-1] - result.scenario.params.span.end) < 1e-9


def test_a_short_run_is_stored_on_its_kinds_grid_and_a_failed_run_never(place, monkeypatch):
    """42.5: a one-hour Moon run from J2000 stores segments of the scene's 4 d, degree 13 (Scene.stored), not of
    one hour; a run that fails after its integration stores nothing."""
    result = run_scenario("moon_libration", [J2000, "span.end=1 h", "span.step=10 min", "output.plots=false"])
    stored = store.read(store.path_of(store.record(result.scenario)), store.record(result.scenario))
    kind = stretches.grid(result.scenario.scene.stored)
    assert stored.segments.length_d == kind.length_d and stored.segments.degree == kind.degree
    assert (stored.segments.origin_d - kind.origin_d) % kind.length_d == 0.0
    shutil.rmtree(place)
    place.mkdir(mode=0o700)
    def broken(*args, **kwargs):
        raise RuntimeError("a comparison that fails")

    from spinorbit.comparisons import moon_de421

    monkeypatch.setattr(moon_de421, "against_de421", broken)       # the scene's comparison, after the run
    with pytest.raises(RuntimeError):
        run_scenario("moon_libration", [J2000, "span.end=2 d", "span.step=1 d", "output.plots=false"])
    assert not list(place.glob("*.npz"))


def test_a_finished_run_does_not_wait_on_the_stores_lock(place):
    """42.6: another process holds the store's lock: the run finishes at once, says it was not stored (summary and
    one line); released after 20 s, a run waiting on it would be stored."""
    scenario = moon(J2000, "span.end=2 d", "span.step=1 d", "output.plots=false")
    path = store.path_of(store.record(scenario))
    handle = open(verified.lock_path(path), "w")
    fcntl.flock(handle, fcntl.LOCK_EX)
    release = threading.Timer(20.0, handle.close)
    release.start()
    started = time.monotonic()
    try:
        result = run_scenario(scenario)
    finally:
        release.cancel()
        handle.close()
    assert time.monotonic() - started < 15.0
    assert result.summary["solution"]["stored"] is None
    assert "another process" in result.summary["solution"]["not_stored_because"]


def test_a_full_disk_keeps_the_answer_with_a_warning_and_leaves_no_file(place, monkeypatch):
    """42.8: EFBIG while writing the store: the solution is answered (the same as one stored), with a warning."""
    def full(*args, **kwargs):
        raise OSError(errno.EFBIG, "File too large")

    monkeypatch.setattr(np, "savez", full)
    with pytest.warns(UserWarning, match="not stored"):
        answered = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    assert not list(place.iterdir()) or all(p.suffix in (".lock", ".json") for p in place.iterdir())
    monkeypatch.undo()
    store.PLACE["directory"] = place
    stored = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    t = np.linspace(0.0, 4.0, 9)
    from spinorbit.base.rotations import quat_angle

    assert quat_angle(answered.part("moon.q", t), stored.part("moon.q", t)).max() < 1e-3 * uas


def test_cache_clear_keeps_a_solution_another_process_holds(place, capsys):
    """42.12: the stored solution and its lock stay while its lock is held; freed, they go."""
    solution = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    handle = open(verified.lock_path(solution.path), "w")
    fcntl.flock(handle, fcntl.LOCK_EX)
    store.clear()
    assert solution.path.exists() and verified.lock_path(solution.path).exists()
    assert "kept" in capsys.readouterr().out
    handle.close()
    store.clear()
    assert not solution.path.exists()


def test_solution_at_refuses_masked_dates():
    """42.13: as its error text (and the API) says."""
    from astropy.time import Time

    from spinorbit.solutions.solution import tdb_days

    times = Time(np.ma.masked_array([2451545.0, 2451546.0], mask=[False, True]), format="jd", scale="tdb")
    with pytest.raises(InputError, match="masked"):
        tdb_days(times)


def test_reversed_dates_are_matched_to_rows_at_once():
    """42.14: 10^5 dates in reverse order matched to the table's rows (closest date) as fast as in order."""
    from spinorbit.edge.api import _rows

    days = np.linspace(0.0, 100.0, 100_000)
    t = days[::-1].copy()
    started = time.perf_counter()
    rows = _rows(t, t)
    assert time.perf_counter() - started < 2.0          # the per-date search took 20 s
    assert np.array_equal(rows, np.arange(t.size))
    shuffled = np.random.default_rng(1).permutation(t)
    assert np.array_equal(t[_rows(t, shuffled)], shuffled)


def test_a_read_error_that_is_not_the_files_keeps_the_file(place, monkeypatch):
    """42.14: EIO or EMFILE say nothing about the file: it stays, and the answer comes without the store."""
    solution = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    store.VERIFIED.clear()

    def failing(*args, **kwargs):
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(verified, "open_regular", failing)
    monkeypatch.setattr(store, "open_regular", failing, raising=False)
    with pytest.warns(UserWarning, match="Input/output error"):
        again = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    assert solution.path.exists()
    assert np.array_equal(again.segments.coefficients, solution.segments.coefficients)


def test_the_store_keeps_within_its_size_bound_oldest_first(place, monkeypatch):
    """42.14: files beyond the bound go, least recently written first; the one just written stays."""
    old = [place / f"moon_libration-old{k}.npz" for k in range(3)]
    for k, path in enumerate(old):
        path.write_bytes(b"\0" * 400_000)
        os.utime(path, ns=(k * 10**9, k * 10**9))
    monkeypatch.setitem(store.LIMIT, "bytes", 500_000)
    solution = solutions.for_scenario(load_scenario("moon_libration"), 0.0, 4.0)
    assert solution.path.exists()
    assert [p.exists() for p in old] == [False, False, True]
