"""Fuzzed scene inputs: every one loads into a sane scenario or is refused in one line naming the key.

Property-based (hypothesis) over the scene schema of four scenes: values of wrong types, NaN, inf,
huge, tiny and zero numbers, wrong units, bad dates, long strings, deep nesting, integers past
Python's digit limit, random bytes (non-UTF-8) in the file, and ``--set`` strings.  Validation only,
no integration; a few cases go through the command line.
"""
import copy
import datetime
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spinorbit.budget import LIMITS
from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.scenarios import Scenario, load_scenario
from spinorbit.schema import dotted_items

ROOT = Path(__file__).parents[1]
SCENE_FILES = {name: ROOT / "scenarios" / f"{name}.toml"
               for name in ("p93_bounded", "free_body", "moon_libration", "earth_precession_nutation")}
SCENES = {name: tomllib.loads(path.read_text()) for name, path in SCENE_FILES.items()}
# The same examples on every machine; to search further, raise max_examples and drop derandomize.
SETTINGS = settings(max_examples=150, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])
MAX_MESSAGE = 1200            # characters: the longest one-line error (a list of accepted keys)


def nested(depth):
    value = 1
    for _ in range(depth):
        value = [value]
    return value


NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-10**30, max_value=10**30),
    st.sampled_from([0, -1, 1, 0.0, -0.0, 1e-300, 1e300, 5e-324, 10**400, 10**4000, 1e-7, 10.0]),
)
UNITS = st.sampled_from(["", "d", "s", "yr", "km", "m", "deg", "rad", "rad/d", "deg/d", "km3/s2", "km3/d2",
                         "1/d", "d d", "foo", "km/s/s", "%", "d^(1/0)"])
QUANTITIES = st.builds(lambda x, unit: f"{x} {unit}".strip(), NUMBERS, UNITS)
DATES = st.one_of(
    st.sampled_from(["2000-01-01T12:00:00", "2000-13-01", "2000-02-30", "1899-12-31", "9999-12-31T23:59:59",
                     "-0001-01-01", "0000-01-01", "2000-01-01T25:00:00", "1e9 yr", "-5 d", "nan d", "inf d",
                     "1e-300 d", "2000-01-01T12:00:00Z", "J2000", "3000000-01-01"]),
    st.datetimes(min_value=datetime.datetime(1, 1, 1)).map(lambda t: t.isoformat()),
    st.dates(), st.datetimes(timezones=st.just(datetime.UTC)), st.times(),
)
TEXT = st.one_of(st.text(max_size=40), st.sampled_from(["x" * 20_000, "\x00", "é", "\udce9"]))
LEAVES = st.one_of(NUMBERS, QUANTITIES, DATES, TEXT, st.booleans())
VALUES = st.one_of(
    LEAVES,
    st.recursive(LEAVES, lambda inner: st.lists(inner, max_size=4)
                 | st.dictionaries(st.text(max_size=6), inner, max_size=3), max_leaves=8),
    st.integers(min_value=5, max_value=5000).map(nested),
    st.lists(QUANTITIES, min_size=3, max_size=3),
)


def keys_of(name):
    extra = ["integrator.rtol", "integrator.atol", "integrator.step", "integrator.max_step", "scene.kind",
             "span", "orbit", "body.moments", "orbit.step", "x" * 300, "span.end.deeper"]
    return sorted({key for key, _ in dotted_items(SCENES[name])} | set(extra))


def assign(data, key, value):
    node = data
    parts = key.split(".")
    for part in parts[:-1]:
        if not isinstance(node.get(part), dict):
            node[part] = {}
        node = node[part]
    node[parts[-1]] = value


def assert_one_line(exc):
    message = str(exc)
    assert "\n" not in message and len(message) < MAX_MESSAGE, message[:2000]
    assert ": got " in message and "; expected " in message


def assert_sane(scenario):
    """What an accepted scenario promises: finite values, a real span, bounded output."""
    for key, value in scenario.values.items():
        if isinstance(value, (float, np.ndarray)):
            assert np.all(np.isfinite(value)), key
    assert math.isfinite(scenario.params.span.start) and scenario.params.span.end > scenario.params.span.start
    assert len(scenario.output_times()) <= LIMITS["output rows"]
    for name in ("rtol", "atol"):
        assert 0 < scenario.params.integrator.options().get(name, 1e-12) < 1


@SETTINGS
@given(st.data())
def test_mutated_values_are_accepted_sanely_or_refused_in_one_line(data):
    name = data.draw(st.sampled_from(sorted(SCENES)))
    scene = copy.deepcopy(SCENES[name])
    for key in data.draw(st.lists(st.sampled_from(keys_of(name)), min_size=1, max_size=3)):
        assign(scene, key, data.draw(VALUES))
    try:
        scenario = Scenario(scene, SCENE_FILES[name])
    except ScenarioError as exc:
        assert_one_line(exc)
    else:
        assert_sane(scenario)


@SETTINGS
@given(name=st.sampled_from(sorted(SCENES)), where=st.floats(0, 1), junk=st.binary(min_size=1, max_size=12))
def test_random_bytes_in_the_file_are_refused_in_one_line(tmp_path_factory, name, where, junk):
    raw = SCENE_FILES[name].read_bytes()
    at = int(where * len(raw))
    path = tmp_path_factory.mktemp("fuzz") / f"{name}.toml"
    path.write_bytes(raw[:at] + junk + raw[at:])
    try:
        scenario = load_scenario(path)
    except ScenarioError as exc:
        assert_one_line(exc)
    else:
        assert_sane(scenario)


@SETTINGS
@given(name=st.sampled_from(sorted(SCENES)), data=st.data())
def test_set_overrides_are_accepted_sanely_or_refused_in_one_line(name, data):
    key = data.draw(st.sampled_from(keys_of(name)) | st.text(max_size=20))
    text = data.draw(st.one_of(st.text(max_size=30), QUANTITIES.map(lambda q: f'"{q}"'), QUANTITIES,
                               st.sampled_from(["{a = 1}", "[" * 3000 + "]" * 3000, "9" * 5000, "nan", "inf",
                                                "-inf", "1e999", "\udce9", "[1, 2", "'x'"])))
    try:
        scenario = load_scenario(SCENE_FILES[name], [f"{key}={text}"])
    except ScenarioError as exc:
        assert_one_line(exc)
    else:
        assert_sane(scenario)


def test_the_issue_cases_each_name_their_key(capsys):
    """The inputs that used to hang, trace back or run to nonsense (issue 13), through the command line."""
    cases = {
        'span.end="inf d"': "span.end", 'span.end="1e-300 d"': "span.end",
        "integrator.atol=1e-300": "integrator.atol",
        "integrator.atol=-1": "integrator.atol", "integrator.atol=0": "integrator.atol",
        "integrator.rtol=nan": "integrator.rtol", "integrator.rtol=inf": "integrator.rtol",
        "integrator.rtol=10": "integrator.rtol", "integrator.rtol=0": "integrator.rtol",
        "integrator.rtol=1": "integrator.rtol", 'span.step="1 s"': "span.step",
        'span.step="1e-7 d"': "span.step", 'span.step="inf d"': "span.step",
        'orbit.gm="1e30 km3/s2"': "orbit.gm", 'orbit.radius="inf km"': "orbit.radius",
        'orbit.rate="1e9 deg/d"': "orbit.rate", "scene.kind={a = 1}": "scene.kind",
        "integrator.rtol=" + "9" * 5000: "integrator.rtol", "body.moments=[nan, 1, 1]": "body.moments",
        'orbit.radius="1 km"': "orbit.radius", "integrator.max_step=1e-6": "integrator.max_step",
    }
    for assignment in ("force.direction=[0, 0, 0]", "force.direction=[1e300, 1e300, 1e300]"):
        p95 = str(ROOT / "scenarios" / "p95_symmetric.toml")
        assert main(["run", p95, "--out", "unused", "--set", assignment]) == 2
        assert capsys.readouterr().err.startswith("error: force.direction: got ")
    for assignment, key in cases.items():
        assert main(["run", str(SCENE_FILES["p93_bounded"]), "--out", "unused", "--set", assignment]) == 2
        err = capsys.readouterr().err
        assert len(err.splitlines()) == 1 and err.startswith(f"error: {key}: got "), (assignment, err)


def test_a_long_key_is_echoed_short(capsys):
    long_key = "x" * 100_000 + "=1"
    assert main(["run", str(SCENE_FILES["p93_bounded"]), "--out", "unused", "--set", long_key]) == 2
    err = capsys.readouterr().err
    assert len(err) < MAX_MESSAGE and "(100000 characters)" in err


def test_non_utf8_bytes_from_the_shell_and_the_file(tmp_path):
    """A Latin-1 title in the file, a Latin-1 byte on the command line: one line each, no traceback."""
    scene = tmp_path / "latin1.toml"
    scene.write_bytes(SCENE_FILES["p93_bounded"].read_bytes().replace(b'title = "', b'title = "\xe9'))
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    code = ("import sys; from spinorbit.cli import main; "
            "sys.exit(max(main(['run', sys.argv[1], '--out', 'x']), "
            "main(['run', sys.argv[2], '--out', 'x', '--set', sys.argv[3]])))")
    done = subprocess.run([sys.executable, "-c", code, scene, SCENE_FILES["p93_bounded"],
                           b"scene.title=\xe9"], cwd=tmp_path, env=env, capture_output=True, check=False)
    err = done.stderr.decode()
    offset = SCENE_FILES["p93_bounded"].read_bytes().index(b'title = "') + len(b'title = "')
    assert done.returncode == 2 and "Traceback" not in err, err
    assert err.splitlines() == [
        (f"error: {scene}: got 'byte 0xe9 at offset {offset}'; expected a UTF-8 text file "
         "(re-save it as UTF-8)"),
        ("error: --set: got 'scene.title=\\udce9'; expected UTF-8 text (a byte that is not UTF-8 at "
         "offset 12)")]


# --- issue 27: the run directory under random user entries; the Python API under random types ------

USER_NAMES = ["notes.txt", "summary.json", "report.md", "sub/x.csv", "sub", "run[1]", "*", "000/summary.json"]
USER_KINDS = ["file", "empty folder", "link", "dangling link", "FIFO"]


def make_user_entry(out, rel, kind):
    path = out / rel
    if os.path.lexists(path) or not path.parent.is_dir() and os.path.lexists(path.parent):
        return None                                      # the name is taken, or its parent is not a folder
    path.parent.mkdir(parents=True, exist_ok=True)
    if kind == "file":
        path.write_text(f"the user's {rel}\n")
    elif kind == "empty folder":
        path.mkdir()
    elif kind == "link":
        os.symlink("/etc", path)
    elif kind == "dangling link":
        os.symlink(out / "nowhere", path)
    else:
        os.mkfifo(path)
    return rel


def state(path):
    """What a user entry is: its kind and content (a file's bytes, a link's target), read without blocking."""
    info = os.lstat(path)
    if os.path.islink(path):
        return "link", os.readlink(path)
    if os.path.isdir(path):
        return "folder", None
    if not os.path.isfile(path):
        return "other", info.st_mode
    return "file", Path(path).read_bytes()


@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(entries=st.lists(st.tuples(st.sampled_from(USER_NAMES), st.sampled_from(USER_KINDS)), max_size=5),
       during=st.booleans(), force=st.booleans(),
       writes=st.sampled_from([("summary.json",), ("a.txt", "b/c.txt")]))
def test_nothing_of_the_users_is_lost(tmp_path_factory, entries, during, force, writes):
    """Entries a user puts in --out, before the run or while it computes: refused (one line) or kept, each
    as it was, except with --force the files of the names the run writes itself."""
    from spinorbit.rundir import RunDirectory

    out = tmp_path_factory.mktemp("rundir") / "run"
    with RunDirectory(out) as run:
        run.commit(lambda d: (d / "summary.json").write_text("{}\n"))

    def add():
        made = [make_user_entry(out, rel, kind) for rel, kind in entries]
        return {rel: state(out / rel) for rel in made if rel is not None}

    def write(directory):
        for rel in writes:
            (directory / rel).parent.mkdir(parents=True, exist_ok=True)
            (directory / rel).write_text("new\n")

    users = {} if during else add()
    try:
        with RunDirectory(out, force=force) as run:
            users.update(add() if during else {})
            run.commit(write)
    except ScenarioError as exc:
        assert_one_line(exc)
    replaced = {rel for rel in users if force and not during and any(rel == w or w.startswith(rel + "/")
                                                                     for w in writes)}
    for rel, before in users.items():
        if rel not in replaced and not any(rel.startswith(r + "/") for r in replaced):
            assert os.path.lexists(out / rel) and state(out / rel) == before, rel


API_VALUES = st.one_of(st.none(), st.integers(), st.floats(), st.binary(max_size=20), st.text(max_size=20),
                       st.lists(st.text(max_size=10), max_size=3),
                       st.dictionaries(st.text(max_size=5), st.integers(), max_size=2))


@SETTINGS
@given(scenario=API_VALUES, overrides=API_VALUES)
def test_run_scenario_with_any_python_values_is_refused_in_one_line(scenario, overrides):
    """Values that are not a scenario file and a list of 'key=value' strings never reach a scene."""
    from spinorbit import run_scenario

    if isinstance(scenario, str) and Path(scenario).is_file():
        return
    try:
        run_scenario(scenario, overrides)
    except ScenarioError as exc:
        assert_one_line(exc)
    else:
        raise AssertionError(f"run_scenario({scenario!r}, {overrides!r}) ran")
