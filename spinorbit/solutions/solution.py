"""A Solution: the continuous result of an integration, a function of time over its span.

The state and its named quantities as piecewise Chebyshev series (solutions.chebyshev) fitted to the
integrator's output (solutions.fit), with what made them (``provenance``: the scene, every key, the
ephemeris, the integrator and its error estimate, the fit's measured error, the code's version, the runs
that made each stretch) and the state where the integration stopped at each end (``ends``: a later run
continues from there).  Evaluated at astropy Times it gives a QTable with units: the lunar 3-1-3 angles
(phi, theta, psi: ICRF -> body is Rz(psi) Rx(theta) Rz(phi)) of each body with an attitude, the figure axis
of each body turned by its spin, the position of each integrated body; ``states(t)`` gives the whole state.
"""
import numpy as np

from ..base.layout import Layout


class Solution:
    """``segments`` (chebyshev.Segments) of the components laid out by ``layout``; ``provenance`` (dict);
    ``ends``: {"start", "end"}: (TDB days, state)."""

    def __init__(self, segments, layout, provenance, ends):
        self.segments, self.layout, self.provenance, self.ends = segments, layout, provenance, ends

    @property
    def span(self):
        """(start, end) TDB days from J2000."""
        return self.segments.span

    def covers(self, t_start, t_end):
        return self.segments.covers(t_start, t_end)

    @property
    def fit_error(self):
        return self.provenance.get("fit_error", {})

    def components(self, t):
        """Every fitted component (n, size) at TDB days ``t`` (quaternions made unit)."""
        return self.layout.normalise(self.segments.evaluate(np.atleast_1d(np.asarray(t, dtype=float))))

    def part(self, name, t):
        """The slice ``name`` (e.g. "moon.q", "earth.pole") at TDB days ``t``, (n, size)."""
        return self.components(t)[:, self.layout[name]]

    def states(self, t, components=None):
        """The integrator's Trajectory (integrators.base: states at times) at TDB days ``t``: what a scene's analysis
        reads (from ``components``, :meth:`components` at ``t``, when the caller has evaluated them already)."""
        from ..integrators.base import Trajectory

        t = np.atleast_1d(np.asarray(t, dtype=float))
        values = self.components(t) if components is None else components
        state_size = self.provenance["state_size"]
        state_layout = Layout([(s.name, s.stop - s.start, s.kind, s.unit) for s in self.layout.slices
                               if s.stop <= state_size])
        return Trajectory(t, values[:, :state_size], self.provenance["integrator"]["method"], layout=state_layout)

    def quantities(self, t):
        """{column name: (values (n,), astropy unit name)} of the named quantities at TDB days ``t``."""
        from ..analysis.librations import icrf_to_body
        from ..base.rotations import euler313_from_matrix

        values, out = self.components(t), {}
        for part in self.layout.slices:
            body, what = part.name.split(".", 1)
            v = values[:, part.index]
            if part.kind == "quaternion":
                angles = euler313_from_matrix(icrf_to_body(v))
                out.update({f"{body}_{name}": (angles[:, i], "rad") for i, name in enumerate(("phi", "theta",
                                                                                               "psi"))})
            elif what == "pole":
                out.update({f"{body}_pole_{axis}": (v[:, i], "") for i, axis in enumerate("xyz")})
            elif what == "r":
                out.update({f"{body}_{axis}": (v[:, i], "km") for i, axis in enumerate("xyz")})
        return out

    def at(self, times):
        """QTable of the named quantities at ``times`` (astropy Time, any scale), ``time`` as given; InputError for a
        masked or non-finite date (as the API refuses them)."""
        import astropy.units as u
        from astropy.table import QTable

        t, when = tdb_days(times)
        table = QTable()
        table["time"] = when.reshape(t.shape)
        for name, (values, unit) in self.quantities(t).items():
            table[name] = values * u.Unit(unit) if unit else values
        table.meta.update({"span_tdb_d": list(self.span), "fit_error": self.fit_error,
                           "provenance": self.provenance})
        return table

    def window(self, t_start, t_end):
        """The Solution over the whole segments covering [t_start, t_end] (its ends: the window's first and last
        states as the series give them)."""
        segments = self.segments.window(t_start, t_end)
        ends = {name: (t, self.states([t]).y[0]) for name, t in zip(("start", "end"), segments.span)}
        return Solution(segments, self.layout, self.provenance, ends)

    def export(self, directory, asked=None):
        """Write SPICE kernels of the solution into ``directory``: spinorbit.solutions.spice.export."""
        from .spice import export

        return export(self, directory, asked)

    def __repr__(self):
        lo, hi = (2000.0 + t / 365.25 for t in self.span)
        return (f"Solution({self.provenance.get('scene')}, {lo:.2f}-{hi:.2f}, "
                f"{', '.join(self.layout.names)}, fit error {self.fit_error})")


def joined(piece_solution, other):
    """One Solution from two adjacent ones of the same model (``other``, the stretch continuing
    ``piece_solution``, before or after): the model's start is ``piece_solution``'s."""
    before, after = sorted((piece_solution, other), key=lambda s: s.span[0])
    provenance = dict(before.provenance)
    provenance["model_start_tdb_d"] = piece_solution.provenance.get("model_start_tdb_d")
    provenance["runs"] = before.provenance.get("runs", []) + after.provenance.get("runs", [])
    provenance["fit_error"] = {k: max(before.fit_error.get(k, 0.0), after.fit_error.get(k, 0.0))
                               for k in set(before.fit_error) | set(after.fit_error)}
    ends = {"start": before.ends["start"], "end": after.ends["end"]}
    return Solution(before.segments.joined(after.segments), before.layout, provenance, ends)


def tdb_days(times):
    """(TDB days from J2000 (n,), the Times) of astropy ``times``; InputError unless Times, finite."""
    from astropy.time import Time

    from ..base.errors import InputError

    if not isinstance(times, Time):
        raise InputError("times", type(times).__name__, "astropy Time (any scale)")
    if times.masked and np.any(times.mask):
        raise InputError("times", f"{int(np.sum(times.mask))} masked of {times.size} dates",
                         "finite astropy Times without masked values: pass times[~times.mask]")
    t = np.atleast_1d(np.asarray(times.tdb.jd1 - 2451545.0, dtype=float) + times.tdb.jd2).ravel()
    if not np.all(np.isfinite(t)):
        raise InputError("times", "non-finite or masked dates", "finite astropy Times")
    return t, times
