"""The non-rigid Earth from a rigid run, and beside its references: IAU 2000A, REN-2000, VLBI's pole.

The Earth scene's non-rigid layer (edge: ERFA through references).  The rigid run's pole (GCRS) is taken to
its nutation about the IAU 2006 mean pole, the transfer function chosen by ``earth.transfer_function`` is
applied term by term (spinorbit.analysis.nonrigid), and the pole is rebuilt; the main terms of the rigid run,
the non-rigid pole, IAU 2000A and REN-2000 (scaled to the run's H_d) are tabled alike
(analysis.precession.term_table).
"""
import numpy as np

from ..analysis import nonrigid
from ..analysis.precession import fit_pole, term_table
from ..analysis.transfer import forms
from ..analysis.transfer.models import MODELS, PUBLISHED_CHANDLER_CPSD, PUBLISHED_FCN_CPSD
from ..base.constants import MAS
from ..references import arguments, erfa_pole, ren2000
from ..starts.earth_pole import geodesic_nutation, ren2000_scaled
from . import earth_vlbi as observed

# Nutation terms of the tables: name -> multipliers of (l, l', F, D, Om).
TABLE_TERMS = {"18.6 yr": (0, 0, 0, 0, 1), "9.3 yr": (0, 0, 0, 0, 2), "1 yr": (0, 1, 0, 0, 0),
               "0.5 yr": (0, 0, 2, -2, 2), "27.55 d": (1, 0, 0, 0, 0), "13.66 d": (0, 0, 2, 0, 2)}


def settings(p):
    """The non-rigid layer's settings from an Earth scene: transfer function, run's H_d, geodesic nutation."""
    from ..starts.earth_ellipticity import dynamical_ellipticity

    return {"model": p.earth.transfer_function, "h_d": dynamical_ellipticity(p)[0],
            "geodesic": p.earth.geodesic_nutation and p.earth.geodesic_precession}


def nonrigid_pole(t, z, model, h_d, geodesic):
    """Figure axes (n, 3) of the non-rigid Earth: the rigid nutation (x, y) = (dpsi sin eps_A, deps) about the
    IAU 2006 mean pole times the transfer function ``model`` (a name of MODELS) term by term, its geodesic
    nutation (``geodesic``) kept as it is, plus MHB2000's nonlinear precession accumulated from the start."""
    (dpsi, deps), sin_eps = erfa_pole.about_mean_pole(t, z), np.sin(erfa_pole.mean_angles(t)[3])
    kinematic = (geodesic_nutation(t) * sin_eps if geodesic else 0.0, 0.0)
    phases, rates = arguments.phases(t, nonrigid.LUNISOLAR_ARGUMENTS)
    x, y = nonrigid.nonrigid_nutation(t, dpsi * sin_eps, deps, phases, rates, MODELS[model], h_d, kinematic)
    return erfa_pole.from_mean_pole(t, x / sin_eps + nonrigid.nonlinear_precession(t - t[0]), y)


def nonrigid_summary(t, z_rigid, z, iau, model, h_d, geodesic):
    """The rigid and non-rigid main terms beside IAU 2000A and REN-2000 (mas), fitted alike on the
    LUNISOLAR_ARGUMENTS the run resolves (a term unresolved from a listed one is in it), the rigid residuals,
    the transfer function's free modes."""
    terms = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    series = {"rigid": erfa_pole.about_mean_pole(t, z_rigid), "nonrigid": erfa_pole.about_mean_pole(t, z),
              "iau2000a": (iau["dpsi_rad"], iau["deps_rad"]), "ren2000": ren2000_scaled(t, h_d, geodesic)}
    cw, fcn = MODELS[model].normal_modes()
    return {"transfer_function": model, "ren2000_h": ren2000.H, "reference_ren2000": ren2000.provenance(),
            "rigid_x_rms_mas": rms((z_rigid[:, 0] - iau["cip_x_rad"]) / MAS),
            "rigid_y_rms_mas": rms((z_rigid[:, 1] - iau["cip_y_rad"]) / MAS),
            "terms_mas": term_table({name: fit_pole(t, *v, terms) for name, v in series.items()},
                                    {name: str(m) for name, m in TABLE_TERMS.items()}),
            "nonlinear_precession_arcsec_cy": nonrigid.NONLINEAR_PRECESSION_ARCSEC_CY,
            "fcn_period_model_d": forms.celestial_period_days(fcn),
            "fcn_period_mhb2000_d": forms.celestial_period_days(PUBLISHED_FCN_CPSD),
            "chandler_period_model_d": forms.wobble_period_days(cw),
            "chandler_period_mhb2000_d": forms.wobble_period_days(PUBLISHED_CHANDLER_CPSD)}


def summaries(t, z_rigid, z, iau, dx_mas, dy_mas, model, h_d, geodesic):
    """The summary's "nonrigid" (nonrigid_summary) and "vlbi" (vlbi.vlbi_summary of the residuals
    ``dx_mas``, ``dy_mas`` against IAU 2006/2000A; the reason when the run shares no time with the
    offsets)."""
    vlbi = observed.vlbi_summary(t, dx_mas, dy_mas) or {
        "not_measured": "the run shares no time with VLBI's offsets (IERS C04, from 1984)"}
    return {"nonrigid": nonrigid_summary(t, z_rigid, z, iau, model, h_d, geodesic), "vlbi": vlbi}


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))
