"""JPL ephemerides read with jplephem: SPK kernels (.bsp) and the ``de421`` package arrays.

States are km and km/day in ICRF axes at TDB days from J2000.0.  Nothing is
downloaded: DE421 comes from the ``skyfield-data`` package, other kernels from
``ephemerides/<name>.bsp`` (in the working directory or this repository) or an
installed ``naif-<name>`` package.
"""
import functools
import hashlib
import importlib
import importlib.util
import weakref
from pathlib import Path

import numpy as np

from ..base.constants import J2000_JD
from ..base.errors import EphemerisRangeError, InputError, tdb_dates
from ..bodies.table import BODIES

EPHEMERIDES_DIR = Path(__file__).resolve().parents[2] / "ephemerides"

# Body name -> NAIF codes to try, first found wins (planet centre, else its barycentre).
NAIF = {name: row.naif for name, row in BODIES.items()}


def kernel_path(source):
    """Path of the SPK kernel called ``source`` ('de421', 'de440', ... or a path to a .bsp)."""
    if source.endswith(".bsp"):
        return Path(source)
    for folder in (Path.cwd() / "ephemerides", EPHEMERIDES_DIR):
        if (folder / f"{source}.bsp").exists():
            return folder / f"{source}.bsp"
    if source == "de421":
        # the package's folder from its spec: importlib.resources.files would first import zipfile and threading
        return Path(importlib.util.find_spec("skyfield_data").origin).parent / "data" / "de421.bsp"
    installed = installed_kernel(source)
    if installed is None:
        shipped = sorted(p.stem for p in EPHEMERIDES_DIR.glob("*.bsp"))
        raise InputError("source", source,
                         f"'de421', a .bsp in ephemerides/ ({shipped or 'none there'}), "
                         f"or an installed naif-{source} package")
    return installed


def installed_kernel(source):
    """The ``<source>.bsp`` an installed ``naif-<source>`` distribution holds, or None: found in its list of
    installed files, nothing imported (a ``naif_<source>.py`` in the working directory is never run)."""
    from importlib import metadata

    try:
        files = metadata.distribution(f"naif-{source}").files or ()
    except (metadata.PackageNotFoundError, ValueError):
        return None
    wanted = f"naif_{source}/{source}.bsp"
    found = [f for f in files if str(f) == wanted]
    return Path(found[0].locate()) if found else None


@functools.lru_cache(maxsize=32)
def file_sha256(path, size, mtime_ns, ctime_ns, inode, device):
    """sha256 of the file at ``path``, hashed once per process for each (size, times, inode): any change to the
    file changes one of them (ctime cannot be set back by a user)."""
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _open_spk(spk_class, path):
    """jplephem's SPK for ``path``; a missing, unreadable or truncated file is an InputError on source."""
    accepted = "a JPL SPK kernel (.bsp): 'de421', a .bsp in ephemerides/, or a path to one"
    if not path.is_file():
        raise InputError("source", str(path), f"{accepted} (no such file)")
    try:
        spk = spk_class.open(str(path))
    except (OSError, ValueError, TypeError, IndexError, EOFError) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise InputError("source", str(path), f"{accepted}; this file cannot be read ({reason})") from None
    size = path.stat().st_size
    short = [seg for seg in spk.segments if seg.end_i * 8 > size]     # DAF addresses are 8-byte words
    if short or not spk.segments:
        spk.close()
        detail = (f"segment of body {short[0].target} ends at byte {short[0].end_i * 8}" if short
                  else "no segments")
        raise InputError("source", str(path), f"{accepted}; this file is truncated or empty "
                                                        f"({size} bytes, {detail})")
    return spk


class JPLKernel:
    """An SPK kernel; states of one body relative to another by chaining segments.

    E.g. Moon relative to Earth = (301 wrt 3) - (399 wrt 3); Sun relative to the
    Moon goes through the solar-system barycentre (10 wrt 0, 3 wrt 0, 301 wrt 3).
    """

    def __init__(self, path=None):
        from jplephem.spk import SPK

        self.path = kernel_path("de421") if path is None else Path(path)
        self.name = self.path.stem
        self._spk = _open_spk(SPK, self.path)
        weakref.finalize(self, self._spk.close)        # the file closed with the kernel, never left to the GC
        self._parent = {}       # target code -> (center code, [segments])
        self._memo = (None, {})
        self._highest_first = {}        # segment -> (start JD, days per set, coefficients (order, set, axis))
        for seg in self._spk.segments:
            self._parent.setdefault(seg.target, (seg.center, []))[1].append(seg)
        # a body may be split over consecutive segments (e.g. DE441): its cover is their union
        starts = [min(s.start_jd for s in segs) for _, segs in self._parent.values()]
        ends = [max(s.end_jd for s in segs) for _, segs in self._parent.values()]
        self.span = (max(starts) - J2000_JD, min(ends) - J2000_JD)

    def code(self, name):
        """NAIF code of ``name`` in this kernel."""
        for code in NAIF.get(name, ()):
            if code == 0 or code in self._parent:
                return code
        held = sorted(n for n in NAIF if self._has(n))
        if name not in NAIF:                     # a name no kernel has
            raise InputError("body", name, f"one of {held}")
        raise InputError("source", str(self.path), f"a kernel holding {name} (this one holds {held})")

    def _has(self, name):
        return any(c == 0 or c in self._parent for c in NAIF[name])

    def _chain(self, code):
        """Codes from ``code`` up to the barycentre (0)."""
        chain = [code]
        while chain[-1] != 0:
            chain.append(self._parent[chain[-1]][0])
        return chain

    def _segment_state(self, code, t):
        """State of ``code`` relative to its parent, km and km/day, shape (3, len(t)) each.

        Kept for the last time array asked for: sampling several bodies on one grid evaluates
        each shared segment (e.g. the Moon's, 301 wrt 3) once."""
        if self._memo[0] is not t:
            self._memo = (t, {})
        if code not in self._memo[1]:
            self._memo[1][code] = self._evaluate(code, t)
        return self._memo[1][code]

    def _evaluate(self, code, t):
        pos, vel = np.empty((3, t.size)), np.empty((3, t.size))
        done = np.zeros(t.size, bool)
        for seg in self._parent[code][1]:
            inside = ~done & (t + J2000_JD >= seg.start_jd) & (t + J2000_JD <= seg.end_jd)
            if inside.any():
                pos[:, inside], vel[:, inside] = self._segment_series(seg, t[inside])
                done |= inside
        if not done.all():
            raise EphemerisRangeError(self.name, (t[~done][0], t[~done][0]), self.span)
        return pos, vel

    def _segment_series(self, seg, t):
        """Position and velocity from one segment at ``t`` (inside it): by :func:`clenshaw` for a Chebyshev
        position segment (type 2, as JPL's DE kernels are), else by jplephem."""
        if seg.data_type != 2:
            return seg.compute_and_differentiate(J2000_JD, t)
        if seg not in self._highest_first:
            start_jd, days_per_set, coefficients = seg.load_array()     # (axis, set, order), lowest order first
            self._highest_first[seg] = (start_jd, days_per_set,
                                        np.ascontiguousarray(coefficients.transpose(2, 1, 0)[::-1]))
        start_jd, days_per_set, coefficients = self._highest_first[seg]
        return series_states(coefficients, start_jd, days_per_set, t)

    def relative_states(self, target, center, t_tdb_days):
        """(pos_km, vel_km_per_day) of ``target`` relative to ``center``, shape (len(t), 3)."""
        t = np.atleast_1d(np.asarray(t_tdb_days, dtype=float))
        self.check_span(t.min(), t.max())
        up, down = self._chain(self.code(target)), self._chain(self.code(center))
        while len(up) > 1 and len(down) > 1 and up[-2] == down[-2]:
            up, down = up[:-1], down[:-1]          # drop the shared part of the chains
        pos, vel = np.zeros((3, t.size)), np.zeros((3, t.size))
        for chain, sign in ((up, 1.0), (down, -1.0)):
            for code in chain[:-1]:
                p, v = self._segment_state(code, t)
                pos += sign * p
                vel += sign * v
        return pos.T, vel.T

    def check_span(self, t_start, t_end):
        """Raise EphemerisRangeError unless [t_start, t_end] (TDB days) lies in the kernel's span."""
        if not (self.span[0] <= t_start and t_end <= self.span[1]):
            raise EphemerisRangeError(self.name, (float(t_start), float(t_end)), self.span)


class DE421Arrays:
    """DE421 from the ``de421`` package: the same Chebyshev series as numpy arrays, 1899-2200.

    jplephem's ``Ephemeris`` reads the arrays and constants; the series are summed over all dates at once by
    :func:`clenshaw`.  Planet entries are the system barycentres; 'moon' in the arrays is geocentric,
    Earth = EMB - Moon/(1 + EMRAT).
    """

    name = "de421 arrays"

    def __init__(self):
        import de421
        from jplephem.ephem import Ephemeris

        self._eph = Ephemeris(de421)
        self._highest_first = {}        # series name -> its coefficients (order, set, axis), highest order first
        self.span = (self._eph.jalpha - J2000_JD, self._eph.jomega - J2000_JD)

    def _series(self, key, t):
        """Position and velocity of series ``key`` at ``t`` TDB days, shape (3, len(t)) each."""
        eph = self._eph
        if key not in self._highest_first:
            self._highest_first[key] = np.ascontiguousarray(eph.load(key).transpose(2, 0, 1)[::-1])
        coefficients = self._highest_first[key]
        return series_states(coefficients, eph.jalpha, (eph.jomega - eph.jalpha) / coefficients.shape[1], t)

    def _barycentric(self, name, t):
        eph = self._eph
        if name == "solar_system_barycenter":
            return np.zeros((3, t.size)), np.zeros((3, t.size))
        if name in ("earth", "moon"):
            emb_p, emb_v = self._series("earthmoon", t)
            moon_p, moon_v = self._series("moon", t)
            share = eph.earth_share if name == "earth" else -eph.moon_share
            return emb_p - share * moon_p, emb_v - share * moon_v
        key = {"earth_moon_barycenter": "earthmoon"}.get(name, name)
        if key not in eph.names or key in ("librations", "nutations"):
            raise InputError("body", name, f"one of {sorted(NAIF)}")
        return self._series(key, t)

    def relative_states(self, target, center, t_tdb_days):
        """(pos_km, vel_km_per_day) of ``target`` relative to ``center``, shape (len(t), 3)."""
        t = np.atleast_1d(np.asarray(t_tdb_days, dtype=float))
        self.check_span(t.min(), t.max())
        if {target, center} == {"earth", "moon"}:   # direct from the geocentric series
            p, v = self._series("moon", t)
            sign = 1.0 if target == "moon" else -1.0
            return sign * p.T, sign * v.T
        tp, tv = self._barycentric(target, t)
        cp, cv = self._barycentric(center, t)
        return (tp - cp).T, (tv - cv).T

    check_span = JPLKernel.check_span


def series_states(coefficients, start_jd, days_per_set, t):
    """Position and velocity (per day) at ``t`` TDB days from J2000 of Chebyshev sets ``days_per_set`` long from
    ``start_jd``, coefficients (order, set, axis) highest order first; shape (axis, len(t)) each."""
    # the sets before J2000 and those after it counted apart (as jplephem's SPK segments): t keeps its precision
    before, before_offset = divmod(J2000_JD - start_jd, days_per_set)
    after, after_offset = divmod(t, days_per_set)
    carry, offset = divmod(before_offset + after_offset, days_per_set)
    index = (before + after + carry).astype(int)
    last = index == coefficients.shape[1]                   # the sets' very end: the last set's end
    index[last] -= 1
    offset[last] += days_per_set
    pos, rate = clenshaw(coefficients, index, 2.0 * offset / days_per_set - 1.0)
    return pos, rate * (2.0 / days_per_set)


def clenshaw(coefficients, index, s):
    """A Chebyshev series and its derivative in ``s`` by Clenshaw's recurrence, as jplephem sums an SPK segment.

    coefficients: (order, set, axis), highest order first; index: each date's set; s: each date in [-1, 1].
    Returns (value, d value / ds), shape (axis, len(s)) each.  Each order's coefficients are gathered per date as
    rows of (set, axis), never a whole (date, axis, order) table.
    """
    s = s[:, None]
    w0 = w1 = dw0 = dw1 = 0.0
    for order in coefficients[:-1]:
        w1, w2 = w0, w1
        w0 = order[index] + (2.0 * s * w1 - w2)
        dw1, dw2 = dw0, dw1
        dw0 = 2.0 * w1 + 2.0 * s * dw1 - dw2
    value = coefficients[-1][index] + (s * w0 - w1)
    return value.T, (w0 + s * dw0 - dw1).T


def open_ephemeris(source, t_start, t_end):
    """The reader for ``source`` covering [t_start, t_end] TDB days.

    'de421' uses the skyfield-data .bsp and, for spans beyond it (to 2200), the
    ``de421`` package arrays; any other name is a .bsp (see :func:`kernel_path`).
    """
    kernel = JPLKernel(kernel_path(source))
    if source != "de421" or kernel.span[0] <= t_start and t_end <= kernel.span[1]:
        kernel.check_span(t_start, t_end)
        return kernel
    arrays = DE421Arrays()
    if not (arrays.span[0] <= t_start and t_end <= arrays.span[1]):
        raise EphemerisRangeError("de421", (t_start, t_end), (kernel.span[0], arrays.span[1]),
                                  note=f" (its .bsp to {tdb_dates([kernel.span[1]])}, the de421 package's arrays "
                                       f"from {tdb_dates([arrays.span[0]])}: one of them must hold the whole span)")
    return arrays
