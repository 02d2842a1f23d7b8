"""The kernel cache runs only its own code: a private directory (refused when another user could write
it), generated modules run only when their bytes match their name, never imported through sys.path,
numba's pickles hash-checked; damage is repaired and said in one line; kernels fingerprint only what
they reach.  Each case runs in a fresh process on its own cache (as a user's run would)."""
import os
import pickle
import stat
import subprocess
import sys
import types
from pathlib import Path

import pytest

from spinorbit.base import linker, rotations
from spinorbit.integrators import rk8, splitting
from spinorbit.models.interactions import point_mass
from tests.second_user import OTHER, as_user, chown_other, needs_root, shared_dir

ROOT = Path(__file__).parents[3]
# A rigid body without torque, its rhs generated and linked (with its torque, not called): Euler's
# equations in closed form, omega' = ((B - C) wy wz / A, (C - A) wz wx / B, (A - B) wx wy / C).
LINK = """
import sys
import numpy as np
from spinorbit.models.assemblies.idealised import free_body
system = free_body(np.array([1.0, 2.0, 3.0]), np.array([1.0, 0, 0, 0]), np.array([0.1, 0.2, 0.3]))
rhs = system.rhs
print(rhs(0.0, system.y0, system.params)[4:].tolist(), sum(rhs.stats.cache_hits.values()))
print(any("kernels" in p for p in sys.path))
"""
EULER = [(2 - 3) * 0.2 * 0.3 / 1, (3 - 1) * 0.3 * 0.1 / 2, (1 - 2) * 0.1 * 0.2 / 3]


def environment(cache, **env):
    return {**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_CACHE_DIR": str(cache), **env}


def run(cache, code=LINK, **env):
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=cache.parent,
                          check=False, env=environment(cache, **env))
    return done


def linked(cache):
    """(omega', cache hits, sys.path holds the cache, stderr lines) of LINK run on ``cache``."""
    done = run(cache)
    assert done.returncode == 0, done.stderr
    values, hits = done.stdout.splitlines()[0].rsplit(" ", 1)
    return eval(values), int(hits), done.stdout.splitlines()[1] == "True", done.stderr.strip().splitlines()


def generated(cache, name="rhs"):
    (path,) = (cache / "kernels").glob(f"spinorbit_{name}_*.py")
    return path


@pytest.fixture(scope="module")
def warm(tmp_path_factory):
    """A cache filled once (the template compiled and saved), copied by each test that damages it."""
    cache = tmp_path_factory.mktemp("warm") / "cache"
    omega, hits, on_path, err = linked(cache)
    assert omega == pytest.approx(EULER, rel=1e-15) and hits == 0 and not on_path and not err
    return cache


@pytest.fixture
def cache(warm, tmp_path):
    copy = tmp_path / "cache"
    subprocess.run(["cp", "-a", str(warm), str(copy)], check=True)
    return copy


def test_a_fresh_cache_is_private_and_a_second_process_loads_it(cache):
    for folder in (cache, cache / "kernels", cache / "kernels" / "numba"):
        assert stat.S_IMODE(os.stat(folder).st_mode) == 0o700
    omega, hits, on_path, err = linked(cache)
    assert omega == pytest.approx(EULER, rel=1e-15) and hits == 1 and not on_path and not err


@pytest.mark.parametrize("damage", ["planted code", "truncated"])
def test_a_generated_module_that_does_not_match_its_name_is_not_run_but_rebuilt(cache, tmp_path, damage):
    path = generated(cache)
    expected = path.read_bytes()
    marker = tmp_path / "ran"
    path.write_text(f"open({str(marker)!r}, 'w').close()\n" if damage == "planted code"
                    else expected[:len(expected) // 2].decode())
    omega, _, _, err = linked(cache)
    assert not marker.exists() and omega == pytest.approx(EULER, rel=1e-15)
    assert len(err) == 1 and f"{path} was damaged" in err[0] and "rebuilt" in err[0]
    assert path.read_bytes() == expected
    assert linked(cache)[3] == []                           # repaired: the next run says nothing


def test_a_module_planted_in_the_cache_never_shadows_another(cache, tmp_path):
    """sortedcontainers (a Dask dependency) imported after a kernel is linked is the installed one."""
    marker = tmp_path / "ran"
    (cache / "kernels" / "sortedcontainers.py").write_text(f"open({str(marker)!r}, 'w').close()\n")
    done = run(cache, LINK + "import sortedcontainers; print(sortedcontainers.__file__)")
    assert done.returncode == 0 and not marker.exists() and "site-packages" in done.stdout.splitlines()[-1]


@pytest.mark.parametrize("damage", ["truncated data", "garbage index", "a pickle that runs code",
                                    "data a link to /dev/zero", "index a FIFO"])
def test_a_damaged_numba_cache_file_is_never_unpickled_but_compiled_again(cache, tmp_path, damage):
    numba_dir = cache / "kernels" / "numba"
    (index,) = numba_dir.glob("spinorbit_rhs_*.nbi")
    (data,) = numba_dir.glob("spinorbit_rhs_*.nbc")
    marker = tmp_path / "ran"
    if damage == "truncated data":
        data.write_bytes(data.read_bytes()[:-100])
    elif damage == "garbage index":
        index.write_bytes(b"\x00" * 64)
    elif damage == "data a link to /dev/zero":          # read whole, it would never end
        data.unlink()
        os.symlink("/dev/zero", data)
    elif damage == "index a FIFO":                      # opened to read, it would wait for a writer
        index.unlink()
        os.mkfifo(index)
    else:
        class Runs:
            def __reduce__(self):
                return (open, (str(marker), "w"))
        index.write_bytes(pickle.dumps("0.68.1") + pickle.dumps(Runs()))
    omega, hits, _, err = linked(cache)
    assert not marker.exists() and omega == pytest.approx(EULER, rel=1e-15) and hits == 0
    assert len(err) == 1 and "numba's cache entry of rhs" in err[0] and "compiled again" in err[0]
    assert linked(cache)[1:] == (1, False, [])             # saved again, loaded by the next process


def refusal(cache, **env):
    """The one line `spinorbit cache` prints (exit 2) for ``cache``."""
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache"], capture_output=True, text=True,
                          check=False, env=environment(cache, **env))
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr
    assert lines[0].startswith(f"error: SPINORBIT_CACHE_DIR: got '{cache}'")
    return lines[0]


@pytest.mark.parametrize("mode", [0o770, 0o707, 0o777])
def test_a_cache_writable_by_others_is_refused(tmp_path, mode):
    cache = tmp_path / "cache"
    cache.mkdir(mode=0o700)
    os.chmod(cache, mode)
    assert f"is writable by others (mode {mode:o})" in refusal(cache)


def test_a_cache_below_a_folder_others_can_rename_is_refused(tmp_path):
    above = tmp_path / "open"
    above.mkdir()
    os.chmod(above, 0o777)                                  # no sticky bit: anyone may rename the cache
    assert f"({above} is writable by others)" in refusal(above / "cache")


@needs_root
def test_a_cache_made_by_another_user_is_refused_and_nothing_in_it_runs(tmp_path):
    """Another user creates the victim's cache directory first (in a shared /tmp), with a 'kernel' in it."""
    shared = shared_dir()
    cache, marker = shared / "so-cache", tmp_path / "ran"

    def plant():
        (cache / "kernels" / "numba").mkdir(parents=True)
        for folder in (cache, cache / "kernels", cache / "kernels" / "numba"):
            os.chmod(folder, 0o755)
        return str(cache)
    as_user(plant)
    for name in ("spinorbit_rhs_0123456789abcdef0123.py", "sortedcontainers.py"):
        (cache / "kernels" / name).write_text(f"open({str(marker)!r}, 'w').close()\n")
        chown_other(cache / "kernels" / name)
    assert f"{cache} belongs to uid {OTHER}" in refusal(cache)
    done = run(cache)
    assert done.returncode != 0 and "SPINORBIT_CACHE_DIR" in done.stderr and not marker.exists()
    moon = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "run", "scenarios/moon_libration.toml",
                           "--out", str(tmp_path / "out"), "--set", 'span.start="2000-01-01T12:00:00"',
                           "--set", "span.end=4 d", "--set", "model.level=1", "--set", "output.plots=false"],
                          capture_output=True, text=True, cwd=ROOT, check=False,
                          env={**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_CACHE_DIR": str(cache)})
    err = moon.stderr.strip().splitlines()
    assert moon.returncode == 2 and len(err) == 1
    assert err[0].startswith(f"error: SPINORBIT_CACHE_DIR: got '{cache}'")
    assert not marker.exists()


def test_no_fallback_into_a_shared_temporary_directory(tmp_path):
    """Home not writable, no SPINORBIT_CACHE_DIR: refused in one line naming SPINORBIT_CACHE_DIR (once, the
    cache fell back to $TMPDIR/spinorbit-<uid>, which another user could create first)."""
    home = Path("/proc/self/no-home")                       # nothing can be created under /proc
    env = {k: v for k, v in os.environ.items() if k not in ("SPINORBIT_CACHE_DIR", "XDG_CACHE_HOME")}
    env.update(HOME=str(home), TMPDIR=str(tmp_path), PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache"], capture_output=True, text=True,
                          check=False, env=env)
    err = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(err) == 1 and "set SPINORBIT_CACHE_DIR" in err[0], done.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_cache_with_one_second_timestamps_loads_what_it_just_wrote(tmp_path, monkeypatch):
    """Two modules written within one second into a folder whose mtime does not change: both load (they
    are loaded by path, not found by an import finder that caches the folder's listing)."""
    from spinorbit.base.linker import cache

    monkeypatch.setenv("SPINORBIT_CACHE_DIR", str(tmp_path / "cache"))
    cache.kernels_dir.cache_clear()
    monkeypatch.setattr(sys, "path", [p for p in sys.path])
    write = cache._write_atomically

    def coarse(path, data):
        before = os.stat(path.parent).st_mtime_ns
        write(path, data)
        os.utime(path.parent, ns=(before, before))
    monkeypatch.setattr(cache, "_write_atomically", coarse)
    try:
        for fn in (rk8.rk_step, splitting.split_loop):
            text = linker._module_source(fn, {name: point_mass.torque for name in fn.free_names}, ["test"])
            name = f"spinorbit_test_{fn.__name__}_{os.getpid()}"
            assert callable(getattr(cache.load_module(name, text), fn.__name__))
            sys.modules.pop(name)
    finally:
        cache.kernels_dir.cache_clear()


def test_cache_lists_every_cache_and_clear_empties_them_all(cache):
    (cache / "heyoka").mkdir(mode=0o700)
    (cache / "heyoka" / "entry").write_bytes(b"x" * 1000)
    solutions = cache / "orbital_solutions"
    solutions.mkdir(mode=0o700)
    (solutions / "de421-0123.npz").write_bytes(b"y" * 3000)
    (solutions / ".de421-0123.npz.tmp-999999999").write_bytes(b"z" * 10)     # a killed save's leftover
    show = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache"], capture_output=True, text=True,
                          check=False, env=environment(cache))
    lines = show.stdout.splitlines()
    assert show.returncode == 0 and len(lines) == 6, show.stdout + show.stderr
    files = [p for p in (cache / "kernels").rglob("*") if p.is_file()]
    kernels = sum(p.stat().st_size for p in files)
    assert lines[0].split()[:4] == ["compiled", "kernels", str(len(files)), "files"]
    assert f"{kernels / 1e6:.3g} MB" in lines[0] and lines[0].endswith(f"{cache}/kernels/")
    assert lines[1].startswith("heyoka's compiled integrators") and "1 files" in lines[1] and "0.001 MB" in lines[1]
    assert lines[2].startswith("orbital solutions") and "2 files" in lines[2] and "0.00301 MB" in lines[2]
    cleared = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache", "clear"], capture_output=True,
                             text=True, check=False, env=environment(cache))
    assert cleared.returncode == 0, cleared.stderr
    assert cleared.stdout.splitlines() == [f"compiled kernels: removed {len(files)} files from {cache}/kernels/",
                                               f"heyoka's compiled integrators: removed 1 files from {cache}/heyoka/",
                                               f"orbital solutions: removed 2 files from {solutions}/",
                                               f"stored solutions: removed 0 files from {cache}/solutions/",
                                               "tidal-history tables: removed 0 files"]
    assert [p.name for p in (cache / "kernels").iterdir()] == ["numba"]
    assert not list((cache / "kernels" / "numba").iterdir()) and not list((cache / "heyoka").iterdir())
    assert [p.name for p in solutions.iterdir()] == ["de421-0123.npz.lock"]
    assert linked(cache)[1] == 0                            # compiled afresh


def test_kernels_reach_only_what_they_use():
    """An interaction's kernel reaches its own module and the rotations it calls, not the modules no kernel
    uses (editing one of those leaves every kernel warm)."""
    reached = linker.reached(point_mass.torque)
    assert {"spinorbit.models.interactions.point_mass", "spinorbit.base.rotations"} <= set(reached)
    assert not {"spinorbit.scene.verdict", "spinorbit.edge.scenarios", "spinorbit.models.system"} & set(reached)
    assert set(linker.reached(rk8.rk_step)) == {"spinorbit.integrators.rk8"}        # rotations.put: a binding
    assert "spinorbit.base.rotations" in linker.reached(rotations.put)


def test_free_names_are_declared_placeholders():
    """A template's free names are module-level placeholders (linters follow them); a bare @template()
    takes them from there; calling one unbound says what to do."""
    assert rk8.rk_step.free_names == ("rhs", "put") and isinstance(rk8.rhs, linker.Free)
    with pytest.raises(TypeError, match="rhs is a free name of a template"):
        rk8.rhs(0.0, None, None)

    bare = types.FunctionType(rk8.rk_step.__code__, rk8.rk_step.__globals__, "rk_step")
    assert linker.template()(bare).free_names == ("put", "rhs")


INDEX_OF_DOT3 = """
import sys
from numba.core import config
from numba.core.caching import FunctionCache
import spinorbit.base.rotations
config.CACHE_DIR = sys.argv[1]
print(FunctionCache(spinorbit.base.rotations.dot3.py_func)._cache_file._index_path)
"""
CALL_DOT3 = "import numpy as np, spinorbit.base.rotations as r; print(r.dot3(np.ones(3), np.ones(3)))"


class _Planted:
    def __init__(self, marker):
        self.marker = marker

    def __reduce__(self):
        return open, (self.marker, "w")


def test_a_numba_cache_dir_others_can_write_is_refused_and_its_pickles_never_run(tmp_path, cache):
    shared, marker = tmp_path / "shared", tmp_path / "ran"
    shared.mkdir()
    os.chmod(shared, 0o777)
    env = {k: v for k, v in environment(cache).items() if k != "NUMBA_CACHE_DIR"}
    index = subprocess.run([sys.executable, "-c", INDEX_OF_DOT3, str(shared)], capture_output=True, text=True,
                           check=True, env=env).stdout.strip()
    assert index.startswith(str(shared))
    Path(index).parent.mkdir(parents=True, exist_ok=True)
    Path(index).write_bytes(pickle.dumps(_Planted(str(marker))))        # numba unpickles an index first
    env["NUMBA_CACHE_DIR"] = str(shared)
    called = subprocess.run([sys.executable, "-c", CALL_DOT3], capture_output=True, text=True, env=env)
    assert called.stdout.strip() == "3.0" and not marker.exists(), called.stderr
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache"], capture_output=True, text=True,
                          env=env)
    err = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(err) == 1, done.stderr
    assert err[0].startswith(f"error: NUMBA_CACHE_DIR: got '{shared}'") and "writable by others" in err[0]
    assert not marker.exists()
    os.chmod(shared, 0o700)                                             # a private one is used
    assert subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "cache"], capture_output=True,
                          env=env).returncode == 0


def test_a_generated_module_that_cannot_be_written_runs_from_memory(tmp_path, monkeypatch, capfd):
    """Found by benchmarks/fuzz_store.py: a full disk (EFBIG) while the cache wrote a generated module was an OSError
    traceback; the module is run from its verified bytes, said in one line."""
    from spinorbit.base.linker import cache

    def full(path, data):
        raise OSError(27, "File too large")

    monkeypatch.setenv(cache.ENVIRONMENT, str(tmp_path / "cache"))
    cache.kernels_dir.cache_clear()
    monkeypatch.setattr(cache, "_write_atomically", full)
    name = f"spinorbit_test_full_disk_{os.getpid()}"
    try:
        assert cache.load_module(name, "answer = 6 * 7\n").answer == 42
    finally:
        sys.modules.pop(name, None)
        cache.kernels_dir.cache_clear()
    said = capfd.readouterr().err.splitlines()
    assert len(said) == 1 and "could not be written (File too large)" in said[0]
