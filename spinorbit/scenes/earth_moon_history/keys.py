"""The earth_moon_history scene's keys: the tidal model and its parameters, the continent's size, position and
history, where the history stops, and the comparison."""
from ...models.tidal_history.calibration import GLOBAL_OCEAN_FIT, OCEAN_FIT, ocean_fit
from ...schema import Key

_OCEAN = ocean_fit(OCEAN_FIT)
_GLOBAL = ocean_fit(GLOBAL_OCEAN_FIT)

MODELS = ("ocean", "global_ocean", "constant_time_lag", "constant_q")
OCEANS = ("ocean", "global_ocean")
SCHEMA = {
    "tides.model": Key(type=str, default="ocean", choices=MODELS,
                       help="the Earth's tidal response: an ocean with its continent (after Farhat et al. "
                            "2022), a global ocean on the rotating Earth, a constant time lag (Mignard 1979) "
                            "or a constant phase lag, Q (Goldreich 1966); the oceans with the solid Earth "
                            "(docs/TIDAL_HISTORY.md)"),
    "tides.ocean_depth": Key(unit="km", default=_OCEAN["depth_km"], min=2.0, max=10.0,
                             help="the depth of the ocean with its continent (its drag is fitted to "
                                  f"tides.recession_rate); {_OCEAN['depth_km']:.4f} km fits the Moon's age "
                                  f"too ({_OCEAN['command']}); 2 to 10 km"),
    "tides.global_ocean_depth": Key(unit="km", default=_GLOBAL["depth_km"], min=2.0, max=8.0,
                                    help="the global ocean's depth (its drag is fitted to "
                                         f"tides.recession_rate); {_GLOBAL['depth_km']:.4f} km fits the "
                                         "Moon's age too "
                                         f"({_GLOBAL['command']}); 2 to 8 km"),
    "tides.continent_radius": Key(unit="deg", default=90.0, min=0.0, max=90.0,
                                  help="the continent's angular radius today (a spherical cap; 90 deg: the "
                                       "hemispheric continent of Farhat et al. 2022); 0 to 90 deg"),
    "tides.continent_colatitude": Key(unit="deg", default=90.0, min=0.0, max=180.0,
                                      help="the colatitude of the continent's centre (90 deg: centred "
                                           "on the equator, the ocean bounded by two meridians as Webb "
                                           "1982's); 0 to 180 deg"),
    "tides.continent_until": Key(unit="Gyr", default=2.5, min=0.0, max=4.6,
                                 help="the age until which the continent keeps today's size (the emergence "
                                      "of the continents ~2.5 Ga, Bindeman et al. 2018); before it its area "
                                      "shrinks linearly with the age; 0 to 4.6 Gyr"),
    "tides.global_ocean_from": Key(unit="Gyr", default=3.5, min=0.0, max=4.6,
                                   help="the age from which the ocean is global (no continent); after "
                                        "tides.continent_until; 0 to 4.6 Gyr"),
    "tides.recession_rate": Key(unit="cm/yr", default=3.830, min=3.0, max=4.6,
                                help="today's lunar recession the tide's parameter is fitted to (LLR: 3.830 "
                                     "+- 0.008 cm/yr); 3.0 to 4.6"),
    "moon.stop_distance": Key(unit="", default=2.89, min=2.5, max=10.0,
                              help="where the history stops, Earth radii (the fluid Roche limit 2.44 "
                                   "(rho_E/rho_M)^(1/3) = 2.89); 2.5 to 10"),
    "compare.models": Key(type=bool, default=True, help="also run the other tidal models, side by side"),
}
