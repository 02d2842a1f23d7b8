"""An ocean's two parameters fitted to today's recession and the Moon's age, and nothing else:

    python benchmarks/fit_tides.py            # prints the fit of the ocean with its continent (the default)
    python benchmarks/fit_tides.py --write    # and stores it in spinorbit/models/tidal_history/ocean_fit.json
    python benchmarks/fit_tides.py --model global_ocean --write      # another ocean (tides.TIDES): its own file
    python benchmarks/fit_tides.py --set 'tides.continent_colatitude="0 deg"' --bracket 3 9   # other keys: printed

At each depth the drag is the one whose recession today is LLR's 3.830 cm/yr (Williams & Boggs 2016;
calibration.ocean_drag); the depth is bisected (models.tidal_history.fit.fit_depth) until the history (the
built-in earth_moon_history with that tide alone, starts.earth_moon_history.fit_trial: its parameters built
typed) reaches the Roche limit at the Moon's age, 4.425 Ga (Maurice et al. 2020), within AGE_TOLERANCE_GYR.
The geological proxies are never used.

The fit is a developer's command, beside the repository's benchmarks and never installed with the package: its
result is a reviewed data file of this checkout (the scene's default depth), written aside and renamed over the
old one (spinorbit.base.files.write_atomically), so a failed write (a full disk) leaves the old fit whole.
"""
import argparse
import json
import math
from pathlib import Path

from spinorbit.base.files import write_atomically
from spinorbit.models.tidal_history.fit import RECESSION_CM_PER_YR, Trial, fit_depth
from spinorbit.models.tidal_history.tides import TIDES

SCENE = "earth_moon_history"
FITS = Path(__file__).resolve().parents[1] / "spinorbit" / "models" / "tidal_history"   # this checkout's
OCEANS = {name: tide for name, tide in TIDES.items() if tide.depth is not None}


def command(model):
    return "python benchmarks/fit_tides.py" + ("" if model == "ocean" else f" --model {model}") + " --write"


def history_at(scenario, depth_km, model="ocean"):
    """The Trial of the ocean's history at this depth: ``scenario`` (earth_moon_history) run back 4.6 Gyr with
    the ocean alone, its drag fitted to LLR's rate, no error estimate (starts.earth_moon_history.fit_trial)."""
    from spinorbit.edge.runner import run_scenario
    from spinorbit.starts.earth_moon_history import fit_trial

    trial = scenario.with_params(fit_trial(scenario.params, model, depth_km, RECESSION_CM_PER_YR))
    summary = run_scenario(trial).summary
    age = summary["comparison"]["moon_age_gyr"]
    return Trial(depth_km, summary["model"]["ocean_drag_per_day"], math.inf if age is None else age)


def fit(model="ocean", bracket=None, log=print, overrides=()):
    """The fit's record (models.tidal_history.fit.Fit.record): the depth bisected inside ``bracket`` (km;
    default the tide's own), whose ends' histories stop on either side of the Moon's age; ``overrides``: the
    scene's other keys ("key=value", the command line's --set)."""
    from spinorbit.edge.scenarios import load_scenario

    scenario = load_scenario(SCENE, list(overrides))
    result = fit_depth(model, bracket or OCEANS[model].depth.bracket_km,
                       lambda depth: history_at(scenario, depth, model), log)
    return result.record(command(model), overrides)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="store the fit in this checkout's package sources")
    parser.add_argument("--model", choices=tuple(OCEANS), default="ocean", help="the ocean to fit")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="another value of one of the scene's keys (e.g. the continent's); not with --write")
    parser.add_argument("--bracket", nargs=2, type=float, metavar=("LOW_KM", "HIGH_KM"),
                        help="the depths whose ages straddle the Moon's (default: the default scene's)")
    args = parser.parse_args(argv)
    if args.write and args.set:
        parser.error("--write stores the default scene's fit; with --set the fit is printed only")
    result = fit(args.model, args.bracket, overrides=tuple(args.set))
    text = json.dumps(result, indent=2) + "\n"
    print(text, end="")
    if args.write:
        write_atomically(FITS / OCEANS[args.model].depth.fit_file, lambda f: f.write(text.encode()),
                         prefix=f".{OCEANS[args.model].depth.fit_file}.")


if __name__ == "__main__":
    main()
