"""``linker.cached``: a compiled function whose callees live in other files compiles afresh when one of those
files changes (numba's own ``cache=True`` stamps the caller's file only), and every such function of the
package is cached that way.  The edit runs in fresh processes on a tiny package of two files, as a developer's
edit would."""
import importlib
import os
import pkgutil
import subprocess
import sys
from pathlib import Path

from numba.core.caching import NullCache

import spinorbit
from spinorbit.base import linker
from spinorbit.base.linker.stamped import ReachCache

ROOT = Path(__file__).parents[3]
CALLEE = """from numba import njit

SCALE = {scale}


@njit(cache=True)
def offset(x):
    return SCALE * x
"""
CALLER = """from spinorbit.base.linker import cached

from .callee import offset


@cached(nogil=True)
def value(x):
    return offset(x) + 1.0
"""
RUN = """from tiny.caller import value
print(value(2.0), sum(value.stats.cache_hits.values()), sum(value.stats.cache_misses.values()))
"""


def run(folder):
    """(value(2.0), cache hits, cache misses) in a fresh process, numba's cache in ``folder``."""
    env = {**os.environ, "PYTHONPATH": f"{folder}{os.pathsep}{ROOT}", "NUMBA_CACHE_DIR": str(folder / "numba")}
    done = subprocess.run([sys.executable, "-c", RUN], capture_output=True, text=True, env=env, check=False)
    assert done.returncode == 0, done.stderr
    result, hits, misses = done.stdout.split()
    return float(result), int(hits), int(misses)


def test_editing_a_callee_in_another_file_compiles_the_caller_afresh(tmp_path):
    """value(2) = SCALE * 2 + 1: 7 from the cache written by the first process; 11 once the callee's file
    alone says SCALE = 5 (numba's own stamp, the caller's file, is unchanged: it would give 7 again)."""
    package = tmp_path / "tiny"
    package.mkdir()
    (tmp_path / "numba").mkdir(mode=0o700)
    (package / "__init__.py").write_text("")
    (package / "caller.py").write_text(CALLER)
    (package / "callee.py").write_text(CALLEE.format(scale=3.0))
    assert run(tmp_path) == (7.0, 0, 1)                 # compiled and saved
    assert run(tmp_path) == (7.0, 1, 0)                 # loaded: the cache holds while nothing changes
    (package / "callee.py").write_text(CALLEE.format(scale=5.0))
    assert run(tmp_path) == (11.0, 0, 1)                # compiled afresh
    assert run(tmp_path) == (11.0, 1, 0)


def test_every_cached_function_reaching_other_files_is_keyed_by_its_reach():
    """Every ``cache=True`` function of the package that uses functions or constants of another module is
    ``@linker.cached`` (a ReachCache), so that no edit leaves it stale."""
    stale = []
    for info in pkgutil.walk_packages(spinorbit.__path__, "spinorbit."):
        module = importlib.import_module(info.name)
        for name, value in vars(module).items():
            cache = getattr(value, "_cache", None)
            if (getattr(getattr(value, "py_func", None), "__module__", None) != module.__name__
                    or cache is None or isinstance(cache, (NullCache, ReachCache))):
                continue
            if set(linker.reached(value)) - {module.__name__}:
                stale.append(f"{module.__name__}.{name}")
    assert not stale, f"@njit(cache=True) reaching other files (use @linker.cached): {stale}"
