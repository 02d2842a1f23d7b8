"""The one table of attracting bodies (spinorbit.bodies.table): its GMs are DE421's published ones, and a new
body added to it alone reaches every list of bodies (kernel codes, GMs, N-body runs, assemblies, starts)."""
import subprocess
import sys

import pytest

from spinorbit.base.constants import DAY_S
from spinorbit.base.errors import InputError
from spinorbit.bodies.table import gm_km3_d2

# DE421's GMs as Folkner, Williams & Boggs (2008, IOM 343R-08-003, Table 2) publish them, km^3/s^2.
IOM_GM_KM3_S2 = {"sun": 132712440040.944, "earth": 398600.436233, "moon": 4902.800076, "mercury": 22032.090,
                 "venus": 324858.592, "mars": 42828.375214}


@pytest.mark.parametrize("name", sorted(IOM_GM_KM3_S2))
def test_gm_from_the_header_are_the_published_ones(name):
    """The header's GMs (the Earth's and the Moon's from GMB and EMRAT) agree with the IOM's to its printed
    digits (the Moon's: 12 significant digits of GMB / (1 + EMRAT), 5e-11)."""
    assert gm_km3_d2(name) / DAY_S**2 == pytest.approx(IOM_GM_KM3_S2[name], rel=1e-10)


def test_a_body_without_a_gm_is_refused_by_name():
    with pytest.raises(InputError, match="^body: got .vulcan."):
        gm_km3_d2("vulcan")


ADD_CERES = """
import dataclasses
from spinorbit.bodies import table
table.BODIES["ceres"] = table.Attractor("ceres", (2000001,), "MA0001")    # the one change: a row of the table
from spinorbit.bodies.de421_header import header
from spinorbit.base.constants import DAY_S
from spinorbit.base.errors import InputError
from spinorbit.models.assemblies import earth_moon, solar_system
from spinorbit.orbits import kernel, nbody, solution
from spinorbit.orbits.sources import gm_of
gm = float(gm_of(("ceres",))[0])
system = solar_system.solar_system(switches=())
try:
    kernel.JPLKernel().relative_states("ceres", "sun", [0.0])
    refusal = ""
except InputError as error:
    refusal = str(error)
print(gm / DAY_S**2, "ceres" in nbody.BODIES, "ceres" in solution.BODIES, "ceres" in earth_moon.EXTERNAL,
      "ceres" in solar_system.FREE, system.bodies["ceres"].gm == gm, "a kernel holding ceres" in refusal)
"""


def test_a_new_attracting_body_is_one_row_of_the_table():
    """Ceres added to the table alone: its GM is read from the header (MA0001; Park et al. 2016, Nature 537,
    515, measured 62.6284 km^3/s^2 by Dawn, DE421's pre-Dawn estimate within 2 %), the N-body runs, the
    deep-time solution, the Earth-Moon pair's external bodies and the solar system's free bodies carry it, and
    the kernel reader looks it up by its NAIF code (DE421's .bsp does not hold it, and says so)."""
    proc = subprocess.run([sys.executable, "-c", ADD_CERES], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    gm, *carried = proc.stdout.split()
    assert float(gm) == pytest.approx(62.6284, rel=0.02)
    assert carried == ["True"] * 6
