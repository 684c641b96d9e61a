"""Assignment 03 (Jacobian and IK): the grader's references agree with kinlib, the cases
cover what they must, each classic mistake gets its diagnosis, and every right answer (the
other elbow, the other form of the DLS step, −ω at θ = π) is accepted.

Submissions are built from the source notebook's own code with one mistake patched in per
function, so every expected diagnosis is decided by the test, not by the grader.
"""

import numpy as np
import pytest
import sympy as sp
from grading_helpers import (
    by_function,
    judge_notebooks,
    misdiagnosed,
    mistake_submissions,
    patched,
    solution_code,
    write_notebook,
)

import kinlib as kl
from kinlib.grade.assignments import jacobian_ik as G
from kinlib.robots import puma560, three_dof_arm

NAME = "03_jacobian_and_ik"


# -- the references -------------------------------------------------------------------------
@pytest.mark.parametrize("robot", [puma560(), three_dof_arm(), *G.prismatic_robots()],
                         ids=lambda r: r.name)
def test_jacobian_from_link_frames_is_kinlibs(robot):
    """z_{i−1}, o_{i−1} read off link{i−1} of a DH robot give robot.jacobian column by column."""
    rng = np.random.default_rng(7)
    kinds = {r.joint for r in robot.dh_rows}
    assert kinds == ({"revolute", "prismatic"} if robot.name in ("stanford", "scara")
                     else {"revolute"})
    for _ in range(10):
        q = G._robot_q(rng, robot)
        z, o, types = G.robot_frames(robot, q)
        assert z.shape == (robot.dof, 3) and o.shape == (robot.dof + 1, 3)
        assert np.allclose(o[-1], robot.fk(q)[:3, 3])
        assert np.allclose(G.jacobian_columns(z, o, types), robot.jacobian(q), atol=1e-12)


def test_det_reference_is_seed_001s_and_kinlibs_jacobian():
    """The reference of det_jacobian_2r (kinlib's DH product, differentiated) is
    l1 l2 sin θ2 (seed 001, typed here), and at numbers the determinant of the first two
    rows of kinlib's planar_2r_jacobian; its mistake models differ from it."""
    check = next(c for c in G.assignment().checks if c.function == "det_jacobian_2r")
    rng = np.random.default_rng(4)
    for t1, t2, l1, l2 in check.make_cases(0):
        free = sorted(sp.Matrix([t1, t2, l1, l2]).free_symbols, key=str)
        for _ in range(3):  # (numbers at random points: exact identities are the judge's)
            at = {s: rng.uniform(0.3, 2.0) if s.is_positive else rng.uniform(-3, 3)
                  for s in free}
            num = [float(sp.sympify(x).subs(at)) for x in (t1, t2, l1, l2)]
            D = float(G._det(t1, t2, l1, l2).subs(at))
            assert np.isclose(D, num[2] * num[3] * np.sin(num[1]))
            assert np.isclose(D, np.linalg.det(kl.planar_2r_jacobian(*num)[:2]))
            for kind in ("absolute", "turned"):
                assert not np.isclose(float(G._det(t1, t2, l1, l2, **{kind: True}).subs(at)), D)


def test_pose_error_reference_is_the_rotation_vector_in_the_base_frame():
    rng = np.random.default_rng(1)
    for R, w in zip(kl.matrix_from_quat(rng.normal(size=(20, 4))), rng.normal(size=(20, 3)),
                    strict=True):
        w = w / np.linalg.norm(w) * rng.uniform(0.0, np.pi)
        T, Tt = G._pose(R, rng.normal(size=3)), G._pose(kl.exp_so3(w) @ R, rng.normal(size=3))
        e = G.pose_error_reference(T, Tt)
        assert np.allclose(e, np.concatenate([Tt[:3, 3] - T[:3, 3], w]), atol=1e-12)


def test_dls_reference_and_its_other_form():
    rng = np.random.default_rng(2)
    for J, e, lam in G._dls_cases(rng):
        ref = G.dls(J, e, lam)
        if lam > 0 or J.shape[0] == J.shape[1]:
            n = J.shape[1]
            other = np.linalg.solve(J.T @ J + lam**2 * np.eye(n), J.T @ e)
            assert np.allclose(ref, other, rtol=1e-8, atol=1e-8)


# -- the cases ------------------------------------------------------------------------------
def test_cases_cover_what_they_must():
    spec = G.assignment()
    cases = {c.function: c.make_cases(0) for c in spec.checks}
    assert sum(map(len, cases.values())) >= 300
    assert all(40 <= len(c) <= 90 for f, c in cases.items() if f != "det_jacobian_2r")
    assert [c.points for c in spec.checks] == [7, 3, 10, 6, 6]
    # det J: the angles are symbols (they are differentiated by); lengths symbolic or exact
    derivation = cases["det_jacobian_2r"]
    assert len(derivation) == 4 and all(isinstance(c[k], sp.Symbol) for c in derivation
                                        for k in (0, 1))
    assert any(c[2].is_Rational for c in derivation) and any(c[2] == c[3] for c in derivation)
    # Jacobian: n = 1..7, mixed types, all-prismatic, and real robots
    jac = cases["geometric_jacobian"]
    assert {len(t) for _, _, t in jac} == set(range(1, 8))
    assert sum("prismatic" in t and "revolute" in t for _, _, t in jac) >= 30
    assert any(set(t) == {"prismatic"} for _, _, t in jac)
    for z, o, t in jac:
        assert z.shape == (len(t), 3) and o.shape == (len(t) + 1, 3)
        assert np.allclose(np.linalg.norm(z, axis=1), 1.0)
    # IK: reachable, on the boundary (within 1e-12), unreachable (1e-5 or more outside)
    kinds = {"inside": 0, "boundary": 0, "unreachable": 0}
    quadrants = set()
    for x, y, l1, l2 in cases["ik_2r"]:
        r = np.hypot(x, y)
        gap = min(abs(r - (l1 + l2)), abs(r - abs(l1 - l2)))
        c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2)
        if gap <= 1e-12 * 4:
            kinds["boundary"] += 1
            assert G.reachable(x, y, l1, l2) and abs(c2) <= 1 + 1e-10
        elif G.reachable(x, y, l1, l2):
            kinds["inside"] += 1
            quadrants.add((np.sign(x), np.sign(y)))
            assert abs(c2) < 1
        else:  # clearly out, whatever small tolerance the student uses
            kinds["unreachable"] += 1
            assert abs(c2) >= 1 + 0.99e-5
    assert kinds["inside"] >= 50 and kinds["boundary"] >= 10 and kinds["unreachable"] >= 12
    assert {(1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)} <= quadrants
    # every reachable case: kinlib's two elbows reach it
    for x, y, l1, l2 in cases["ik_2r"]:
        if G.reachable(x, y, l1, l2):
            for elbow in ("up", "down"):
                s = kl.planar_2r_ik(x, y, l1, l2, elbow=elbow)
                assert np.allclose(G._tip(s.theta1, s.theta2, l1, l2), [x, y], atol=1e-9)
    # DLS: λ = 0 only for square well-conditioned J; λ ≠ 1 often (λ vs λ² must differ)
    dls = cases["dls_step"]
    for J, _, lam in dls:
        if lam == 0:
            assert J.shape[0] == J.shape[1] and np.linalg.cond(J) < 1e4
    assert sum(lam not in (0.0, 1.0) for _, _, lam in dls) >= 40
    shapes = {J.shape for J, _, _ in dls}
    assert {(6, 6), (6, 7), (3, 2), (2, 2), (6, 2)} <= shapes
    near_singular = [J for J, _, _ in dls if J.shape == (2, 2) and np.linalg.cond(J) > 1e3]
    assert len(near_singular) >= 6
    # pose error: θ = 0, θ = π exactly, near π, and in between
    angles = [np.linalg.norm(G.pose_error_reference(T, Tt)[3:]) for T, Tt in cases["pose_error"]]
    assert sum(a == 0 for a in angles) >= 3 and sum(a > np.pi - 1e-9 for a in angles) >= 5
    assert sum(np.pi - 1e-3 < a < np.pi - 1e-9 for a in angles) >= 2


# -- the judges on hand-made answers --------------------------------------------------------
def test_ik_judge_on_hand_made_answers():
    key = lambda args, got: G._judge_ik(args, got).key  # noqa: E731
    args = (0.5, 1.2, 1.0, 0.8)
    up = kl.planar_2r_ik(*args, elbow="up")
    down = kl.planar_2r_ik(*args, elbow="down")
    for t1, t2 in ((up.theta1, up.theta2), (down.theta1, down.theta2)):
        assert G._judge_ik(args, (float(t1), float(t2))).ok
        assert G._judge_ik(args, np.array([t1 + 2 * np.pi, t2 - 4 * np.pi])).ok
        assert G._judge_ik(args, [t1, t2]).ok
    assert key(args, (float(up.theta1), float(down.theta2))) == "branches"
    assert key(args, (float(down.theta1), float(up.theta2))) == "branches"
    assert key(args, tuple(np.rad2deg([down.theta1, down.theta2]))) == "degrees"
    assert key(args, (float(down.theta2), float(down.theta1))) == "order"
    for mirror in ((0.5, -1.2), (-0.5, 1.2), (-0.5, -1.2)):
        s = kl.planar_2r_ik(*mirror, 1.0, 0.8)
        assert key(args, (float(s.theta1), float(s.theta2))) == "quadrant"
    assert key(args, (0.0, 0.0)) == "wrong"
    assert key(args, None) == "missed"
    assert key(args, (1.0, float("nan"))) == "nan"
    assert key(args, "theta") == "type" and key(args, (1.0, 2.0, 3.0)) == "shape"
    far = (3.0, 0.0, 1.0, 0.8)
    assert G._judge_ik(far, None).ok
    assert key(far, (0.0, 0.0)) == "unreachable"
    assert key(far, (float("nan"), float("nan"))) == "nan unreachable"
    rim = (1.8 + 1e-12, 0.0, 1.0, 0.8)  # on the boundary
    assert G._judge_ik(rim, (0.0, 0.0)).ok
    assert key(rim, None) == "missed" and "clip" in G._judge_ik(rim, None).message
    assert key(rim, (0.0, float("nan"))) == "boundary"
    base = (0.0, 0.0, 0.9, 0.9)  # reachable, folded, any θ1
    assert G._judge_ik(base, (1.234, np.pi)).ok and G._judge_ik(base, (0.0, -np.pi)).ok
    assert key(base, (float("nan"), np.pi)) == "base"
    assert key(base, None) == "missed"


def test_dls_judge_names_the_transpose_step_for_any_scale():
    rng = np.random.default_rng(5)
    J, e = rng.normal(size=(6, 7)), rng.normal(size=6)
    args = (J, e, 0.1)
    assert G._judge_dls(args, G.dls(*args)).ok
    for alpha in (1.0, 0.3, 25.0):
        assert G._judge_dls(args, alpha * J.T @ e).key == "transpose"
    assert G._judge_dls(args, G.dls(*args) + 0.01).key == "wrong"
    assert G._judge_dls(args, -G.dls(*args)).key == "sign"
    assert G._judge_dls(args, np.zeros(7)).key == "wrong"
    # where the DLS step itself points along Jᵀe (J Jᵀ a multiple of I), no transpose
    # diagnosis for a wrongly scaled step
    Q, _ = np.linalg.qr(rng.normal(size=(4, 4)))
    args = (2.0 * Q, e[:4], 0.5)
    assert G._judge_dls(args, 3.0 * G.dls(*args)).key == "wrong"


def test_pose_judge_accepts_both_signs_at_pi_only():
    R = kl.matrix_from_quat([0.3, 0.1, -0.5, 0.8])
    k = np.array([2.0, -1.0, 2.0]) / 3
    T, Tt = G._pose(R, [0.1, 0.2, 0.3]), G._pose(kl.matrix_from_axis_angle(k, np.pi) @ R,
                                                [0.0, 0.0, 0.0])
    for s in (1.0, -1.0):
        assert G._judge_pose((T, Tt), np.concatenate([[-0.1, -0.2, -0.3], s * np.pi * k])).ok
    Tt = G._pose(kl.matrix_from_axis_angle(k, 2.0) @ R, [0.0, 0.0, 0.0])
    assert G._judge_pose((T, Tt), np.concatenate([[-0.1, -0.2, -0.3], 2.0 * k])).ok
    assert G._judge_pose((T, Tt), np.concatenate([[-0.1, -0.2, -0.3], -2.0 * k])).key == \
        "rotation sign"


# -- classic mistakes, graded for real ------------------------------------------------------
JAC_CROSS = "np.cross(z[i], o[n] - o[i])"
JACOBIAN_MISTAKES = [  # (edit or tuple of edits, diagnosis)
    (("    return J\n", "    return np.vstack([J[3:], J[:3]])\n"), "order"),
    ((JAC_CROSS, "np.cross(o[n] - o[i], z[i])"), "cross"),
    ((JAC_CROSS, "np.cross(z[i], o[n] - o[i + 1])"), "origins"),
    (('if kind == "revolute":', "if True:"), "prismatic"),
    (("else:  # prismatic\n            J[:3, i] = z[i]",
      "else:  # prismatic\n            J[3:, i] = z[i]"), "prismatic"),
    ((JAC_CROSS, "np.cross(z[i], o[n])"), "subtract"),
    (("    return J\n", "    return J.T\n"), "transposed"),
]
IK_RETURN = "return float(theta1), float(theta2)"
IK_MISTAKES = [
    ((IK_RETURN, "return float(np.rad2deg(theta1)), float(np.rad2deg(theta2))"), "degrees"),
    (("theta2 = np.arctan2(s2, c2)", "theta2 = np.arctan2(-s2, c2)"), "branches"),
    (("theta1 = np.arctan2(y, x) -", "theta1 = np.arccos(x / np.hypot(x, y)) -"), "quadrant"),
    (("theta1 = np.arctan2(y, x) -", "theta1 = np.arctan(y / x) -"), "quadrant"),
    (("        return None\n", "        return float('nan'), float('nan')\n"),
     "nan unreachable"),
    (("        return None\n", "        raise ValueError('target out of reach')\n"), "raised"),
    (("if abs(c2) > 1 + 1e-9:", "if False:"), "unreachable"),
    (("if abs(c2) > 1 + 1e-9:", "if abs(c2) > 1:"), "missed"),
    (("    c2 = min(1.0, max(-1.0, c2))\n", ""), "boundary"),
    ((IK_RETURN, "return float(theta2), float(theta1)"), "order"),
]
DLS_SOLVE = "np.linalg.solve(J @ J.T + damping**2 * np.eye(m), e)"
DLS_MISTAKES = [
    (("return J.T @ " + DLS_SOLVE, "return 0.5 * J.T @ e"), "transpose"),
    (("damping**2 * np.eye(m)", "damping * np.eye(m)"), "lambda"),
    (("return J.T @ " + DLS_SOLVE, "return -J.T @ " + DLS_SOLVE), "sign"),
    (("return J.T @ " + DLS_SOLVE, "return np.linalg.pinv(J) @ e"), "undamped"),
    ((DLS_SOLVE, "(J @ J.T + damping**2 * np.eye(m)) @ e"), "inverse"),
    (("return J.T @ " + DLS_SOLVE, "return np.linalg.inv(J) @ e"), "raised"),  # J⁻¹
]
POSE_OMEGA = "omega = theta * w / np.linalg.norm(w)"
RE = "Re = T_target[:3, :3] @ T[:3, :3].T"
POSE_MISTAKES = [
    (("dp = T_target[:3, 3] - T[:3, 3]", "dp = T[:3, 3] - T_target[:3, 3]"), "sign"),
    ((RE, "Re = T[:3, :3].T @ T_target[:3, :3]"), "frame"),
    (("return np.concatenate([dp, omega])", "return np.concatenate([omega, dp])"), "order"),
    ((RE, "Re = T[:3, :3] @ T_target[:3, :3].T"), "rotation sign"),
    ((("elif c < 0:", "elif False:"), (POSE_OMEGA, "omega = w")), "sin"),
    (("return np.concatenate([dp, omega])", "return -np.concatenate([dp, omega])"), "sign"),
    (("if theta < 1e-12:", "if False:"), "zero angle"),
    (("elif c < 0:", "elif False:"), "near pi"),
]
DET_X = "l1 * sp.cos(theta1) + l2 * sp.cos(theta1 + theta2)"
DET_Y = "l1 * sp.sin(theta1) + l2 * sp.sin(theta1 + theta2)"
DET_MISTAKES = [  # det J derived with sympy
    (("p.jacobian([theta1, theta2])", "p.jacobian([theta2, theta1])"), "sign"),
    (((DET_X, "l1 * sp.cos(theta1) + sp.cos(theta1 + theta2)"),
      (DET_Y, "l1 * sp.sin(theta1) + sp.sin(theta1 + theta2)")), "factor"),
    (((DET_X, "l1 * sp.cos(theta1) + l2 * sp.cos(theta2)"),
      (DET_Y, "l1 * sp.sin(theta1) + l2 * sp.sin(theta2)")), "absolute"),
    (((DET_X, "l1 * sp.cos(theta1) - l2 * sp.sin(theta1 + theta2)"),
      (DET_Y, "l1 * sp.sin(theta1) + l2 * sp.cos(theta1 + theta2)")), "cos"),
    ((DET_X, "l1 * np.cos(theta1) + l2 * np.cos(theta1 + theta2)"), "raised"),
]
ALL = (("geometric_jacobian", JACOBIAN_MISTAKES), ("det_jacobian_2r", DET_MISTAKES),
       ("ik_2r", IK_MISTAKES), ("dls_step", DLS_MISTAKES), ("pose_error", POSE_MISTAKES))


def test_jacobian_ik_mistakes_are_diagnosed(tmp_path):
    graded = judge_notebooks(mistake_submissions(tmp_path, NAME, solution_code(NAME), ALL))
    wrong = misdiagnosed(graded, ALL)
    results = [by_function(r) for r in graded]
    assert not wrong, wrong
    by_key = {(fn, key): results[n][fn] for fn, ms in ALL for n, (_, key) in enumerate(ms)}
    # the exceptions show the student's own message
    assert "target out of reach" in by_key["ik_2r", "raised"]["diagnoses"][0]["message"]
    numpy_cos = by_key["det_jacobian_2r", "raised"]["diagnoses"][0]["message"]
    assert "Symbol" in numpy_cos and "sympy's functions (sp.cos" in numpy_cos, numpy_cos
    inv = by_key["dls_step", "raised"]
    assert "LinAlgError" in inv["diagnoses"][0]["message"]
    assert "undamped" in {d["key"] for d in inv["diagnoses"]}  # square J, λ > 0
    # the rare mistakes fail only where they matter
    ik = next(c for c in G.assignment().checks if c.function == "ik_2r").make_cases(0)
    out = sum(not G.reachable(*c) for c in ik)
    for key in ("nan unreachable", "raised", "unreachable"):
        c = by_key["ik_2r", key]
        assert c["total"] - c["passed"] == out, key
    for key in ("missed", "boundary"):
        c = by_key["ik_2r", key]
        assert 1 <= c["total"] - c["passed"] <= 16, key
    pi = by_key["pose_error", "near pi"]
    assert 4 <= pi["total"] - pi["passed"] <= 8
    zero = by_key["pose_error", "zero angle"]
    assert 3 <= zero["total"] - zero["passed"] <= 6
    lam = by_key["dls_step", "lambda"]  # λ = 0 and λ = 1 give the same step
    assert lam["passed"] >= 10


def test_other_right_answers_are_accepted(tmp_path):
    """The other elbow as an array shifted by 2π; the Jacobian built with vectorised numpy;
    det J from a Jacobian differentiated by hand, expanded; the DLS step as
    (JᵀJ + λ²I)⁻¹Jᵀe; −ω at θ = π; a pose error by the arccos route."""
    code = patched(
        solution_code(NAME),
        ("    J = np.zeros((6, n))\n    for i, kind in enumerate(joint_types):\n",
         "    rev = np.array([k == 'revolute' for k in joint_types])\n"
         "    lin = np.where(rev[:, None], np.cross(z, o[-1] - o[:-1]), z)\n"
         "    return np.vstack([lin.T, (z * rev[:, None]).T])\n"
         "    J = np.zeros((6, n))\n    for i, kind in enumerate(joint_types):\n"),
        ("return p.jacobian([theta1, theta2]).det()",
         "J = sp.Matrix([[sp.diff(p[0], theta1), sp.diff(p[0], theta2)],\n"
         "               [sp.diff(p[1], theta1), sp.diff(p[1], theta2)]])\n"
         "    return sp.expand(J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0], trig=True)"),
        ("s2 = np.sqrt(1 - c2 * c2)", "s2 = -np.sqrt(1 - c2 * c2)"),
        (IK_RETURN, "return np.array([theta1 + 2 * np.pi, theta2])"),
        ("return J.T @ " + DLS_SOLVE,
         "n = J.shape[1]\n    return np.linalg.solve(J.T @ J + damping**2 * np.eye(n), J.T @ e)"),
        ("omega = theta * (k if k @ w >= 0 else -k)",
         "omega = theta * (k if k @ w >= 0 else -k)\n"
         "        if np.pi - theta < 1e-9:\n            omega = -omega"),
    )
    arccos = patched(
        code, ("    c = (np.trace(Re) - 1) / 2                     # w = sin(theta) k, c = cos",
               "    c = (np.trace(Re) - 1) / 2\n    if np.linalg.norm(w) > 0.5:\n"
               "        return np.concatenate([dp, np.arccos(np.clip(c, -1, 1)) * w\n"
               "                               / np.linalg.norm(w)])  # c"))
    subs = [write_notebook(tmp_path / f"alt{i}.ipynb", c, assignment=NAME)
            for i, c in enumerate((code, arccos))]
    for result in judge_notebooks(subs):
        for fn, check in by_function(result).items():
            assert check["passed"] == check["total"], (fn, check["diagnoses"])
