"""The earth_moon_history scene's keys: the tidal model and its parameters, the continent's size, position and
history, where the history stops, and the comparison."""
from ...models.tidal_history.tides import TIDES
from ...schema import Key

MODELS = tuple(TIDES)
OCEANS = tuple(name for name, tide in TIDES.items() if tide.depth is not None)


def _depth_key(tide):
    fit, depth = tide.depth.fitted(), tide.depth
    return Key(unit="km", default=fit["depth_km"], min=depth.low_km, max=depth.high_km,
               help=f"the depth of {tide.name} (its drag is fitted to tides.recession_rate); "
                    f"{fit['depth_km']:.4f} km fits the Moon's age too ({fit['command']}"
                    + (f"; with {fit['fitted_with']}" if "fitted_with" in fit else "")
                    + f"); {depth.low_km:g} to {depth.high_km:g} km")


SCHEMA = {
    "tides.model": Key(type=str, default="ocean", choices=MODELS,
                       help="the Earth's tidal response: " + "; ".join(f"{name}: {tide.summary}"
                                                                      for name, tide in TIDES.items())
                            + " (docs/TIDAL_HISTORY.md)"),
    **{tide.depth.key: _depth_key(tide) for tide in TIDES.values() if tide.depth is not None},
    "tides.continent_radius": Key(unit="deg", default=65.4, min=0.0, max=90.0,
                                  help="the continent's angular radius today (a spherical cap: 65.4 deg "
                                       "holds the land's 29.2% of the Earth's surface; 90 deg: Farhat et "
                                       "al. 2022's hemispheric continent); 0 to 90 deg"),
    "tides.continent_colatitude": Key(unit="deg", default=43.0, min=0.0, max=180.0,
                                      help="the colatitude of the continent's centre (43 deg: the centre of "
                                           "the land hemisphere, ~47 N; 90 deg: on the equator, the ocean "
                                           "bounded by two meridians as Webb 1982's); 0 to 180 deg"),
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
