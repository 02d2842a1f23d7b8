"""Mercury in its 3:2 spin-orbit resonance on an N-body orbit: the Cassini-state obliquity and the 88-day forced
libration, against the radar (Margot et al. 2012, JGR 117, E00L09) and the altimeter (Stark et al. 2015).

Mercury turns under the Sun's torque on its degree-2 figure (Euler ch. 16 P91, §815) as a mantle over a fluid
core (spinorbit.models.rotators.MantleCore; J2, C22, C/(M R^2) = 0.346 and C_m/C = 0.431 from
spinorbit.bodies.mercury), on DE421's orbit (or REBOUND's), whose node and perihelion precess under the
planets.  The core is pulled to the mantle's rotation by friction in ``core.coupling_time`` (1 yr): long against
the 88 days, so the mantle librates alone ((B - A)/C_m), short against the precession, so the whole planet (C)
precesses -- the assumption under which Margot et al. read C from the obliquity and C_m from the libration.  It
lags the spin axis by |dk/dt| tau (0.6" at 1 yr) and delays the libration by (C_c/C_m)/(n tau) (3 deg).

The start (analysis/resonant_spin): the spin axis in Peale's Cassini state for the orbit normal's mean speed
over the run (analysis/cassini), the long axis on the forced libration.  The obliquity reported is the state
the spin settles to: the spin circles it at the free precession (~1300 yr), and from its velocity over the run
the centre is found (``cassini.settled_axis``; ``start.obliquity_offset`` starts it away to show that the centre
does not depend on the start).  The libration is the sin M term fitted with M's harmonics, a quadratic and the
free libration.  Further runs with the orbit's node precession scaled (``precession.scales``: the orbit turned
about k x dk/dt, orbits.interpolant.turned) show the obliquity follows Peale's equation (Baland et al. 2017).
"""
import math

from ...bodies import mercury
from ...errors import ScenarioError
from ...scene import Cost, Model, Scene
from ...schema import ANGLE, SAMPLE_STEP, Key
from ...verdict import Check, Verdict

MARGOT, STARK = "Margot et al. 2012 radar (1 sigma)", "Stark et al. 2015 laser altimetry (1 sigma)"
PEALE_TOLERANCE_ARCMIN = 0.05
PEALE_WHY = ("3\": the core's lag |dk/dt| tau (0.6\"), the orbit normal's periodic wobbles over the run "
             "(~1\" on DE421) and the pericentre's precession (0.1 % of eps, Baland et al. 2017), which "
             "Peale's equation omits")
CLOSED_FORM_WHY = ("1 %: the e^6 remainder (0.13 %), the core's friction (0.1-0.5 %) and the planets' "
                   "perturbations of the orbit, which the closed form omits")


def verdict(p, comparison):
    """The obliquity and the libration within the radar's and the altimeter's 1 sigma; the libration against the
    closed form; the obliquity against Peale's equation (and, with scaled precession, every run's)."""
    checks = [Check("obliquity (radar)", "obliquity_arcmin", mercury.OBLIQUITY_ARCMIN[1], "′", MARGOT,
                    expected=mercury.OBLIQUITY_ARCMIN[0]),
              Check("libration (radar)", "libration_amplitude_arcsec", mercury.LIBRATION_AMPLITUDE_ARCSEC[1], "″",
                    MARGOT, expected=mercury.LIBRATION_AMPLITUDE_ARCSEC[0]),
              Check("obliquity (altimetry)", "obliquity_arcmin", mercury.STARK_2015["obliquity_arcmin"][1], "′",
                    STARK, expected=mercury.STARK_2015["obliquity_arcmin"][0]),
              Check("libration (altimetry)", "libration_amplitude_arcsec", mercury.STARK_2015["libration_arcsec"][1],
                    "″", STARK, expected=mercury.STARK_2015["libration_arcsec"][0]),
              Check("libration vs (3/2)(B-A)/C_m (1 - 11e^2 + 959e^4/48)", "libration_amplitude_arcsec", 0.01, "",
                    CLOSED_FORM_WHY, versus="libration_closed_form_arcsec", relative=True),
              Check("obliquity vs Peale's equation", "obliquity_arcmin", PEALE_TOLERANCE_ARCMIN, "′", PEALE_WHY,
                    versus="obliquity_peale_arcmin")]
    if p.precession.scales:
        checks.append(Check("scaled precession vs Peale's equation", "precession_peale_error_max_arcsec",
                            60 * PEALE_TOLERANCE_ARCMIN, "″", PEALE_WHY))
    return Verdict("Margot et al. 2012; Stark et al. 2015; closed forms", tuple(checks),
                   "C/MR^2 and C_m/C were inferred from these observations with this theory: agreement checks "
                   "that the integrated spin realises it on an N-body orbit, not the interior")


SCHEMA = {
    "orbit.source": Key(type=str, default="de421", help="'de421', a .bsp name, or 'rebound'"),
    "orbit.step": Key(**SAMPLE_STEP, default=0.5, help="orbit sampling step (the Sun from Mercury)"),
    "body.c_mr2": Key(unit="", default=mercury.C_MR2, min=0.2, max=0.4, help="C/(M R^2) (Margot et al. 2012)"),
    "body.cm_over_c": Key(unit="", default=mercury.C_MANTLE_OVER_C, min=0.05, max=0.999,
                          help="C_m/C, the librating mantle's share (Margot et al. 2012)"),
    "body.j2": Key(unit="", default=mercury.J2, positive=True, max=1e-3, help="J2, unnormalised"),
    "body.c22": Key(unit="", default=mercury.C22, positive=True, max=1e-3, help="C22, unnormalised"),
    "core.coupling_time": Key(unit="d", default=365.25, min=5.0, max=36525.0,
                              help="time in which friction pulls the core to the mantle's rotation"),
    "start.obliquity_offset": Key(**ANGLE, default=0.0, help="start this far beyond Peale's state (away from "
                                                             "the orbit normal)"),
    "precession.scales": Key(type=list, default=[0.0, 0.5, 2.0],
                             help="further runs with the orbit's node precession times each (0: none)"),
}


def interior(p):
    """The Interior of the parameters (J2 and C22 from bodies.mercury unless set)."""
    from ...analysis.resonant_spin import Interior

    return Interior(p.body.j2, p.body.c22, p.body.c_mr2, p.body.cm_over_c, p.core.coupling_time)


def model(p, times, scale=1.0):
    """(System, context) started in the Cassini state, on the orbit with its node precession times ``scale``."""
    import numpy as np

    from ...analysis.resonant_spin import cassini_system, mean_orbit
    from ...bodies.table import gm_km3_d2
    from ...orbits.interpolant import turned
    from ...orbits.sources import orbit_source

    t0, t1 = float(min(times)), float(max(times))
    orbits = orbit_source(p.orbit.source).relative("mercury", ("sun",), t0, t1, p.orbit.step)
    gm = gm_km3_d2("sun") + gm_km3_d2("mercury")
    if scale != 1.0:
        orbit = mean_orbit(orbits, t0, t1, gm)
        orbits = turned(orbits, (scale - 1.0) * np.cross(orbit.normal, orbit.normal_rate), t0)
    return cassini_system(orbits, interior(p), p.t_start, t1 if p.t_start == t0 else t0, gm,
                          math.radians(mercury.LAPLACE_INCLINATION_DEG), p.start.obliquity_offset)


def scales(p):
    """The precession scales asked, checked: numbers in [0, 10]."""
    given = p.precession.scales
    if not all(isinstance(s, (int, float)) and not isinstance(s, bool) and 0 <= s <= 10 for s in given):
        raise ScenarioError("precession.scales", given, "a list of numbers in [0, 10], e.g. [0, 0.5, 2]")
    return [float(s) for s in given]


def build(p, times):
    scales(p)
    system, context = model(p, times)
    return Model(system, context=context)


def compare_run(p, run):
    from ...comparisons import mercury_spin as vs

    rows = []
    for scale in scales(p):
        system, context = model(p, run.times, scale)
        solution, _ = run.integrate(system, run.times, f"precession x{scale:g}")
        rows.append(vs.precession_row(float(scale), vs.measured(solution.t, solution.quaternion, context),
                                      context))
    return vs.outcome(run.solution.t, run.solution.quaternion, run.model.context, rows)


SCENE = Scene(SCHEMA, build, compare_run, verdict, Cost(step_s=6e-5, sample_bytes=400))
