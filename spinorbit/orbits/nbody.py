"""Orbits from a REBOUND N-body run: IAS15 with REBOUNDx ``gr_full`` and the Earth's J2.

Sun, Mercury..Neptune, Earth, Moon and Pluto start from a JPL kernel's barycentric states at an
epoch, are integrated once over the span, and sampled into a :class:`HermiteOrbits` relative to
the spinning body, or barycentric (the simulation's own frame).  The Earth-Moon barycentre is a
body too, from the Earth and Moon particles.  Units inside REBOUND: km, days, G = 1 with masses
given as GM (km^3/day^2), DE421 values.
"""
import numpy as np

from ..base.constants import DAY_S, JULIAN_YEAR_D
from ..base.errors import InputError
from ..base.progress import progress
from ..base.rotations import vector_angle
from ..bodies.de421_header import header
from ..bodies.table import gm_km3_d2, integrated
from .interpolant import HermiteOrbits, grid
from .interrupts import python_sigint
from .kernel import DE421Arrays, JPLKernel

BODIES = integrated()
EMB = "earth_moon_barycenter"           # the GM-weighted mean of the Earth and Moon particles
OUT_CHUNK_D = 3652.5                    # integrating out from an epoch: a signal is handled every 10 yr


def de421_gm():
    """GM of each body in :data:`BODIES` and of the EMB (the Earth's plus the Moon's), km^3/day^2,
    from the DE421 header."""
    gm = {name: gm_km3_d2(name) for name in BODIES}
    gm[EMB] = gm["earth"] + gm["moon"]
    return gm


def weights(name, gm):
    """Weights (len(BODIES),) on the particles' states that give body ``name`` (a BODIES name or EMB);
    None gives zeros (the barycentric frame's origin)."""
    row = np.zeros(len(BODIES))
    if name == EMB:
        row[BODIES.index("earth")] = gm["earth"] / gm[EMB]
        row[BODIES.index("moon")] = gm["moon"] / gm[EMB]
    elif name is not None:
        row[BODIES.index(name)] = 1.0
    return row


class ReboundOrbits(HermiteOrbits):
    """``bodies`` relative to ``center``, integrated by REBOUND from ``t_start`` to ``t_end`` (TDB d), started
    from ``kernel``'s states at ``epoch`` (default t_start; a span the kernel does not cover is reached by
    integrating out from an epoch it does).

    bodies, center: names in :data:`BODIES` or :data:`EMB`; center None: barycentric, in the
    simulation's frame, the kernel's barycentric one at t_start kept inertial (DE421's barycentre
    holds its asteroids too, so the bodies' own centre of mass moves in it: 6.6e-4 km/d in 1969).
    kernel: the JPLKernel or DE421Arrays giving the initial barycentric states at t_start
    (default: the DE421 .bsp).
    gr: REBOUNDx ``gr_full`` (all bodies, c in km/day); earth_j2: REBOUNDx
    ``gravitational_harmonics`` on the Earth, J2 and R_eq from the DE421 header, axis
    along ICRF z (the J2000 pole; precession moves it ~20"/yr, ignored).
    """

    def __init__(self, center, bodies, t_start, t_end, step=0.25, kernel=None, gr=True,
                 earth_j2=True, epsilon=1e-9, epoch=None):
        import rebound
        import reboundx

        gm = de421_gm()
        unknown = [b for b in (*bodies, center) if b is not None and b not in gm]
        if unknown:
            raise InputError("bodies", unknown, f"bodies of the REBOUND run: {sorted(gm)}")
        kernel = JPLKernel() if kernel is None else kernel
        epoch = t_start if epoch is None else float(epoch)
        kernel.check_span(epoch, epoch)
        sim = rebound.Simulation()
        sim.G = 1.0
        sim.integrator = "ias15"
        sim.integrator.epsilon = epsilon
        for name in BODIES:
            p, v = kernel.relative_states(name, "solar_system_barycenter", [epoch])
            sim.add(m=gm[name], x=p[0, 0], y=p[0, 1], z=p[0, 2], vx=v[0, 0], vy=v[0, 1], vz=v[0, 2],
                    name=name)
        extras = reboundx.Extras(sim)
        if gr:
            force = extras.load_force("gr_full")
            extras.add_force(force)
            force.params["c"] = header()["CLIGHT"] * DAY_S
        if earth_j2:
            force = extras.load_force("gravitational_harmonics")
            extras.add_force(force)
            c = header()
            sim.particles["earth"].params["J2"] = c["J2E"]
            sim.particles["earth"].params["R_eq"] = c["RE"]
        self.simulation, self.extras = sim, extras        # keep extras alive with sim

        times = grid(t_start, t_end, step)
        _integrate_out(sim, t_start - epoch)                      # out from the kernel's epoch, if it differs
        n = len(BODIES)
        xyz, vxyz = np.empty((n, 3)), np.empty((n, 3))
        relative = np.array([weights(b, gm) - weights(center, gm) for b in bodies])
        pos = np.empty((len(bodies), times.size, 3))
        vel = np.empty_like(pos)
        with progress("rebound", times[0], times[-1]) as advance_to:
            for k, t in enumerate(times):
                with python_sigint():
                    sim.integrate(t - epoch, exact_finish_time=1)
                sim.serialize_particle_data(xyz=xyz, vxvyvz=vxyz)
                pos[:, k] = relative @ xyz
                vel[:, k] = relative @ vxyz
                if k % 256 == 0:
                    advance_to(t)
        super().__init__(bodies, [gm[b] for b in bodies], t_start, step, pos, vel, source="rebound")


def _integrate_out(sim, t):
    """Integrate ``sim`` to ``t`` in pieces of OUT_CHUNK_D (not landing on their ends: the steps are those of
    one call), so that a signal is handled between them, then exactly to ``t``."""
    direction = 1.0 if t >= sim.t else -1.0
    while direction * (t - sim.t) > OUT_CHUNK_D:
        with python_sigint():
            sim.integrate(sim.t + direction * OUT_CHUNK_D, exact_finish_time=0)
    with python_sigint():
        sim.integrate(t, exact_finish_time=1)


def moon_drift(years, t_start=0.0, step=0.01):
    """How far REBOUND's geocentric Moon runs from DE421's in ``years`` from t_start (TDB d).

    Returns (max angle rad, max distance km) over outputs every ``step`` years.
    """
    t = t_start + np.linspace(0.0, years * JULIAN_YEAR_D, int(years / step) + 1)
    ours = ReboundOrbits("earth", ("moon",), t[0], t[-1]).positions(t)[:, 0]
    truth = DE421Arrays().relative_states("moon", "earth", t)[0]
    angle = vector_angle(ours, truth)
    return float(angle.max()), float(np.linalg.norm(ours - truth, axis=1).max())
