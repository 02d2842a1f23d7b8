"""What fitting a run's main integration into a Solution adds to a whole run, for each kind kept as a solution.

    python benchmarks/bench_run_fit.py [--reps 2] [kind=span.end ...]

Each kind's built-in scene (or those named, to the span.end given; the solar system by default to 1971) is run
through ``runner.run_scenario`` twice in turn in one process: fitted (its main run integrated once into a Solution,
solutions.for_run) and not (integrated to the output times; solutions.not_fitted made to refuse), plots off,
``reps`` times; the CPU time of the whole run (process_time: both threads, the error estimate's too) is
compared, warm (a first run of each compiles, not counted).  The ratio is what fitting every run of these kinds costs.
"""
import argparse
import time

from spinorbit import solutions
from spinorbit.edge.runner import run_scenario

KINDS = {"moon_libration": None, "earth_precession_nutation": None, "earth_moon_coupled": None,
         "solar_system": "1971-01-01"}


def cpu_of(kind, sets, fitted):
    """CPU seconds of one run of ``kind`` (its Solution forced or refused)."""
    original = solutions.not_fitted
    solutions.not_fitted = (lambda s, system: "") if fitted else (lambda s, system: "refused by the benchmark")
    try:
        started = time.process_time()
        result = run_scenario(kind, sets)
        return time.process_time() - started, result
    finally:
        solutions.not_fitted = original


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--reps", type=int, default=2)
    parser.add_argument("ends", nargs="*", help="kind=span.end")
    args = parser.parse_args()
    ends = dict(e.split("=", 1) for e in args.ends) or KINDS
    print("| kind | span | CPU s to the outputs | CPU s fitted | ratio | fit / integration error: attitude ″ "
          "| position km |")
    print("|---|---|---|---|---|---|---|")
    for kind, end in ends.items():
        sets = ["output.plots=false"] + ([f"span.end={end}"] if end else [])
        cpu_of(kind, sets, True), cpu_of(kind, sets, False)          # compile
        plain, fitted = [], []
        for _ in range(args.reps):
            plain.append(cpu_of(kind, sets, False)[0])
            seconds, result = cpu_of(kind, sets, True)
            fitted.append(seconds)
        section = result.summary["solution"]
        print(f"| {kind} | {result.summary['span']['years']} | {min(plain):.2f} | {min(fitted):.2f} | "
              f"{min(fitted) / min(plain):.2f} | {errors(section, ('attitude', 'direction'), 'attitude_arcsec')} | "
              f"{errors(section, ('position',), 'position_km')} |")


def errors(section, fitted, estimated):
    """"fit / integration" of a run's summary["solution"]: the largest fit error of the ``fitted`` kinds, the
    integration's estimate ``estimated`` (or "not estimated")."""
    fit = [v for k, v in section.items() if k.startswith(tuple(f"fit_error_{f}" for f in fitted))]
    estimate = section.get(f"integration_error_{estimated}")
    if not fit:
        return "—"
    return f"{max(fit):.2g} / " + (f"{estimate:.2g}" if estimate is not None else "not estimated")


if __name__ == "__main__":
    main()
