"""Mars's obliquity and precession over Myr on its orbit in earth_deep_time's (cached) orbital solution: the
averaged precession under the Sun set by the present rate, the Sun's tide, from the IAU 2015 mean pole
(spinorbit.starts.mars_deep_time), against La2004 Mars over 1, 5 and 20 Myr; a sweep's obliquity band."""
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, at_defaults, key, table
from ..starts.earth_deep_time import MYR_D, DeepTimeOrbitTable, check_span, nbody_counts


@table
class MarsTable:
    """Mars's spin; its defaults and the [tides] table's are La2004's parameters (its README), which the verdict
    judges."""

    precession_rate: float = key(unit="arcsec/yr", default=-7.597, min=-7.7, max=-7.5,
                                 help="present precession rate in longitude (La2004: -7.597; Konopliv et al. "
                                      "2016: -7.6083 +- 0.0021), sets the dynamical ellipticity")


@table
class TidesTable:
    k2: float = key(unit="", default=0.149, min=0.0, max=0.5, help="Mars's Love number k2 (the Sun's tide)")
    Q: float = key(unit="", default=92.0, min=10.0, max=1000.0, help="Mars's tidal quality factor")


@table
class MarsDeepTimeParams(Params):
    orbit: DeepTimeOrbitTable
    mars: MarsTable
    tides: TidesTable


def verdict(p, comparison):
    from ..comparisons.mars_deep_time import LA2004_OBLIQUITY_MAX_DEG_1MYR, TARGET
    from ..scene.verdict import Check, Verdict

    judged = at_defaults(p.mars) and at_defaults(p.tides) and abs(p.span.end) >= MYR_D - 1.0
    checks = (Check("obliquity vs La2004 Mars (1myr)", LA2004_OBLIQUITY_MAX_DEG_1MYR, 0.1, "°", TARGET,
                    min_span_d=MYR_D - 1.0),) if judged else ()
    judged_note = "not La2004's parameters (the [mars] and [tides] tables' defaults) over 1 Myr: compared, not judged"
    return Verdict("La2004 Mars (Laskar et al. 2004, Icarus 170, 343)", checks, "" if judged else judged_note)


def build(p, times):
    from ..starts import earth_deep_time as orbits
    from ..starts import mars_deep_time as model

    check_span(p)
    orbit, wall = orbits.timed_orbital_solution(p, "mars_deep_time: orbital solution")
    return Model((spin := model.spin_model(p, orbit)).system, spin=spin, orbit=orbit, orbit_wall=wall)


def compare_run(p, run):
    from ..comparisons import mars_deep_time as compare

    q = compare.quantities(run.times, run.solution.y, run.model.spin)
    metrics, not_measured, provenance, la2004 = compare.laskar_metrics(run.times, q)
    figures = {} if la2004 is None else {"obliquity_climatic_precession": compare.figure(q, la2004)}
    return Outcome(metrics, figures=figures, sections=compare.sections(run.model, provenance),
                   not_measured=not_measured, table=compare.table(run.times, q))


def sweep_figures(tables):
    from ..comparisons import mars_deep_time as compare

    return {"band_obliquity": compare.band_figure(tables)}


SCENE = Scene(MarsDeepTimeParams, build, compare_run, verdict, backward=True, nbody_counts=nbody_counts,
              sweep_figures=sweep_figures)
