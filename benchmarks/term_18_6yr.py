"""The non-rigid scene's 18.6-yr nutation out of phase, taken apart.

Run: ``python benchmarks/term_18_6yr.py`` (one 1950-2050 run of the non-rigid scenario with the layer off;
about 1 min).  Prints, in mas:

* the 18.6-yr term of the rigid run, the non-rigid pole (the layer applied to it) and IAU 2000A (ERFA),
  fitted as the scene fits them (quadratic + the resolved luni-solar arguments), then with a cubic and
  with Poisson terms T sin Om, T cos Om added: if the secular line or IAU 2000A's time-dependent
  amplitude leaked into the out-of-phase part, non-rigid - IAU would move with the design;
* the layer with the IERS 1996 factors (``analysis.transfer.models.IERS1996``) applied to a pure in-phase
  rigid 18.6-yr term, against the out-of-phase
  coefficients T. Herring's KSV_1996_3 series prints for that term (IERS Conventions 1996: the rigid
  KSRE95 series times the same resonance factors): what is left is the rigid series' own out-of-phase
  part (Williams 1994; Souchay & Kinoshita 1996);
* the first-order torque of DE421's Moon and Sun on the IAU 2006 mean pole (no run), with the Moon's orbit as
  it is and turned so that its mean pole's offset along the equinox (the planets' tilt of the lunar orbit,
  -1.517", precession_budget.laplace_tilt) is taken out: what that offset puts into the out-of-phase part;
* how far DE421's lunar node leads the series' Om, and what that lead puts into the out-of-phase part;
* what the drift of the mean obliquity (-46.84"/cy) puts into the out-of-phase part: a forced term dpsi/dt =
  F(t) cos Om with F = F0 + F1 T integrates to (F0 + F1 T) sin Om / Om' + F1 cos Om / Om'^2, so a Poisson term
  A1 T sin Om comes with B = A1 / Om' in cos Om.  The first-order torque fitted with T sin Om, T cos Om on the
  mean pole, on that pole held at eps0, and with the displacement dpsi sin eps_A integrated before dividing by
  sin eps_A (as in the run, where the ecliptic of date turns under the pole and takes back the 1/sin eps share):
  against the closed forms of the two shares of the in-phase A0's drift, A0 (-2 tan 2eps) eps' / Om' (the
  torque's) and A0 (-cot eps) eps' / Om' (the kinematic 1/sin eps).
"""
import numpy as np
from precession_budget import EPS0, integrated, laplace_tilt, lunar_orbit_pole, lunisolar, mean_pole, turned

from spinorbit.analysis import nonrigid
from spinorbit.analysis.spans import resolvable
from spinorbit.analysis.transfer.models import IERS1996
from spinorbit.base.constants import ARCSEC, JULIAN_CENTURY_D, MAS
from spinorbit.bodies.earth import H_D
from spinorbit.comparisons import earth_nonrigid
from spinorbit.edge.runner import run_scenario
from spinorbit.references import arguments, erfa_pole
from spinorbit.starts.earth_ellipticity import torque_rates

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
KSV_1996_OUT_MAS = (3.608, 1.543)      # KSV_1996_3, term (0 0 0 0 1): out-of-phase dpsi (cos), deps (sin)
IAU_2000A_OUT_MAS = (3.3386, 1.5377)   # IERS Conventions 2010 Table 5.3a, the same term
OM_RATE = -6962890.5431 * ARCSEC       # rad/cy, Om's rate (IERS Conventions 2010, eq. 5.43)
EPS_A_RATE = -46.836769 * ARCSEC       # rad/cy, the IAU 2006 mean obliquity's rate at J2000 (P03)


def fit_om(t, values, phases, degree, poisson):
    """(sin Om, cos Om) coefficients, mas, of a fit with a polynomial of ``degree`` and the arguments, and with
    ``poisson`` also T sin Om, T cos Om: then a third, the T sin Om coefficient (mas/cy; else None)."""
    big_t, om = t / JULIAN_CENTURY_D, phases[0]
    cols = [big_t**k for k in range(degree + 1)] + list(np.sin(phases)) + list(np.cos(phases))
    cols += [big_t * np.sin(om), big_t * np.cos(om)] if poisson else []
    coef = np.linalg.lstsq(np.column_stack(cols), values, rcond=None)[0]
    n = phases.shape[0]
    return coef[degree + 1] / MAS, coef[degree + 1 + n] / MAS, coef[-2] / MAS if poisson else None


def first_order_inputs(along):
    """(t (d), the Moon and the Sun (n, 3) km geocentric GCRS, their GMs, the luni-solar phases) over 1950-2050,
    from DE421, the Moon's orbit turned so that its mean pole moves by ``along`` rad along the equinox of the
    ecliptic of date."""
    t = np.arange(-0.5 * JULIAN_CENTURY_D, 0.5 * JULIAN_CENTURY_D, 0.5)
    (moon, sun), gm, _ = lunisolar(t)
    return t, [turned(t, moon, along=along), sun], gm, arguments.phases(t, nonrigid.LUNISOLAR_ARGUMENTS)[0]


def first_order_term(along):
    """18.6-yr (dpsi sin, dpsi cos, deps cos, deps sin), mas, of the first-order torque (DE421 Moon and Sun on
    the IAU 2006 mean pole, 1950-2050, integrated), the Moon's orbit turned by ``along`` (first_order_inputs)."""
    t, bodies, gm, phases = first_order_inputs(along)
    rates = torque_rates(t, mean_pole(t), bodies, gm)
    (ps, pc, _), (es, ec, _) = (fit_om(t, integrated(t, r) * ARCSEC, phases, 3, False) for r in rates)
    return ps, pc, ec, es


def obliquity_drift(along):
    """Three (A1 mas/cy, B mas): the 18.6-yr dpsi's A1 T sin Om and B cos Om in a fit with a cubic, the arguments
    and T sin Om, T cos Om, of the first-order torque (as first_order_term, the Moon's orbit turned by ``along``)
    integrated on the IAU 2006 mean pole, on that pole held at eps0 (its obliquity's drift taken out), and on the
    mean pole with the displacement dpsi sin eps_A integrated and then divided by sin eps_A."""
    t, bodies, gm, phases = first_order_inputs(along)
    _, _, psi_bar, eps_a = erfa_pole.mean_angles(t)

    def fit(rate, weight=1.0):
        _, b, a1 = fit_om(t, integrated(t, rate * weight) / weight * ARCSEC, phases, 3, True)
        return a1, b

    held = erfa_pole.pole_from_angles(t, psi_bar, np.full_like(t, EPS0))
    on_mean, on_held = (torque_rates(t, z, bodies, gm)[0] for z in (mean_pole(t), held))
    return fit(on_mean), fit(on_held), fit(on_mean, np.sin(eps_a))


def node_lead(step_d=0.5):
    """How far (rad) DE421's lunar node leads the series' Om over 1950-2050: the phase of the Moon's orbital
    pole about the ecliptic pole of date (IAU 2006) against Om - 90 deg, Hann-weighted so that the node's
    periodic terms (1.5 deg at 173 d and smaller) average out."""
    t = np.arange(-0.5 * JULIAN_CENTURY_D, 0.5 * JULIAN_CENTURY_D, step_d)
    normal = lunar_orbit_pole(t)
    pole = normal[:, 0] + 1j * normal[:, 1]
    return np.angle(np.sum(np.hanning(t.size) * pole * np.exp(-1j * (arguments.delaunay(t)[4] - np.pi / 2))))


def main():
    result = run_scenario(SCENARIO, ["earth.nonrigid=false", "output.plots=false", "integrator.estimate_error=false"])
    table = result.table
    t = np.asarray(table["time"].tdb.jd - 2451545.0)
    x, y = (np.asarray(table[k].to_value("rad")) for k in ("cip_x", "cip_y"))
    rigid = np.column_stack([x, y, np.sqrt(1.0 - x**2 - y**2)])
    iau = erfa_pole.IauPole()(t)
    phases, rates = arguments.phases(t, nonrigid.LUNISOLAR_ARGUMENTS)
    phases = phases[resolvable(rates, t[-1] - t[0])]
    series = {"rigid": erfa_pole.about_mean_pole(t, rigid),
              "non-rigid": erfa_pole.about_mean_pole(
                  t, earth_nonrigid.nonrigid_pole(t, rigid, "iers1996", H_D, True)),
              "IAU 2000A": (iau["dpsi_rad"], iau["deps_rad"])}
    print("| design | series | dpsi in (sin) | dpsi out (cos) | deps in (cos) | deps out (sin) |")
    print("|---|---|---|---|---|---|")
    for degree, poisson in ((2, False), (3, False), (2, True)):
        parts = {}
        for name, (dpsi, deps) in series.items():
            (ps, pc, _), (es, ec, _) = (fit_om(t, v, phases, degree, poisson) for v in (dpsi, deps))
            parts[name] = (ps, pc, ec, es)
            label = f"degree {degree}" + (" + T sin, T cos" if poisson else "")
            print(f"| {label} | {name} | {ps:.3f} | {pc:.3f} | {ec:.3f} | {es:.3f} |")
        diff = np.subtract(parts["non-rigid"], parts["IAU 2000A"])
        print(f"| | non-rigid - IAU | {diff[0]:+.3f} | **{diff[1]:+.3f}** | {diff[2]:+.3f} | {diff[3]:+.3f} |")
    # the layer on a pure in-phase rigid term with the rigid run's amplitudes
    sin_eps = np.sin(EPS0)
    grid = np.arange(-50 * 365.25, 50 * 365.25, 2.0)
    ph, rt = arguments.phases(grid, nonrigid.LUNISOLAR_ARGUMENTS)
    a_psi, _, b_eps, _ = parts["rigid"]
    xn, yn = nonrigid.nonrigid_nutation(grid, a_psi * MAS * sin_eps * np.sin(ph[0]), b_eps * MAS * np.cos(ph[0]),
                                        ph, rt, IERS1996, H_D)
    design = np.column_stack([np.sin(ph[0]), np.cos(ph[0]), np.ones_like(grid)])
    out_psi = np.linalg.lstsq(design, xn / sin_eps / MAS, rcond=None)[0][1]
    out_eps = np.linalg.lstsq(design, yn / MAS, rcond=None)[0][0]
    print(f"\nIERS1996 factors on a pure in-phase rigid term: out of phase dpsi {out_psi:.3f}, deps {out_eps:.3f}; "
          f"KSV_1996_3 prints {KSV_1996_OUT_MAS[0]:.3f}, {KSV_1996_OUT_MAS[1]:.3f} (its rigid series' own out-of-phase "
          f"part: {KSV_1996_OUT_MAS[0] - out_psi:+.3f}, {KSV_1996_OUT_MAS[1] - out_eps:+.3f}); IAU 2000A prints "
          f"{IAU_2000A_OUT_MAS[0]:.4f}, {IAU_2000A_OUT_MAS[1]:.4f} (IAU 2000A - KSV_1996_3: "
          f"{IAU_2000A_OUT_MAS[0] - KSV_1996_OUT_MAS[0]:+.3f}, {IAU_2000A_OUT_MAS[1] - KSV_1996_OUT_MAS[1]:+.3f})")

    along = laplace_tilt()[1]
    shares = (-2 * np.tan(2 * EPS0), -1 / np.tan(EPS0))     # d ln(cos 2eps / sin eps) / d eps, by factor
    torque_share, sin_share = (a_psi * f * EPS_A_RATE / OM_RATE for f in shares)
    for label, shift in (("as DE421 has it", 0.0), (f"its {along / ARCSEC:.3f}\" along the equinox taken out", -along)):
        ps, pc, ec, es = first_order_term(shift)
        print(f"first-order torque, lunar orbit {label}: dpsi {ps:.3f} sin, {pc:.3f} cos; "
              f"deps {ec:.3f} cos, {es:.3f} sin")
        if shift == 0.0:
            lead = node_lead()      # -17.2" sin(Om + lead) has cos Om coefficient (sin coefficient) x lead
            print(f"DE421's lunar node leads Om by {lead / ARCSEC:.2f}\" (1950-2050): {ps * lead:+.3f} mas in dpsi out "
                  f"of phase, {ec * -lead:+.3f} in deps")
        (a1, b), (a1_held, b_held), (_, b_disp) = obliquity_drift(shift)
        print(f"  the same with T sin Om, T cos Om: A1 {a1:.2f} mas/cy, B {b:+.3f} (A1/Om' {a1 / OM_RATE:+.3f}); "
              f"pole held at eps0: A1 {a1_held:.2f}, B {b_held:+.3f}, so the drift of eps_A puts in {b - b_held:+.3f} "
              f"(dA1/Om' {(a1 - a1_held) / OM_RATE:+.3f}); dpsi sin eps_A integrated, then / sin eps_A: B "
              f"{b_disp:+.3f}, the drift's {b_disp - b_held:+.3f}; closed forms: torque (cos 2eps) share "
              f"{torque_share:+.3f}, 1/sin eps share {sin_share:+.3f}")


if __name__ == "__main__":
    main()
