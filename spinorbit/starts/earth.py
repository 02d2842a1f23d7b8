"""The Earth scene's System and its start: the rigid Earth (spinorbit.models.assemblies.earth) driven by
DE421 or Euler's circles, started on the IAU 2006/2000A pole (ERFA) with forced initial conditions, or on
the IAU mean pole plus the rigid model's own nutation there (found by a first gyroscopic run fitted on
IAU 2000A's arguments)."""

import numpy as np

from ..base.errors import ScenarioError
from ..bodies import earth
from ..references import euler_p96
from .earth_pole import PLANETS, ecliptic_pole, ren2000_scaled, started

# direct torques; Uranus, Neptune: GM/r^3 ~1e-3 of Jupiter's
RIGID_START_STEP_D = 2.0              # rk8 step of the first gyroscopic run (converged: RESULTS.md)


def orbits(p):
    """(orbit source, tilt of the circles' plane or None): DE421 sampled once, or Euler's circles."""
    source = p.orbit.source
    if source.circular:
        return euler_p96.circles()
    margin = 1.0        # the figure axes reported difference the torque at t +- 1/64 d
    bodies = ("moon", "sun") + (PLANETS if p.orbit.planets else ())
    first, last = p.span.bounds
    return source.relative("earth", bodies, first - margin, last + margin,
                           p.orbit.sample_step), None


def check(p):
    """Settings that cannot go together, refused on the key that sets them."""
    circular = p.orbit.source.circular
    if p.earth.hd != "iau2006" and circular:
        raise ScenarioError("earth.hd", p.earth.hd, '"iau2006" with orbit.source = "circular" (the '
                            'observed rate is IAU 2006\'s, on the real Moon and Sun)')
    if p.earth.hd != "iau2006" and p.earth.dynamical_ellipticity != earth.H_D:
        raise ScenarioError("earth.dynamical_ellipticity", p.earth.dynamical_ellipticity,
                            f'{earth.H_D} (IAU 2006\'s) with earth.hd = "observed_rate", which sets it')
    if p.earth.nonrigid and circular:
        raise ScenarioError("earth.nonrigid", True,
                            'false with orbit.source = "circular" (the non-rigid '
                            'response is applied on the luni-solar arguments of DE421)')
    for name in ("j4", "geodesic_nutation"):
        if getattr(p.earth, name) and p.earth.model != "gyroscopic":
            raise ScenarioError(f"earth.{name}", True,
                                'false with earth.model = "full" (it acts in the gyroscopic model)')


def earth_system(p, source, model, t0):
    """The rigid Earth of the p on ``source`` (orbit source, tilt), rotator ``model``, not yet
    started."""
    from ..models.assemblies.earth import rigid_earth

    orbit, tilt = source
    pole = ecliptic_pole(tilt) if p.earth.geodesic_precession else None
    from .earth_ellipticity import dynamical_ellipticity

    return rigid_earth(orbit, model, dynamical_ellipticity(p)[0],
                       p.earth.b_minus_a_over_c, p.earth.j2_rate, p.earth.j4,
                       pole, p.earth.geodesic_nutation, t0)


def build(p, t):
    """(System started, orbits, (start pole, ecliptic pole, tilt or None)); ``t``: the output times, which the
    rigid start reads (a first gyroscopic pass)."""
    from ..references import erfa_pole

    check(p)
    source, t0 = orbits(p), p.span.start
    pole = erfa_pole.cip_vector(t0)
    if p.earth.start_pole == "iau_mean_plus_ren2000" and source[1] is None:
        pole = ren2000_start(p, t0)
    elif p.earth.start_pole != "iau" and source[1] is None:
        pole = rigid_start(p, source, t0, pole, t)
    system = started(earth_system(p, source, p.earth.model, t0), t0, pole,
                     p.earth.forced_start)
    return system, source[0], (pole, ecliptic_pole(source[1]), source[1])


def ren2000_start(p, t0):
    """IAU mean pole at t0 plus REN-2000's rigid nutation there (all its long-period constituents, times
    H_d / H_REN, with the model's geodesic nutation): the rigid run follows REN-2000 to < 0.06 mas in its main
    terms, and the non-rigid layer then lands on IAU 2006/2000A's pole to that, where the fitted start
    (rigid_start) misses the terms it does not fit (0.1 mas in X in 1950)."""
    from ..references import erfa_pole
    from .earth_ellipticity import dynamical_ellipticity

    geodesic = p.earth.geodesic_nutation and p.earth.geodesic_precession
    t = np.array([t0])
    return erfa_pole.from_mean_pole(t, *ren2000_scaled(t, dynamical_ellipticity(p)[0], geodesic))[0]


def rigid_start(p, source, t0, pole, t):
    """IAU mean pole at t0 plus the rigid nutation there: the IAU pole + (rigid - IAU) fitted periodic
    terms."""
    from ..analysis.precession import fit_pole, periodic_part
    from ..integrators import simulate
    from ..references import arguments, erfa_pole

    gyro = started(earth_system(p, source, "gyroscopic", t0), t0, pole)
    run, _ = simulate(gyro, t, "rk8", {"step": RIGID_START_STEP_D}, estimate_error=False, label="rigid start")
    z, iau = gyro.figure_axes("earth", t, run.y), erfa_pole.IauPole()(t)
    terms = arguments.named(t, erfa_pole.NUTATION_ARGUMENTS)
    at_t0 = {name: phase[0]
             for name, (phase, _) in arguments.named([t0], erfa_pole.NUTATION_ARGUMENTS).items()}
    model = fit_pole(t, *erfa_pole.about_mean_pole(t, z), terms, separate=False)     # only their sum is used
    ref = fit_pole(t, iau["dpsi_rad"], iau["deps_rad"], terms, separate=False)
    psi0, eps0 = (v[0] for v in erfa_pole.pole_angles(np.array([t0]), pole[None]))
    return erfa_pole.pole_from_angles(t0, *(a + periodic_part(m, at_t0) - periodic_part(r, at_t0)
                                            for a, m, r in zip((psi0, eps0), model, ref)))


def restarted(p, start):
    """The rigid Earth of ``p`` started at a stored state ``start`` = (t0, y) (a continuous solution's
    extension, spinorbit.solutions)."""
    check(p)
    return earth_system(p, orbits(p), p.earth.model, float(start[0])).with_start(*start)


def gyroscopic_twin(p, pole):
    """The gyroscopic Earth on the same orbits and start as the full model (what the full model is checked
    against)."""
    return started(earth_system(p, orbits(p), "gyroscopic", p.span.start), p.span.start, pole)
