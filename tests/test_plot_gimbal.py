"""kinlib.plot.gimbal: the rings turn about the axes of the sequence (built here with scipy,
not with kinlib), and rings 1 and 3 share a plane exactly at gimbal lock."""

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.plot import AXIS_COLORS, axes_3d
from kinlib.plot.gimbal import RING_RADII, gimbal_rings, plot_gimbal

RNG = np.random.default_rng(4)
SEQS = ("ZYX", "XYZ", "ZXZ", "XYX", "YZY")


def scipy_axes(angles, seq):
    """e_A, R_A e_B, R_A R_B e_C from scipy's elementary rotations."""
    out, F = [], np.eye(3)
    for letter, angle in zip(seq, angles, strict=True):
        axis = "XYZ".index(letter)
        out.append(F[:, axis])
        F = F @ Rotation.from_euler(letter.lower(), angle).as_matrix()
    return np.array(out), F


@pytest.mark.parametrize("seq", SEQS)
def test_ring_normals_are_the_axes_of_the_sequence_and_the_columns_of_E(seq):
    for angles in RNG.uniform(-np.pi, np.pi, (20, 3)):
        g = gimbal_rings(angles, seq)
        axes, body = scipy_axes(angles, seq)
        np.testing.assert_allclose(g.normals, axes, atol=1e-12)
        np.testing.assert_allclose(g.normals.T, kl.euler_rate_matrix(angles, seq), atol=1e-12)
        # the innermost ring carries the body: scipy's intrinsic (uppercase) rotation
        np.testing.assert_allclose(g.frames[-1], body, atol=1e-12)
        np.testing.assert_allclose(body, Rotation.from_euler(seq, angles).as_matrix(),
                                   atol=1e-12)


def test_each_ring_is_a_closed_circle_of_its_radius_perpendicular_to_its_axis():
    angles = [0.4, -1.1, 2.3]
    g = gimbal_rings(angles, "ZYX", radii=(1.5, 1.0, 0.5), n=50)
    assert g.circles.shape == (3, 50, 3)
    for k, r in enumerate((1.5, 1.0, 0.5)):
        np.testing.assert_allclose(np.linalg.norm(g.circles[k], axis=1), r, atol=1e-12)
        np.testing.assert_allclose(g.circles[k] @ g.normals[k], 0.0, atol=1e-12)
        np.testing.assert_allclose(g.circles[k][0], g.circles[k][-1], atol=1e-12)
        # the points go all the way round: they span the plane, not an arc of it
        assert np.linalg.matrix_rank(g.circles[k], tol=1e-9) == 2
        assert np.isclose(np.linalg.norm(g.marks[k]), r)


@pytest.mark.parametrize("k", range(3))
def test_a_mark_turns_with_its_angle_about_its_axis(k):
    angles = np.array([0.3, 0.7, -0.2])
    turned = angles.copy()
    turned[k] += 0.5
    before, after = gimbal_rings(angles, "ZYX"), gimbal_rings(turned, "ZYX")
    np.testing.assert_allclose(after.normals[k], before.normals[k], atol=1e-12)
    spin = Rotation.from_rotvec(0.5 * before.normals[k]).as_matrix()
    np.testing.assert_allclose(after.marks[k], spin @ before.marks[k], atol=1e-12)
    # the rings outside it do not move
    np.testing.assert_allclose(after.marks[:k], before.marks[:k], atol=1e-12)


def off_plane(g):
    """How far ring 3 leaves the plane of ring 1."""
    return np.abs(g.circles[2] @ g.normals[0]).max()


def test_rings_one_and_three_share_a_plane_exactly_at_gimbal_lock():
    for beta in np.deg2rad(np.linspace(-90, 90, 37)):
        g = gimbal_rings([0.5, beta, -0.8], "ZYX")
        # |n1 × n3| = |cos β| for Z-Y-X: the closed form of the angle between the axes
        assert np.isclose(np.linalg.norm(np.cross(g.normals[0], g.normals[2])),
                          abs(np.cos(beta)), atol=1e-12)
        locked = np.isclose(abs(beta), np.pi / 2)
        assert (off_plane(g) < 1e-12) == locked, np.rad2deg(beta)
    for beta in np.deg2rad([0.0, 45.0, 90.0, 135.0, 180.0]):   # X-Y-X locks at 0 and 180°
        g = gimbal_rings([0.5, beta, -0.8], "XYX")
        assert (off_plane(g) < 1e-12) == bool(np.isclose(np.sin(beta), 0.0, atol=1e-12))


def test_the_drawing_shows_the_rings_in_the_colours_of_their_axes():
    ax = axes_3d()
    lines = plot_gimbal(ax, [0.2, 0.5, -0.3], "ZYX")
    g = gimbal_rings([0.2, 0.5, -0.3], "ZYX")
    assert [ln.get_label() for ln in lines] == ["ring 1: α about Z", "ring 2: β about Y",
                                                "ring 3: γ about X"]
    for k, (line, axis) in enumerate(zip(lines, (2, 1, 0), strict=True)):
        np.testing.assert_allclose(np.array(line.get_data_3d()).T, g.circles[k], atol=1e-12)
        assert matplotlib.colors.same_color(line.get_color(), AXIS_COLORS[axis])
    assert ax.get_xlim() == pytest.approx((-1.1 * RING_RADII[0], 1.1 * RING_RADII[0]))
    plt.close("all")


def test_the_drawing_has_no_ticks_unless_asked():
    bare, ticked = axes_3d(), axes_3d()
    plot_gimbal(bare, [0.2, 0.5, -0.3])
    plot_gimbal(ticked, [0.2, 0.5, -0.3], ticks=True)
    for get in ("get_xticks", "get_yticks", "get_zticks"):
        assert len(getattr(bare, get)()) == 0
        assert len(getattr(ticked, get)()) > 0
    assert [bare.get_xlabel(), bare.get_ylabel(), bare.get_zlabel()] == ["x", "y", "z"]
    plt.close("all")


@pytest.mark.parametrize("bad, match", [
    (dict(angles=[0.1, 0.2]), "angles"),
    (dict(angles=np.zeros((2, 3))), "one triple"),
    (dict(angles=[0.1, np.nan, 0.2]), "NaN"),
    (dict(seq="zyx"), "intrinsic"),
    (dict(seq="ZZX"), "same axis"),
    (dict(radii=(1.0, -0.5, 0.2)), "positive"),
    (dict(radii=(1.0, 0.5)), "radii"),
    (dict(n=4), "at least 8"),
    (dict(n=True), "whole number"),
])
def test_bad_input_is_a_clear_error(bad, match):
    args = dict(angles=[0.1, 0.2, 0.3], seq="ZYX", radii=RING_RADII, n=20) | bad
    with pytest.raises(kl.KinlibError, match=match):
        gimbal_rings(args["angles"], args["seq"], radii=args["radii"], n=args["n"])
