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
