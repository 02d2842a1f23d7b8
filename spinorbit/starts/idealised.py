"""The Systems and starts of Euler's idealised problems (ch. 16 P92-P96) and of the stress scenes on them (a fast
spinner on P96's forced solution, Mercury's 3:2 libration): the rigid body of a scene's moments on its centre of
forces, started as each problem sets it, with the closed form it is compared with; each a ``scene.Model`` whose
context the scene's comparison reads."""
import math

import numpy as np

from ..analysis.planar_libration import planar_system
from ..base.errors import PhysicsError, ResonanceError, ScenarioError
from ..bodies import RigidBody
from ..models.assemblies.idealised import under_point_masses
from ..scene.declaration import Model

RADIUS = 1.0          # the fast spinner's F distance (length unit arbitrary: only GM/s^3 enters)


def rigid_body(moments, key="body.moments"):
    """RigidBody from the principal ``moments`` a scenario ``key`` gives; a non-physical body is a ScenarioError
    on that key."""
    try:
        return RigidBody.from_principal(*moments, name=key)
    except PhysicsError as exc:
        raise ScenarioError(key, moments.tolist(), f"a rigid body ({exc})") from None


def check_methods(methods):
    """``stress.methods``: each the name of an integrator (integrators.METHODS), or a ScenarioError on the key."""
    from ..integrators import METHODS

    for method in methods:
        if not isinstance(method, str) or method not in METHODS:
            raise ScenarioError("stress.methods", method, f"method names, of {sorted(METHODS)}")


def at_rest(p):
    """The body at rest, F fixed (rate 0) at ``force.direction``: a circle point (cos a, sin a cos i,
    sin a sin i)."""
    from ..orbits.analytic import CircularOrbits

    body = rigid_body(p.body.moments)
    u = p.force.direction / np.linalg.norm(p.force.direction)
    orbit = CircularOrbits(("F",), [p.orbit.gm], [p.orbit.radius], [0.0], phase=[math.acos(u[0])],
                           inclination=[math.atan2(u[2], u[1])])
    system = under_point_masses(body.moments, orbit, [1.0, 0, 0, 0], np.zeros(3), p.span.start, "body at rest")
    return Model(system, direction=u)


def planar_libration(p):
    """The body on Euler's circle with zeta = 0 and zeta' from the energy constant; the closed form."""
    from ..analysis.theory import PlanarLibration, libration_n
    from ..orbits.analytic import CircularOrbits

    body = rigid_body(p.body.moments)
    gm, s, delta = p.orbit.gm, p.orbit.radius, p.orbit.rate
    n = libration_n(body.moments, gm, s)
    zeta_dot0 = math.sqrt(max(p.libration.energy_over_n * n + n, 0.0))
    orbit = CircularOrbits(("F",), [gm], [s], [delta], phase=[-delta * p.span.start])
    return Model(planar_system(body.moments, orbit, p.span.start, 0.0, zeta_dot0, delta), n=n,
                 theory=PlanarLibration(n, 0.0, zeta_dot0))


def forced_libration(p):
    """The body with A towards F and the spin §838 prescribes (no free libration excited)."""
    from ..analysis.theory import forced_libration_initial_rate, libration_n
    from ..orbits.analytic import UnevenCircle

    body, o = rigid_body(p.body.moments), p.orbit
    n = libration_n(body.moments, o.gm, o.f)
    orbit = UnevenCircle(("F",), [o.gm], [o.f], [o.rate], [o.alpha], [o.beta], [o.frequency])
    if p.span.start != 0.0:
        raise ScenarioError("span.start", p.span.start,
                            "'2000-01-01T12:00:00' (J2000): Euler's inequality sin At is timed from t = 0")
    zeta_dot0 = forced_libration_initial_rate(n, o.frequency, o.alpha, o.beta)
    start_rate = zeta_dot0 - o.frequency * o.alpha
    return Model(planar_system(body.moments, orbit, p.span.start, 0.0, start_rate, o.rate), n=n)


def near_principal_axis(p):
    """The symmetric body spinning about a pole alpha from its figure axis, F fixed at ``force.direction``."""
    from ..orbits.analytic import CircularOrbits

    body, b = rigid_body(p.body.moments), p.body
    cc, aa = body.moments[0], body.moments[2]
    if abs(body.moments[1] - cc) > 1e-12 * aa:
        raise ScenarioError("body.moments", body.moments.tolist(),
                            "a symmetric body [cc, cc, aa] (§841: bb = cc)")
    u_euler = p.force.direction / np.linalg.norm(p.force.direction)
    u = np.array([u_euler[1], u_euler[2], u_euler[0]])          # our (x, y, z) = Euler's (B, C, A)
    orbit = CircularOrbits(("F",), [p.orbit.gm], [p.orbit.radius], [0.0], phase=[math.acos(u[0])],
                           inclination=[math.atan2(u[2], u[1])])
    alpha, rho = b.pole_offset, b.pole_angle
    omega0 = b.spin * np.array([math.sin(alpha) * math.cos(rho), math.sin(alpha) * math.sin(rho),
                                math.cos(alpha)])
    system = under_point_masses(body.moments, orbit, [1.0, 0, 0, 0], omega0, p.span.start, "near principal axis")
    return Model(system, u_euler=u_euler)


def symmetric_spinner(p):
    """The spinner on Euler's forced solution (§844), or at its pole where the formulas fail (§849); the
    closed forms of Euler's text and with the pole's free rotation (``true``)."""
    from ..analysis.theory import SymmetricPrecession, p96_initial_state, precession_constant
    from ..orbits.analytic import CircularOrbits

    body = rigid_body(p.body.moments)
    cc, aa = body.moments[0], body.moments[2]
    if not (abs(body.moments[1] - cc) <= 1e-12 * aa and aa > cc):
        raise ScenarioError("body.moments", body.moments.tolist(),
                            "a symmetric oblate body [cc, cc, aa] with aa > cc")
    eps, n, o = p.body.spin, p.body.obliquity, p.orbit
    big_n = precession_constant(o.gm, o.radius, eps, aa, cc)
    euler = SymmetricPrecession(eps, o.rate, big_n, n)
    true = SymmetricPrecession(eps, o.rate, big_n, n, ratio=aa / cc)
    try:
        e, f, _ = true.coefficients()
        x0, resonance = e + f, None
    except ResonanceError as exc:
        x0, resonance = 0.0, exc
    q0, omega0 = p96_initial_state(n, eps, x0, 0.0)
    orbit = CircularOrbits(("F",), [o.gm], [o.radius], [o.rate], phase=[-o.rate * p.span.start])
    system = under_point_masses(body.moments, orbit, q0, omega0, p.span.start, "symmetric spinner")
    return Model(system, big_n=big_n, euler=euler, true=true, resonance=resonance)


def fast_spinner(p):
    """No main run (a converged reference and the ladder of ``stress.runs``, compare): the spinner started on
    Euler's forced solution (§844), its closed form."""
    from ..analysis.theory import SymmetricPrecession, p96_initial_state, precession_constant
    from ..orbits.analytic import CircularOrbits

    body = rigid_body(p.body.moments)
    a_, b_, aa = body.moments
    cc = 0.5 * (a_ + b_)
    eps, n = p.body.spin, p.body.obliquity
    delta = eps / p.stress.spin_over_orbit
    big_n = p.stress.precession_over_orbit * delta
    gm = big_n / precession_constant(1.0, RADIUS, eps, aa, cc)          # N is proportional to GM
    theory = SymmetricPrecession(eps, delta, big_n, n, ratio=aa / cc)
    e, f, _ = theory.coefficients()
    q0, omega0 = p96_initial_state(n, eps, e + f, 0.0)
    t0 = p.span.start
    orbit = CircularOrbits(("F",), [gm], [RADIUS], [delta], phase=[-delta * t0])
    system = under_point_masses(body.moments, orbit, q0, omega0, t0, "fast spinner, slow orbit")
    return Model(None, spinner=system, theory=theory, delta=delta)


def mercury_3_2(p):
    """The body in the 3:2 state on its linear forced solution (gamma(0) = 0 at periapsis)."""
    from ..analysis.planar_spin_orbit import kepler_orbit, libration_theory, rigid_body_system

    body = rigid_body(p.body.moments)
    a_, b_, c_ = body.moments
    gamma, o = (b_ - a_) / c_, p.orbit
    n = math.sqrt(o.gm / o.a**3)
    theory = libration_theory(gamma, o.e)
    k = np.arange(1, theory["g"].size + 1)
    gamma_dot0 = n * float(np.sum(k * theory["g"]))
    system = rigid_body_system(body.moments, kepler_orbit(o.gm, o.a, o.e, p.span.start), p.span.start, 0.0,
                               1.5 * n + gamma_dot0)
    return Model(system, gamma=gamma, n=n, theory=theory)
