"""A cached kernel and its callee cached apart (the kernel cache and another NUMBA_CACHE_DIR) stay callable in
every later process (spinorbit.base.compiled_names): numba numbers compiled functions from 1 in each process, so a
process that loads the kernel and compiles the callee afresh under the number the kernel's copy already had
saved code the next process ran on the wrong environment ('descr' is NULL, issue 42 item 3: the main job's
core_omega).  Three fresh processes on a tiny package, as the main job's second run met it."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).parents[2]
PACKAGE = {
    "__init__.py": "",
    "callee.py": """from numba import njit


@njit(cache=True)
def scaled(x):
    return 3.0 * x
""",
    "kernel.py": """from spinorbit.base import linker

from .callee import scaled

f = linker.free("f")


@linker.template("f")
def doubled(x):
    return 2.0 * f(x)


def compiled():
    return linker.link(doubled, f=scaled)
""",
}
FIRST = """import numpy as np
from tiny.callee import scaled
from tiny.kernel import compiled
x = np.arange(3.0)
print(compiled()(x).sum(), scaled(x).sum(), next(iter(scaled.overloads.values())).fndesc.uid)
"""
SECOND = """import numba, numpy as np
from numba.core.bytecode import FunctionIdentity
from tiny.callee import scaled
from tiny.kernel import compiled
x = np.arange(3.0)
kernel_sum = compiled()(x).sum()                    # loaded from the kernel cache, its copy of scaled inside
number = int({number})
while 0 < number - 1 - (current := next(FunctionIdentity._unique_ids)) < 200:
    numba.njit(lambda y: y)(1.0)                    # another process's history: other functions compiled first
print(kernel_sum, scaled(x).sum(), current)        # scaled compiled afresh (a new numba folder), saved there
"""
THIRD = """import numpy as np
from tiny.callee import scaled
from tiny.kernel import compiled
x = np.arange(3.0)
print(compiled()(x).sum(), scaled(x).sum(), 0)
"""


def run(folder, code, numba_folder):
    env = {**os.environ, "PYTHONPATH": f"{folder}{os.pathsep}{ROOT}", "SPINORBIT_CACHE_DIR": str(folder / "cache"),
           "NUMBA_CACHE_DIR": str(folder / numba_folder), "SPINORBIT_QUIET": "1"}
    done = subprocess.run([sys.executable, "-c", "import spinorbit\n" + code], capture_output=True, text=True,
                          env=env, check=False)
    assert done.returncode == 0, done.stderr
    kernel_sum, callee_sum, number = done.stdout.split()
    return float(kernel_sum), float(callee_sum), int(number)


def test_a_kernel_and_its_callee_cached_by_different_processes_both_run(tmp_path):
    """Sums of 2 * 3x and 3x over x = 0, 1, 2 (18 and 9), in three processes: the first compiles and caches
    both; the second loads the kernel, compiles the callee afresh in a new numba folder after as many other
    functions as bring numba's count to the number the callee had in the first; the third loads both."""
    (tmp_path / "tiny").mkdir()
    for name, text in PACKAGE.items():
        (tmp_path / "tiny" / name).write_text(text)
    for folder in ("cache", "numba_first", "numba_second"):
        (tmp_path / folder).mkdir(mode=0o700)
    expected = (2.0 * 3.0 * np.arange(3.0).sum(), 3.0 * np.arange(3.0).sum())
    *sums, number = run(tmp_path, FIRST, "numba_first")
    assert tuple(sums) == expected
    assert tuple(run(tmp_path, SECOND.format(number=number), "numba_second")[:2]) == expected
    assert tuple(run(tmp_path, THIRD, "numba_second")[:2]) == expected


NO_NUMBA = """import sys
class Blocked:
    def find_spec(self, name, path, target=None):
        if name.partition(".")[0] == "numba":
            raise ImportError(f"{name} imported on the read path")
sys.meta_path.insert(0, Blocked())
import spinorbit.edge.api, spinorbit.solutions.tables, spinorbit.solutions.earth_layer, spinorbit.analysis.librations
import spinorbit.comparisons.moon_de421, spinorbit.references.eckhardt, spinorbit.references.moon_de421
from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import store
for scene in ("moon_libration", "earth_precession_nutation_nonrigid"):
    store.path_of(store.record(load_scenario(scene)))
"""


def test_the_stored_answer_path_imports_no_numba(tmp_path):
    """What answering from a stored solution imports -- the API, the store, the tables and comparisons it
    evaluates, the built-in scenes' validation and their records -- runs with numba's import refused
    (docs/DEVELOPING.md, light imports)."""
    (tmp_path / "cache").mkdir(mode=0o700)
    done = subprocess.run([sys.executable, "-c", NO_NUMBA], capture_output=True, text=True, check=False,
                          env={**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_CACHE_DIR": str(tmp_path / "cache")})
    assert done.returncode == 0, done.stderr[-2000:]
