"""kinlib.plot draws what it is given: arrows along the frame's axes, from its origin."""

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

import kinlib as kl
from kinlib.plot import AXIS_COLORS, axes_3d, plot_frame, plot_point


def segments(quiver):
    """(start, end) of a 3-D quiver's shaft (matplotlib stores it tip first)."""
    seg = np.asarray(quiver._segments3d)[0]
    return seg[1], seg[0]


def test_frame_arrows_follow_the_rotation_columns():
    T = kl.transform(kl.matrix_from_euler([0.3, -0.4, 1.1], "ZYX"), [0.5, -0.2, 0.1])
    ax = axes_3d()
    arrows = plot_frame(ax, T, label="B", length=0.5)
    assert len(arrows) == 3
    for k, q in enumerate(arrows):
        start, end = segments(q)
        np.testing.assert_allclose(start, T[:3, 3], atol=1e-12)
        np.testing.assert_allclose(end - start, 0.5 * T[:3, k], atol=1e-12)
        assert matplotlib.colors.same_color(q.get_edgecolor()[0], AXIS_COLORS[k])
    assert any(t.get_text() == "{B}" for t in ax.texts)
    plt.close("all")


def test_point_and_bad_input():
    ax = axes_3d(((0, 2), (0, 2), (0, 2)))
    dot = plot_point(ax, [1.0, 1.5, 0.5], label="P")
    np.testing.assert_allclose(np.array(dot._offsets3d).ravel(), [1.0, 1.5, 0.5])
    with pytest.raises(kl.KinlibError, match="limits"):
        axes_3d(((1, 0), (0, 1), (0, 1)))
    with pytest.raises(kl.KinlibError, match="T"):
        plot_frame(ax, np.zeros((4, 4)))
    with pytest.raises(kl.KinlibError, match="one point"):
        plot_point(ax, np.zeros((2, 3)))
    plt.close("all")


def test_arm_points_against_the_link_lengths_and_fk():
    """The polyline of the 2R arm: the elbow is l1 from the base, the tip l2 from the elbow
    and at the forward kinematics, for a batch (and the law of cosines for |tip|)."""
    from kinlib.plot import arm_points

    rng = np.random.default_rng(1)
    q = rng.uniform(-np.pi, np.pi, (50, 2))
    pts = arm_points(q, 0.7, 0.4)
    assert pts.shape == (50, 3, 2) and np.all(pts[:, 0] == 0)
    np.testing.assert_allclose(np.linalg.norm(pts[:, 1], axis=1), 0.7, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(pts[:, 2] - pts[:, 1], axis=1), 0.4, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(pts[:, 2], axis=1) ** 2,
                               0.49 + 0.16 + 2 * 0.28 * np.cos(q[:, 1]), rtol=1e-12)
    np.testing.assert_allclose(pts[:, 2], kl.planar_2r_fk(q[:, 0], q[:, 1], 0.7, 0.4)[:, :2, 3])
    with pytest.raises(kl.KinlibError, match="q"):
        arm_points([0.1, 0.2, 0.3], 1, 1)


def test_plot_arm_draws_one_configuration():
    from kinlib.plot import arm_points, plot_arm

    fig, ax = plt.subplots()
    line = plot_arm(ax, [0.3, 1.1], 1.0, 0.8, color="k")
    np.testing.assert_allclose(np.c_[line.get_xdata(), line.get_ydata()],
                               arm_points([0.3, 1.1], 1.0, 0.8))
    assert line.get_marker() == "o"
    with pytest.raises(kl.KinlibError, match="one configuration"):
        plot_arm(ax, np.zeros((2, 2)), 1.0, 0.8)
    plt.close(fig)


def test_animate_makes_a_player_with_every_frame_and_closes_the_figure():
    import re

    from kinlib.plot import animate

    fig, ax = plt.subplots()
    (line,) = ax.plot([], [])
    drawn = []

    def draw(k):
        drawn.append(k)
        line.set_data([0, k], [0, k])

    html = animate(fig, draw, frames=7, interval=80).data
    assert "<script" in html and set(drawn) == set(range(7))
    assert len(set(re.findall(r"frames\[(\d+)\]", html))) == 7
    assert not plt.fignum_exists(fig.number)
    # a player that needs no network: no icon font from a CDN (blank buttons offline)
    assert "font-awesome" not in html and "https://" not in html and 'class="fa' not in html
    assert html.count('class="kl-icon"') == 9 and "▶" in html and "❚❚" in html
    from matplotlib import animation  # the control: matplotlib's own player links it

    fig3 = plt.figure()
    raw = animation.FuncAnimation(fig3, lambda k: None, frames=2).to_jshtml()
    assert "font-awesome" in raw and "https://" in raw
    fig2, _ = plt.subplots()
    with pytest.raises(kl.KinlibError, match="frames"):
        animate(fig2, draw, frames=0)
    with pytest.raises(kl.KinlibError, match="interval"):
        animate(fig2, draw, frames=3, interval=-1)
    plt.close("all")


def test_animate_renders_each_frame_once():
    """Each frame is drawn once, into its PNG: FuncAnimation's redraw of the screen canvas
    after every frame is skipped (it doubled the cost of every player)."""
    from unittest import mock

    from matplotlib.figure import Figure

    from kinlib.plot import animate

    draws, draw = [], Figure.draw

    def counted(self, renderer):
        draws.append(self)
        return draw(self, renderer)

    fig, ax = plt.subplots()
    (line,) = ax.plot([], [])
    with mock.patch.object(Figure, "draw", counted):
        html = animate(fig, lambda k: line.set_data([0, k], [0, k]), frames=5).data
    assert html.count("data:image/png") == 5 and len(draws) == 5
