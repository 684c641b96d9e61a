"""The planar 2R arm: Jacobian and inverse kinematics against seed 001's closed forms."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinlib import KinlibError, planar_2r_fk, planar_2r_ik, planar_2r_jacobian

angles = st.floats(-np.pi, np.pi)
lengths = st.floats(0.1, 3.0)


def xy_phi(t1, t2, l1, l2):
    """Seed 001: x = l1 c1 + l2 c12, y = l1 s1 + l2 s12, φ = θ1 + θ2."""
    return np.array([l1 * np.cos(t1) + l2 * np.cos(t1 + t2),
                     l1 * np.sin(t1) + l2 * np.sin(t1 + t2), t1 + t2])


@settings(max_examples=200, deadline=None)
@given(angles, angles, lengths, lengths)
def test_jacobian_is_the_derivative_and_det(t1, t2, l1, l2):
    J = planar_2r_jacobian(t1, t2, l1, l2)
    h = 1e-6
    for k, (d1, d2) in enumerate([(h, 0.0), (0.0, h)]):
        fd = (xy_phi(t1 + d1, t2 + d2, l1, l2) - xy_phi(t1 - d1, t2 - d2, l1, l2)) / (2 * h)
        np.testing.assert_allclose(J[:, k], fd, atol=1e-8)
    assert np.linalg.det(J[:2]) == pytest.approx(l1 * l2 * np.sin(t2), abs=1e-12)


def test_jacobian_batched():
    rng = np.random.default_rng(0)
    t = rng.uniform(-3, 3, (2, 50))
    J = planar_2r_jacobian(t[0], t[1], 0.7, 0.3)
    assert J.shape == (50, 3, 2)
    for i in (0, 17, 49):
        np.testing.assert_array_equal(J[i], planar_2r_jacobian(t[0, i], t[1, i], 0.7, 0.3))


@settings(max_examples=300, deadline=None)
@given(angles, st.floats(0.01, np.pi - 0.01), lengths, lengths, st.booleans())
def test_ik_inverts_fk_on_both_branches(t1, t2, l1, l2, flip):
    t2 = -t2 if flip else t2
    x, y, _ = xy_phi(t1, t2, l1, l2)
    elbow = "up" if t2 < 0 else "down"
    sol = planar_2r_ik(x, y, l1, l2, elbow=elbow)
    assert sol.success
    assert sol.theta2 == pytest.approx(t2, abs=1e-6)
    np.testing.assert_allclose(xy_phi(sol.theta1, sol.theta2, l1, l2)[:2], [x, y], atol=1e-10)
    other = planar_2r_ik(x, y, l1, l2, elbow="down" if elbow == "up" else "up")
    assert other.theta2 == pytest.approx(-t2, abs=1e-6)
    np.testing.assert_allclose(xy_phi(other.theta1, other.theta2, l1, l2)[:2], [x, y],
                               atol=1e-10)


def test_elbow_up_is_above_the_line_to_a_target_on_the_x_axis():
    sol = planar_2r_ik(1.5, 0.0, 1.0, 1.0, elbow="up")
    elbow = planar_2r_fk(sol.theta1, 0.0, 1.0, 1e-9)[:2, 3]
    assert elbow[1] > 0 and sol.theta2 < 0


@pytest.mark.parametrize("x, y, stretched", [(5.0, 0.0, True), (0.0, -2.5, True),
                                             (0.1, 0.0, False), (0.0, 0.0, False)])
def test_unreachable_targets_give_the_closest_configuration(x, y, stretched):
    l1, l2 = 1.0, 0.5  # workspace: 0.5 <= r <= 1.5
    sol = planar_2r_ik(x, y, l1, l2)
    assert not sol.success
    assert np.isfinite([sol.theta1, sol.theta2]).all()
    assert sol.theta2 == pytest.approx(0.0 if stretched else np.pi)
    p = xy_phi(sol.theta1, sol.theta2, l1, l2)[:2]
    r = np.hypot(x, y)
    assert np.linalg.norm(p - [x, y]) == pytest.approx(abs(r - (1.5 if stretched else 0.5)))


def test_boundary_is_reachable_and_both_branches_agree():
    up = planar_2r_ik(1.5, 0.0, 1.0, 0.5, elbow="up")
    down = planar_2r_ik(1.5, 0.0, 1.0, 0.5, elbow="down")
    assert up.success and down.success
    assert float(up.theta2) == float(down.theta2) == 0.0
    base = planar_2r_ik(0.0, 0.0, 1.0, 1.0)
    assert base.success and base.theta2 == pytest.approx(np.pi)


def test_ik_batched_and_bad_input():
    x = np.array([1.0, 3.0, 0.5])
    sol = planar_2r_ik(x, 0.2, 1.0, 1.0)
    assert sol.theta1.shape == (3,) and sol.success.tolist() == [True, False, True]
    with pytest.raises(KinlibError, match="elbow"):
        planar_2r_ik(1.0, 0.0, 1.0, 1.0, elbow="left")
    with pytest.raises(KinlibError, match="positive"):
        planar_2r_ik(1.0, 0.0, 0.0, 1.0)
    with pytest.raises(KinlibError, match="NaN"):
        planar_2r_ik(np.nan, 0.0, 1.0, 1.0)


def test_ik_on_the_rim_is_exact_not_rounding_amplified():
    """√(1 − c2²) turns c2 = 1 − 1e-16 into θ2 ≈ 1.5e-8; the half-angle form gives 0 for
    targets exactly on the rim (3-4-5 triangles: exactly representable)."""
    from kinlib import planar_2r_ik

    l1, l2 = 2.0, 3.0
    for x, y in ((3.0, 4.0), (-4.0, 3.0), (0.0, -5.0), (5.0, 0.0), (-3.0, -4.0)):
        for elbow in ("up", "down"):
            sol = planar_2r_ik(x, y, l1, l2, elbow=elbow)
            assert sol.success and sol.theta2 == 0.0
            assert abs(sol.theta1 - np.arctan2(y, x)) < 1e-15
    for x, y in ((1.0, 0.0), (0.0, -1.0), (0.6, 0.8)):
        sol = planar_2r_ik(x, y, l1, l2)
        assert sol.success and sol.theta2 == np.pi
    c2 = (1.7**2 - 1.0 - 0.49) / 1.4  # the textbook formula on the rim of a 1.0/0.7 arm
    assert np.arctan2(np.sqrt(1 - c2**2), c2) > 1e-9  # the control: it loses 8 digits
    assert planar_2r_ik(1.7, 0.0, 1.0, 0.7).theta2 == 0.0
