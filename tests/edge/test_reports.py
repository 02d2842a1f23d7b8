"""The run directory's writers against astropy's and matplotlib's own: the ECSV, the plots drawn in a child."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.table import QTable
from astropy.time import Time

from spinorbit.edge.reports import painter, write_ecsv
from spinorbit.plots import common

AWKWARD = [0.0, -0.0, 1e-300, 1e-5, 0.1, 1 / 3, 123456789.123, 1e16, -2.5e-7, np.nan, np.inf, -np.inf]


def numeric_table():
    table = QTable()
    table["time"] = Time(2451545.0, np.arange(len(AWKWARD)) * 0.37, format="jd", scale="tdb")
    table["x"] = np.array(AWKWARD) * u.arcsec
    table["n"] = np.arange(len(AWKWARD)) - 5
    table.meta["scene"] = "test"
    return table


def test_ecsv_is_astropys_byte_for_byte(tmp_path):
    """The fast body writes what astropy's writer writes (shortest round-trip repr, nan, inf, -0.0, ints)."""
    table = numeric_table()
    write_ecsv(table, tmp_path / "fast.ecsv")
    table.write(tmp_path / "astropy.ecsv", format="ascii.ecsv")
    assert (tmp_path / "fast.ecsv").read_bytes() == (tmp_path / "astropy.ecsv").read_bytes()
    back = QTable.read(tmp_path / "fast.ecsv", format="ascii.ecsv")
    assert np.array_equal(back["x"].value, table["x"].value, equal_nan=True)
    assert np.array_equal(back["time"].jd, table["time"].jd)


def test_ecsv_other_columns_are_astropys(tmp_path):
    """A column that is not one plain numeric column (strings, float32, 2-d) leaves the whole table to astropy."""
    for name, column in (("label", ["a b", "c"]), ("f32", np.array([0.1, 0.2], np.float32)),
                         ("vec", np.ones((2, 3)))):
        table = QTable({"t": [1.0, 2.0], name: column})
        write_ecsv(table, tmp_path / "fast.ecsv")
        table.write(tmp_path / "astropy.ecsv", format="ascii.ecsv", overwrite=True)
        assert (tmp_path / "fast.ecsv").read_bytes() == (tmp_path / "astropy.ecsv").read_bytes(), name


def test_thinned_keeps_every_pixel_column_extremes():
    """Each of common.COLUMNS intervals of x keeps its lowest and highest point (the line covers the same
    pixels), and the ends; a long oscillating series shrinks to at most 2 points per interval."""
    x = np.linspace(1900.0, 2050.0, 27393)
    y = np.sin(x * 2 * np.pi * 13.4) * 200 + np.random.default_rng(1).normal(size=x.size)
    xt, yt = common.thinned(x, y)
    assert xt.size <= 2 * common.COLUMNS + 2 and (xt[0], xt[-1]) == (x[0], x[-1])
    assert np.all(np.diff(xt) > 0)
    edges = np.linspace(x[0], x[-1], common.COLUMNS + 1)
    for lo, hi in zip(edges[:-1:97], edges[1::97]):      # every 97th interval
        inside, kept = (x >= lo) & (x < hi), (xt >= lo) & (xt < hi)
        assert yt[kept].min() == y[inside].min() and yt[kept].max() == y[inside].max()


def test_painter_draws_what_it_is_sent(tmp_path):
    """The child forked before the run draws the (pickled) figures into the run directory, at their
    own size (common.plot_panels: 1 + 2.2 in a panel, 110 dpi) and with their own title."""
    x = np.arange(10.0)
    figures = {"panels": common.titled(common.plot_panels(x, [([x], ["a"], "y")] * 3, "x"), "three panels")}
    with painter() as paint:
        if paint is None:
            pytest.skip("no fork on this platform")
        paint.draw(figures, {"scene": "test"}, tmp_path)
        paths = paint.wait()
    assert paths == [tmp_path / "panels.png"]
    png = paths[0].read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert (width, height) == (8 * 110, round(7.6 * 110))


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")
def test_painter_ends_when_its_parent_dies(tmp_path):
    """A parent killed before sending anything (kill -9, os._exit) leaves no painter waiting for ever."""
    code = ("import os; from spinorbit.edge.reports import painter; "
            "paint = painter().__enter__(); print(paint.pid, flush=True); os._exit(0)")
    pid = int(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout)
    for _ in range(600):                                  # it ends once matplotlib is imported (~1 s)
        stat = Path(f"/proc/{pid}/stat")
        if not stat.exists() or stat.read_text().split(")")[-1].split()[0] == "Z":
            return
        time.sleep(0.1)
    os.kill(pid, signal.SIGKILL)
    pytest.fail(f"painter {pid} still running 60 s after its parent died")
