"""What the models ask of each other is said, not assumed: the frame rate a splitting integrator turns the
attitude by is the System's generated one, and a new figure torque tells a gyroscopic body's figure axis which
point masses it comes from (spinorbit.models.interactions.base.Interaction.tidal_attractors)."""
import math
from dataclasses import dataclass

import numpy as np
import pytest

from spinorbit.bodies import earth
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.constants import JULIAN_CENTURY_D
from spinorbit.errors import PhysicsError
from spinorbit.integrators import simulate
from spinorbit.models import System
from spinorbit.models.assemblies.earth import figure, rigid_earth
from spinorbit.models.figure import Body
from spinorbit.models.interactions import PointMass, point_mass
from spinorbit.models.interactions.base import Interaction
from spinorbit.models.motion import Centred
from spinorbit.models.rotators import Gyroscopic, Rigid, oppolzer_attractors
from spinorbit.models.start import on_pole
from spinorbit.orbits.analytic import CircularOrbits
from spinorbit.rotations import matrix_from_quat, quat_angle
from tests.units import arcsec

EPS0 = 84381.406 * arcsec
ECLIPTIC_POLE = np.array([0.0, -math.sin(EPS0), math.cos(EPS0)])
RADIUS_KM = {"moon": 384400.0, "sun": 149597870.7, "venus": 1.0e8}
PERIOD_D = {"moon": 27.321661, "sun": 365.256363, "venus": 583.92}


def circles(bodies=("moon", "sun")):
    """The bodies on uniform circles about the Earth in the ecliptic tilted EPS0 (Euler's hypothesis, §844)."""
    return CircularOrbits(bodies, [gm_km3_d2(b) for b in bodies], [RADIUS_KM[b] for b in bodies],
                          [2 * math.pi / PERIOD_D[b] for b in bodies], [0.3, 1.0, 2.0][:len(bodies)],
                          [EPS0] * len(bodies))


def started(system):
    system.y0 = system.layout.pack(on_pole(system, "earth", 0.0, [0.0, 0.0, 1.0], earth.ERA_RATE_RAD_D,
                                           np.array([1.0, 0, 0])))
    return system


@pytest.mark.slow             # 60 s with its compilation on a loaded machine
def test_splitting_keeps_the_geodesic_precession_with_its_annual_term():
    """A full Earth with the geodesic nutation on, 30 d: suzuki4 turning the attitude by the System's generated
    frame rate agrees with a converged rk8 run far inside the geodesic precession over the span, 1.92"/cy x 30 d
    = 7.6e-9 rad (what a splitting that dropped it would miss); bound 1e-10 rad (rk8 at 0.05 d and suzuki4 at
    0.125 d carry ~1e-12 rad each, tests/test_bench.py)."""
    system = started(rigid_earth(circles(), "full", j2_rate=False, ecliptic_pole=ECLIPTIC_POLE,
                                 geodesic_nutation=True))
    t = np.linspace(0.0, 30.0, 31)
    converged, _ = simulate(system, t, "rk8", {"step": 0.05}, estimate_error=False)
    split, _ = simulate(system, t, "suzuki4", {"step": 0.125}, estimate_error=False)
    geodesic_over_span = earth.GEODESIC_PRECESSION_ARCSEC_CY * arcsec * 30.0 / JULIAN_CENTURY_D
    assert geodesic_over_span == pytest.approx(7.6e-9, rel=0.02)
    assert quat_angle(split.quaternion, converged.quaternion).max() < 1e-10


@dataclass(frozen=True)
class VenusOnTheEarthsFigure(Interaction):
    """A new interaction, written in this one module: Venus as a point mass on the Earth's degree-2 figure
    (Euler's P91 torque, §815), with no reaction (Venus is read from the orbit source)."""

    def bodies(self):
        return ("earth", "venus")

    def tidal_attractors(self, name):
        return ("venus",) if name == "earth" else ()

    def emit(self, code):
        rows, gm = code.rows("earth", ("venus",))
        code.add_torque("earth", f"{code.bind(point_mass.torque, 'venus_torque')}({code.rot('earth')}, "
                                 f"{code.inertia('earth')}, {rows}, {gm})")


def earth_with_venus(rotator):
    gm = gm_km3_d2("earth")
    orbits = circles(("moon", "sun", "venus"))
    body = Body("earth", gm, figure(gm, b_minus_a_over_c=0.0 if isinstance(rotator, Gyroscopic) else 1e-5,
                                    j2_rate=False), rotator)
    return started(System("earth", [body], Centred("earth", orbits),
                          [PointMass("earth", ("moon", "sun")), VenusOnTheEarthsFigure()])), orbits


def test_a_new_interaction_acts_from_its_own_module():
    """The Earth's angular acceleration from the rhs is Euler's equations with the P91 torque of the Moon, the
    Sun and the new Venus term, 3 GM/r^5 r x (I r) in body axes (§815), evaluated here by hand; Venus's share is
    what it should be (its torque ~ GM/r^3: 1e-5 of the Sun's at 1e8 km)."""
    system, orbits = earth_with_venus(Rigid())
    y = system.y0
    q, omega = y[system.layout["earth.q"]], y[system.layout["earth.omega"]]
    moments = system.bodies["earth"].figure.moments
    rows = matrix_from_quat(q).T @ orbits.positions([0.0])[0].T                 # body axes, (3, n)
    torque = sum(3 * gm / np.linalg.norm(r) ** 5 * np.cross(r, moments * r) for r, gm in zip(rows.T, orbits.gm))
    venus = 3 * orbits.gm[2] / np.linalg.norm(rows[:, 2]) ** 5 * np.cross(rows[:, 2], moments * rows[:, 2])
    expected = (torque - np.cross(omega, moments * omega)) / moments
    got = system.rhs(0.0, y, system.params)[system.layout["earth.omega"]]
    assert np.abs(got - expected).max() < 1e-12 * np.abs(expected).max()
    assert 1e-7 < np.linalg.norm(venus) / np.linalg.norm(torque) < 1e-4


@dataclass(frozen=True)
class VenusWithoutItsTidalTensor(VenusOnTheEarthsFigure):
    def tidal_attractors(self, name):
        return ()


def test_a_gyroscopic_figure_axis_takes_the_new_interactions_point_mass():
    """The gyroscopic Earth's figure axis comes from every point mass whose tidal tensor acts on its figure,
    Venus's too, as the new interaction says: its spin's rate is that of the Earth with Venus among the
    assembly's own point masses (PointMass, P91) to rounding, and differs from it when Venus is left out of the
    Oppolzer terms (the axial component of the spin's rate, which the figure axis's offset sets, by 8e-5)."""
    system, orbits = earth_with_venus(Gyroscopic())
    assert oppolzer_attractors(system, "earth") == ("moon", "sun", "venus")
    same = System("earth", list(system.bodies.values()), Centred("earth", orbits),
                  [PointMass("earth", ("moon", "sun", "venus"))])
    blind = System("earth", list(system.bodies.values()), Centred("earth", orbits),
                   [PointMass("earth", ("moon", "sun")), VenusWithoutItsTidalTensor()])
    rate, reference, without = (s.rhs(0.0, system.y0, s.params) for s in (system, same, blind))
    assert np.all(np.abs(rate - reference) <= 1e-12 * np.abs(reference))
    assert np.abs(without - reference).max() / np.abs(reference[2]) > 1e-6      # the axial rate: 8e-5 of it


@dataclass(frozen=True)
class SilentTorque(Interaction):
    """A torque on the Earth that does not say where its Oppolzer terms come from."""

    def bodies(self):
        return ("earth",)

    def emit(self, code):
        code.add_torque("earth", "np.zeros(3)")


def test_a_torque_that_does_not_say_what_the_figure_axis_needs_is_refused():
    """No silent loss of Oppolzer terms: on a gyroscopic body an interaction must answer tidal_attractors."""
    gm = gm_km3_d2("earth")
    body = Body("earth", gm, figure(gm, j2_rate=False), Gyroscopic())
    with pytest.raises(PhysicsError, match="SilentTorque acts on 'earth'"):
        System("earth", [body], Centred("earth", circles()), [PointMass("earth", ("moon", "sun")), SilentTorque()])
