"""What a report prints and a plot shows is what was computed, labelled for what it is: the monthly means
leave out a month the span cuts, an unsigned angle is not labelled a signed difference, the verdict table's
figures carry their unit, deep time's title, tolerance sources and provenance say what they are, and legends
sit off the curves."""
import math

import numpy as np
import pytest

from spinorbit.edge.reports import verdict_markdown
from spinorbit.plots import common, deep_time, moon, solar_system


def drawn(draw):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=getattr(draw, "figsize", (8, 4.5)))
    draw(fig)
    fig.canvas.draw()
    return fig


def test_monthly_means_leave_out_the_month_the_span_cuts():
    month = 27.321661
    days = np.arange(0.0, 3 * month + 1.0, 0.5)                 # three whole months and one day of a fourth
    years = 2000.0 + days / 365.25
    y = np.where(days >= 3 * month, -176.0, 1.0)                 # the cut month's lone samples: far off
    middles, means = moon.monthly_means(years, y)
    assert len(middles) == 3 and np.allclose(means, 1.0)          # the three whole months, each mean exact
    assert middles[-1] < 2000.0 + 3 * month / 365.25


def test_the_lunar_residuals_label_the_pole_an_unsigned_angle_and_the_longitude_a_difference():
    from astropy import units as u
    from astropy.table import QTable

    t = np.linspace(0.0, 800.0, 401)
    table = QTable({"libration_longitude": np.sin(t / 27.3) * u.arcsec, "libration_latitude": np.cos(t) * u.arcsec,
                    "pole_error": np.abs(np.sin(t / 100)) * 1e-3 * u.arcsec,
                    "longitude_error": np.sin(t / 50) * 1e-4 * u.arcsec})
    zoom = t > 700
    figures = moon.moon_libration(t, table, [], [], zoom, {"tau": np.zeros(zoom.sum()), "rho": np.zeros(zoom.sum())})
    pole_axis, longitude_axis = drawn(figures["residuals_vs_de421"]).axes
    assert pole_axis.get_ylabel() == "pole: |model, DE421| [arcsec]"
    assert np.all(pole_axis.lines[0].get_ydata() >= 0)           # the angle between two poles: never negative
    assert longitude_axis.get_legend().get_texts()[0].get_text() == "model − DE421"
    assert np.array_equal(longitude_axis.lines[0].get_ydata(), table["longitude_error"].value)


def test_panel_legends_sit_above_their_panel_off_the_curves():
    x = np.linspace(0.0, 1.0, 50)
    fig = drawn(common.plot_panels(x, [([x, x ** 2], ["model", "IAU 2000A"], "Δψ [arcsec]")] * 3, "year"))
    for ax in fig.axes:
        assert ax.get_legend().get_window_extent().y0 >= ax.get_window_extent().y1 - 1.0


def test_the_moon_against_de421_gives_each_quantity_its_own_panel_and_sign():
    year = np.linspace(1950.0, 2050.0, 101)
    direction, pole, longitude = np.full(101, 0.08), np.full(101, 0.002), np.linspace(-0.07, 0.07, 101)
    axes = drawn(solar_system.moon_vs_de421(year, direction, pole, longitude, "arcsec")).axes
    assert [ax.get_ylabel() for ax in axes] == ["Moon direction [arcsec]", "lunar pole [arcsec]",
                                                "libration longitude [arcsec]"]
    assert [ax.lines[0].get_ydata()[50] for ax in axes] == [0.08, 0.002, 0.0]
    assert axes[2].get_legend().get_texts()[0].get_text() == "model − DE421"


def test_the_planets_against_de421_are_on_a_log_axis():
    year = np.linspace(1950.0, 2050.0, 11)
    ax = drawn(solar_system.planets_vs_de421(year, {"mercury": np.full(11, 0.7), "mars": np.full(11, 69.0)})).axes[0]
    assert ax.get_yscale() == "log" and ax.get_ylim()[0] == 1e-3 and ax.get_ylim()[1] > 69.0
    assert [line.get_ydata()[0] for line in ax.lines] == [0.7, 69.0]
    highest = ax.transData.transform((year[0], 69.0))[1]
    assert ax.get_legend().get_window_extent().y0 > highest          # the legend above the highest curve


def test_deep_time_draws_model_minus_la2004_beneath_each_overlay():
    t = -np.arange(0.0, 1001.0)
    model = {"obliquity_deg": 23.4 + 0.5 * np.sin(t / 41), "climatic_precession": 0.02 * np.sin(t / 23)}
    la2004 = {"obliquity_deg": model["obliquity_deg"] + 1e-3, "climatic_precession": model["climatic_precession"]}
    axes = drawn(deep_time.deep_time(t, model, la2004, "La2004")).axes
    assert axes[1].get_ylabel() == "obliquity: model − La2004 [deg]"
    assert np.allclose(axes[1].lines[0].get_ydata(), -1e-3)      # the difference drawn is model minus La2004
    assert axes[3].get_ylabel() == "e sin(ϖ̄): model − La2004"


def test_the_spectra_name_the_periods_above_the_plots_all_inside_the_axis():
    t = -np.arange(0.0, 1001.0)
    series = {"obliquity_deg": np.sin(2 * np.pi * t / 41), "climatic_precession": np.sin(2 * np.pi * t / 23),
              "eccentricity": np.sin(2 * np.pi * t / 405)}
    fig = drawn(deep_time.deep_time_spectra(t, series, series, "La2004"))
    top = fig.axes[0].child_axes[0]
    labels = {tick.get_text(): tick.get_position()[0] for tick in top.get_xticklabels()}
    assert set(labels) == {"41", "23", "19", "100", "405"}
    low, high = fig.axes[0].get_xlim()
    assert all(low <= x <= high for x in labels.values())        # 405 kyr inside the axis, not clipped


def test_the_verdict_table_gives_each_figure_its_unit():
    verdict = {"result": "pass", "headline": "moon: pass — pole 0.0036″ ≤ 0.1″", "checks": [
        {"label": "pole", "figure": 0.00357839, "tolerance": 0.1, "unit": "″", "result": "pass", "source": "s"},
        {"label": "n_dot", "figure": -0.29, "expected": -25.8, "tolerance": 1.0, "unit": "″/cy²",
         "result": "pass", "source": "LLR"}]}
    table = "\n".join(verdict_markdown(verdict))
    assert "| pole | 0.00357839″ | 0.1″ | pass |" in table
    assert "| n_dot | -26.09″/cy² (expected -25.8″/cy²) | 1″/cy² | pass |" in table


def test_deep_time_titles_say_kyr_sources_and_the_ephemeris_it_starts_from():
    from spinorbit.comparisons import earth_deep_time as compare
    from spinorbit.edge.provenance import ephemeris
    from spinorbit.edge.runner import span_label
    from spinorbit.edge.scenarios import load_scenario

    scenario = load_scenario("earth_deep_time")
    assert span_label(scenario) == "0 to −1000 kyr from J2000"
    assert ephemeris(scenario)["name"].startswith("de421 (the solar system's state at J2000")
    sources = {check.source for check in scenario.scene.verdict_for(scenario.params, {}).checks}
    assert not any("issue" in source for source in sources)
    assert any("La93 with and without tides differ by 3°" in source for source in sources)
    assert set(compare.EXPLAINED) == {"la2004_*", "la93_tides_*", "la2004_minus_la93_*"}
    assert span_label(load_scenario("earth_moon_history")) == "0 to −4.5 Gyr from J2000"


def test_the_solar_system_table_carries_the_moons_angles():
    from spinorbit.base.rotations import matrix_from_euler313
    from spinorbit.comparisons import solar_system_de421 as compare

    angles = np.array([[0.1, 0.4, 1.3], [2.0, 0.3, 5.0]])               # phi, theta, psi in [0, 2 pi)
    mats = np.array([matrix_from_euler313(*a) for a in angles])
    zeros = np.zeros(2)
    table = compare.table(np.array([0.0, 1.0]), np.ones((2, 3)), mats,
                          {"direction": zeros, "range": zeros, "pole": zeros, "longitude": zeros}, {})
    for i, name in enumerate(("phi", "theta", "psi")):
        assert table[name].to_value("rad") == pytest.approx(angles[:, i], abs=1e-12)
    assert math.isclose(float(table["psi"][0].to_value("rad")), 1.3, abs_tol=1e-12)
