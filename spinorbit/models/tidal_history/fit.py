"""An ocean's depth fitted to the Moon's age, its drag fitted at each depth to today's recession (the
ocean's calibration): the bisection, typed.  The history at a depth is the caller's, ``age_at(depth_km) ->
Trial`` (``python benchmarks/fit_tides.py`` runs the scene), so this module integrates nothing itself; the
geological proxies are never used.
"""
from dataclasses import dataclass, field

MOON_AGE_GYR = 4.425                   # Maurice et al. 2020 (Sci. Adv. 6, eaba8949): 4.425 +- 0.025 Ga
RECESSION_CM_PER_YR = 3.830            # Williams & Boggs 2016 (LLR): 3.830 +- 0.008 cm/yr
AGE_TOLERANCE_GYR = 0.001
TARGETS = {"recession_rate_cm_per_yr": "3.830 +- 0.008 (LLR, Williams & Boggs 2016)",
           "moon_age_gyr": "4.425 +- 0.025 (Maurice et al. 2020)"}


@dataclass(frozen=True)
class Trial:
    """One history: its depth (km), the drag fitted to today's recession there (rad/day) and where it stops
    (Gyr ago; inf when it does not within the span)."""

    depth_km: float
    drag_per_day: float
    moon_age_gyr: float


@dataclass(frozen=True)
class Fit:
    """The fitted depth's trial and every trial the bisection made."""

    model: str
    best: Trial
    trials: tuple = field(default=())

    def record(self, command, overrides=()):
        """The stored fit's JSON dict (tides.Depth.fitted reads it)."""
        import datetime

        return {"model": self.model, "depth_km": self.best.depth_km, "drag_per_day": self.best.drag_per_day,
                "drag_per_s": self.best.drag_per_day / 86400.0, "moon_age_gyr": self.best.moon_age_gyr,
                "recession_rate_cm_per_yr": RECESSION_CM_PER_YR, "targets": TARGETS, "overrides": list(overrides),
                "command": command, "date": datetime.date.today().isoformat()}


def fit_depth(model, bracket_km, age_at, log=print, target_gyr=MOON_AGE_GYR, tolerance_gyr=AGE_TOLERANCE_GYR):
    """The depth inside ``bracket_km`` whose history stops at ``target_gyr`` within ``tolerance_gyr``,
    bisected; its ends' ages must lie on either side (a ValueError says they do not)."""
    low, high = bracket_km
    ends = (age_at(low), age_at(high))
    if (ends[0].moon_age_gyr - target_gyr) * (ends[1].moon_age_gyr - target_gyr) >= 0.0:
        raise ValueError(f"the bracket {bracket_km} km does not straddle the Moon's age: the histories stop "
                         f"{ends[0].moon_age_gyr} and {ends[1].moon_age_gyr} Gyr ago")
    trials = list(ends)
    while True:
        trial = age_at(0.5 * (low + high))
        trials.append(trial)
        log(f"depth {trial.depth_km:.6f} km, drag {trial.drag_per_day:.6g}/d: the history stops "
            f"{trial.moon_age_gyr:.4f} Gyr ago")
        if abs(trial.moon_age_gyr - target_gyr) <= tolerance_gyr or high - low < 1e-9:
            return Fit(model, trial, tuple(trials))
        if (trial.moon_age_gyr < target_gyr) == (ends[0].moon_age_gyr < target_gyr):
            low = trial.depth_km
        else:
            high = trial.depth_km
