"""A Solution as SPICE kernels (written with spiceypy: ``pip install "spinorbit[spice]"``).

* Each body with an attitude: a binary PCK of type 2 -- Chebyshev series of the 3-1-3 Euler angles (phi,
  theta, psi) of its ICRF-to-body rotation Rz(psi) Rx(theta) Rz(phi) relative to J2000, the layout of JPL's
  ``moon_pa_de421_1900-2050.bpc`` (NAIF, PCK Required Reading, "Binary PCK Kernel Format", type 2) -- and a text
  frame kernel naming its frame (``<BODY>_PA_SPINORBIT_<solution id>``, class 2: a PCK frame; one name and ID
  per solution, :func:`frame_name`, :func:`frame_id`), as JPL's ``moon_080317.tf`` (for the Moon also
  ``MOON_ME_SPINORBIT_<id>``, its mean-Earth/polar-axis frame: a TK frame relative to the PA one, as JPL's
  MOON_ME_DE421 is to MOON_PA_DE421).
  The angles are refitted on the solution's own grid at its Chebyshev points; the difference of the rotation
  they give from the solution's, measured between those points, is returned.
* The positions of the integrated bodies: an SPK of type 2 (Chebyshev positions; SPK Required Reading) in the
  frame J2000 (ICRF), time in TDB seconds past J2000 (SPICE's ET), one segment per body on its own record length
  and degree as DE421's (solutions.tracks: refitted from the solution's series, each fit's error stated): a
  barycentric ``<body>.r`` about the solar-system barycentre (centre 0); the Moon seen from the Earth
  (``moon.r``) as DE421 writes it, the Moon (301) and the Earth (399) about the Earth-Moon barycentre (3), and
  that barycentre about 0 -- the solar system's own, or for the coupled Earth-Moon the run's ephemeris's -- so
  the file alone reaches the barycentre.  Codes (spinorbit.bodies.table): a point mass carrying a planet's
  system is that system's barycentre (Mercury 1 ... Pluto 9, as DE421's segments about 0), the Sun 10, the Moon
  301, the Earth 399.  The comments state, per body, the fit's error and how far it lies from DE421 over the
  span (heliocentric planets and Earth, the geocentric Moon, the Sun about 0: the barycentre's drift).

Every kernel's comment area (lines of at most COMMENT_LINE characters) names what made it: the scene, every key
of its model and of the scenario asked, the ephemeris, the integrator, the code's version, the span, the grid and
the fit's error.  SPICE writes each kernel under a short name in a private temporary folder (it cuts a file
name at SPICE_FILE_NAME characters); it is then copied beside its place and renamed there.  Read back by
spiceypy (``furnsh``; ``pxform("J2000", frame, et)``, ``spkezr`` / ``spkpos``) or skyfield
(``PlanetaryConstants.read_text`` / ``read_binary`` / ``build_frame_named``; ``load_file`` / ``SpiceKernel``
for the SPK).
"""
import hashlib
import json
import os
import shutil
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from ..base.constants import ARCSEC, DAY_S
from ..base.errors import EphemerisRangeError, InputError
from ..base.files import write_atomically
from ..bodies.table import EMB
from .chebyshev import Segments, interpolating_at
from .tracks import body_code, tracks

# Frame IDs: NAIF leaves 1 400 000 to 2 000 000 to users (Frames Required Reading, "Selecting a Name and ID");
# JPL's lunar frames (31000-31008) and the built-in ones lie below it.  A solution's frames take the block of
# FRAMES_PER_SOLUTION IDs its identity's hash picks, one ID each for the axes it defines (AXES).
FRAME_BASE = 1_400_000
FRAME_BLOCKS = 150_000                  # (2 000 000 - 1 400 000) / FRAMES_PER_SOLUTION
FRAMES_PER_SOLUTION = 4
# The axes a PCK's angles turn to: the principal axes (a body whose solution holds its attitude; the Moon's
# mean Earth beside them), or the figure axis and the prime meridian (IAU convention: a gyroscopic body's
# solutions.attitude_layer).
AXES = ("PA", "ME", "PM")
AXES_SAID = {"PA": "the principal axes", "PM": "the figure axis (z) and prime meridian (x)"}
COMMENT_LINE = 80                       # a comment line's longest (spiceypy.dafec reads lines of up to ~80)
SPICE_FILE_NAME = 255                   # SPICE's longest file name: a longer one is cut (FILEN, SPICE Toolkit)


def identity(solution):
    """8 hex digits naming what decides the solution's numbers: its scene, its model's keys (the store's
    record), the ephemeris, the code's version and where the model starts (TDB days)."""
    p = solution.provenance
    what = {key: p.get(key) for key in ("scene", "keys", "ephemeris", "code_version", "model_start_tdb_d")}
    return hashlib.sha256(json.dumps(what, sort_keys=True, default=str).encode()).hexdigest()[:8]


def frame_name(body, solution_id, axes="PA"):
    """``<BODY>_<axes>_SPINORBIT_<solution id>``: one name per exported solution (at most 32 characters, as
    SPICE's frame names)."""
    return f"{body.upper()}_{axes}_SPINORBIT_{solution_id.upper()}"


def frame_id(solution_id, axes="PA"):
    """The frame's ID: FRAME_BASE + FRAMES_PER_SOLUTION x (the identity's hash mod FRAME_BLOCKS) + the axes'
    place in AXES.  Two solutions share a block with probability 1 / FRAME_BLOCKS."""
    block = int(solution_id, 16) % FRAME_BLOCKS
    return FRAME_BASE + FRAMES_PER_SOLUTION * block + AXES.index(axes)


def export(solution, directory, asked=None):
    """Write the solution's kernels into ``directory`` (created); ``asked``: {key: value} of the scenario asked
    for, written in the comments beside the solution's own.  Returns {"files": [...], "frames": {body: name,
    "moon_mean_earth": the Moon's ME frame's name}, "fit_error": {...}}."""
    try:
        import spiceypy
    except ImportError:
        raise InputError("export", "spiceypy not installed", 'pip install "spinorbit[spice]"') from None
    name = solution.provenance.get("scene", "solution")
    attitudes = {s.name.split(".")[0]: "PA" for s in solution.layout.slices if s.kind == "quaternion"}
    attitudes.update({s.name.split(".")[0]: "PM" for s in solution.layout.slices
                      if s.name.endswith(".prime_meridian")})
    positions = any(s.name.endswith(".r") for s in solution.layout.slices)
    if not attitudes and not positions:
        raise InputError("scene", f"{name} (its solution holds {', '.join(solution.layout.names)})",
                         "a solution with an attitude (<body>.q) or integrated positions (<body>.r)")
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    solution_id = identity(solution)
    files, frames, error = [], {}, {}
    for body, axes in attitudes.items():
        frames[body] = frame_name(body, solution_id, axes)
        if body == "moon":
            frames["moon_mean_earth"] = frame_name(body, solution_id, "ME")
        coefficients, error[f"{body}_angles_arcsec"] = angle_series(solution, body)
        lines = comments(solution, f"the orientation of {body} (frame {frames[body]})", asked)
        files.append(_written(directory / f"{name}_{body}.bpc", lambda path, b=body, c=coefficients, k=lines, a=axes:
                              _pck(spiceypy, solution, b, c, k, frame_id(solution_id, a), path)))
        files.append(_written(directory / f"{name}_{body}.tf",
                              lambda path, b=body, a=axes: path.write_text(frame_kernel(b, solution_id, a))))
    if positions:
        def spk(path):
            error.update(_spk(spiceypy, solution, asked, path))

        files.append(_written(directory / f"{name}.bsp", spk))
    return {"files": [str(f) for f in files], "frames": frames, "fit_error": error}


def angle_series(solution, body):
    """(Chebyshev coefficients (segments, 3, degree + 1) of the 3-1-3 angles of ``body`` on the solution's grid,
    the largest rotation (arcsec) between the angles' series and the solution's attitude between the points)."""
    from ..base.rotations import matrix_from_euler313

    segments = solution.segments
    count, degree = len(segments.coefficients), segments.degree
    nodes, checks = segments.nodes(segments.first, count)
    angles = body_angles(solution, body, nodes.ravel()).reshape(count, degree + 1, 3)
    turning = 3 if f"{body}.q" in solution.layout else 2     # a prime meridian's series is continuous already
    angles[..., :turning] = np.unwrap(angles[..., :turning], axis=1)         # continuous within a segment
    coefficients = interpolating_at(angles.transpose(0, 2, 1), segments.normalised(nodes, segments.first))
    turns = np.round(coefficients[:, :, 0] / (2 * np.pi))
    coefficients[:, :, 0] -= 2 * np.pi * turns                               # the same rotation, small values
    series = Segments(segments.origin_d, segments.length_d, segments.first, coefficients)
    fitted = series.at_normalised(segments.normalised(checks, segments.first)).reshape(-1, 3)
    mats = matrix_from_euler313(*np.moveaxis(fitted, -1, 0))
    truth = matrix_from_euler313(*body_angles(solution, body, checks.ravel()).T)
    difference = np.linalg.norm(mats - truth, axis=(1, 2)) / np.sqrt(2.0)     # the angle, for small angles
    return coefficients, float(difference.max() / ARCSEC)


def body_angles(solution, body, t):
    """The 3-1-3 angles (n, 3) of ``body``'s ICRF-to-body rotation at TDB days ``t``: from its attitude
    quaternion, or from its pole and prime meridian (phi = alpha + 90 deg, theta = 90 deg - delta, psi = W)."""
    from ..analysis.librations import icrf_to_body
    from ..base.rotations import euler313_from_matrix

    if f"{body}.q" in solution.layout:
        return euler313_from_matrix(icrf_to_body(solution.part(f"{body}.q", t)))
    values = solution.components(t)
    pole = values[:, solution.layout[f"{body}.pole"]]
    pole = pole / np.linalg.norm(pole, axis=1)[:, None]
    return np.column_stack([np.arctan2(pole[:, 1], pole[:, 0]) + np.pi / 2, np.arccos(pole[:, 2]),
                            values[:, solution.layout[f"{body}.prime_meridian"]][:, 0]])


def frame_kernel(body, solution_id, axes="PA"):
    """The text frame kernel naming ``body``'s PCK frame (as JPL's moon_080317.tf names MOON_PA_DE421)."""
    code, name = frame_id(solution_id, axes), frame_name(body, solution_id, axes)
    about = (f"{name}: {AXES_SAID[axes]} of {body} integrated by spinorbit (solution {solution_id}); a binary "
             f"PCK of type 2 gives its 3-1-3 angles relative to J2000.  Each exported solution names its "
             f"frames <BODY>_<AXES>_SPINORBIT_<solution id>, IDs {FRAME_BASE} + {FRAMES_PER_SOLUTION} x "
             f"(id mod {FRAME_BLOCKS}) + the axes' place (PA 0, the Moon's ME 1, PM 2).")
    text = (f"KPL/FK\n\n{_wrapped(about)}\n\n\\begindata\n\n"
            f"    FRAME_{name} = {code}\n    FRAME_{code}_NAME = '{name}'\n    FRAME_{code}_CLASS = 2\n"
            f"    FRAME_{code}_CLASS_ID = {code}\n    FRAME_{code}_CENTER = {body_code(body)}\n\n\\begintext\n")
    return text + mean_earth_frame(name, solution_id) if body == "moon" else text


def mean_earth_frame(principal, solution_id):
    """The Moon's mean-Earth/polar-axis frame as a TK frame relative to its principal-axis frame ``principal``,
    turned as MOON_ME_DE421 is from MOON_PA_DE421 (NAIF's moon_080317.tf, frame 31007:
    references.moon_de421.MEAN_EARTH_TK_ANGLES)."""
    from ..references.moon_de421 import MEAN_EARTH_TK_ANGLES

    code, name = frame_id(solution_id, "ME"), frame_name("moon", solution_id, "ME")
    angles = "  ".join(f"{angle:.2f}" for _, angle in MEAN_EARTH_TK_ANGLES)
    axes = ", ".join(str(axis) for axis, _ in MEAN_EARTH_TK_ANGLES)
    about = (f"{name}: the Moon's mean-Earth/polar-axis frame, the principal axes above turned as MOON_ME_DE421 "
             "is from MOON_PA_DE421 (NAIF's moon_080317.tf, frame 31007; the angles from Williams, Boggs & Folkner "
             "2008, JPL IOM 335-JW,DB,WF-20080314-001).")
    return (f"\n{_wrapped(about)}\n\n\\begindata\n\n"
            f"    FRAME_{name} = {code}\n    FRAME_{code}_NAME = '{name}'\n    FRAME_{code}_CLASS = 4\n"
            f"    FRAME_{code}_CLASS_ID = {code}\n    FRAME_{code}_CENTER = {body_code('moon')}\n"
            f"    TKFRAME_{code}_SPEC = 'ANGLES'\n    TKFRAME_{code}_RELATIVE = '{principal}'\n"
            f"    TKFRAME_{code}_ANGLES = ( {angles} )\n    TKFRAME_{code}_AXES = ( {axes} )\n"
            f"    TKFRAME_{code}_UNITS = 'ARCSECONDS'\n\n\\begintext\n")


def _wrapped(text):
    """``text`` in lines of at most COMMENT_LINE characters (a word longer than that cut), continued indented."""
    return "\n".join(textwrap.wrap(text, COMMENT_LINE, subsequent_indent="    ", break_on_hyphens=False))


def _seconds(solution):
    """(first, last, segment length) in TDB seconds from J2000."""
    first, last = solution.span
    return first * DAY_S, last * DAY_S, solution.segments.length_d * DAY_S


def comments(solution, what, asked=None):
    """The comment area's lines (at most COMMENT_LINE characters, ASCII): what the kernel holds and what made
    it (the solution's provenance: ``made with``), and ``asked``, the scenario's every key (``asked``)."""
    p = solution.provenance
    lo, hi = solution.span
    text = [f"spinorbit {p.get('code_version')}: {what} of the solution {identity(solution)} of the "
            f"'{p.get('scene')}' scene",
            f"span: {lo:.6f} to {hi:.6f} TDB days from J2000 ({lo * DAY_S:.3f} to {hi * DAY_S:.3f} TDB s), "
            f"Chebyshev segments of {solution.segments.length_d:g} d, degree {solution.segments.degree}"]
    made = {key: p.get(key) for key in ("scene", "keys", "ephemeris", "integrator", "code_version",
                                        "model_start_tdb_d", "grid", "fit_error")}
    sections = [("made with", made)] + ([("asked", asked)] if asked is not None else [])
    for title, values in sections:
        text.append(f"{title}:")
        text += [f"  {key} = {json.dumps(value, default=str, sort_keys=True)}" for key, value in _flat(values)]
    lines = [line for entry in text for line in _wrapped(entry).splitlines()]
    return [line.encode("ascii", "replace").decode() for line in lines]


def _flat(values, prefix=""):
    """[(dotted key, value)] of nested dicts."""
    out = []
    for key, value in sorted(values.items()):
        if isinstance(value, dict) and value:
            out += _flat(value, f"{prefix}{key}.")
        else:
            out.append((f"{prefix}{key}", value))
    return out


def _pck(spiceypy, solution, body, coefficients, lines, code, path):
    first, last, length = _seconds(solution)
    handle = spiceypy.pckopn(str(path), f"spinorbit {body}", sum(len(line) + 1 for line in lines))
    try:
        spiceypy.dafac(handle, lines)
        spiceypy.pckw02(handle, code, "J2000", first, last, f"spinorbit {body} orientation"[:40],
                        length, len(coefficients), solution.segments.degree,
                        np.ascontiguousarray(coefficients).ravel(), first)
    finally:
        spiceypy.pckcls(handle)


def _spk(spiceypy, solution, asked, path):
    """The SPK of the solution's tracks, its comments stating each one's records, fit error and distance from
    DE421; returns {"<body>_position_km": fit error}."""
    held = tracks(solution)
    lines = comments(solution, "the positions of " + ", ".join(f"{t.name} ({t.target} about {t.centre})"
                                                                for t in held), asked)
    lines += [line for entry in ["each body: its records, the fit's error, its distance from DE421:",
                                 *track_lines(held, from_de421(held, solution.span))]
              for line in _wrapped(entry).splitlines()]
    handle = spiceypy.spkopn(str(path), f"spinorbit {solution.provenance.get('scene')}"[:60],
                             sum(len(line) + 1 for line in lines))
    try:
        spiceypy.dafac(handle, lines)
        for track in held:
            s = track.segments
            lo, hi = (d * DAY_S for d in s.span)
            spiceypy.spkw02(handle, track.target, track.centre, "J2000", lo, hi, f"spinorbit {track.name}"[:40],
                            s.length_d * DAY_S, len(s.coefficients), s.degree,
                            np.ascontiguousarray(s.coefficients).ravel(), lo)
    finally:
        spiceypy.spkcls(handle)
    return {f"{t.name}_position_km": t.fit_error_km for t in held}


def track_lines(held, distances):
    """One comment entry per track: its records, its fit's error, its distance from DE421 (``distances``)."""
    out = []
    for t in held:
        s = t.segments
        fit = (f"refit within {t.fit_error_km * 1e6:.2g} mm of {t.source}" if t.fit_error_km else
               f"{t.source}'s own series")
        out.append(f"  {t.name} ({t.target} about {t.centre}): {len(s.coefficients)} records of "
                   f"{s.length_d:.6g} d, degree {s.degree}; {fit}; "
                   f"{distances.get(t.name, 'not compared with DE421')}")
    return out


DE421_DATES = 2000          # dates spread over the span where each body is compared with DE421


def from_de421(held, span):
    """{track name: "<distance> from DE421's ..."}: the largest distance over the span between what the tracks
    give and DE421 -- the planets and the Earth heliocentric, the Moon geocentric, the Sun about 0 (the
    barycentre's drift), the Earth-Moon barycentre about 0 when it is the ephemeris's -- or {} beyond DE421."""
    from ..orbits.kernel import open_ephemeris

    t = np.linspace(*span, DE421_DATES)
    try:
        de421 = open_ephemeris("de421", *span)
    except (EphemerisRangeError, InputError):          # beyond its span, or the de421 package not installed
        return {}
    by_name = {track.name: track for track in held}
    at = {name: track.segments.evaluate(t) for name, track in by_name.items()}
    about_0 = {name: at[name] for name, track in by_name.items() if track.centre == 0}
    if "moon" in at and 3 in {track.target for track in held}:
        centre = about_0.get(EMB, 0.0)
        about_0.update(moon=centre + at["moon"], earth=centre + at["earth"])
    out = {}

    def largest(x, name, centre):
        return np.linalg.norm(x - de421.relative_states(name, centre, t)[0], axis=1).max()

    for name, x in about_0.items():
        if name in ("sun", EMB):
            what = "about 0 (the barycentre's drift)" if name == "sun" else "about 0"
            out[name] = f"{largest(x, name, 'solar_system_barycenter'):.3g} km from DE421's {what}"
        elif name != "moon" and "sun" in about_0:
            out[name] = f"{largest(x - about_0['sun'], name, 'sun'):.3g} km from DE421's, heliocentric"
    if "moon" in at and "earth" in at:
        out["moon"] = (f"{largest(at['moon'] - at['earth'], 'moon', 'earth') * 1e3:.3g} m from DE421's, "
                       f"geocentric")
    return out


def _written(path, write):
    """``write(draft)`` to a short-named file in a private temporary folder (SPICE cuts a longer name than
    SPICE_FILE_NAME, and would write elsewhere), then copied to ``path`` aside and renamed
    (files.write_atomically): nothing half-written is left, nothing is written outside ``path``'s folder but the
    temporary folder, removed."""
    with tempfile.TemporaryDirectory(prefix="spinorbit-") as folder:
        draft = Path(folder) / f"kernel{path.suffix}"
        if len(str(draft)) > SPICE_FILE_NAME:
            raise InputError("TMPDIR", folder, f"a temporary folder whose kernel paths fit SPICE's "
                                               f"{SPICE_FILE_NAME} characters")
        write(draft)
        with open(draft, "rb") as source:
            write_atomically(path, lambda f: shutil.copyfileobj(source, f), prefix=f".{path.name}.tmp-{os.getpid()}-")
    return path
