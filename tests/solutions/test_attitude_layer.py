"""A gyroscopic body's attitude from its stored spin (spinorbit.solutions.attitude_layer), Mars's: against the scene's
own run (its figure axes, its prime meridian integrated on the output grid), exported as a binary PCK of type 2
with its frame kernel and read back by spiceypy and skyfield within 1 uas, and answered by
``spinorbit.orientation``."""
import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit import solutions
from spinorbit.base.constants import DAY_S
from spinorbit.base.errors import InputError
from spinorbit.base.rotations import matrix_from_euler313
from spinorbit.edge.runner import run_scenario
from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import store
from spinorbit.solutions.spice import FRAME_BASE, body_angles
from tests.units import arcsec, deg, mas

spiceypy = pytest.importorskip("spiceypy")
uas = arcsec * 1e-6
SPAN = ["span.start=1999-01-01", "span.end=2001-01-01"]
DECADES = ["span.start=1990-01-01", "span.end=2010-01-01"]


@pytest.fixture(scope="module")
def mars(tmp_path_factory):
    """The stored Mars solution over 1990-2010 (a private store), its attitude layer and its kernels."""
    place = tmp_path_factory.mktemp("mars")
    saved = dict(store.PLACE)
    store.PLACE["directory"] = place / "store"
    (place / "store").mkdir()
    scenario = load_scenario("mars_orientation", DECADES)
    layer = solutions.for_export(scenario)
    written = layer.export(place / "out")
    yield scenario, layer, written
    store.PLACE.clear()
    store.PLACE.update(saved)
    spiceypy.kclear()


def wrapped(angle):
    """|angle| in [0, pi]."""
    return np.abs(np.angle(np.exp(1j * angle)))


def rotation_angle(a, b):
    return np.linalg.norm(a - b, axis=(1, 2)) / np.sqrt(2.0)


def test_the_layer_is_the_scenes_run(mars):
    """The pole the scene's run reports (its figure axes) within 1 uas, and its prime meridian (the same
    kinematics integrated by trapezoids on a 0.25-d grid: their error, (h w)^2 / 12 of the nutation's share of
    W, is under 0.01 mas) within 0.05 mas."""
    _, layer, _ = mars
    run = run_scenario("mars_orientation", [*SPAN, "span.step=0.25 d", "output.plots=false",
                                            "integrator.estimate_error=false"])
    t = run.states.t
    angles = body_angles(layer, "mars", t)
    ra, dec = (np.radians(np.asarray(run.table[k].value, dtype=float)) for k in ("pole_ra", "pole_dec"))
    assert np.max(wrapped(angles[:, 0] - np.pi / 2 - ra) * np.cos(dec)) < 1 * uas
    assert np.max(np.abs(angles[:, 1] - (np.pi / 2 - dec))) < 1 * uas
    w = np.radians(np.asarray(run.table["prime_meridian"].value, dtype=float))
    assert np.max(wrapped(angles[:, 2] - w)) < 0.05 * mas


def test_the_pck_read_back_by_spiceypy_matches_the_layer(mars):
    """A frame of its own (MARS_PM_SPINORBIT_<id>, an ID in NAIF's users' range, above JPL's) within 1 uas over
    1990-2010 (W turns by 2e4 rad in 10 years: turned_part keeps it to the last bit), at dates whose TDB seconds
    are exact doubles (a day count rounded to its last bit turns Mars by up to 0.7 uas in 2010)."""
    _, layer, written = mars
    frame = written["frames"]["mars"]
    assert frame.startswith("MARS_PM_SPINORBIT_") and written["fit_error"]["mars_angles_arcsec"] < 1e-6
    for path in written["files"]:
        spiceypy.furnsh(str(path))
    assert FRAME_BASE <= spiceypy.namfrm(frame) < 2_000_000
    t = np.round(np.random.default_rng(7).uniform(*layer.span, 100) * 2 ** 20) / 2 ** 20   # x 86400 exact:
    read = np.array([spiceypy.pxform("J2000", frame, ti * DAY_S) for ti in t])    # SPICE reads the same instant
    assert rotation_angle(read, matrix_from_euler313(*body_angles(layer, "mars", t).T)).max() < 1 * uas


def test_the_pck_read_back_by_skyfield_matches_the_layer(mars):
    """skyfield at a two-part TDB date (J2000 + days whose seconds are exact) within 1 uas;
    ``Frame.rotation_at(t)`` reads one float JD, whose spacing near J2000 (2^-31 d) turns Mars by up to 2.9e-9
    rad: 1 uas plus that there."""
    from skyfield.api import load
    from skyfield.functions import mxm, rot_x, rot_z
    from skyfield.planetarylib import PlanetaryConstants

    _, layer, written = mars
    constants = PlanetaryConstants()
    constants.read_text(load.open([f for f in written["files"] if f.endswith(".tf")][0]))
    constants.read_binary(load.open([f for f in written["files"] if f.endswith(".bpc")][0]))
    frame = constants.build_frame_named(written["frames"]["mars"])
    t = np.round(np.random.default_rng(8).uniform(*layer.span, 50) * 2 ** 20) / 2 ** 20   # seconds exact
    expected = matrix_from_euler313(*body_angles(layer, "mars", t).T)
    angles = [frame._segment.compute(2451545.0, ti, False) for ti in t]
    two_part = np.array([mxm(rot_z(-w), mxm(rot_x(-dec), rot_z(-ra))) for ra, dec, w in angles])
    assert rotation_angle(two_part, expected).max() < 1 * uas
    read = np.array([frame.rotation_at(ti) for ti in load.timescale().tdb_jd(2451545.0 + t)])
    rounding = np.radians(350.892) * np.spacing(2451545.0)
    assert rotation_angle(read, expected).max() < 1 * uas + rounding


def test_orientation_answers_mars_from_the_layer(mars):
    """spinorbit.orientation("mars", ...) gives the layer's pole and W at the dates (the same stored solution),
    and its pole within the scene's 0.3 arcsec of IAU 2015's; an unknown body is refused in one line."""
    _, layer, _ = mars
    when = Time(["1999-06-01", "2000-03-01T06:00:00"], scale="tdb")
    answer = spinorbit.orientation("mars", when)
    angles = body_angles(layer, "mars", when.tdb.jd - 2451545.0)
    assert np.max(wrapped(np.radians(answer["pole_ra"].value) - angles[:, 0] + np.pi / 2)) < 1 * uas
    assert np.max(wrapped(np.radians(answer["pole_dec"].value) - np.pi / 2 + angles[:, 1])) < 1 * uas
    assert np.max(wrapped(np.radians(answer["prime_meridian"].value) - angles[:, 2])) < 1 * uas
    assert np.all(answer["pole_minus_iau2015"].value * arcsec < 0.3 * arcsec)
    assert answer.meta["expected_accuracy"]["pole_arcsec"] == 0.3
    with pytest.raises(InputError, match="body.*venus.*mars"):
        spinorbit.orientation("venus", when)


def test_turned_part_is_exact_to_the_last_bit():
    """rate x days modulo 2 pi against exact decimal arithmetic, to 1e-15 rad over +-100 years of Mars's turn."""
    from decimal import Decimal, getcontext

    from spinorbit.solutions.attitude_layer import turned_part

    getcontext().prec = 50
    two_pi = 2 * Decimal("3.14159265358979323846264338327950288419716939937510")
    rate, days = 6.124216737, np.array([4.0, 18260.0, -18268.0, 36524.0, -36516.0])
    for d, got in zip(days, turned_part(rate, days)):
        exact = Decimal(rate) * Decimal(d)
        exact -= two_pi * (exact / two_pi).to_integral_value()
        assert abs(float(Decimal(got) - exact)) < 1e-15


def test_spinorbit_at_mars_prints_the_answer(mars, capsys):
    """`spinorbit at mars DATE`: the API's row as CSV, units in the header."""
    from spinorbit.edge.cli import main

    assert main(["--quiet", "at", "mars", "2000-06-01T00:00", "--scale", "tdb"]) == 0
    header, row = (line.split(",") for line in capsys.readouterr().out.splitlines()[:2])
    answer = spinorbit.orientation("mars", Time(["2000-06-01T00:00"], scale="tdb"))
    for name, unit in (("pole_ra", "deg"), ("pole_dec", "deg"), ("prime_meridian", "deg")):
        assert float(row[header.index(f"{name} [{unit}]")]) * deg == pytest.approx(answer[name].value[0] * deg,
                                                                                   abs=1 * uas)
