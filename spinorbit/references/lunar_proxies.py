"""Geological records of the Earth-Moon system's past (data and provenance only): the Moon's distance and
the length of day read from tidal rhythmites and from Milankovitch cycles in sediments.  They test a tidal
history; nothing is fitted to them.

Each proxy: its age (Gyr before present), the quantity (``length_of_day`` h, ``semi_major_axis`` km,
``distance_ratio`` a/a_today, ``precession_constant`` "/yr), the value and its one-sigma uncertainty below and
above (None where the source states none that could be checked here), and the source.  Two-sigma ranges are
halved.  ``unit``: the quantity's unit as a key's suffix (``<name>_residual_<unit>``).
"""
from dataclasses import dataclass


@dataclass(frozen=True)
class Proxy:
    name: str
    age_gyr: float
    quantity: str
    value: float
    sigma_below: float | None
    sigma_above: float | None
    source: str

    @property
    def unit(self):
        return UNITS[self.quantity]

    def residual_sigma(self, model_value):
        """(model - value) in the proxy's own sigma on the residual's side; None without an uncertainty."""
        sigma = self.sigma_below if model_value < self.value else self.sigma_above
        return None if sigma is None else (model_value - self.value) / sigma


UNITS = {"length_of_day": "h", "semi_major_axis": "km", "distance_ratio": "a_over_a_today",
         "precession_constant": "arcsec_per_yr"}
XIAMALING = "Meyers & Malinverno 2018, PNAS 115, 6363 (Xiamaling Fm., 1.4 Ga; 2-sigma values halved)"
NANFEN = ("J. Geol. Soc. 2022, doi:10.1144/jgs2022-022 (Nanfen Fm., North China craton, ~1.1 Ga; its +- "
          "taken as one sigma: the abstract does not say)")
PROXIES = (
    Proxy("elatina_lod", 0.62, "length_of_day", 21.9, 0.4, 0.4,
          "Williams 2000, Rev. Geophys. 38, 37 (Elatina-Reynella tidal rhythmites, ~620 Ma)"),
    Proxy("nanfen_distance", 1.1, "semi_major_axis", 343_000.0, 4_000.0, 4_000.0, NANFEN),
    Proxy("nanfen_lod", 1.1, "length_of_day", 18.94, 0.39, 0.39, NANFEN),
    Proxy("xiamaling_distance", 1.4, "semi_major_axis", 340_900.0, 1_300.0, 1_300.0, XIAMALING),
    Proxy("xiamaling_lod", 1.4, "length_of_day", 18.68, 0.125, 0.125, XIAMALING),
    Proxy("xiamaling_precession_constant", 1.4, "precession_constant", 85.79, 1.36, 1.36, XIAMALING),
    Proxy("joffre_distance", 2.46, "semi_major_axis", 321_800.0, None, None,
          "Lantink et al. 2022, PNAS 119, e2117146119 (Joffre Member BIF, 2.46 Ga); its uncertainty could "
          "not be read from the sources stored here"),
    Proxy("joffre_lod", 2.46, "length_of_day", 16.9, None, None,
          "Lantink et al. 2022, PNAS 119, e2117146119 (Joffre Member BIF, 2.46 Ga); its uncertainty could "
          "not be read from the sources stored here"),
    Proxy("moodies_distance_ratio", 3.22, "distance_ratio", 0.703, 0.703 - 0.628, 0.749 - 0.703,
          "Eulenfeld & Heubeck 2023, JGR Planets 128, e2022JE007466 (Moodies Group tidal bundles, 3.22 Ga; "
          "the range 0.628-0.749 taken as one sigma each side)"),
)


def provenance():
    return {"proxies": {p.name: p.source for p in PROXIES}}
