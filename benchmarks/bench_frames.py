"""The API's frames against independent references, over many dates.

    python benchmarks/bench_frames.py [cio|all] [--dates N]

* cio: ``earth_pole``'s CIO locator s and GCRS-to-CIRS matrix at N dates over 1950-2050 (the validated non-rigid
  Earth's century), against ERFA's IAU 2006/2000A (``s06a``, ``c2i06a``): the largest difference, and where s
  differs by more than 1 uas, what the model's CIP makes of it (-(X dY + Y dX) / 2).
"""
import argparse
import json
import warnings

import numpy as np

UAS = np.pi / 180 / 3600 / 1e6
MAS = UAS * 1e3
CENTURY_1950_2050 = (-18262.5 + 1.0, 18262.5 - 1.0)         # TDB days from J2000


def dates(span, count, seed):
    from astropy.time import Time

    days = np.sort(np.random.default_rng(seed).uniform(*span, count))
    return Time(2451545.0, days, format="jd", scale="tdb")


def rotation_angle(a, b):
    return np.linalg.norm(a - b, axis=(1, 2)) / np.sqrt(2.0)


def cio(count):
    import erfa

    import spinorbit

    t = dates(CENTURY_1950_2050, count, 44)
    table = spinorbit.earth_pole(t)
    tt = t.tt
    s = table["cio_locator_s"].to_value("rad")
    ds = s - erfa.s06a(tt.jd1, tt.jd2)
    x, y = table["cip_x"].to_value("rad"), table["cip_y"].to_value("rad")
    dx, dy = table["cip_x_minus_erfa"].to_value("rad"), table["cip_y_minus_erfa"].to_value("rad")
    by_cip = -(x * dy + y * dx + dx * dy) / 2                     # s06's -XY/2 of the model's CIP less IAU's
    over = np.abs(ds) > UAS
    years = 2000.0 + (t.tdb.jd1 - 2451545.0 + t.tdb.jd2) / 365.25
    angle = rotation_angle(np.asarray(table["celestial_to_intermediate"]), erfa.c2i06a(tt.jd1, tt.jd2))
    return {"dates": count, "span": "1950-2050", "s_minus_s06a_max_uas": float(np.abs(ds).max() / UAS),
            "dates_over_1_uas": int(over.sum()),
            "years_over_1_uas": [round(float(y), 2) for y in years[over]],
            "s_minus_s06a_less_the_cip_term_max_uas": float(np.abs(ds - by_cip).max() / UAS),
            "matrix_minus_c2i06a_max_mas": float(angle.max() / MAS)}


PARTS = {"cio": cio}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("part", choices=[*PARTS, "all"], nargs="?", default="all")
    parser.add_argument("--dates", type=int, default=1000)
    args = parser.parse_args()
    warnings.simplefilter("ignore")          # ERFA's "dubious year" for UTC of future dates
    for name in PARTS if args.part == "all" else [args.part]:
        print(name, json.dumps(PARTS[name](args.dates), indent=1))


if __name__ == "__main__":
    main()
