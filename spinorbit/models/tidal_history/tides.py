"""The tidal models of the Earth-Moon history, one class each: its code in the rhs (``response.MODELS``), its
description and source, its calibration to today's recession rate, and, for an ocean, its depth (the scene's
key, the stored fit, the bracket the fit searches, the depths accepted).  The scene's keys, its verdict, the
summary's description and ``python benchmarks/fit_tides.py`` all read ``TIDES``; adding a tide is one class.
"""
import functools
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...base.constants import DAY_S, JULIAN_YEAR_D
from . import calibration, cap_ocean, equations, ocean, response, rotating_cap, solid

GYR_D = 1e9 * JULIAN_YEAR_D
LOVE_K2 = 0.30                         # the solid Earth's degree-2 Love number, to quote a time lag
SOLID_Q = 280.0                        # the solid Earth's Q at M2 (Ray, Eanes & Lemoine 2001, GJI 146, 781)
FITS = Path(__file__).parent


@dataclass(frozen=True)
class Continent:
    """The continent through time: a spherical cap of ``radius_deg`` centred at ``colatitude_deg`` until the
    age ``until_gyr``, its area shrinking linearly with the age to none at ``global_from_gyr``."""

    radius_deg: float
    colatitude_deg: float
    until_gyr: float
    global_from_gyr: float


@dataclass(frozen=True)
class Setting:
    """What a tide is calibrated on: the equations' constants, today's state, the recession rate to give
    (cm/yr), an ocean's depth (km) and continent, and ``keep(name, settings, compute)``: the caller's cache
    for a costly table (the edge's; ``compute()`` when there is none)."""

    constants: np.ndarray
    today: np.ndarray
    recession_cm_per_yr: float
    depth_km: float | None = None
    continent: Continent | None = None
    keep: object = None


@dataclass(frozen=True)
class Depth:
    """An ocean's depth: the scene's key, the file of its fit (beside this module), the bracket (km) the fit
    bisects and the depths the key accepts (km)."""

    key: str
    fit_file: str
    bracket_km: tuple
    low_km: float
    high_km: float

    @property
    def field(self):
        """The key's field in the scene's [tides] table ("tides.ocean_depth" -> "ocean_depth")."""
        return self.key.split(".", 1)[1]

    def fitted(self):
        """The stored fit: {depth_km, drag_per_day, moon_age_gyr, command, ...}."""
        return json.loads((FITS / self.fit_file).read_text())


class NoDrag(ValueError):
    """No drag gives the recession rate at this depth."""


class Tide:
    """A tidal model: ``response(setting)`` the rhs's constants calibrated to the setting's recession rate,
    ``describe(response)`` its fitted parameters for the summary.  ``judged``: what the scene's verdict
    holds it to beyond today's rates ("moon_age", "xiamaling")."""

    name = ""
    code = -1
    summary = ""
    depth = None
    judged = ()

    def response(self, setting):
        raise NotImplementedError

    def describe(self, values):
        raise NotImplementedError


class _OneParameter(Tide):
    """A tide of one parameter, its strength, calibrated to today's recession rate (calibration.calibrated)."""

    def response(self, setting):
        return calibration.calibrated(setting.constants, self.code, setting.today, setting.recession_cm_per_yr)


class ConstantTimeLag(_OneParameter):
    name, code = "constant_time_lag", response.CONSTANT_TIME_LAG
    summary = "a constant time lag (Mignard 1979), k2 dt fitted to the recession rate"

    def describe(self, values):
        return {"k2_time_lag_s": float(values[response.STRENGTH]) * DAY_S,
                "time_lag_s_for_k2_0.30": calibration.time_lag_s(values, LOVE_K2)}


class ConstantQ(_OneParameter):
    name, code = "constant_q", response.CONSTANT_Q
    summary = "a constant phase lag (Goldreich 1966), k2/Q fitted to the recession rate"

    def describe(self, values):
        strength = float(values[response.STRENGTH])
        return {"k2_over_q": strength, "q_for_k2_0.30": LOVE_K2 / strength if strength else math.inf}


class _Ocean(Tide):
    """An ocean's tide: its drag fitted to the recession rate at the setting's depth."""

    judged = ("moon_age",)

    def describe(self, values):
        drag = float(values[response.DRAG])
        return {"ocean_depth_km": float(values[response.DEPTH]), "ocean_drag_per_day": drag,
                "ocean_drag_per_s": drag / DAY_S, "solid_k2_over_q": float(values[response.STRENGTH])}

    def response(self, setting):
        at, full = self.responses(setting)
        drag = self.drag(setting, at)
        if drag is None:
            raise NoDrag(f"no drag gives the recession {setting.recession_cm_per_yr} cm/yr at the depth "
                             f"{setting.depth_km} km")
        return full(drag)

    def responses(self, setting):
        """(drag -> the response the drag is fitted with, drag -> the run's response)."""
        raise NotImplementedError

    @staticmethod
    def drag(setting, at):
        """The drag (rad/day) giving the setting's recession with the responses ``at(drag)``, None if none
        does."""
        return calibration.ocean_drag(setting.constants, setting.today, setting.recession_cm_per_yr, at)

    @staticmethod
    def water(setting):
        c = setting.constants
        return ocean.constants(c[equations.GM_EARTH] / c[equations.RADIUS] ** 2, c[equations.RADIUS])

    @staticmethod
    def andrade(setting):
        """The Andrade solid Earth holding k2 and Q at today's M2 (solid.constants)."""
        c, y0 = setting.constants, setting.today
        mean_motion = math.sqrt((c[equations.GM_EARTH] + c[equations.GM_MOON]) / y0[0] ** 3)
        return solid.constants(2.0 * (y0[2] - mean_motion))


class GlobalOcean(_Ocean):
    name, code = "global_ocean", response.GLOBAL_OCEAN
    summary = "a global ocean on the rotating Earth (Laplace tidal equations) with a constant-Q solid Earth"
    depth = Depth("tides.global_ocean_depth", "global_ocean_fit.json", (4.0, 6.0), 2.0, 8.0)

    def responses(self, setting):
        water = self.water(setting)

        def at(drag):
            return response.responses(self.code, LOVE_K2 / SOLID_Q, depth=setting.depth_km, drag=drag,
                                      ocean=water)

        return at, at


class OceanWithoutCoriolis(_Ocean):
    """Reported beside the default, not judged: its depth was fitted with Farhat et al.'s equatorial
    hemisphere (tides.continent_radius = tides.continent_colatitude = 90 deg), not the default continent."""

    name, code = "ocean_without_coriolis", response.OCEAN_WITHOUT_CORIOLIS
    summary = ("the ocean with its continent without the Coriolis force (the basin's damped resonances, as "
               "Webb 1982) with an Andrade solid Earth")
    judged = ()
    depth = Depth("tides.ocean_without_coriolis_depth", "ocean_without_coriolis_fit.json", (8.6, 8.76), 2.0,
                  10.0)

    def responses(self, setting):
        k = setting.continent
        water = cap_ocean.constants(self.water(setting), k.radius_deg, k.colatitude_deg, k.until_gyr * GYR_D,
                                    k.global_from_gyr * GYR_D, setting.keep)
        andrade = self.andrade(setting)

        def at(drag):
            return response.responses(self.code, LOVE_K2 / SOLID_Q, depth=setting.depth_km, drag=drag,
                                      ocean=water, solid=andrade)

        return at, at


class Ocean(_Ocean):
    name, code = "ocean", response.OCEAN_WITH_CONTINENT
    summary = ("an ocean with its continent on the rotating Earth (Laplace tidal equations with the Coriolis "
               "force in the basin, after Farhat et al. 2022) with an Andrade solid Earth")
    depth = Depth("tides.ocean_depth", "ocean_fit.json", (4.26, 4.30), 2.0, 10.0)
    judged = ("moon_age", "xiamaling")

    def responses(self, setting):
        k, depth = setting.continent, setting.depth_km
        water = self.water(setting)
        andrade = self.andrade(setting)
        loads = (float(water[ocean.DENSITY_RATIO]), float(water[ocean.LOAD_K2]), float(water[ocean.LOAD_H2]))
        b = rotating_cap.basin(float(k.radius_deg), float(k.colatitude_deg), *loads)
        spins = rotating_cap.spin_nodes(setting.today[2])
        today = functools.cache(lambda: rotating_cap.today_tables(depth, water, b, spins))

        def with_table(drag, table):
            head = rotating_cap.constants(water, k.until_gyr * GYR_D, k.global_from_gyr * GYR_D, spins, table)
            return response.responses(self.code, LOVE_K2 / SOLID_Q, depth=depth, drag=drag, ocean=head,
                                      solid=andrade)

        def full(drag):
            settings = {"depth_km": depth, "drag_per_day": drag, "continent_radius_deg": k.radius_deg,
                        "continent_colatitude_deg": k.colatitude_deg, "spins": spins.tolist(),
                        "water": water.tolist(), **rotating_cap.resolution()}

            def compute():
                return rotating_cap.table(depth, drag, water, b, spins)

            table = compute() if setting.keep is None else setting.keep("rotating_cap", settings, compute)
            return with_table(drag, table)

        return (lambda drag: with_table(drag, today()(drag))), full

    def drag(self, setting, at):
        """The fitted drag, kept by the setting's cache (one eigen-decomposition per frequency spared)."""
        k = setting.continent
        settings = {"depth_km": setting.depth_km, "recession_cm_per_yr": setting.recession_cm_per_yr,
                    "continent_radius_deg": k.radius_deg, "continent_colatitude_deg": k.colatitude_deg,
                    "today": np.asarray(setting.today).tolist(), "constants": np.asarray(setting.constants).tolist(),
                    **rotating_cap.resolution()}

        def fit():
            drag = super(Ocean, self).drag(setting, at)
            return np.array([math.nan if drag is None else drag])

        kept = fit() if setting.keep is None else setting.keep("rotating_cap_drag", settings, fit)
        return None if math.isnan(kept[0]) else float(kept[0])


TIDES = {tide.name: tide for tide in (Ocean(), GlobalOcean(), OceanWithoutCoriolis(), ConstantTimeLag(),
                                      ConstantQ())}
