"""A Solution exported as SPICE kernels and read back by spiceypy and skyfield: the Moon's orientation (binary PCK
type 2 + frame kernel) and the integrated geocentric Moon (SPK type 2) reproduce the solution within 1 uas and
1 mm."""
import numpy as np
import pytest

from spinorbit import solutions
from spinorbit.analysis.librations import icrf_to_body
from spinorbit.constants import DAY_S
from spinorbit.solutions import store
from tests.units import arcsec

spiceypy = pytest.importorskip("spiceypy")
uas = arcsec * 1e-6


@pytest.fixture
def place(tmp_path, monkeypatch):
    monkeypatch.setitem(store.PLACE, "directory", tmp_path / "store")
    (tmp_path / "store").mkdir()
    return tmp_path


def rotation_angle(a, b):
    """Angle (rad) between rotation matrices (n, 3, 3), accurate for small angles."""
    return np.linalg.norm(a - b, axis=(1, 2)) / np.sqrt(2.0)


@pytest.fixture
def moon_kernels(place):
    solution = solutions.solve("moon_libration", [], -20.0, 60.0)
    written = solution.export(place / "out")
    yield solution, written
    spiceypy.kclear()


def test_the_moon_read_back_by_spiceypy_matches_the_solution(moon_kernels):
    solution, written = moon_kernels
    assert written["fit_error"]["moon_angles_arcsec"] < 1e-6
    for path in written["files"]:
        spiceypy.furnsh(path)
    t = np.random.default_rng(5).uniform(*solution.span, 100)
    read = np.array([spiceypy.pxform("J2000", "MOON_PA_SPINORBIT", ti * DAY_S) for ti in t])
    assert rotation_angle(read, icrf_to_body(solution.part("moon.q", t))).max() < 1 * uas


def test_the_moon_read_back_by_skyfield_matches_the_solution(moon_kernels):
    """skyfield's reader at a two-part TDB date (J2000 + days) within 1 uas; its ``Frame.rotation_at(t)`` reads
    the date as one float JD, whose spacing near J2000 (2^-31 d, 40 us) turns the Moon by up to 1.1e-10 rad: the
    bound there is 1 uas plus that rounding."""
    from skyfield.api import load
    from skyfield.functions import mxm, rot_x, rot_z
    from skyfield.planetarylib import PlanetaryConstants

    solution, written = moon_kernels
    constants = PlanetaryConstants()
    constants.read_text(load.open([f for f in written["files"] if f.endswith(".tf")][0]))
    constants.read_binary(load.open([f for f in written["files"] if f.endswith(".bpc")][0]))
    frame = constants.build_frame_named("MOON_PA_SPINORBIT")
    t = np.random.default_rng(6).uniform(*solution.span, 50)
    expected = icrf_to_body(solution.part("moon.q", t))
    angles = [frame._segment.compute(2451545.0, ti, False) for ti in t]
    two_part = np.array([mxm(rot_z(-w), mxm(rot_x(-dec), rot_z(-ra))) for ra, dec, w in angles])
    assert rotation_angle(two_part, expected).max() < 1 * uas
    times = load.timescale().tdb_jd(2451545.0 + t)
    read = np.array([frame.rotation_at(ti) for ti in times])
    rounding = 2 * np.pi / 27.3217 * np.spacing(2451545.0)                # rad: the Moon's turn in one JD ulp
    assert rotation_angle(read, expected).max() < 1 * uas + rounding


def test_the_integrated_moons_position_read_back_by_spiceypy_matches_the_solution(place):
    solution = solutions.solve("earth_moon_coupled", [], 0.0, 40.0)
    written = solution.export(place / "out")
    try:
        for path in written["files"]:
            spiceypy.furnsh(path)
        t = np.random.default_rng(7).uniform(*solution.span, 100)
        read = np.array([spiceypy.spkpos("301", ti * DAY_S, "J2000", "NONE", "399")[0] for ti in t])
        assert np.linalg.norm(read - solution.part("moon.r", t), axis=1).max() < 1e-6      # km: 1 mm
    finally:
        spiceypy.kclear()


def test_spinorbit_export_writes_the_scenes_kernels(place, capsys):
    from spinorbit import cli

    out = place / "kernels"
    assert cli.main(["export", "moon_libration", "--set", "span.start=2000-01-01T12:00:00",
                     "--set", "span.end=2000-01-21T12:00:00", "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["moon_libration_moon.bpc", "moon_libration_moon.tf"]
    assert "fit errors" in capsys.readouterr().out
