"""A Solution exported as SPICE kernels and read back by spiceypy and skyfield: the Moon's orientation (binary PCK
type 2 + a frame kernel naming it per solution) and the positions of an integrated system's bodies (SPK type 2:
the closed Earth-Moon's Moon and Earth about their barycentre and that barycentre about 0 from DE421; the solar
system's every body about 0 and the Earth-Moon barycentre, each on DE421's record length) reproduce the solution
within 1 uas and 1 mm plus each track's stated refit error -- or, for a barycentric outer planet, within what two
sums of the same series in doubles can differ by; the solar system's read back against DE421 within its scene's
tolerances.  ``spinorbit export`` writes exactly the model and span asked, comment lines dafec reads, and
nothing outside --out however long."""
import numpy as np
import pytest

from spinorbit import solutions
from spinorbit.analysis.librations import icrf_to_body
from spinorbit.base.constants import DAY_S
from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import store
from tests.units import arcsec

spiceypy = pytest.importorskip("spiceypy")
uas = arcsec * 1e-6
mm = 1e-6                                   # km
DE421_EPOCH = -11144.5                      # TDB days: DE421's JDEPOC, where the solar system's solution starts


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
    solution = solutions.for_scenario(load_scenario("moon_libration"), -20.0, 60.0)
    written = solution.export(place / "out")
    yield solution, written
    spiceypy.kclear()


def test_the_moon_read_back_by_spiceypy_matches_the_solution(moon_kernels):
    solution, written = moon_kernels
    assert written["fit_error"]["moon_angles_arcsec"] < 1e-6
    for path in written["files"]:
        spiceypy.furnsh(str(path))
    t = np.random.default_rng(5).uniform(*solution.span, 100)
    read = np.array([spiceypy.pxform("J2000", written["frames"]["moon"], ti * DAY_S) for ti in t])
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
    frame = constants.build_frame_named(written["frames"]["moon"])
    t = np.random.default_rng(6).uniform(*solution.span, 50)
    expected = icrf_to_body(solution.part("moon.q", t))
    angles = [frame._segment.compute(2451545.0, ti, False) for ti in t]
    two_part = np.array([mxm(rot_z(-w), mxm(rot_x(-dec), rot_z(-ra))) for ra, dec, w in angles])
    assert rotation_angle(two_part, expected).max() < 1 * uas
    times = load.timescale().tdb_jd(2451545.0 + t)
    read = np.array([frame.rotation_at(ti) for ti in times])
    rounding = 2 * np.pi / 27.3217 * np.spacing(2451545.0)                # rad: the Moon's turn in one JD ulp
    assert rotation_angle(read, expected).max() < 1 * uas + rounding


def exact_dates(span, count, seed):
    """``count`` TDB days in ``span`` whose seconds (x 86400) are exact doubles: SPICE and the solution are read at
    the same instant (a day count rounded to its last bit moves Mercury by up to 4 mm far from J2000)."""
    t = np.round(np.random.default_rng(seed).uniform(*span, count) * 2 ** 20) / 2 ** 20
    assert np.array_equal(t * DAY_S / DAY_S, t)
    return np.clip(t, *span)


def summing_floor(r, degree):
    """km: what two sums of one Chebyshev series of degree ``degree`` in doubles can differ by at values of size
    |r| ((degree + 1) roundings of the largest term), or 1 mm where that is less."""
    return np.maximum(1 * mm, (degree + 1) * np.finfo(float).eps * np.linalg.norm(r, axis=1).max())


def segments_of(path):
    """{(centre, target): jplephem segment} of an SPK."""
    from jplephem.spk import SPK

    with SPK.open(str(path)) as kernel:
        return {(s.center, s.target): (s.frame, s.data_type, s.start_second, s.end_second) for s in kernel.segments}


def test_the_closed_earth_moon_read_back_by_spiceypy_and_skyfield_matches_the_solution(place):
    """The Moon and the Earth about their barycentre (3), as DE421 writes them, and that barycentre about 0 from
    the run's ephemeris (DE421), fitted on its own records: the file alone takes skyfield from the barycentre to
    the Moon.  The geocentric Moon is the integrated one within 1 mm by either reader and DE421's within the
    scene's 1" and 2 km; the barycentre DE421's within its stated fit error (and a summing floor of 1 mm)."""
    from skyfield.api import load
    from skyfield.jpllib import SpiceKernel

    from spinorbit.comparisons import earth_moon_de421
    from spinorbit.orbits.kernel import open_ephemeris

    solution = solutions.for_scenario(load_scenario("earth_moon_coupled"), 0.0, 40.0)
    written = solution.export(place / "out")
    bsp = next(f for f in written["files"] if f.endswith(".bsp"))
    first, last = (d * DAY_S for d in solution.span)
    assert segments_of(bsp) == {(3, 301): (1, 2, first, last), (3, 399): (1, 2, first, last),
                                (0, 3): (1, 2, first, last)}
    t = exact_dates(solution.span, 100, 7)
    truth = solution.part("moon.r", t)
    try:
        for path in written["files"]:
            spiceypy.furnsh(path)
        read = np.array([spiceypy.spkpos("MOON", ti * DAY_S, "J2000", "NONE", "EARTH")[0] for ti in t])
        assert np.linalg.norm(read - truth, axis=1).max() < 1 * mm
    finally:
        spiceypy.kclear()
    kernel = SpiceKernel(bsp)
    try:
        at = load.timescale().tdb_jd(2451545.0, t)
        by_skyfield = (kernel["moon"] - kernel["earth"]).at(at).position.km.T
        barycentre = kernel[3].at(at).position.km.T
    finally:
        kernel.close()
    assert np.linalg.norm(by_skyfield - truth, axis=1).max() < 1 * mm
    direction, distance = earth_moon_de421.orbit_errors(t, by_skyfield)
    assert direction.max() < 1 * arcsec and np.abs(distance).max() < 2.0
    de421 = open_ephemeris("de421", *solution.span).relative_states("earth_moon_barycenter",
                                                                     "solar_system_barycenter", t)[0]
    fit = written["fit_error"]["earth_moon_barycenter_position_km"]
    assert np.linalg.norm(barycentre - de421, axis=1).max() < fit + 1 * mm


@pytest.fixture(scope="module")
def solar_system(tmp_path_factory):
    """The solar system's solution over 60 days about DE421's epoch, exported; the store kept for the module."""
    place = tmp_path_factory.mktemp("solar")
    with pytest.MonkeyPatch.context() as patch:
        patch.setitem(store.PLACE, "directory", place / "store")
        (place / "store").mkdir()
        solution = solutions.for_scenario(load_scenario("solar_system"), DE421_EPOCH - 20.0, DE421_EPOCH + 40.0)
        written = solution.export(place / "out")
        yield solution, written, place
    spiceypy.kclear()


def carried(solution, t):
    """{NAIF code: (n, 3) km about the solar-system barycentre} of every body the solution carries: the free ones
    as integrated, the Earth and the Moon from their barycentre by the model's own mass ratio (its System's)."""
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.solutions import stretches

    share = stretches.system(load_scenario("solar_system", []), solution.ends["start"]).motion.share
    codes = {"sun": 10, "mercury": 1, "venus": 2, "mars": 4, "jupiter": 5, "saturn": 6, "uranus": 7,
             "neptune": 8, "pluto": 9, "earth_moon_barycenter": 3}
    out = {code: solution.part(f"{name}.r", t) for name, code in codes.items()}
    moon = solution.part("moon.r", t)
    out.update({301: out[3] + (1 - share) * moon, 399: out[3] - share * moon})
    return out


NAMES = {10: "sun", 1: "mercury", 2: "venus", 4: "mars", 5: "jupiter", 6: "saturn", 7: "uranus", 8: "neptune",
         9: "pluto", 3: "earth_moon_barycenter", 301: "earth_moon_barycenter", 399: "earth_moon_barycenter"}


def within(written, code, truth, solution):
    """km: what the SPK may differ from the solution by for body ``code`` about 0: its track's stated fit error
    (the Moon and the Earth: their barycentre's; they are the solution's own about it) plus the summing floor."""
    return written["fit_error"][f"{NAMES[code]}_position_km"] + summing_floor(truth, solution.segments.degree)


def furnished(files):
    for path in files:
        spiceypy.furnsh(str(path))


def test_the_solar_system_is_stored_from_de421s_epoch(solar_system):
    from spinorbit.base.constants import J2000_JD
    from spinorbit.bodies.de421_header import header
    from spinorbit.scenes import scene_of

    solution, _, _ = solar_system
    assert scene_of("solar_system").stored.anchor == header()["JDEPOC"] - J2000_JD
    assert [run["start_tdb_d"] for run in solution.provenance["runs"]] == [DE421_EPOCH]


def test_the_solar_systems_spk_is_laid_out_as_de421s(solar_system):
    """Every body about the barycentre (0), the Moon and the Earth about theirs (3); J2000 (1), type 2, the
    solution's span in TDB seconds past J2000, on DE421's record lengths (the span, 64 d, holds a whole number of
    each); each track's fit within 1 mm or its rounding floor; the comment area names the scene, its keys, the
    code, each body's fit and its distance from DE421."""
    from jplephem.spk import SPK

    from spinorbit.orbits.kernel import kernel_path

    solution, written, _ = solar_system
    bsp = next(f for f in written["files"] if f.endswith(".bsp"))
    first, last = (d * DAY_S for d in solution.span)
    expected = {(0, code) for code in (10, 1, 2, 4, 5, 6, 7, 8, 9, 3)} | {(3, 301), (3, 399)}
    assert segments_of(bsp) == {pair: (1, 2, first, last) for pair in expected}
    assert last - first == 64 * DAY_S
    with SPK.open(str(bsp)) as ours, SPK.open(str(kernel_path("de421"))) as de421:
        lengths = {(s.center, s.target): s.load_array()[1] for s in de421.segments}
        assert {(s.center, s.target): s.load_array()[1] for s in ours.segments} == {p: lengths[p] for p in expected}
    for name, error in written["fit_error"].items():
        if name.endswith("_position_km"):
            size = np.linalg.norm(solution.part(name.replace("_position_km", ".r"), solution.span), axis=1).max() \
                if name.split("_position")[0] not in ("moon", "earth") else 0.0
            assert error < max(1 * mm, 15 * np.finfo(float).eps * size), name
    text = " ".join(comment_lines(bsp))
    assert "'solar_system' scene" in text and store.code_version() in text and 'start.epoch = "de421"' in text
    assert "mercury (1 about 0): 8 records of 8 d, degree 13" in text and "from DE421's, heliocentric" in text


def comment_lines(path):
    """The comment area of a DAF kernel as spiceypy.dafec reads it (lines of at most 80 characters: a longer one
    is SPICE(COMMENTTOOLONG)), every line read."""
    handle = spiceypy.dafopr(str(path))
    try:
        count, lines, done = spiceypy.dafec(handle, 1000, 81)
    finally:
        spiceypy.dafcls(handle)
    assert done and count < 1000
    return lines[:count]


def test_the_solar_system_read_back_by_spiceypy_matches_the_solution(solar_system):
    solution, written, _ = solar_system
    t = exact_dates(solution.span, 200, 9)
    furnished(written["files"])
    try:
        for code, truth in carried(solution, t).items():
            read = np.array([spiceypy.spkpos(str(code), ti * DAY_S, "J2000", "NONE", "0")[0] for ti in t])
            assert np.linalg.norm(read - truth, axis=1).max() < within(written, code, truth, solution), code
        moon = np.array([spiceypy.spkezr("MOON", ti * DAY_S, "J2000", "NONE", "EARTH")[0] for ti in t])
        assert np.linalg.norm(moon[:, :3] - solution.part("moon.r", t), axis=1).max() < 1 * mm
        # SPK type 2's velocity is the series' derivative: a 1 mm error's is at most degree^2 / (L / 2) times it
        # (Markov's inequality), 1e-3 mm/s on 4-d segments of degree 13
        markov = solution.segments.degree ** 2 / (solution.segments.length_d * DAY_S / 2) * mm
        assert np.linalg.norm(moon[:, 3:] - solution.part("moon.v", t) / DAY_S, axis=1).max() < markov
    finally:
        spiceypy.kclear()


def test_the_solar_system_read_back_by_skyfield_matches_the_solution(solar_system):
    from skyfield.api import load
    from skyfield.jpllib import SpiceKernel

    solution, written, _ = solar_system
    kernel = SpiceKernel(next(f for f in written["files"] if f.endswith(".bsp")))
    t = exact_dates(solution.span, 200, 10)
    at = load.timescale().tdb_jd(2451545.0, t)
    try:
        for code, truth in carried(solution, t).items():
            read = kernel[code].at(at).position.km.T
            assert np.linalg.norm(read - truth, axis=1).max() < within(written, code, truth, solution), code
        moon = (kernel["moon"] - kernel["earth"]).at(at).position.km.T
    finally:
        kernel.close()
    assert np.linalg.norm(moon - solution.part("moon.r", t), axis=1).max() < 1 * mm


def test_the_solar_system_read_back_agrees_with_de421_within_its_scenes_tolerances(solar_system):
    """Started from DE421's initial conditions: 60 days on, the Moon read back within the scene's 1 mas and
    0.1 m, the lunar pole and longitude within 1 mas, each planet within twice what DE421's asteroids move it."""
    from spinorbit.analysis.librations import pole_and_longitude_difference
    from spinorbit.comparisons import earth_moon_de421, solar_system_de421
    from spinorbit.references.moon_de421 import Orientation
    from tests.units import mas

    solution, written, _ = solar_system
    t = exact_dates(solution.span, 60, 11)
    furnished(written["files"])
    try:
        moon = np.array([spiceypy.spkpos("MOON", ti * DAY_S, "J2000", "NONE", "EARTH")[0] for ti in t])
        mats = np.array([spiceypy.pxform("J2000", written["frames"]["moon"], ti * DAY_S) for ti in t])
        planets = {name: np.array([spiceypy.spkpos(str(code), ti * DAY_S, "J2000", "NONE", "SUN")[0]
                                   for ti in t])
                   for name, code in (("mercury", 1), ("venus", 2), ("earth", 399), ("mars", 4), ("jupiter", 5),
                                      ("saturn", 6), ("uranus", 7), ("neptune", 8), ("pluto", 9))}
    finally:
        spiceypy.kclear()
    direction, distance = earth_moon_de421.orbit_errors(t, moon)
    assert direction.max() < 1 * mas and np.abs(distance).max() < 1e-4           # km: 0.1 m
    pole, longitude = pole_and_longitude_difference(mats, Orientation()(t)["icrf_to_body"])
    assert np.abs(pole).max() < 1 * mas and np.abs(longitude).max() < 1 * mas
    for name, error in solar_system_de421.planet_errors(t, planets).items():
        assert error.max() < 2 * solar_system_de421.ASTEROIDS_KM[name], name


def test_the_solar_system_extended_equals_one_computed_whole(solar_system, tmp_path):
    """Extended forward from where the stored run stopped, the same as a run over the whole span from DE421's
    epoch: each body within 1e-13 of its distance (the Taylor integrator's 1e-15 per step over the ~100 steps
    of 100 days, with room)."""
    solution, _, place = solar_system
    with pytest.MonkeyPatch.context() as patch:
        patch.setitem(store.PLACE, "directory", place / "store")
        extended = solutions.for_scenario(load_scenario("solar_system"), DE421_EPOCH - 20.0, DE421_EPOCH + 80.0)
        patch.setitem(store.PLACE, "directory", tmp_path)
        whole = solutions.for_scenario(load_scenario("solar_system"), DE421_EPOCH - 20.0, DE421_EPOCH + 80.0)
    assert len(extended.provenance["runs"]) == 2 and len(whole.provenance["runs"]) == 1
    assert extended.span == whole.span
    t = np.linspace(solution.span[1], extended.span[1], 200)
    for part in whole.layout.slices:
        if part.name.endswith(".r"):
            a, b = extended.part(part.name, t), whole.part(part.name, t)
            assert (np.linalg.norm(a - b, axis=1) / np.linalg.norm(b, axis=1)).max() < 1e-13, part.name


def test_spinorbit_export_writes_the_scenes_kernels(place, capsys):
    from spinorbit.edge import cli

    out = place / "kernels"
    assert cli.main(["export", "moon_libration", "--set", "span.start=2000-01-01T12:00:00",
                     "--set", "span.end=2000-01-21T12:00:00", "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["moon_libration_moon.bpc", "moon_libration_moon.tf"]
    assert "fit errors" in capsys.readouterr().out


def test_spinorbit_export_writes_the_solar_systems_kernels_from_its_store(solar_system, capsys):
    from spinorbit.edge import cli

    _, _, place = solar_system
    out = place / "kernels"
    with pytest.MonkeyPatch.context() as patch:
        patch.setitem(store.PLACE, "directory", place / "store")
        assert cli.main(["export", "solar_system", "--set", "span.start=1969-06-28T00:00:00",
                         "--set", "span.end=1969-07-28T00:00:00", "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["solar_system.bsp", "solar_system_moon.bpc",
                                                     "solar_system_moon.tf"]
    assert "solar_system solution" not in capsys.readouterr().err              # read from the store: no run


def test_spinorbit_export_refuses_a_scene_without_kernels_before_integrating(tmp_path, capsys, monkeypatch):
    from spinorbit import solutions as package
    from spinorbit.edge import cli

    monkeypatch.setattr(package, "for_export", lambda *a, **k: pytest.fail("integrated before refusing"))
    assert cli.main(["export", "earth_precession_nutation", "--out", str(tmp_path / "k")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "earth_precession_nutation" in err and "moon_libration" in err
    assert not (tmp_path / "k").exists()


def test_a_solution_with_nothing_spice_holds_is_refused_in_one_line(tmp_path):
    from spinorbit.base.errors import InputError
    from spinorbit.base.layout import Layout
    from spinorbit.solutions.chebyshev import Segments

    pole = solutions.Solution(Segments(0.0, 8.0, 0, np.zeros((1, 3, 15))), Layout([("earth.pole", 3, "vector", "")]),
                              {"scene": "earth_precession_nutation"}, {})
    with pytest.raises(InputError, match="earth_precession_nutation.*earth.pole.*an attitude"):
        pole.export(tmp_path / "out")
    assert not (tmp_path / "out").exists()


def frame_rotations(written, t):
    """spiceypy's J2000-to-frame rotations at TDB days ``t`` of the exported solution ``written``'s Moon."""
    return np.array([spiceypy.pxform("J2000", written["frames"]["moon"], ti * DAY_S) for ti in t])


def pck_cover(path, written):
    """(first, last) TDB days the PCK at ``path`` covers for the exported frame."""
    frame = int(spiceypy.gipool(f"FRAME_{written['frames']['moon']}", 0, 1)[0])
    cell = spiceypy.stypes.SPICEDOUBLE_CELL(10)
    spiceypy.pckcov(str(path), frame, cell)
    return tuple(np.array(spiceypy.wnfetd(cell, 0)) / DAY_S)


def test_a_key_that_starts_the_model_elsewhere_exports_that_model_over_the_span_asked(place):
    """``model.start`` starts the Moon from DE421's state at that date (its scene's start): exported, the frame
    there is DE421's within 1 uas (the J2000-started stored solution is 0.35 mas from it then), the PCK covers the
    span asked (7 days), and the comments name every key asked."""
    from spinorbit.analysis.librations import pole_and_longitude_difference
    from spinorbit.edge import cli
    from spinorbit.references.moon_de421 import Orientation

    out = place / "kernels"
    asked = ["--set", "span.start=2000-12-01T00:00:00", "--set", "span.end=2000-12-08T00:00:00",
             "--set", "model.start=2000-12-01T00:00:00"]
    assert cli.main(["export", "moon_libration", *asked, "--out", str(out)]) == 0
    start = 334.5                                       # TDB days: 2000-12-01T00:00 TDB
    pck, frame_kernel = out / "moon_libration_moon.bpc", out / "moon_libration_moon.tf"
    try:
        furnished([pck, frame_kernel])
        written = {"frames": {"moon": frame_kernel.read_text().split("FRAME_")[1].split(" =")[0]}}
        assert pck_cover(pck, written) == (start, start + 7.0)
        pole, longitude = pole_and_longitude_difference(frame_rotations(written, [start]),
                                                        Orientation()([start])["icrf_to_body"])
    finally:
        spiceypy.kclear()
    assert abs(pole[0]) < 1 * uas and abs(longitude[0]) < 1 * uas
    text = "\n".join(comment_lines(pck))
    assert f"model.start = {start}" in text and f"span.end = {start + 7.0}" in text      # as loaded: TDB days


def test_an_export_writes_the_segments_covering_its_span_whatever_the_store_holds(moon_kernels, place):
    """The store holds -20..60 d; asked 10..17 d, the PCK covers the 4-d segments 8..20 d, no more."""
    from spinorbit.edge import cli

    solution, written = moon_kernels
    out = place / "week"
    assert cli.main(["export", "moon_libration", "--set", "span.start=2000-01-11T12:00:00",
                     "--set", "span.end=2000-01-18T12:00:00", "--out", str(out)]) == 0
    assert solution.span == (-20.0, 60.0)
    try:
        furnished([out / "moon_libration_moon.tf"])
        assert pck_cover(out / "moon_libration_moon.bpc", written) == (8.0, 20.0)
    finally:
        spiceypy.kclear()


def test_two_exported_solutions_loaded_together_each_read_in_its_own_frame(moon_kernels, place):
    """The J2000-started solution and one started at 2000-01-21 (another model: 0.1 mas from it a week on), loaded
    together: each frame gives its own solution within 1 uas, under its own name and ID."""
    from spinorbit.edge.scenarios import load_scenario

    solution, written = moon_kernels
    restarted = solutions.for_export(load_scenario("moon_libration", [
        "span.start=2000-01-21T12:00:00", "span.end=2000-01-28T12:00:00", "model.start=2000-01-21T12:00:00"]))
    other = restarted.export(place / "other")
    assert other["frames"]["moon"] != written["frames"]["moon"]
    t = np.linspace(20.0, 27.0, 15)
    try:
        furnished(written["files"] + other["files"])
        ids = {int(spiceypy.gipool(f"FRAME_{w['frames']['moon']}", 0, 1)[0]) for w in (written, other)}
        first, second = frame_rotations(written, t), frame_rotations(other, t)
    finally:
        spiceypy.kclear()
    assert len(ids) == 2 and all(1_400_000 <= i < 2_000_000 for i in ids)
    assert rotation_angle(first, icrf_to_body(solution.part("moon.q", t))).max() < 1 * uas
    assert rotation_angle(second, icrf_to_body(restarted.part("moon.q", t))).max() < 1 * uas
    assert rotation_angle(first, second).max() > 10 * uas


def test_every_comment_line_reads_back_with_dafec(moon_kernels):
    """Every kernel's comment lines (and the frame kernel's) are at most 80 characters; the Moon's PCK names every
    key of its model."""
    _, written = moon_kernels
    text = comment_lines(next(f for f in written["files"] if f.endswith(".bpc")))
    assert max(map(len, text)) <= 80 and "  keys.model.level = 3" in text
    frame_kernel = next(f for f in written["files"] if f.endswith(".tf"))
    assert max(len(line) for line in open(frame_kernel).read().splitlines()) <= 80


def test_export_to_a_folder_path_spice_cannot_name_writes_only_there(moon_kernels, place, capsys):
    """An --out of 262 characters (SPICE cuts a file name at 255): the kernels are in it and nothing is written
    anywhere else; a name the system cannot hold is refused in one line naming --out."""
    from spinorbit.edge import cli

    root = place / "long"
    out = root.joinpath(*["d" * 50] * 5)
    week = ["--set", "span.start=2000-01-11T12:00:00", "--set", "span.end=2000-01-18T12:00:00"]
    assert len(str(out)) > 255
    assert cli.main(["export", "moon_libration", *week, "--out", str(out)]) == 0
    written = sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_file())
    assert written == [str(out.relative_to(root) / name) for name in ("moon_libration_moon.bpc",
                                                                      "moon_libration_moon.tf")]
    capsys.readouterr()
    too_long = root / ("e" * 300)
    assert cli.main(["export", "moon_libration", *week, "--out", str(too_long)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("error: --out:") and "255" in err
    assert sorted(root.iterdir()) == [root / ("d" * 50)]


def test_each_bodys_records_are_whole_segments_of_the_solution(solar_system, tmp_path):
    """Over 72 days (18 segments of 4 d) the Earth-Moon barycentre's 16-d records become 12 d (3 segments), not
    14.4 d: SPICE (in seconds) and the series (in days) then place a date alike in its record, and the barycentre
    reads back within its fit and 1 mm (14.4-d records: 1.9 mm from a 0.12 mm fit)."""
    import shutil

    from jplephem.spk import SPK

    _, _, place = solar_system
    shutil.copytree(place / "store", tmp_path / "store")
    with pytest.MonkeyPatch.context() as patch:
        patch.setitem(store.PLACE, "directory", tmp_path / "store")
        solution = solutions.for_scenario(load_scenario("solar_system"), DE421_EPOCH - 20.0, DE421_EPOCH + 48.0)
    solution = solution.window(DE421_EPOCH - 20.0, DE421_EPOCH + 48.0)
    assert solution.span[1] - solution.span[0] == 72.0
    written = solution.export(tmp_path / "out")
    bsp = next(f for f in written["files"] if f.endswith(".bsp"))
    with SPK.open(bsp) as kernel:
        length = next(s for s in kernel.segments if s.target == 3).load_array()[1]
    assert length == 12.0
    t = exact_dates(solution.span, 200, 12)
    try:
        furnished([bsp])
        read = np.array([spiceypy.spkpos("3", ti * DAY_S, "J2000", "NONE", "0")[0] for ti in t])
    finally:
        spiceypy.kclear()
    truth = solution.part("earth_moon_barycenter.r", t)
    assert np.linalg.norm(read - truth, axis=1).max() < written["fit_error"]["earth_moon_barycenter_position_km"] + mm
