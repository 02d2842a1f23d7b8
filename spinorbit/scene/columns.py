"""What every column of a run's table means: its description, with the frame and the convention it follows.

Each scene builds its table (``timeseries.ecsv``, ``RunResult.table``) with unit-carrying columns;
:func:`describe` sets each column's astropy ``description`` from :data:`COLUMNS`, which the ECSV header then
carries.  A column a scene adds is described here, or by the scene itself where its meaning is its own (deep
time's La2004 quantities, whose ``obliquity`` is not the Earth scene's); tests/scene/test_columns.py holds every scene
to it, and the README lists them.
"""

ATTITUDE = "the body's attitude quaternion, body -> inertial (ICRF), scalar first: "
JPL_ANGLES = ("JPL 3-1-3 angle {} of the lunar principal axes: M = Rz(psi) Rx(theta) Rz(phi) takes the ICRF to "
              "the body (Williams, Boggs & Folkner 2008)")
COLUMNS = {
    "time": "TDB",
    **{f"q_{c}": ATTITUDE + c for c in "wxyz"},
    **{f"omega_{c}": f"the body's angular velocity about its principal axis {c} (x: A, the least moment; z: C)"
       for c in "xyz"},
    "phi": JPL_ANGLES.format("phi (node of the lunar equator on the ICRF equator)"),
    "theta": JPL_ANGLES.format("theta (inclination of the lunar equator to the ICRF equator)"),
    "psi": JPL_ANGLES.format("psi (the prime meridian from the node; continuous)"),
    "pole_error": "angle between the model's and DE421's lunar polar axes (body z); NaN where DE421 has no data",
    "longitude_error": "the model's rotation about the polar axis minus DE421's (positive: the model leads); NaN "
                       "where DE421 has no data",
    **{f"{a}_minus_de421": f"the model's JPL angle {a} minus DE421's, wrapped to +-180 deg" for a in ("phi", "theta",
                                                                                                      "psi")},
    "libration_longitude": "physical libration in longitude tau: the prime meridian's longitude on the mean ecliptic "
                           "and equinox of date minus (the Moon's mean longitude L + 180 deg) (Eckhardt; Meeus ch. 53)",
    "libration_latitude": "physical libration in inclination rho: the lunar equator's inclination to the mean "
                          "ecliptic of date minus the mean I = 1.54242 deg",
    "libration_node": "physical libration in node sigma: the lunar equator's node on the mean ecliptic of date minus "
                      "(Om + 180 deg); large (~5600\") because it is the node's offset, sigma ~ rho / sin I",
    "sub_earth_longitude": "longitude of the Earth's geometric direction (no light time, no aberration) in the "
                           "Moon's principal-axis frame (frame='ME': the mean-Earth/polar-axis frame) (the total "
                           "libration in longitude: optical + physical)",
    "sub_earth_latitude": "latitude of the Earth's geometric direction in the Moon's principal-axis frame (the "
                          "total libration in latitude)",
    "sub_observer_longitude": "the apparent topocentric libration in longitude: the longitude, in the frame "
                              "meta['frame'] names, of the direction from the Moon to the observer against its "
                              "apparent place (light time and aberration), the lunar frame at the light's "
                              "departure",
    "sub_observer_latitude": "the apparent topocentric libration in latitude (as sub_observer_longitude)",
    "axis_position_angle": "the position angle of the Moon's axis (the z axis of the frame meta['frame'] names) "
                           "on the observer's sky, from the north of the true equator of date (IAU 2006/2000A) "
                           "eastward",
    "optical_libration_longitude": "optical libration in longitude: the sub-Earth longitude of the Cassini state "
                                   "(tau = rho = sigma = 0)",
    "optical_libration_latitude": "optical libration in latitude: the sub-Earth latitude of the Cassini state",
    "cip_x": "the model's Celestial Intermediate Pole X: its figure axis in the GCRS, x component (IAU convention)",
    "cip_y": "the model's Celestial Intermediate Pole Y: its figure axis in the GCRS, y component",
    "cip_x_minus_erfa": "the model's CIP X minus IAU 2006/2000A's (ERFA bpn2xy(pnm06a))",
    "cip_y_minus_erfa": "the model's CIP Y minus IAU 2006/2000A's (ERFA bpn2xy(pnm06a))",
    "cio_locator_s": "the CIO locator s of the model's CIP X, Y (IAU 2006's series given X, Y: ERFA s06)",
    "celestial_to_intermediate": "the GCRS-to-CIRS matrix (3 x 3) of the model's X, Y and s (ERFA c2ixys, as "
                                 "c2i06a builds it from IAU 2006/2000A's): v_CIRS = M v_GCRS",
    "precession_longitude": "the model's mean pole: Fukushima-Williams psi_bar of its pole with the nutation fitted "
                            "out (IAU 2006's mean pole plus the model's mean offset)",
    "obliquity": "the model's mean pole: its obliquity on the ecliptic of date (IAU 2006 eps_A plus the model's "
                 "mean offset)",
    "nutation_longitude": "the model's nutation in longitude, delta psi, about its own mean pole",
    "nutation_obliquity": "the model's nutation in obliquity, delta epsilon, about its own mean pole",
    **{f"moon_geocentric_{c}": f"the Moon's centre seen from the Earth's, ICRF {c}" for c in "xyz"},
    "moon_direction_error": "angle between the model's and DE421's geocentric Moon; NaN where DE421 has no data",
    "moon_range_error": "the model's Earth-Moon distance minus DE421's; NaN where DE421 has no data",
    **{f"earth_axis_{c}": f"the Earth's figure axis (its spin angular momentum carried by the Oppolzer terms), "
                          f"ICRF {c}, unit vector" for c in "xyz"},
    "earth_axis_minus_cip": "angle of the Earth's figure axis from IAU 2006/2000A's CIP: DE421 turned its Earth "
                            "by IAU 1976 precession, so this is reported, not judged",
    "L_norm_rel_change": "the closed system's |angular momentum| relative to its start, minus 1",
    "L_vector_rel_change": "|L - L_0| / |L_0| of the closed system's angular momentum vector",
    "energy_rel_change": "the closed system's total energy relative to its start, minus 1 (absolute value)",
    "attitude_error": "angle between the integrated attitude and Euler's closed form (§808)",
    "zeta": "angle of the body's axis A from the direction of the attracting mass F, in the orbit plane (Euler "
            "P93, §825)",
    "zeta_closed_form": "zeta from Euler's closed form (§826-831)",
    "zeta_euler": "zeta from Euler's forced solution (§835)",
    "ZA": "arc ZA from the orbit's pole Z to the figure axis A (Euler P96, §844)",
    "XZA": "angle XZA of the figure axis about the orbit's pole from the fixed direction X (Euler P96, §844)",
    "libration": "the 3:2 spin's forced libration: the body's angle minus 3/2 the mean anomaly (Mercury's 88-d "
                 "term, Margot et al. 2007)",
    "spin_obliquity": "the spin axis's angle from the orbit normal moving as fitted over the run (Mercury's "
                      "obliquity, its Cassini state plus the free precession)",
}


def describe(table):
    """Set each column's description from :data:`COLUMNS` where the scene has not given its own; the names
    described nowhere (empty when all are known)."""
    missing = []
    for name in table.colnames:
        if table[name].info.description:
            continue
        if name in COLUMNS:
            table[name].info.description = COLUMNS[name]
        else:
            missing.append(name)
    return missing


def quantity_table(t, values, columns):
    """A QTable of the TDB ``time`` at t (days from J2000) and each of ``columns`` ({name: (unit, description)})
    taken from ``values`` ({name: array}) with its unit and description."""
    import astropy.units as u
    from astropy.table import QTable

    from .schema import tdb_days_to_time

    out = QTable()
    out["time"] = tdb_days_to_time(t)
    for name, (unit, text) in columns.items():
        out[name] = values[name] * u.Unit(unit) if unit else values[name]
        out[name].info.description = text
    return out
