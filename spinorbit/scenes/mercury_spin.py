"""Mercury in its 3:2 spin-orbit resonance on an N-body orbit (DE421's, or REBOUND's: node and perihelion
precessing under the planets), a mantle over a fluid core spun by the Sun's torque (Euler ch. 16 P91, §815),
started in its Cassini state: the obliquity it settles to and the 88-day forced libration, against the radar
(Margot et al. 2012) and the altimeter (Stark et al. 2015), the libration's closed form, and Peale's equation
with the orbit's node precession scaled.  The model, its start and how each figure is measured:
spinorbit.comparisons.mercury_spin.
"""
from ..bodies import mercury
from ..comparisons.mercury_spin import verdict
from ..orbits.sources import OrbitSource
from ..scene.declaration import Cost, Model, Scene
from ..scene.params import Params, key, source_key, table
from ..scene.schema import ANGLE, SAMPLE_STEP


@table
class OrbitTable:
    source: OrbitSource = source_key("'de421', a .bsp name, or 'rebound'")
    step: float = key(**SAMPLE_STEP, default=0.5, help="orbit sampling step (the Sun from Mercury)")


@table
class BodyTable:
    c_mr2: float = key(unit="", default=mercury.C_MR2, min=0.2, max=0.4, help="C/(M R^2), Margot et al. 2012")
    cm_over_c: float = key(unit="", default=mercury.C_MANTLE_OVER_C, min=0.05, max=0.999,
                           help="C_m/C, the librating mantle's share (Margot et al. 2012)")
    j2: float = key(unit="", default=mercury.J2, positive=True, max=1e-3, help="J2, unnormalised")
    c22: float = key(unit="", default=mercury.C22, positive=True, max=1e-3, help="C22, unnormalised")


@table
class CoreTable:
    coupling_time: float = key(unit="d", default=365.25, min=5.0, max=36525.0,
                               help="time in which friction pulls the core to the mantle's rotation")


@table
class StartTable:
    obliquity_offset: float = key(**ANGLE, default=0.0, help="start this far beyond Peale's state (away from "
                                                             "the orbit normal)")


@table
class PrecessionTable:
    scales: list = key(type=list, default=[0.0, 0.5, 2.0],
                       help="further runs with the orbit's node precession times each (0: none)")


@table
class MercurySpinParams(Params):
    orbit: OrbitTable
    body: BodyTable
    core: CoreTable
    start: StartTable
    precession: PrecessionTable


def build(p, times):
    from ..starts.mercury import model, scales

    scales(p)
    system, context = model(p, times)
    return Model(system, context=context)


def compare_run(p, run):
    from ..comparisons.mercury_spin import compare

    return compare(p, run)


# measured: the century's main run, 73 050 rk8 steps in 5.1 s (the precession runs as many again each)
SCENE = Scene(MercurySpinParams, build, compare_run, verdict, Cost(step_s=7e-5, sample_bytes=400))
