"""kinlib.plot.rodrigues: the split of b along k and its turn, against scipy's rotation and
the geometry the derivation relies on."""

import matplotlib.pyplot as plt
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.plot import axes_3d
from kinlib.plot.rodrigues import plot_rodrigues, rodrigues_parts, split_along_axis

RNG = np.random.default_rng(11)


def random_case():
    axis = RNG.normal(size=3) * RNG.uniform(0.2, 3.0)      # not unit: it is normalised
    return RNG.normal(size=3), axis, RNG.uniform(-2 * np.pi, 2 * np.pi)


def test_the_turned_vector_is_scipys_rotation():
    for _ in range(50):
        b, axis, angle = random_case()
        p = rodrigues_parts(b, axis, angle)
        k = axis / np.linalg.norm(axis)
        expected = Rotation.from_rotvec(angle * k).apply(b)
        np.testing.assert_allclose(p.rotated, expected, atol=1e-12)
        np.testing.assert_allclose(p.parallel + p.perpendicular_rotated, expected, atol=1e-12)
        np.testing.assert_allclose(p.axis, k, atol=1e-15)


def test_the_parts_have_the_geometry_of_the_derivation():
    for _ in range(50):
        b, axis, angle = random_case()
        p = rodrigues_parts(b, axis, angle)
        k = p.axis
        np.testing.assert_allclose(p.parallel + p.perpendicular, b, atol=1e-12)
        np.testing.assert_allclose(np.cross(p.parallel, k), 0.0, atol=1e-12)   # along k
        assert abs(p.perpendicular @ k) < 1e-12                                # across k
        np.testing.assert_allclose(p.perpendicular, -np.cross(k, np.cross(k, b)), atol=1e-12)
        # b⊥ and k × b: perpendicular to each other and to k, of equal length
        assert abs(p.k_cross_b @ p.perpendicular) < 1e-12 and abs(p.k_cross_b @ k) < 1e-12
        assert np.isclose(np.linalg.norm(p.k_cross_b), np.linalg.norm(p.perpendicular))
        # b⊥′ is b⊥ turned by the angle: same length, cos and sin of the angle, about +k
        r2 = p.perpendicular @ p.perpendicular
        assert np.isclose(p.perpendicular_rotated @ p.perpendicular, r2 * np.cos(angle))
        np.testing.assert_allclose(np.cross(p.perpendicular, p.perpendicular_rotated),
                                   r2 * np.sin(angle) * k, atol=1e-12)


def test_the_split_is_the_average_of_b_and_its_half_turn():
    """A half turn about k keeps b∥ and sends b⊥ to −b⊥ (scipy's rotation, not kinlib)."""
    for _ in range(50):
        b, axis, _ = random_case()
        half = Rotation.from_rotvec(np.pi * axis / np.linalg.norm(axis)).apply(b)
        par, perp = split_along_axis(b, axis)
        np.testing.assert_allclose(par, (b + half) / 2, atol=1e-12)
        np.testing.assert_allclose(perp, (b - half) / 2, atol=1e-12)


def test_the_symbolic_split_is_the_numeric_one_and_the_derivations():
    import sympy as sp

    from kinlib.symbolic import sym_equal

    k = sp.Matrix(sp.symbols("k_x k_y k_z", real=True))
    b = sp.Matrix(sp.symbols("b_x b_y b_z", real=True))
    par, perp = split_along_axis(b, k)
    assert par.shape == perp.shape == (3, 1)
    assert sym_equal(par + perp, b)
    assert sym_equal(perp, -k.cross(k.cross(b)), list(k))       # seed 000's cross products
    assert sym_equal(par.cross(k), sp.zeros(3, 1)) and sym_equal(k.dot(perp), 0, list(k))
    for _ in range(5):
        bn, axis, _ = random_case()
        kn = axis / np.linalg.norm(axis)
        values = dict(zip(list(k) + list(b), list(kn) + list(bn), strict=True))
        for sym, num in zip((par, perp), split_along_axis(bn, kn), strict=True):
            np.testing.assert_allclose(np.array(sym.subs(values), dtype=float).ravel(), num,
                                       atol=1e-12)
    # a sequence of expressions is read as a column
    x, y, z = sp.symbols("x y z")
    par, perp = split_along_axis((x, y, z), [1, 0, 0])
    assert par == sp.Matrix([x, 0, 0]) and perp == sp.Matrix([0, y, z])


@pytest.mark.parametrize("args, match", [
    (([1.0, 0.0], [0, 0, 1]), "b"),
    (([1.0, 0.0, 0.0], [0, 0, 0]), "non-zero"),
    (([1.0, 0.0, 0.0], np.ones((2, 3))), "one 3-vector"),
])
def test_the_split_rejects_bad_input(args, match):
    with pytest.raises(kl.KinlibError, match=match):
        split_along_axis(*args)


def test_the_symbolic_split_rejects_a_wrong_shape():
    import sympy as sp

    x, y = sp.symbols("x y")
    with pytest.raises(kl.KinlibError, match="3-vectors"):
        split_along_axis([x, y], [0, 0, 1])


def test_the_circle_and_the_arc_are_where_the_tip_travels():
    b, axis, angle = np.array([0.8, -0.4, 0.5]), np.array([0.0, 1.0, 1.0]), 2.0
    p = rodrigues_parts(b, axis, angle, n=40)
    radius = np.linalg.norm(p.perpendicular)
    for pts in (p.circle, p.arc):
        np.testing.assert_allclose(np.linalg.norm(pts - p.parallel, axis=1), radius, atol=1e-12)
        np.testing.assert_allclose((pts - p.parallel) @ p.axis, 0.0, atol=1e-12)
    assert p.circle.shape == (40, 3)
    np.testing.assert_allclose(p.circle[0], b, atol=1e-12)
    np.testing.assert_allclose(p.arc[0], b, atol=1e-12)
    np.testing.assert_allclose(p.arc[-1], p.rotated, atol=1e-12)
    # every arc point is b turned by an angle between 0 and the angle
    turns = [np.arctan2(np.cross(p.perpendicular, q - p.parallel) @ p.axis,
                        p.perpendicular @ (q - p.parallel)) for q in p.arc]
    assert np.all(np.diff(turns) > 0) and np.isclose(turns[-1], angle)


def test_b_along_the_axis_does_not_move():
    p = rodrigues_parts([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 1.3)
    np.testing.assert_allclose(p.rotated, [0.0, 0.0, 2.0], atol=1e-15)
    np.testing.assert_allclose(p.circle, np.tile([0.0, 0.0, 2.0], (73, 1)), atol=1e-15)


def quiver_ends(q):
    seg = np.asarray(q._segments3d)[0]      # matplotlib keeps the shaft tip first
    return seg[1], seg[0]


def test_the_drawing_draws_the_parts_from_where_they_start():
    b, axis, angle = [1.0, -0.2, 0.7], [0.0, 0.0, 1.0], np.deg2rad(110)
    p = rodrigues_parts(b, axis, angle)
    ax = axes_3d()
    drawn = plot_rodrigues(ax, b, axis, angle)
    for name, start, vec in (("b", 0.0, p.b), ("b_par", 0.0, p.parallel),
                             ("b_perp", p.parallel, p.perpendicular),
                             ("k_cross_b", p.parallel, p.k_cross_b),
                             ("b_perp_rot", p.parallel, p.perpendicular_rotated),
                             ("b_rot", 0.0, p.rotated)):
        s, e = quiver_ends(drawn[name])
        np.testing.assert_allclose(s, start + np.zeros(3), atol=1e-12, err_msg=name)
        np.testing.assert_allclose(e - s, vec, atol=1e-12, err_msg=name)
    np.testing.assert_allclose(np.array(drawn["circle"].get_data_3d()).T, p.circle, atol=1e-12)
    np.testing.assert_allclose(np.array(drawn["arc"].get_data_3d()).T[-1],
                               kl.rodrigues_rotate(b, axis, angle), atol=1e-12)
    plt.close("all")


@pytest.mark.parametrize("args, match", [
    (([1.0, 0.0], [0, 0, 1], 0.5), "b"),
    ((np.ones((2, 3)), [0, 0, 1], 0.5), "one 3-vector"),
    (([1.0, 0.0, 0.0], [0, 0, 0], 0.5), "axis"),
    (([1.0, 0.0, 0.0], [0, 0, 1], [0.5, 0.6]), "one angle"),
    (([1.0, 0.0, 0.0], [0, 0, 1], np.nan), "NaN"),
    (([1.0, 0.0, 0.0], [0, 0, 1], "90"), "angle"),
])
def test_bad_input_is_a_clear_error(args, match):
    with pytest.raises(kl.KinlibError, match=match):
        rodrigues_parts(*args)
    with pytest.raises(kl.KinlibError, match="at least 8"):
        rodrigues_parts([1.0, 0.0, 0.0], [0, 0, 1], 0.5, n=3)
