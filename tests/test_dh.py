"""DH link transforms and DH robots against products of elementary transforms."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from kinlib import DHRow, KinlibError, Robot, dh_transform, load_urdf, mdh_transform


def Rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def Rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def Tz(d):
    T = np.eye(4)
    T[2, 3] = d
    return T


def Tx(a):
    T = np.eye(4)
    T[0, 3] = a
    return T


angles = st.floats(-4.0, 4.0)
lengths = st.floats(-2.0, 2.0)


@given(angles, lengths, lengths, angles)
def test_dh_is_rz_tz_tx_rx(theta, d, a, alpha):
    expected = Rz(theta) @ Tz(d) @ Tx(a) @ Rx(alpha)
    np.testing.assert_allclose(dh_transform(theta=theta, d=d, a=a, alpha=alpha), expected,
                               atol=1e-14)


@given(angles, lengths, lengths, angles)
def test_mdh_is_rx_tx_rz_tz(theta, d, a, alpha):
    expected = Rx(alpha) @ Tx(a) @ Rz(theta) @ Tz(d)
    np.testing.assert_allclose(mdh_transform(theta=theta, d=d, a=a, alpha=alpha), expected,
                               atol=1e-14)


def test_seed_dh_matrix_entries():
    # seed 001's printed A_i, entry by entry
    t, d, a, al = 0.7, 0.3, -1.2, 2.1
    ct, st_, ca, sa = np.cos(t), np.sin(t), np.cos(al), np.sin(al)
    seed = np.array([[ct, -ca * st_, sa * st_, a * ct],
                     [st_, ca * ct, -sa * ct, a * st_],
                     [0, sa, ca, d],
                     [0, 0, 0, 1]])
    np.testing.assert_allclose(dh_transform(theta=t, d=d, a=a, alpha=al), seed, atol=1e-15)


def test_batched_broadcast():
    rng = np.random.default_rng(0)
    th = rng.uniform(-3, 3, (5, 1))
    al = rng.uniform(-3, 3, (1, 4))
    for f, ref in ((dh_transform, lambda t, l: Rz(t) @ Tz(0.2) @ Tx(0.5) @ Rx(l)),
                   (mdh_transform, lambda t, l: Rx(l) @ Tx(0.5) @ Rz(t) @ Tz(0.2))):
        T = f(theta=th, d=0.2, a=0.5, alpha=al)
        assert T.shape == (5, 4, 4, 4)
        for i in range(5):
            for j in range(4):
                np.testing.assert_allclose(T[i, j], ref(th[i, 0], al[0, j]), atol=1e-14)


def test_symbolic_matches_numeric():
    t, d, a, al = sp.symbols("theta d a alpha")
    for f in (dh_transform, mdh_transform):
        M = f(theta=t, d=d, a=a, alpha=al)
        assert isinstance(M, sp.Matrix)
        num = sp.lambdify((t, d, a, al), M)(0.4, -0.3, 0.9, 1.3)
        np.testing.assert_allclose(num, f(theta=0.4, d=-0.3, a=0.9, alpha=1.3), atol=1e-15)


def test_symbolic_planar_2r_is_eq_5_4():
    t1, t2, l1, l2 = sp.symbols("theta1 theta2 l1 l2")
    A = sp.simplify(dh_transform(theta=t1, a=l1) * dh_transform(theta=t2, a=l2))
    expected = sp.Matrix([
        [sp.cos(t1 + t2), -sp.sin(t1 + t2), 0, l1 * sp.cos(t1) + l2 * sp.cos(t1 + t2)],
        [sp.sin(t1 + t2), sp.cos(t1 + t2), 0, l1 * sp.sin(t1) + l2 * sp.sin(t1 + t2)],
        [0, 0, 1, 0], [0, 0, 0, 1]])
    assert sp.simplify(A - expected) == sp.zeros(4, 4)


# -- DH robots -------------------------------------------------------------------------
@st.composite
def dh_tables(draw):
    n = draw(st.integers(1, 7))
    rows = []
    for _ in range(n):
        kind = draw(st.sampled_from(["revolute", "revolute", "prismatic", "fixed"]))
        row = dict(a=draw(lengths), alpha=draw(angles), offset=draw(st.floats(-1, 1)),
                   joint=kind)
        if kind == "revolute":
            row["d"] = draw(lengths)
            if draw(st.booleans()):
                row["limits"] = (-2.5, 2.5)
        elif kind == "prismatic":
            row["theta"] = draw(angles)
            row["limits"] = (-1.0, 1.0)
        else:
            row.update(d=draw(lengths), theta=draw(angles))
            del row["offset"]
        rows.append(row)
    return rows


def chain(rows, q, modified):
    """The DH product written out from the rows, q replacing θ or d (the textbook rule)."""
    f = mdh_transform if modified else dh_transform
    T, k, frames = np.eye(4), 0, [np.eye(4)]
    for r in rows:
        th, d = r.get("theta", 0.0), r.get("d", 0.0)
        if r["joint"] == "revolute":
            th, k = q[k] + r["offset"], k + 1
        elif r["joint"] == "prismatic":
            d, k = q[k] + r["offset"], k + 1
        T = T @ f(theta=th, d=d, a=r["a"], alpha=r["alpha"])
        frames.append(T)
    return frames


@settings(max_examples=60, deadline=None)
@given(dh_tables(), st.sampled_from(["standard", "modified"]), st.integers(0, 2**32 - 1))
def test_from_dh_equals_row_product_and_urdf_export(rows, convention, seed):
    robot = Robot.from_dh(rows, convention)
    assert robot.dof == sum(r["joint"] != "fixed" for r in rows)
    q = np.random.default_rng(seed).uniform(-1, 1, (4, robot.dof))
    poses = robot.link_poses(q)
    exported = load_urdf(robot.to_urdf())
    assert exported.joint_names == robot.joint_names
    np.testing.assert_allclose(exported.limits, np.where(np.isfinite(robot.limits),
                                                         robot.limits, exported.limits))
    again = exported.link_poses(q)
    for n in range(4):
        frames = chain(rows, q[n], convention == "modified")
        for i, T in enumerate(frames):
            np.testing.assert_allclose(poses[f"link{i}"][n], T, atol=1e-12)
            np.testing.assert_allclose(again[f"link{i}"][n], T, atol=1e-12)


def test_revolute_without_limits_is_continuous():
    robot = Robot.from_dh([DHRow(a=1.0, alpha=0.0), DHRow(a=1.0, alpha=0.0, limits=(-1, 2))])
    assert [j.type for j in robot.joints] == ["continuous", "revolute"]
    np.testing.assert_array_equal(robot.limits, [[-np.inf, np.inf], [-1, 2]])


@pytest.mark.parametrize("rows, phrase", [
    ([], "at least one row"),
    ("abc", "sequence of DH rows"),
    (5, "sequence of DH rows"),
    ([{"a": 1.0}], "missing ['alpha']"),
    ([{"a": 1.0, "alpha": 0.0, "lenght": 2}], "unknown keys ['lenght']"),
    ([{"a": "x", "alpha": 0.0}], "a must be a real number"),
    ([{"a": np.nan, "alpha": 0.0}], "a must be finite"),
    ([{"a": 1.0, "alpha": 0.0, "joint": "hinge"}], "joint must be one of"),
    ([{"a": 1.0, "alpha": 0.0, "limits": (2, 1)}], "lower <= upper"),
    ([{"a": 1.0, "alpha": 0.0, "theta": 0.5}], "offset=0.5"),
    ([{"a": 1.0, "alpha": 0.0, "joint": "prismatic", "d": 0.5}], "offset=0.5"),
    ([{"a": 1.0, "alpha": 0.0, "joint": "fixed", "limits": (0, 1)}], "no joint variable"),
    ([3.0], "expected a DHRow or a dict"),
])
def test_bad_dh_tables(rows, phrase):
    with pytest.raises(KinlibError) as exc:
        Robot.from_dh(rows)
    assert phrase in str(exc.value)


def test_bad_convention():
    with pytest.raises(KinlibError, match="'standard' or 'modified'"):
        Robot.from_dh([DHRow(a=1.0, alpha=0.0)], "craig")
