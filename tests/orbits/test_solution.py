"""The orbital-solution file as hostile input: every array it holds is covered by its hash (the end states a
branch continues from too), only a regular file is opened (a FIFO never blocks), every read failure is one line,
a killed save's leftovers are cleaned, and the folder of solutions is private.

References: a fresh solution of the same settings (an extension from an intact file is bit for bit the same,
tests/models/test_deep_time.py), and the rule of the kernel cache (spinorbit.base.linker.cache) for the folder."""
import os
import subprocess
import sys

import numpy as np
import pytest

from spinorbit.base.errors import InputError
from spinorbit.orbits import solution

YEAR_D = 365.25
SETTINGS = solution.Settings(output_d=3650.0)


@pytest.fixture(scope="module")
def short_solution(tmp_path_factory):
    """A solution 100 yr back (ten outputs, 7305 WHFast steps: a second)."""
    path = tmp_path_factory.mktemp("solution") / "a.npz"
    solution.solve(SETTINGS, -100 * YEAR_D, 0.0, path=path)
    return path.read_bytes()


def rewritten(path, **changes):
    """Rewrite an npz with some of its arrays replaced, as an editor of the file would."""
    with np.load(path, allow_pickle=False) as data:
        arrays = {name: data[name] for name in data.files}
    arrays.update(changes)
    with open(path, "wb") as f:
        np.savez(f, **arrays)


def test_an_edited_end_state_is_refused_not_continued_from(tmp_path, short_solution):
    path = tmp_path / "a.npz"
    path.write_bytes(short_solution)
    with np.load(path) as data:
        states = data["end_backward_states"].copy()
    states[3, 0] *= 1 + 1e-6                      # the EMB's x moved by 150 km
    rewritten(path, end_backward_states=states)
    with pytest.raises(InputError, match="do not match their hash") as info:
        solution.solve(SETTINGS, -200 * YEAR_D, 0.0, path=path)
    assert "\n" not in str(info.value)


def test_an_edited_end_time_is_refused(tmp_path, short_solution):
    path = tmp_path / "a.npz"
    path.write_bytes(short_solution)
    rewritten(path, end_backward_t=np.float64(-50 * YEAR_D))
    with pytest.raises(InputError, match="do not match their hash"):
        solution.OrbitalSolution.load(path, SETTINGS.record())


def test_an_added_array_is_refused(tmp_path, short_solution):
    path = tmp_path / "a.npz"
    path.write_bytes(short_solution)
    rewritten(path, extra=np.zeros(3))
    with pytest.raises(InputError, match="orbit_file"):
        solution.OrbitalSolution.load(path, SETTINGS.record())


def test_an_intact_file_still_extends_bit_for_bit(tmp_path, short_solution):
    path = tmp_path / "a.npz"
    path.write_bytes(short_solution)
    extended = solution.solve(SETTINGS, -200 * YEAR_D, 0.0, path=path)
    fresh = solution.solve(SETTINGS, -200 * YEAR_D, 0.0, path=tmp_path / "b.npz")
    assert np.array_equal(extended.eccentricity_vector, fresh.eccentricity_vector)


@pytest.mark.parametrize("damage", ["truncated", "bit flipped", "zero bytes", "text"])
def test_a_damaged_file_is_one_line(tmp_path, short_solution, damage):
    path = tmp_path / "a.npz"
    data = bytearray(short_solution)
    if damage == "truncated":
        data = data[:len(data) // 2]
    elif damage == "bit flipped":
        data[len(data) // 3] ^= 0x10
    elif damage == "zero bytes":
        data = b""
    else:
        data = b"orbital solution\n" * 100
    path.write_bytes(bytes(data))
    with pytest.raises(InputError, match="orbit_file") as info:
        solution.solve(SETTINGS, -100 * YEAR_D, 0.0, path=path)
    assert "\n" not in str(info.value)


def test_a_fifo_is_refused_without_blocking(tmp_path):
    path = tmp_path / "fifo.npz"
    os.mkfifo(path)
    code = ("from spinorbit.orbits import solution as s\n"
            "try:\n    s.solve(s.Settings(output_d=3650.0), -36525.0, 0.0, path=%r)\n"
            "except s.InputError as e:\n    print(e)\n" % str(path))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert "regular file" in done.stdout, done.stdout + done.stderr


def test_a_link_to_a_fifo_is_refused(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    os.symlink(tmp_path / "fifo", tmp_path / "a.npz")
    with pytest.raises(InputError, match="regular file"):
        solution.OrbitalSolution.load(tmp_path / "a.npz", SETTINGS.record())


def test_a_folder_that_does_not_exist_is_one_line(tmp_path):
    with pytest.raises(InputError, match="orbit_file") as info:
        solution.solve(SETTINGS, -100 * YEAR_D, 0.0, path=tmp_path / "nowhere" / "a.npz")
    assert "\n" not in str(info.value)


def test_stale_leftovers_of_a_killed_save_are_removed_live_ones_kept(tmp_path, short_solution):
    path = tmp_path / "a.npz"
    path.write_bytes(short_solution)
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    stale, live = tmp_path / f".a.npz.tmp-{dead}", tmp_path / f".a.npz.tmp-{os.getppid()}"
    foreign = tmp_path / ".b.npz.tmp-x"
    for leftover in (stale, live, foreign):
        leftover.write_bytes(short_solution[:100])
    solution.solve(SETTINGS, -100 * YEAR_D, 0.0, path=path)
    assert not stale.exists()
    assert live.exists() and foreign.exists()


def test_the_folder_of_solutions_is_private(tmp_path, monkeypatch):
    from spinorbit.base.linker import cache

    monkeypatch.setenv(cache.ENVIRONMENT, str(tmp_path / "cache"))
    cache.kernels_dir.cache_clear()
    try:
        folder = solution.cache_directory()
        assert oct(folder.stat().st_mode & 0o777) == oct(0o700)
        folder.chmod(0o777)
        with pytest.raises(InputError, match="writable by others") as info:
            solution.cache_directory()
        assert "\n" not in str(info.value)
    finally:
        cache.kernels_dir.cache_clear()


def test_the_command_line_says_an_orbit_file_at_a_fifo_in_one_line(tmp_path):
    os.mkfifo(tmp_path / "fifo.npz")
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "--quiet", "run", "earth_deep_time", "--set",
                           f"orbit.file={tmp_path / 'fifo.npz'}", "--set", "output.plots=false", "--out",
                           str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "orbit.file" in done.stderr and "regular file" in done.stderr


def test_the_command_line_says_any_os_error_in_one_line(monkeypatch, capsys):
    from spinorbit.edge import cli

    def denied(scene):
        raise PermissionError(13, "Permission denied", "/somewhere/scene.toml")

    monkeypatch.setattr(cli, "_show", denied)
    assert cli.main(["show", "free_body"]) == 2
    assert capsys.readouterr().err == "error: /somewhere/scene.toml: Permission denied\n"


STORE_FIFO = """
import os, sys
from spinorbit.solutions import store
os.mkfifo(sys.argv[1])
print(store.read(__import__("pathlib").Path(sys.argv[1]), {"scene": "x"}), os.path.lexists(sys.argv[1]))
"""


def test_a_fifo_in_the_store_of_solutions_is_refused_without_blocking(tmp_path):
    done = subprocess.run([sys.executable, "-c", STORE_FIFO, str(tmp_path / "s.npz")], capture_output=True,
                          text=True, timeout=60)
    assert done.stdout.split() == ["None", "False"], done.stdout + done.stderr
    assert "not a regular file" in done.stderr and done.stderr.count("\n") == 1


def test_a_folder_in_place_of_a_stored_solution_is_refused_and_replaced(tmp_path, capsys):
    from spinorbit.solutions import store

    (tmp_path / "s.npz").mkdir()
    (tmp_path / "s.npz" / "inside").write_text("x")
    assert store.read(tmp_path / "s.npz", {"scene": "x"}) is None
    assert not (tmp_path / "s.npz").exists() and capsys.readouterr().err.count("\n") == 1
