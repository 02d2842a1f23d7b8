"""A Solution as SPICE kernels (written with spiceypy: ``pip install "spinorbit[spice]"``).

* Each body with an attitude: a binary PCK of type 2 -- Chebyshev series of the 3-1-3 Euler angles (phi,
  theta, psi) of its ICRF-to-body rotation Rz(psi) Rx(theta) Rz(phi) relative to J2000, the layout of JPL's
  ``moon_pa_de421_1900-2050.bpc`` (NAIF, PCK Required Reading, "Binary PCK Kernel Format", type 2) -- and a text
  frame kernel naming its frame (``<BODY>_PA_SPINORBIT``, class 2: a PCK frame), as JPL's ``moon_080317.tf``.
  The angles are refitted on the solution's own grid at its Chebyshev points; the difference of the rotation
  they give from the solution's, measured between those points, is returned.
* The positions of the integrated bodies (every ``<body>.r`` slice: barycentric, or from the primary its unit
  names): an SPK of type 2 (Chebyshev positions; SPK Required Reading), the series the solution already holds.

Read back by spiceypy (``furnsh``; ``pxform("J2000", frame, et)``, ``spkezr``) or skyfield
(``PlanetaryConstants.read_text`` / ``read_binary`` / ``build_frame_named``; ``load(...)`` for the SPK).
"""
import os
from pathlib import Path

import numpy as np

from ..constants import ARCSEC, DAY_S
from ..errors import InputError
from .chebyshev import interpolating, second_kind

NAIF_IDS = {"sun": 10, "mercury": 199, "venus": 299, "earth_moon_barycenter": 3, "earth": 399, "moon": 301,
            "mars": 4, "jupiter": 5, "saturn": 6, "uranus": 7, "neptune": 8, "pluto": 9}
FRAME_BASE = 1_400_000          # NAIF's range for frames users define: 1 400 000 to 2 000 000


def frame_name(body):
    return f"{body.upper()}_PA_SPINORBIT"


def frame_id(body):
    return FRAME_BASE + NAIF_IDS[body]


def export(solution, directory):
    """Write the solution's kernels into ``directory`` (created); return {"files": [...], "fit_error": {...}}."""
    try:
        import spiceypy
    except ImportError:
        raise InputError("export", "spiceypy not installed", 'pip install "spinorbit[spice]"') from None
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    name = solution.provenance.get("scene", "solution")
    files, error = [], {}
    attitudes = [s.name.split(".")[0] for s in solution.layout.slices if s.kind == "quaternion"]
    positions = [s for s in solution.layout.slices if s.name.endswith(".r")]
    for body in attitudes:
        coefficients, error[f"{body}_angles_arcsec"] = angle_series(solution, body)
        files.append(_written(directory / f"{name}_{body}.bpc",
                              lambda path, b=body, c=coefficients: _pck(spiceypy, solution, b, c, path)))
        files.append(_written(directory / f"{name}_{body}.tf", lambda path, b=body: path.write_text(frame_kernel(b))))
    if positions:
        files.append(_written(directory / f"{name}.bsp", lambda path: _spk(spiceypy, solution, positions, path)))
    return {"files": [str(f) for f in files], "fit_error": error}


def angle_series(solution, body):
    """(Chebyshev coefficients (segments, 3, degree + 1) of the 3-1-3 angles of ``body`` on the solution's grid,
    the largest rotation (arcsec) between the angles' series and the solution's attitude between the points)."""
    from ..analysis.librations import icrf_to_body
    from ..rotations import euler313_from_matrix, matrix_from_euler313

    segments = solution.segments
    count, degree = len(segments.coefficients), segments.degree
    nodes, checks = segments.nodes(segments.first, count)
    angles = euler313_from_matrix(icrf_to_body(solution.part(f"{body}.q", nodes.ravel())))
    angles = np.unwrap(angles.reshape(count, degree + 1, 3), axis=1)         # continuous within a segment
    coefficients = interpolating(angles.transpose(0, 2, 1))
    turns = np.round(coefficients[:, :, 0] / (2 * np.pi))
    coefficients[:, :, 0] -= 2 * np.pi * turns                               # the same rotation, small values
    x = second_kind(degree)
    fitted = np.polynomial.chebyshev.chebval(x, coefficients.transpose(2, 0, 1))   # (segments, 3, points)
    mats = matrix_from_euler313(*np.moveaxis(fitted.transpose(0, 2, 1).reshape(-1, 3), -1, 0))
    truth = icrf_to_body(solution.part(f"{body}.q", checks.ravel()))
    difference = np.linalg.norm(mats - truth, axis=(1, 2)) / np.sqrt(2.0)     # the angle, for small angles
    return coefficients, float(difference.max() / ARCSEC)


def frame_kernel(body):
    """The text frame kernel naming ``body``'s PCK frame (as JPL's moon_080317.tf names MOON_PA_DE421)."""
    code, name = frame_id(body), frame_name(body)
    return (f"KPL/FK\n\n{name}: the principal axes of {body} integrated by spinorbit (a binary PCK of type 2 "
            f"gives its 3-1-3 angles relative to J2000).\n\n\\begindata\n\n"
            f"    FRAME_{name} = {code}\n    FRAME_{code}_NAME = '{name}'\n    FRAME_{code}_CLASS = 2\n"
            f"    FRAME_{code}_CLASS_ID = {code}\n    FRAME_{code}_CENTER = {NAIF_IDS[body]}\n\n\\begintext\n")


def _seconds(solution):
    """(first, last, segment length, first segment's start) in TDB seconds from J2000."""
    s = solution.segments
    first, last = solution.span
    return first * DAY_S, last * DAY_S, s.length_d * DAY_S, first * DAY_S


def _pck(spiceypy, solution, body, coefficients, path):
    first, last, length, begin = _seconds(solution)
    handle = spiceypy.pckopn(str(path), f"spinorbit {body}", 0)
    try:
        spiceypy.pckw02(handle, frame_id(body), "J2000", first, last, f"spinorbit {body} orientation", length,
                        len(coefficients), solution.segments.degree, np.ascontiguousarray(coefficients).ravel(),
                        begin)
    finally:
        spiceypy.pckcls(handle)


def _spk(spiceypy, solution, slices, path):
    first, last, length, begin = _seconds(solution)
    handle = spiceypy.spkopn(str(path), "spinorbit", 0)
    try:
        for part in slices:
            body = part.name.split(".")[0]
            center = 0 if "barycentric" in part.unit else NAIF_IDS[part.unit.split("from ")[1].split(",")[0]]
            coefficients = solution.segments.coefficients[:, part.index, :]
            spiceypy.spkw02(handle, NAIF_IDS[body], center, "J2000", first, last, f"spinorbit {body}", length,
                            len(coefficients), solution.segments.degree, np.ascontiguousarray(coefficients).ravel(),
                            begin)
    finally:
        spiceypy.spkcls(handle)


def _written(path, write):
    """``write(aside)`` to a file beside ``path``, then renamed over it (nothing half-written is left)."""
    aside = path.with_name(f".{path.name}.tmp-{os.getpid()}{path.suffix}")
    aside.unlink(missing_ok=True)
    try:
        write(aside)
        os.replace(aside, path)
    finally:
        aside.unlink(missing_ok=True)
    return path
