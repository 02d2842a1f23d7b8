"""Right-hand-side evaluations per second: numba vs pure NumPy vs heyoka, same model (benchmarks/models.py).

Run: ``python benchmarks/bench_rhs.py``.  Compilation (numba JIT, heyoka LLVM)
is done before timing and reported separately.
"""
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

sys.path.insert(0, str(Path(__file__).parent))
import models  # noqa: E402


def rate(fn, n):
    start = time.perf_counter()
    fn(n)
    return n / (time.perf_counter() - start)


@njit
def _loop(rhs, params, y, n):
    acc = 0.0
    for i in range(n):
        acc += rhs(1e-6 * i, y, params)[4]
    return acc


def main():
    rows = []
    system = models.numba_system()
    rhs, params, y = system.rhs, system.params, system.y0
    start = time.perf_counter()
    _loop(rhs, params, y, 1)
    compile_numba = time.perf_counter() - start
    assert np.allclose(rhs(0.3, y, params), models.numpy_rhs(0.3, y), rtol=1e-12, atol=1e-14)
    rows.append(("numba rhs, compiled loop (as the integrators call it)",
                 rate(lambda n: _loop(rhs, params, y, n), 2_000_000)))
    rows.append(("numba rhs, called from Python",
                 rate(lambda n: [rhs(1e-6 * i, y, params) for i in range(n)], 200_000)))
    rows.append(("pure NumPy rhs, called from Python",
                 rate(lambda n: [models.numpy_rhs(1e-6 * i, y) for i in range(n)], 50_000)))
    compile_heyoka = None
    try:
        import heyoka as hy

        variables, exprs = models.heyoka_equations()
        start = time.perf_counter()
        cf = hy.cfunc(exprs, variables)
        compile_heyoka = time.perf_counter() - start
        assert np.allclose(cf(y, time=0.3), models.numpy_rhs(0.3, y), rtol=1e-12, atol=1e-14)
        batch = np.repeat(y[:, None], 100_000, axis=1)
        times = np.linspace(0, 0.1, 100_000)
        rows.append(("heyoka cfunc, batch of 1e5 states (SIMD)",
                     rate(lambda n: [cf(batch, time=times) for _ in range(n // 100_000)], 2_000_000)))
        rows.append(("heyoka cfunc, one state per call from Python",
                     rate(lambda n: [cf(y, time=1e-6 * i) for i in range(n)], 100_000)))
    except ImportError:
        rows.append(("heyoka (not installed)", float("nan")))
    print("| right-hand side | evaluations / s |")
    print("|---|---|")
    for name, r in rows:
        print(f"| {name} | {r:.3g} |")
    print(f"\nCompilation excluded: numba {compile_numba:.2f} s" +
          (f", heyoka cfunc {compile_heyoka:.2f} s" if compile_heyoka is not None else ""))


if __name__ == "__main__":
    main()
