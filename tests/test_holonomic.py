"""The holonomic base of seed 000: pose, heading/lateral vectors, stepping."""

import numpy as np
import pytest

from kinlib import KinlibError, rotx
from kinlib.kinematics.holonomic import base_heading_lateral, base_pose, base_step

YAWS = np.linspace(-np.pi, np.pi, 13)


@pytest.mark.parametrize("yaw", YAWS)
def test_heading_and_lateral_closed_form(yaw):
    heading, lateral = base_heading_lateral(base_pose(3.0, -2.0, yaw))
    np.testing.assert_allclose(heading, [np.cos(yaw), np.sin(yaw), 0.0], atol=1e-12)
    np.testing.assert_allclose(lateral, [-np.sin(yaw), np.cos(yaw), 0.0], atol=1e-12)


def test_base_pose_is_on_the_ground_and_batched():
    T = base_pose(YAWS, 2 * YAWS, YAWS)
    assert T.shape == (len(YAWS), 4, 4)
    np.testing.assert_allclose(T[:, :3, 3], np.stack([YAWS, 2 * YAWS, 0 * YAWS], axis=1))
    np.testing.assert_allclose(T[:, 2, :], np.tile([0.0, 0.0, 1.0, 0.0], (len(YAWS), 1)))
    np.testing.assert_allclose(T[:, 3, :], np.tile([0.0, 0.0, 0.0, 1.0], (len(YAWS), 1)))


def test_heading_lateral_orthonormal_and_free_vectors():
    rng = np.random.default_rng(7)
    T = base_pose(rng.uniform(-5, 5, 50), rng.uniform(-5, 5, 50), rng.uniform(-4, 4, 50))
    h, s = base_heading_lateral(T)
    np.testing.assert_allclose(np.linalg.norm(h, axis=-1), 1.0)
    np.testing.assert_allclose(np.linalg.norm(s, axis=-1), 1.0)
    np.testing.assert_allclose(np.einsum("ni,ni->n", h, s), 0.0, atol=1e-12)
    # heading × lateral = world up: lateral is to the base's left
    np.testing.assert_allclose(np.cross(h, s), np.tile([0.0, 0.0, 1.0], (50, 1)), atol=1e-12)
    # free vectors: the translation does not enter
    h0, s0 = base_heading_lateral(base_pose(0.0, 0.0, 0.4))
    h1, s1 = base_heading_lateral(base_pose(100.0, -50.0, 0.4))
    np.testing.assert_allclose(h0, h1)
    np.testing.assert_allclose(s0, s1)


def test_heading_of_a_tilted_base_uses_the_rotation():
    T = np.eye(4)
    T[:3, :3] = rotx(np.pi / 2)  # lateral (local y) now points up
    T[:3, 3] = [1.0, 2.0, 3.0]
    h, s = base_heading_lateral(T)
    np.testing.assert_allclose(h, [1.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(s, [0.0, 0.0, 1.0], atol=1e-12)


@pytest.mark.parametrize("yaw", [0.0, 0.7, -2.5, np.pi])
def test_step_moves_along_heading_and_lateral(yaw):
    T = base_pose(1.0, 2.0, yaw)
    moved = base_step(T, forward=0.3, lateral=-0.2)
    expected = np.array([1.0, 2.0, 0.0]) + 0.3 * np.array([np.cos(yaw), np.sin(yaw), 0.0]) \
        - 0.2 * np.array([-np.sin(yaw), np.cos(yaw), 0.0])
    np.testing.assert_allclose(moved[:3, 3], expected, atol=1e-12)
    np.testing.assert_allclose(moved[:3, :3], T[:3, :3])  # no turn


def test_forward_then_back_returns_the_pose():
    T = base_pose(-1.5, 0.25, 2.2)
    there = base_step(T, forward=0.8, lateral=0.3)
    assert not np.allclose(there, T)
    back = base_step(there, forward=-0.8, lateral=-0.3)
    np.testing.assert_allclose(back, T, atol=1e-12)


def test_turn_composes_and_stays_in_place():
    T = base_pose(4.0, -3.0, 0.3)
    once = base_step(T, turn=0.5)
    np.testing.assert_allclose(once[:3, 3], T[:3, 3])
    np.testing.assert_allclose(once, base_pose(4.0, -3.0, 0.8), atol=1e-12)
    twice = base_step(base_step(T, turn=0.2), turn=0.3)
    np.testing.assert_allclose(twice, once, atol=1e-12)
    full = T
    for _ in range(8):
        full = base_step(full, turn=np.pi / 4)
    np.testing.assert_allclose(full, T, atol=1e-12)


def test_step_translates_before_turning():
    T = base_step(base_pose(0.0, 0.0, 0.0), forward=1.0, turn=np.pi / 2)
    np.testing.assert_allclose(T[:3, 3], [1.0, 0.0, 0.0], atol=1e-12)  # not [0, 1, 0]
    np.testing.assert_allclose(base_heading_lateral(T)[0], [0.0, 1.0, 0.0], atol=1e-12)


def test_step_is_batched():
    T = base_pose(np.zeros(3), 0.0, [0.0, np.pi / 2, np.pi])
    moved = base_step(T, forward=[1.0, 2.0, 3.0])
    np.testing.assert_allclose(moved[:, :3, 3], [[1, 0, 0], [0, 2, 0], [-3, 0, 0]], atol=1e-12)


@pytest.mark.parametrize("call, match", [
    (lambda: base_pose("1", 0.0, 0.0), "x"),
    (lambda: base_pose(0.0, np.nan, 0.0), "y"),
    (lambda: base_pose([1.0, 2.0], [1.0, 2.0, 3.0], 0.0), "batch"),
    (lambda: base_pose(0.0, 0.0, True), "yaw"),
    (lambda: base_heading_lateral(np.ones((4, 4))), "bottom row"),
    (lambda: base_heading_lateral(np.eye(3)), "T_world_base"),
    (lambda: base_step(np.eye(4), forward="far"), "forward"),
    (lambda: base_step(np.eye(4), lateral=np.inf), "lateral"),
    (lambda: base_step(np.eye(4), turn=None), "turn"),
    (lambda: base_step(np.diag([2.0, 1.0, 1.0, 1.0])), "rotation"),
    (lambda: base_step(np.eye(4), forward=[1.0, 2.0], turn=[1.0, 2.0, 3.0]), "batch"),
])
def test_bad_input_raises_kinlib_error(call, match):
    with pytest.raises(KinlibError, match=match):
        call()
