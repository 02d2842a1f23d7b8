"""The runs of scene stress_separatrix: Euler's planar libration (P93) started on the axis A on the line to F
(zeta = 0) with zeta'^2 = C + n, C = n (1 + offset) for each of ``stress.offsets``, and its closed form
(analysis.theory.PlanarLibration)."""
import math


def planar_run(p, offset):
    """(System, closed form) of the libration started at C/n - 1 = ``offset``."""
    from ..analysis.planar_libration import planar_system
    from ..analysis.theory import PlanarLibration, libration_n
    from ..orbits.analytic import CircularOrbits

    gm, s, delta = p.orbit.gm, p.orbit.radius, p.orbit.rate
    n = libration_n(p.body.moments, gm, s)
    zeta_dot0 = math.sqrt(n * (2.0 + offset))
    orbit = CircularOrbits(("F",), [gm], [s], [delta], phase=[-delta * p.span.start])
    theory = PlanarLibration(n, 0.0, zeta_dot0)
    return planar_system(p.body.moments, orbit, p.span.start, 0.0, zeta_dot0, delta), theory


def runs(p):
    """[(offset, System, closed form)] for each of ``stress.offsets``; ``stress.methods`` checked."""
    from .idealised import check_methods

    check_methods(p.stress.methods)
    return [(float(offset), *planar_run(p, float(offset))) for offset in p.stress.offsets]
