"""A System as data (spinorbit.models): its layout (named slices, pack, normalise), its parameter record, the
checks on what it is given, and the idealised assemblies' generated rhs against Euler's equations by hand."""
import math

import numpy as np
import pytest

from spinorbit.base.rotations import matrix_from_quat, quat_rate
from spinorbit.models import Body, Centred, Figure, Layout, Rigid, System
from spinorbit.models.assemblies.idealised import free_body, under_point_masses
from spinorbit.models.interactions import PointMass
from spinorbit.orbits.analytic import CircularOrbits

MOMENTS = np.array([0.8, 1.0, 1.3])
ORBIT = CircularOrbits(("m", "n"), gm=[0.5, 0.2], radius=[1.0, 2.5], rate=[1.0, 0.3], inclination=[0.3, -0.7])
LAYOUT = Layout([("moon.r", 3, "vector", "km"), ("moon.q", 4, "quaternion", "body -> inertial"),
                 ("earth.spin", 3, "vector", "G-scaled")])


def test_layout_names_its_slices_in_state_order():
    assert LAYOUT.names == ["moon.r", "moon.q", "earth.spin"] and LAYOUT.size == 10
    assert LAYOUT["moon.q"] == slice(3, 7) and "earth.spin" in LAYOUT and "earth.q" not in LAYOUT
    assert LAYOUT.quaternions == [slice(3, 7)]


def test_pack_places_each_part_and_makes_quaternions_unit():
    q = np.array([2.0, 0.0, 0.0, 0.0])
    y = LAYOUT.pack({"earth.spin": [7.0, 8.0, 9.0], "moon.q": q, "moon.r": [1.0, 2.0, 3.0]})
    assert np.array_equal(y, [1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0, 7.0, 8.0, 9.0])
    assert np.array_equal(q, [2.0, 0.0, 0.0, 0.0])                 # the caller's array is left alone
    split = LAYOUT.split(np.stack([y, 2 * y]))
    assert np.array_equal(split["earth.spin"], [[7.0, 8.0, 9.0], [14.0, 16.0, 18.0]])


def test_pack_refuses_missing_and_unknown_parts_by_name():
    with pytest.raises(KeyError, match=r"missing \['earth.spin'\], unknown \['moon.omega'\]"):
        LAYOUT.pack({"moon.r": np.zeros(3), "moon.q": [1.0, 0, 0, 0], "moon.omega": np.zeros(3)})
    with pytest.raises(ValueError):                                    # a part of the wrong size
        LAYOUT.pack({"moon.r": np.zeros(2), "moon.q": [1.0, 0, 0, 0], "earth.spin": np.zeros(3)})


def test_normalise_makes_every_quaternion_unit_and_nothing_else():
    """normalise (states (n, size)) and normalise_state (one) divide each quaternion slice by its norm; the
    vectors keep their bits; the input is not changed."""
    states = np.array([[1.0, 2.0, 3.0, 0.0, 3.0, 0.0, 4.0, 5.0, 6.0, 7.0],
                       [1e5, -2e5, 3e5, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]])
    out = LAYOUT.normalise(states)
    assert np.array_equal(out[:, 3:7], [[0.0, 0.6, 0.0, 0.8], [0.5, 0.5, 0.5, 0.5]])
    assert np.array_equal(out[:, :3], states[:, :3]) and np.array_equal(out[:, 7:], states[:, 7:])
    assert states[0, 4] == 3.0
    assert np.array_equal(LAYOUT.normalise_state(states[0]), out[0])


def test_an_interaction_naming_no_body_of_the_system_is_refused():
    body = Body("body", figure=Figure(MOMENTS), rotator=Rigid())
    with pytest.raises(KeyError, match=r"PointMass names \['sun'\], which are not bodies of the system"):
        System("s", [body], Centred("body", ORBIT), [PointMass("body", ("m", "sun"))])


def test_the_parameter_record_is_named_and_with_start_shares_the_compiled_functions():
    system = under_point_masses(MOMENTS, ORBIT, [1.0, 0, 0, 0], [0.3, -0.4, 1.2])
    assert list(system.parameters)[:1] == ["external_data"] and len(system.params) == len(system.parameters)
    assert np.array_equal(system.parameters["body_moments"], MOMENTS)
    other = system.with_start(5.0, np.concatenate([[0.0, 3.0, 0.0, 4.0], [1.0, 2.0, 3.0]]))
    assert other.rhs is system.rhs and other.torque is system.torque and other.t0 == 5.0
    assert np.array_equal(other.y0[:4], [0.0, 0.6, 0.0, 0.8]) and system.t0 == 0.0
    assert system.lone_rigid_body == "body" and system.layout.names == ["body.q", "body.omega"]


def euler_rhs(moments, orbit, t, y):
    """Euler's equations by hand (§813, §815): q' = q (0, w)/2, A w_x' = (B - C) w_y w_z + sum 3 GM/r^5
    (C - B) y z, and cyclic, r the masses in body axes."""
    q, w = y[:4], y[4:]
    a, b, c = moments
    torque = np.zeros(3)
    for r_inertial, gm in zip(orbit.positions(t)[0], orbit.gm):
        x, yy, z = matrix_from_quat(q).T @ r_inertial
        torque += 3 * gm / np.linalg.norm(r_inertial) ** 5 * np.array([(c - b) * yy * z, (a - c) * z * x,
                                                                         (b - a) * x * yy])
    w_dot = np.array([((b - c) * w[1] * w[2] + torque[0]) / a, ((c - a) * w[2] * w[0] + torque[1]) / b,
                      ((a - b) * w[0] * w[1] + torque[2]) / c])
    return np.concatenate([quat_rate(q, w), w_dot]), torque


def test_a_rigid_body_under_point_masses_is_eulers_problem_91():
    """The idealised assembly's generated rhs and its torque (what splitting integrators kick with) at a few
    states against Euler's P, Q, R (§815) and equations (§813) written out."""
    system = under_point_masses(MOMENTS, ORBIT, [1.0, 0, 0, 0], [0.3, -0.4, 1.2])
    rng = np.random.default_rng(91)
    for t in (0.0, 1.7, -3.2):
        q = rng.normal(size=4)
        y = system.layout.pack({"body.q": q, "body.omega": rng.normal(size=3)})
        expected, torque = euler_rhs(MOMENTS, ORBIT, t, y)
        np.testing.assert_allclose(system.rhs(t, y, system.params), expected, rtol=0, atol=1e-14)
        np.testing.assert_allclose(system.torque(t, y, system.params), torque, rtol=0,
                                   atol=1e-14 * np.abs(torque).max())


def test_the_free_body_has_no_torque():
    """Euler's free body (ch. 15 §808): the rhs is Euler's equations with N = 0, bit for bit in the rates."""
    from spinorbit.models.spin import euler_omega_dot

    omega = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / MOMENTS
    system = free_body(MOMENTS, [1.0, 0, 0, 0], omega)
    dy = system.rhs(0.0, system.y0, system.params)
    assert np.array_equal(dy[4:], euler_omega_dot(MOMENTS, omega, np.zeros(3)))
    assert not system.torque(0.0, system.y0, system.params).any()
