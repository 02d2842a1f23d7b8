"""A scene's output table at any dates, evaluated from its stored Solution with the scene's own comparison code
(comparisons/): the columns a run would have given at those dates, without the run."""
import numpy as np

FRAMES = {"PA": "the Moon's principal axes (the integrated figure, as DE421's MOON_PA_DE421)",
          "ME": "the Moon's mean-Earth/polar-axis frame: the principal axes turned as DE421's MOON_ME_DE421 is "
                "from MOON_PA_DE421 (NAIF moon_080317.tf; Williams, Boggs & Folkner 2008)"}


def moon(solution, t, source, frame="PA"):
    """The Moon scene's table (comparisons.moon_de421.table) at TDB days ``t``: the JPL angles, their
    differences from DE421 where its series has data, the physical librations and the sub-Earth point in
    ``frame`` (FRAMES)."""
    from ..analysis.librations import icrf_to_body, sub_point
    from ..comparisons import moon_de421 as vs
    from ..references import eckhardt

    values = solution.components(t)            # the series evaluated once: the state and the Earth sliced from it
    states = solution.states(t, values)
    mats = icrf_to_body(states.quaternion)
    de421, covered = vs.de421_where_covered(t)            # the table computes the differences itself
    earth = values[:, solution.layout["earth.from_moon"]] if "earth.from_moon" in solution.layout else \
        earth_from_moon(source, t)
    lib = eckhardt.physical_librations(t, mats, earth)
    if frame == "ME":
        lib["sub_earth_lon"], lib["sub_earth_lat"] = sub_point(in_frame(mats, frame), earth)
    table = vs.table(states, mats, de421, covered, lib)
    if frame == "ME":
        for name, what in (("longitude", "longitude"), ("latitude", "latitude")):
            table[f"sub_earth_{name}"].info.description = (
                f"{what} of the Earth's geometric direction (no light time, no aberration) in the Moon's "
                "mean-Earth/polar-axis frame (DE421's MOON_ME_DE421 from its principal axes)")
    return table


def in_frame(icrf_to_body, frame):
    """ICRF-to-``frame`` matrices (n, 3, 3) of ICRF-to-principal-axes ones."""
    if frame == "PA":
        return icrf_to_body
    from ..references.moon_de421 import principal_to_mean_earth

    return np.einsum("ij,njk->nik", principal_to_mean_earth(), icrf_to_body)


def earth_moon(solution, t):
    """The coupled scene's table (comparisons.earth_moon_de421.table) at TDB days ``t``."""
    from ..comparisons import earth_moon_de421 as vs

    values = solution.components(t)            # the series evaluated once, each part sliced from it
    r, q, axis = (values[:, solution.layout[name]] for name in ("moon.r", "moon.q", "earth.pole"))
    direction, distance = vs.orbit_errors(t, r)
    mats, _, pole, longitude, _ = vs.lunar_errors(t, q)
    errors = {"direction": direction, "range": distance, "pole": pole, "longitude": longitude,
              "earth_axis": vs.earth_axis_error(t, axis)}
    return vs.table(t, r, mats, errors, axis)


def attitude(layer, body, t):
    """A gyroscopic body's table at TDB days ``t`` from its attitude layer (attitude_layer): its pole and prime
    meridian, and what its scene compares them with (its ``Stored.attitude_table``)."""
    from ..scenes import scene_of
    from .spice import body_angles

    angles = body_angles(layer, body, t)
    ra, dec = angles[:, 0] - np.pi / 2, np.pi / 2 - angles[:, 1]
    poles = np.column_stack([np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra), np.sin(dec)])
    return scene_of(layer.provenance["scene"]).stored.attitude_table(t, poles, angles[:, 2])


def earth_from_moon(source, t):
    """The Earth seen from the Moon (n, 3) km, ICRF, at TDB days ``t`` from orbit source ``source``: read from
    the ephemeris at the dates where it is a JPL kernel, else sampled (orbits.sources)."""
    from ..base.errors import InputError
    from ..orbits import kernel
    from ..orbits.sources import sample_orbits

    try:
        return kernel.open_ephemeris(source, t.min(), t.max()).relative_states("earth", "moon", t)[0]
    except InputError:
        orbits = sample_orbits(source, "moon", ("earth",), t.min() - 1.0, t.max() + 1.0)
        return np.asarray(orbits.positions(t))[:, 0]
