"""kinlib.plot.dh: the picture of one DH row shows the row's four parameters.

The distances and angles are measured back from what is drawn and compared with the row,
the frames are the poses kl.dh_transform gives (frames i−1 and i), and bad input is a
KinlibError."""

from itertools import pairwise

import matplotlib.pyplot as plt
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.plot import axes_3d
from kinlib.plot.dh import dh_geometry, plot_dh_row


def rows(seed=3, n=25):
    rng = np.random.default_rng(seed)
    out = [(np.deg2rad(50), 0.6, 0.8, np.deg2rad(60)),        # the notebook's row
           (0.0, 0.0, 0.0, 0.0), (-2.5, -0.3, -0.7, -1.2),   # negative everything
           (3.0, 0.2, 0.5, 3.1), (5.0, 0.1, 0.4, -4.0)]      # angles beyond ±π
    out += [tuple(r) for r in rng.uniform([-np.pi, -1, -1, -np.pi], [np.pi, 1, 1, np.pi],
                                          (n, 4))]
    return out


def poses(seed=4):
    rng = np.random.default_rng(seed)
    R = Rotation.random(random_state=5).as_matrix()
    return [None, kl.transform(R, rng.uniform(-1, 1, 3))]


def swept(points, center, axis):
    """The signed angle an arc turns through about ``axis`` (unwrapped, right-handed)."""
    v = points - center
    steps = [np.arctan2(np.dot(np.cross(p, q), axis), np.dot(p, q))
             for p, q in pairwise(v)]
    return float(np.sum(steps))


def unit(v):
    return v / np.linalg.norm(v)


@pytest.mark.parametrize("T_prev", poses(), ids=["identity", "posed"])
@pytest.mark.parametrize("theta, d, a, alpha", rows())
def test_the_drawn_distances_and_angles_are_the_rows_parameters(theta, d, a, alpha, T_prev):
    g = dh_geometry(theta, d, a, alpha, T_prev=T_prev)
    F0 = np.eye(4) if T_prev is None else T_prev
    F1 = F0 @ kl.dh_transform(theta=theta, d=d, a=a, alpha=alpha)   # frame i, from kinlib
    o0, x0, z0 = F0[:3, 3], F0[:3, 0], F0[:3, 2]
    o1, x1, z1 = F1[:3, 3], F1[:3, 0], F1[:3, 2]
    assert np.allclose(g.T_prev, F0) and np.allclose(g.T, F1)
    # d: from o_{i−1} along z_{i−1} to the foot, which lies on z_{i−1}
    start, foot = g.d_segment
    assert np.allclose(start, o0) and np.allclose(foot, g.foot)
    assert np.isclose(np.dot(foot - o0, z0), d)
    assert np.allclose(np.cross(foot - o0, z0), 0.0, atol=1e-12)
    # a: from the foot along the common normal x_i to o_i; x_i ⟂ z_{i−1} and z_i (DH1)
    foot_a, end = g.a_segment
    assert np.allclose(foot_a, foot) and np.allclose(end, o1)
    assert np.isclose(np.dot(end - foot, x1), a)
    assert np.allclose(np.cross(end - foot, x1), 0.0, atol=1e-12)
    assert abs(np.dot(x1, z0)) < 1e-12 and abs(np.dot(x1, z1)) < 1e-12
    # θ: an arc about z_{i−1} at the foot, from x_{i−1} to x_i, turning through θ
    arc = g.theta_arc
    assert np.allclose(np.linalg.norm(arc - foot, axis=1), g.radius)
    assert np.allclose((arc - foot) @ z0, 0.0, atol=1e-12)
    assert np.allclose(unit(arc[0] - foot), x0) and np.allclose(unit(arc[-1] - foot), x1)
    assert np.isclose(swept(arc, foot, z0), theta)
    # α: an arc about x_i at o_i, from z_{i−1} to z_i, turning through α
    arc = g.alpha_arc
    assert np.allclose(np.linalg.norm(arc - o1, axis=1), g.radius)
    assert np.allclose((arc - o1) @ x1, 0.0, atol=1e-12)
    assert np.allclose(unit(arc[0] - o1), z0) and np.allclose(unit(arc[-1] - o1), z1)
    assert np.isclose(swept(arc, o1, x1), alpha)


def on_line(p, point, direction):
    return np.allclose(np.cross(p - point, direction), 0.0, atol=1e-12)


@pytest.mark.parametrize("T_prev", poses(), ids=["identity", "posed"])
@pytest.mark.parametrize("theta, d, a, alpha", rows())
def test_the_two_links_meet_the_joint_axes_where_dh_says(theta, d, a, alpha, T_prev):
    g = dh_geometry(theta, d, a, alpha, T_prev=T_prev)
    F0 = np.eye(4) if T_prev is None else T_prev
    F1 = F0 @ kl.dh_transform(theta=theta, d=d, a=a, alpha=alpha)
    o0, x0, z0 = F0[:3, 3], F0[:3, 0], F0[:3, 2]
    o1, z1 = F1[:3, 3], F1[:3, 2]
    # link i−1 arrives at o_{i−1} along x_{i−1} (its common normal), from the far side
    start, end = g.link_prev
    assert np.allclose(end, o0) and on_line(start, o0, x0) and np.dot(end - start, x0) > 0
    # link i: a segment from joint i's axis to joint i+1's, perpendicular to both
    start, end = g.link
    assert on_line(start, o0, z0) and on_line(end, o1, z1)
    assert abs(np.dot(end - start, z0)) < 1e-12 and abs(np.dot(end - start, z1)) < 1e-12
    assert np.isclose(np.linalg.norm(end - start), abs(a))     # the distance of the axes
    # the joints lie on their axes; joint i holds both links' ends, joint i+1 is at o_i
    for seg, point, axis in ((g.joint, o0, z0), (g.joint_next, o1, z1)):
        assert all(on_line(p, point, axis) for p in seg)
    lo, hi = sorted(np.dot(g.joint - o0, z0))
    assert lo < 0.0 < hi and lo < d < hi                         # o_{i−1} and the foot
    assert np.allclose(g.joint_next.mean(axis=0), o1)


def test_a_row_worked_by_hand():
    # θ = 90°: x1 = y0; d = 0.5 up z0; a = 1 along x1; α = 90°: z1 = z0 turned about y0 = x0
    g = dh_geometry(np.pi / 2, 0.5, 1.0, np.pi / 2, radius=0.2)
    assert np.allclose(g.foot, [0, 0, 0.5]) and np.allclose(g.T[:3, 3], [0, 1, 0.5])
    assert np.allclose(g.T[:3, 0], [0, 1, 0]) and np.allclose(g.T[:3, 2], [1, 0, 0])
    assert np.allclose(g.theta_arc[0], [0.2, 0, 0.5]) and np.allclose(g.theta_arc[-1],
                                                                       [0, 0.2, 0.5])
    assert np.allclose(g.alpha_arc[0], [0, 1, 0.7]) and np.allclose(g.alpha_arc[-1],
                                                                     [0.2, 1, 0.5])


def test_what_is_plotted_is_the_geometry():
    ax = axes_3d(((-1, 1), (-1, 1), (-1, 1)))
    try:
        g, art = plot_dh_row(ax, 0.7, 0.4, 0.6, -0.9, index="2")
        for key, points in (("d", g.d_segment), ("a", g.a_segment), ("theta", g.theta_arc),
                            ("alpha", g.alpha_arc)):
            drawn = np.column_stack(art[key].get_data_3d())
            assert np.allclose(drawn, points), key
        labels = {t.get_text() for t in ax.texts}
        assert {"$d_{2}$", "$a_{2}$", r"$\theta_{2}$", r"$\alpha_{2}$", "{1}", "{2}"} <= labels
        # the joint axes are drawn along z_{i−1} through o_{i−1} and along z_i through o_i
        for key, F in (("z_prev", g.T_prev), ("z_next", g.T)):
            p, q = np.column_stack(art[key].get_data_3d())
            assert np.allclose(np.cross(q - p, F[:3, 2]), 0.0, atol=1e-12)
            assert np.allclose(np.cross(F[:3, 3] - p, F[:3, 2]), 0.0, atol=1e-12)
        for key, points in (("link_prev", g.link_prev), ("link", g.link)):
            assert np.allclose(np.column_stack(art[key].get_data_3d()), points), key
        assert {"link 1", "link 2"} <= {t.get_text().strip() for t in ax.texts}
        assert art["joint"] is not None and art["joint_next"] is not None
        _, bare = plot_dh_row(axes_3d(), 0.7, 0.4, 0.6, -0.9, links=False)
        assert not {"link_prev", "link", "joint", "joint_next"} & set(bare)
    finally:
        plt.close("all")


@pytest.mark.parametrize("kwargs, words", [
    (dict(theta="1"), "theta"),
    (dict(d=np.nan), "d: expected a finite"),
    (dict(a=[1.0, 2.0]), "a: expected one real number"),
    (dict(alpha=None), "alpha"),
    (dict(theta=True), "theta"),
    (dict(T_prev=2 * np.eye(4)), "T_prev"),
    (dict(T_prev=np.stack([np.eye(4)] * 2)), "one 4×4"),
    (dict(radius=0.0), "radius"),
    (dict(radius=-1.0), "radius"),
    (dict(n=1), "n:"),
    (dict(n=2.5), "n:"),
])
def test_bad_input_is_a_kinlib_error(kwargs, words):
    args = dict(theta=0.3, d=0.1, a=0.5, alpha=0.2)
    args.update(kwargs)
    with pytest.raises(kl.KinlibError, match=words):
        dh_geometry(**args)


def test_bad_plot_options_are_a_kinlib_error():
    ax = axes_3d()
    try:
        with pytest.raises(kl.KinlibError, match="index"):
            plot_dh_row(ax, 0.3, 0.1, 0.5, 0.2, index="")
        with pytest.raises(kl.KinlibError, match="frame_length"):
            plot_dh_row(ax, 0.3, 0.1, 0.5, 0.2, frame_length=0.0)
        with pytest.raises(kl.KinlibError, match="links"):
            plot_dh_row(ax, 0.3, 0.1, 0.5, 0.2, links="yes")
    finally:
        plt.close("all")
