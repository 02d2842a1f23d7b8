"""An ocean's two parameters fitted to today's recession and the Moon's age, and nothing else:

    python -m spinorbit.fit_tides            # prints the fit of the ocean with its continent (the default)
    python -m spinorbit.fit_tides --write    # and stores it in spinorbit/models/tidal_history/ocean_fit.json
    python -m spinorbit.fit_tides --model global_ocean --write      # another ocean (tides.TIDES): its own file
    python -m spinorbit.fit_tides --set 'tides.continent_colatitude="0 deg"' --bracket 3 9   # other keys: printed

At each depth the drag is the one whose recession today is LLR's 3.830 cm/yr (Williams & Boggs 2016;
calibration.ocean_drag); the depth is bisected until the history (scenarios/earth_moon_history.toml with
that tides.model, the continent's keys at their defaults) reaches the Roche limit at the Moon's age,
4.425 Ga (Maurice et al. 2020), within AGE_TOLERANCE_GYR.  The geological proxies are never used.

The fit is a developer's command: its result is a reviewed data file of the repository (the scene's default
depth), written aside and renamed over the old one, so a failed write (a full disk) leaves the old fit whole.
"""
import argparse
import json
import math
import os
from pathlib import Path

from .models.tidal_history.fit import RECESSION_CM_PER_YR, Trial, fit_depth
from .models.tidal_history.tides import FITS, TIDES

SCENE = Path(__file__).with_name("builtin_scenarios") / "earth_moon_history.toml"
OCEANS = {name: tide for name, tide in TIDES.items() if tide.depth is not None}


def command(model):
    return "python -m spinorbit.fit_tides" + ("" if model == "ocean" else f" --model {model}") + " --write"


def history_at(depth_km, model="ocean", overrides=()):
    """The Trial of the ocean's history at this depth (the scene run back 4.6 Gyr, its drag fitted to LLR's
    rate, no error estimate); ``overrides``: the scene's other keys ("key=value")."""
    from .runner import run_scenario

    summary = run_scenario(SCENE, [*overrides, f'tides.model="{model}"', f'{OCEANS[model].depth.key}="{depth_km!r} km"',
                                   "compare.models=false", "integrator.estimate_error=false",
                                   'span.end="-4.6 Gyr"', f'tides.recession_rate="{RECESSION_CM_PER_YR} cm/yr"'
                                   ]).summary
    age = summary["comparison"]["moon_age_gyr"]
    return Trial(depth_km, summary["model"]["ocean_drag_per_day"], math.inf if age is None else age)


def fit(model="ocean", bracket=None, log=print, overrides=()):
    """The fit's record (models.tidal_history.fit.Fit.record): the depth bisected inside ``bracket`` (km;
    default the tide's own), whose ends' histories stop on either side of the Moon's age."""
    result = fit_depth(model, bracket or OCEANS[model].depth.bracket_km,
                       lambda depth: history_at(depth, model, overrides), log)
    return result.record(command(model), overrides)


def write_fit(path, result):
    """``result`` as JSON at ``path``, written aside, synced and renamed over it: never half a file."""
    path = Path(path)
    aside = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(aside, "w") as f:
            f.write(json.dumps(result, indent=2) + "\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(aside, path)
    finally:
        aside.unlink(missing_ok=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="store the fit in the package")
    parser.add_argument("--model", choices=tuple(OCEANS), default="ocean", help="the ocean to fit")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="another value of one of the scene's keys (e.g. the continent's); not with --write")
    parser.add_argument("--bracket", nargs=2, type=float, metavar=("LOW_KM", "HIGH_KM"),
                        help="the depths whose ages straddle the Moon's (default: the default scene's)")
    args = parser.parse_args(argv)
    if args.write and args.set:
        parser.error("--write stores the default scene's fit; with --set the fit is printed only")
    result = fit(args.model, args.bracket, overrides=tuple(args.set))
    print(json.dumps(result, indent=2))
    if args.write:
        write_fit(FITS / OCEANS[args.model].depth.fit_file, result)


if __name__ == "__main__":
    main()
