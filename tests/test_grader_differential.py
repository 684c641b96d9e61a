"""Assignment 06 (differential kinematics): the grader's references agree with kinlib and
with independent routes (scipy's expm, Modern Robotics in its [ω; v] order, finite
differences, scipy's bounded least squares; the 3R arm's symbolic J_s against Modern
Robotics and finite differences), its cases cover what they must (exact and near
singularities, targets reachable only outside the limits), each classic mistake gets its
diagnosis from a real wrong submission, and right alternatives are accepted.

Submissions are built from the source notebook's own code with one mistake patched in per
function; poe_fk, space_jacobian and ik_with_limits call right copies (_exp, _fk, _sj) so
that each function carries exactly its own mistake. All submissions are graded in one run.
"""

import modern_robotics as mr
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
    top,
    write_notebook,
)
from scipy.linalg import expm
from scipy.optimize import least_squares

import kinlib as kl
from kinlib.grade.assignments import _limited_ik as L
from kinlib.grade.assignments import _singular as G
from kinlib.grade.assignments import _sj_symbolic as Q
from kinlib.grade.assignments import differential as D

NAME = "06_differential_kinematics"


@pytest.fixture(scope="module")
def cases():
    return {c.function: c.make_cases(0) for c in D.assignment().checks}


def _mr(S):
    """Screw axes [v; ω] → Modern Robotics' [ω; v] (rows of a 6×n array or a 6-vector)."""
    return np.roll(np.asarray(S, dtype=float), 3, axis=0)


# -- the references against independent routes ----------------------------------------------
def test_exp_reference_is_the_matrix_exponential(cases):
    for (xi,) in cases["exp_twist"]:
        X = np.zeros((4, 4))
        X[:3, :3], X[:3, 3] = kl.skew(xi[3:]), xi[:3]
        T = kl.exp_se3(xi)
        assert np.allclose(T, expm(X), atol=1e-9 * (1 + np.abs(X).max() ** 2))
        if not 0 < np.linalg.norm(xi[3:]) < 1e-5:  # (MR treats |ω| < 1e-6 as 0)
            assert np.allclose(T, mr.MatrixExp6(mr.VecTose3(_mr(xi))), atol=1e-9)


def test_fk_and_space_jacobian_references_are_modern_robotics(cases):
    for M, S, q in cases["poe_fk"]:
        assert np.allclose(kl.poe_fk(M, S, q), mr.FKinSpace(M, _mr(S), q), atol=1e-10)
    for S, q in cases["space_jacobian"]:
        assert np.allclose(kl.space_jacobian(S, q), _mr(mr.JacobianSpace(_mr(S), q)),
                           atol=1e-10)


def test_space_jacobian_is_the_derivative_of_the_pose():
    """[J_i] = ∂T/∂q_i T⁻¹, by central differences, on robots and random chains."""
    rng = np.random.default_rng(3)
    for M, S, q in D.chains(rng, per_robot=1, random_n=range(2, 8, 2)):
        J, h = kl.space_jacobian(S, q), 1e-6
        Tinv = kl.transform_inverse(kl.poe_fk(M, S, q))
        for i in range(len(q)):
            dq = np.eye(len(q))[i] * h
            X = (kl.poe_fk(M, S, q + dq) - kl.poe_fk(M, S, q - dq)) / (2 * h) @ Tinv
            assert np.allclose(J[:, i], [*X[:3, 3], X[2, 1], X[0, 2], X[1, 0]], atol=1e-7)


def test_symbolic_3r_jacobian_is_modern_robotics_and_the_derivative_of_the_pose():
    """The reference of space_jacobian_3r at numbers: Modern Robotics' JacobianSpace, kinlib's
    space_jacobian, central differences of the PoE pose, and column 3 typed here; its
    body and geometric mistake models are kinlib's body_jacobian and the geometric
    Jacobian of the DH robot; the other models differ from it."""
    t, l = sp.symbols("theta1:4", real=True), sp.symbols("l1:4", positive=True)
    J = Q.planar_3r_jacobian(*t, *l)
    assert J.free_symbols <= {*t[:2], *l[:2]}
    s12, c12 = sp.sin(t[0] + t[1]), sp.cos(t[0] + t[1])
    typed = [l[0] * sp.sin(t[0]) + l[1] * s12, -l[0] * sp.cos(t[0]) - l[1] * c12, 0, 0, 0, 1]
    assert sp.simplify(J[:, 2] - sp.Matrix(typed)) == sp.zeros(6, 1)
    rng, h = np.random.default_rng(9), 1e-6
    models = [lambda *a: Q.planar_3r_jacobian(*a, moment=1),
              lambda *a: Q.planar_3r_jacobian(*a, carry=Q._mr_adjoint),
              lambda *a: Q.planar_3r_jacobian(*a, carry=Q._swapped_adjoint)]
    for _ in range(4):
        q, lengths = rng.uniform(-np.pi, np.pi, 3), rng.uniform(0.3, 1.5, 3)
        at = dict(zip([*t, *l], [*q, *lengths], strict=True))
        num = lambda M, at=at: np.array(M.subs(at), dtype=float)  # noqa: E731
        S = np.array([[0, -x, 0, 0, 0, 1] for x in (0, lengths[0], lengths[:2].sum())]).T
        M = kl.transform(p=[lengths.sum(), 0, 0])
        assert np.allclose(num(J), _mr(mr.JacobianSpace(_mr(S), q)), atol=1e-12)
        assert np.allclose(num(J), kl.space_jacobian(S, q), atol=1e-12)
        Tinv = kl.transform_inverse(kl.poe_fk(M, S, q))
        for i in range(3):
            dq = np.eye(3)[i] * h
            X = (kl.poe_fk(M, S, q + dq) - kl.poe_fk(M, S, q - dq)) / (2 * h) @ Tinv
            assert np.allclose(num(J)[:, i], [*X[:3, 3], X[2, 1], X[0, 2], X[1, 0]], atol=1e-7)
        B = kl.adjoint(kl.transform_inverse(M)) @ S
        assert np.allclose(num(Q.planar_3r_body_jacobian(*t, *l)), kl.body_jacobian(B, q))
        robot = kl.Robot.from_dh([{"a": float(x), "alpha": 0.0} for x in lengths])
        assert np.allclose(num(Q.planar_3r_geometric_jacobian(*t, *l)), robot.jacobian(q))
        for model in models:
            assert not np.allclose(num(model(*t, *l)), num(J))


def test_robot_chains_are_the_robots():
    from kinlib import robots

    rng = np.random.default_rng(4)
    for name in ("puma560", "ur5", "panda"):
        S, M, limits = D.robot_chain(name)
        robot = getattr(robots, name)()
        q = D.chain_q(rng, S, limits)
        assert np.allclose(mr.FKinSpace(M, _mr(S), q), robot.fk(q), atol=1e-10)


def test_manipulability_reference_and_its_tolerance(cases):
    for (J,) in cases["manipulability"]:
        w = float(kl.manipulability(J))
        direct = np.sqrt(max(np.linalg.det(J @ J.T), 0.0))
        assert abs(direct - w) <= G.manipulability_tolerance(J)  # the formula is right
        if J.shape[0] == J.shape[1]:
            assert abs(w - abs(np.linalg.det(J))) <= 1e-9 * (1 + w) + 1e-12 * np.abs(J).max()
    # the tolerance stays far below what the mistakes change (a 6×6 at its scale)
    J = G.with_singular_values(np.random.default_rng(0), 6, 6, [2, 1.5, 1, 0.7, 0.5, 0.3])
    assert G.manipulability_tolerance(J) < 1e-3 * float(kl.manipulability(J))


def test_singular_configurations_are_singular():
    """Rank drops where the geometry says: the PUMA's and UR5's wrist axes 4 and 6 are
    parallel at q5 = 0, the 2R arm's columns are parallel when stretched or folded."""
    rng = np.random.default_rng(5)
    configs = G.singular_configurations(rng)
    assert len(configs) >= 14
    names = {name for _, _, name in configs}
    assert {"puma560", "ur5", "panda", "planar_2r", "three_dof_arm"} <= names
    for J, q, name in configs:
        s = np.linalg.svd(J, compute_uv=False)
        assert s[-1] < 1e-12 * s[0], (name, q)
        if name in ("puma560", "ur5") and q[4] == 0.0:  # joints 4 and 6 at q: parallel axes
            Js = kl.space_jacobian(D.robot_chain(name)[0], q)
            assert np.allclose(np.cross(Js[3:, 3], Js[3:, 5]), 0, atol=1e-12)
        if name == "planar_2r":
            assert abs(J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]) < 1e-12


def test_lost_direction_cases(cases):
    lost = cases["lost_direction"]
    singular = [c for c in lost if G.lost_subspace(*c).shape[1] > 0]
    assert 25 <= len(singular) <= len(lost) - 25  # both answers common
    for J, tol in lost:
        assert J.shape[0] <= J.shape[1]
        s = np.linalg.svd(J, compute_uv=False)
        r = s / s[0]
        assert np.all((r < tol / 1.5) | (r > tol * 1.5))  # never near the threshold
        assert bool(kl.is_near_singular(J, tol)) == (G.lost_subspace(J, tol).shape[1] > 0)
    kinds = {G.lost_subspace(*c).shape[1] for c in lost}
    assert {0, 1, 2, 3} <= kinds
    absolute = [c for c in lost if (np.linalg.svd(c[0], compute_uv=False)[-1] < c[1])
                != bool(kl.is_near_singular(*c))]
    assert len(absolute) >= 4  # an absolute threshold gets these wrong
    # the stretched 2R arm loses the direction along the arm
    J, tol = lost[0]
    u = G.lost_subspace(J, tol)[:, 0]
    assert np.isclose(abs(u @ [np.cos(0.4), np.sin(0.4)]), 1.0)


def _residual(M, S, T_target):
    return lambda q: (kl.poe_fk(M, S, q) - T_target)[:3].ravel()


def test_ik_cases_are_what_they_claim(cases):
    ik = cases["ik_with_limits"]
    kinds = [L._kind(c) for c in ik]
    reach = [(c, q) for c, (ok, q) in zip(ik, kinds, strict=True) if ok]
    assert 18 <= len(reach) and 12 <= len(ik) - len(reach)
    for (M, S, limits, T_target, q0), q_star in reach:
        assert np.all(limits[:, 0] <= q_star) and np.all(q_star <= limits[:, 1])
        assert np.allclose(kl.poe_fk(M, S, q_star), T_target, atol=1e-12)
        # scipy's bounded least squares from the same start gets there too
        box = np.where(np.isfinite(limits), limits, np.array([-50.0, 50.0]))
        start = np.clip(q0, box[:, 0] + 1e-12, box[:, 1] - 1e-12)
        fit = least_squares(_residual(M, S, T_target), start, bounds=(box[:, 0], box[:, 1]),
                            xtol=1e-15, ftol=1e-15, gtol=1e-15)
        assert L.reached(M, S, fit.x, T_target)
    assert sum(np.any(c[2][:, 0] == q) or np.any(c[2][:, 1] == q) for c, q in reach) >= 3
    assert sum(np.any((c[4] < c[2][:, 0]) | (c[4] > c[2][:, 1])) for c, _ in reach) >= 4
    # unreachable within the limits: no start within the limits gets closer than 1e-2
    rng = np.random.default_rng(6)
    for M, S, limits, T_target, _ in (c for c, (ok, _) in zip(ik, kinds, strict=True)
                                      if not ok):
        best = np.inf
        for _ in range(3):
            fit = least_squares(_residual(M, S, T_target),
                                rng.uniform(limits[:, 0], limits[:, 1]),
                                bounds=(limits[:, 0], limits[:, 1]))
            best = min(best, np.abs(kl.poe_fk(M, S, fit.x) - T_target).max())
        assert best > 1e-2


def test_ik_loop_of_the_notebook_solves_every_seed():
    """The notebook's loop (the grader's reference) reaches every reachable target and
    reports the unreachable ones, on another seed than the public one."""
    for seed in (11,):
        for c in L._ik_cases(np.random.default_rng(seed)):
            q, ok = L.limited_dls(*c)
            assert ok == L._kind(c)[0]
            assert np.all(c[2][:, 0] <= q) and np.all(q <= c[2][:, 1])


def test_the_closed_form_solutions_of_the_planar_chains():
    rng = np.random.default_rng(8)
    S, M = L.planar_chain("RRR", [0.7, 0.5, 0.3])
    for _ in range(10):
        q = rng.uniform(-np.pi, np.pi, 3)
        sols = L.solutions_3r(kl.poe_fk(M, S, q), 0.7, 0.5, 0.3)
        assert len(sols) == 2 and any(max(L.circle_gap(a - b, 0, 0) for a, b in
                                          zip(s, q, strict=True)) < 1e-9 for s in sols)
        for s in sols:
            assert np.allclose(kl.poe_fk(M, S, s), kl.poe_fk(M, S, q), atol=1e-9)
    assert L.circle_gap(3.0, -1.0, 1.0) == pytest.approx(2.0)
    assert L.circle_gap(3.0 + 2 * np.pi, 2.5, 4.0) == 0.0


# -- the cases ------------------------------------------------------------------------------
def test_case_counts_and_points(cases):
    spec = D.assignment()
    assert sum(map(len, cases.values())) >= 300
    assert [c.points for c in spec.checks] == [6, 6, 8, 4, 4, 6, 10]
    assert all(35 <= len(c) <= 80 for f, c in cases.items() if f != "space_jacobian_3r")
    # the derivation: symbolic angles; lengths symbolic, exact, or one symbol for all links
    derivation = cases["space_jacobian_3r"]
    assert len(derivation) == 4 and all(isinstance(x, sp.Symbol) for c in derivation
                                        for x in c[:3])
    assert any(c[3].is_Rational for c in derivation) and any(c[3] == c[5] for c in derivation)
    angles = [np.linalg.norm(xi[3:]) for (xi,) in cases["exp_twist"]]
    assert sum(a == 0 for a in angles) >= 5 and sum(0 < a < 1e-3 for a in angles) >= 8
    assert sum(abs(a - np.pi) < 1e-9 for a in angles) >= 3 and max(angles) > 6 * np.pi
    dofs = {len(q) for _, _, q in cases["poe_fk"]}
    assert set(range(1, 8)) <= dofs


# -- hand-made answers ------------------------------------------------------------------------
def test_ik_judge_on_hand_made_answers(cases):
    ik = cases["ik_with_limits"]
    (args, q_star) = next((c, L._kind(c)[1]) for c in ik if L._kind(c)[0])
    unreachable = next(c for c in ik if not L._kind(c)[0])
    key = lambda a, got: L._judge_ik(a, got).key  # noqa: E731
    assert L._judge_ik(args, (q_star, True)).ok and L._judge_ik(args, [list(q_star), True]).ok
    assert key(args, (q_star, 1)) == "type" and key(args, q_star) == "type"
    assert key(args, (q_star[:-1], True)) == "shape"
    assert key(args, (q_star, False)) == "unclaimed"
    start = np.clip(args[4], args[2][:, 0], args[2][:, 1])
    assert key(args, (start, False)) == "missed" and key(args, (start, True)) == "claimed"
    outside = q_star.copy()
    outside[1] = args[2][1, 1] + 0.01 if np.isfinite(args[2][1, 1]) else outside[1]
    if np.isfinite(args[2][1, 1]):
        v = L._judge_ik(args, (outside, True))
        assert v.key == "limits" and "joint 2" in v.message
    lo = np.where(np.isfinite(unreachable[2][:, 0]), unreachable[2][:, 0], 0.0)
    assert L._judge_ik(unreachable, (lo, False)).ok
    assert key(unreachable, (lo, True)) == "claimed"


def test_lost_direction_judge_on_hand_made_answers():
    J = kl.planar_2r_jacobian(0.4, 0.0, 1.0, 0.8)[:2]
    u = np.array([np.cos(0.4), np.sin(0.4)])
    assert G._judge_lost((J, 1e-6), u).ok and G._judge_lost((J, 1e-6), -u).ok
    assert G._judge_lost((J, 1e-6), None).key == "missed"
    assert G._judge_lost((J, 1e-6), 2 * u).key == "unit"
    assert G._judge_lost((J, 1e-6), [-u[1], u[0]]).key == "largest"
    bent = kl.planar_2r_jacobian(0.4, 1.0, 1.0, 0.8)[:2]
    assert G._judge_lost((bent, 1e-6), None).ok
    assert G._judge_lost((bent, 1e-6), u).key == "phantom"
    assert G._judge_lost((bent * 1e-6, 1e-6), u).key == "absolute"


# -- classic mistakes, graded for real --------------------------------------------------------
EXP_P = "T[:3, 3] = (np.eye(3) + b * W + c * W @ W) @ v"
EXP_MISTAKES = [  # (edit or tuple of edits, diagnosis)
    (("v, w = xi[:3], xi[3:]", "w, v = xi[:3], xi[3:]"), "rows"),
    ((EXP_P, "T[:3, 3] = v"), "V"),
    ((EXP_P, "T[:3, 3] = (np.eye(3) * theta + (1 - np.cos(theta)) * W / theta\n"
             "                 + (theta - np.sin(theta)) * W @ W / theta**2) @ v"), "screw"),
    (("np.eye(3) + a * W + b * W @ W", "np.eye(3) - a * W + b * W @ W"), "transposed"),
    (("if theta < 1e-12:", "if theta < 1e-3:"), "small angle"),
    (("if theta < 1e-12:", "if False:"), "zero angle"),
]
FK_STEP = "        T = T @ _exp(S[:, i] * q[i])\n    return T @ M"
FK_MISTAKES = [
    ((FK_STEP, "        T = _exp(S[:, i] * q[i]) @ T\n    return T @ M"), "order"),
    (("return T @ M", "return M @ T"), "body"),
    (("return T @ M", "return T"), "home"),
    ((FK_STEP, "        T = T @ _exp(np.concatenate([S[3:, i], S[:3, i]]) * q[i])\n"
               "    return T @ M"), "rows"),
    ((FK_STEP, "        T = T @ _exp(S[:, i] * np.deg2rad(q[i]))\n    return T @ M"),
     "degrees"),
]
SJ_STEP = "        T = T @ _exp(S[:, i] * q[i])\n    return J"
SJ_MISTAKES = [
    (("J[:, i] = Ad @ S[:, i]", "J[:, i] = S[:, i]"), "untransformed"),
    ((SJ_STEP, "        T = _exp(S[:, i] * q[i]) @ T\n    return J"), "order"),
    (("R, p = T[:3, :3], T[:3, 3]", "R, p = T[:3, :3].T, -T[:3, :3].T @ T[:3, 3]"), "inverse"),
    ((("for i in range(S.shape[1]):\n        R, p = T[:3, :3], T[:3, 3]",
       "for i in reversed(range(S.shape[1])):  # T: the joints after i\n"
       "        R, p = np.linalg.inv(T)[:3, :3], np.linalg.inv(T)[:3, 3]"),
      (SJ_STEP, "        T = _exp(S[:, i] * q[i]) @ T\n    return J")), "body"),
    (("Ad[:3, 3:] = skew(p) @ R", "Ad[3:, :3] = skew(p) @ R"), "mr adjoint"),
    (("Ad[:3, 3:] = skew(p) @ R", "Ad[:3, 3:] = R @ skew(p)"), "adjoint"),
    (("    return J\n", "    return np.vstack([J[3:], J[:3]])\n"), "rows"),
]
SJ3_AXES = ("axes = [sp.Matrix.vstack(-z.cross(sp.Matrix([x, 0, 0])), z) "
            "for x in (0, l1, l1 + l2)]")
SJ3_AD = ("sp.Matrix.hstack(R, sym_skew(t) * R),\n"
          "                                sp.Matrix.hstack(sp.zeros(3), R))")
SJ3_TIDY = "    return sp.trigsimp(sp.expand(sp.Matrix.hstack(*columns)))"
SJ3_RETURN = "    return sp.Matrix.hstack(*columns)"  # the submissions' (see graded)
SJ3_TIP = ("    M = sp.eye(4)\n    M[0, 3] = l1 + l2 + l3\n"
           "    R, p = (T * M)[:3, :3], (T * M)[:3, 3]  # the end effector's pose\n")
SJ3_MISTAKES = [  # the 3R arm's J_s derived with sympy
    (("columns.append(adjoint(T) * S)", "columns.append(S)"), "untransformed"),
    ((SJ3_AXES, SJ3_AXES.replace("-z.cross", "z.cross")), "moment"),
    ((SJ3_RETURN, "    J = sp.Matrix.hstack(*columns)\n"
                  "    return sp.Matrix.vstack(J[3:, :], J[:3, :])"), "rows"),
    ((SJ3_AD, "sp.Matrix.hstack(R, sp.zeros(3)),\n"
              "                                sp.Matrix.hstack(sym_skew(t) * R, R))"),
     "mr adjoint"),
    ((SJ3_AD, SJ3_AD.replace("sym_skew(t) * R", "R * sym_skew(t)")), "adjoint"),
    ((SJ3_RETURN, SJ3_TIP + "    Rt, pt = R.T, -R.T * p  # T^-1\n"
                  "    Ad_inv = sp.Matrix.vstack(sp.Matrix.hstack(Rt, sym_skew(pt) * Rt),\n"
                  "                              sp.Matrix.hstack(sp.zeros(3), Rt))\n"
                  "    return Ad_inv * sp.Matrix.hstack(*columns)"), "body"),
    ((SJ3_RETURN, SJ3_TIP + "    J = sp.Matrix.hstack(*columns)  # v + w x p at the tip\n"
                  "    return sp.Matrix.vstack(J[:3, :] - sym_skew(p) * J[3:, :], J[3:, :])"),
     "geometric"),
]
W_RET = "    return float(np.sqrt(max(d, 0.0)))"
MANIP_MISTAKES = [
    (("    d = np.linalg.det(J @ J.T)\n",
      "    if J.shape[0] == J.shape[1]:\n        return float(np.linalg.det(J))\n"
      "    d = np.linalg.det(J @ J.T)\n"), "sign"),
    ((W_RET, "    return float(d)"), "squared"),
    (("d = np.linalg.det(J @ J.T)", "d = abs(np.linalg.det(J.T @ J))"), "JTJ"),
    ((W_RET, "    return float(np.linalg.svd(J, compute_uv=False)[-1])"), "smallest"),
    (("max(d, 0.0)", "d"), "negative"),
]
LOST_RET = "    return U[:, len(s) - 1]"
LOST_MISTAKES = [
    (("if s[-1] >= tol * s[0]:", "if s[-1] >= tol:"), "absolute"),
    ((LOST_RET, "    return U[:, 0]"), "largest"),
    ((LOST_RET, "    return Vt[-1]"), "joint space"),
    ((LOST_RET, "    return U[-1]"), "row"),
    ((LOST_RET, "    return U[:, s < tol * s[0]].sum(axis=1)"), "unit"),
    (("    if s[-1] >= tol * s[0]:\n        return None\n", ""), "phantom"),
    (("if s[-1] >= tol * s[0]:", "if True:"), "missed"),
]
IK_MISTAKES = [
    (("q_new = np.clip(q + dq, lo, hi)", "q_new = q + dq"), "limits"),
    (("    return q, False\n    ### END SOLUTION", "    return q, True\n    ### END SOLUTION"),
     "claimed"),
    (("# stuck: at a limit or a local minimum\n            break",
      "# stuck: at a limit or a local minimum\n            return q, True"), "claimed"),
    (("e = np.array([*p_e", "e = -np.array([*p_e"), "missed"),
    (("if np.abs(T - T_target).max() < 1e-10:", "if np.abs(T - T_target).max() < 1e-17:"),
     "unclaimed"),
    (("    damping = 0.01\n", "    return np.clip(np.asarray(q0, dtype=float), lo, hi), False\n"),
     "missed"),
]
TABLE = (("exp_twist", EXP_MISTAKES), ("poe_fk", FK_MISTAKES), ("space_jacobian", SJ_MISTAKES),
         ("space_jacobian_3r", SJ3_MISTAKES),
         ("manipulability", MANIP_MISTAKES), ("lost_direction", LOST_MISTAKES),
         ("ik_with_limits", IK_MISTAKES))


def _isolated(code: str) -> str:
    """poe_fk and space_jacobian calling _exp, ik_with_limits calling _fk and _sj."""
    assert code.count("exp_twist(S[:, i] * q[i])") == 2
    code = code.replace("exp_twist(S[:, i] * q[i])", "_exp(S[:, i] * q[i])")
    return patched(code, ("T = poe_fk(M, S, q)", "T = _fk(M, S, q)"),
                   ("J = space_jacobian(S, q)", "J = _sj(S, q)"))


def _right_copies(code: str) -> str:
    """The right exp_twist, poe_fk and space_jacobian as _exp, _fk and _sj (calling each
    other, not the names a mistake redefines)."""
    return patched(_isolated(code), ("def exp_twist(", "def _exp("), ("def poe_fk(", "def _fk("),
                   ("def space_jacobian(", "def _sj("))


ALT = (  # other right answers: the series near 0 and G(θ)v/θ; M multiplied in first; the
    # adjoint by conjugation; the 3R arm's columns from the moved points, expanded; the
    # singular values; the eigenvectors of J Jᵀ with the other
    # sign; a loop with capped steps returning a list and numpy's bool
    ("    if theta < 1e-12:  # a pure translation (to rounding)\n",
     "    X = np.zeros((4, 4))\n    X[:3, :3], X[:3, 3] = skew(w), v\n"
     "    if theta < 1e-6:\n        return np.eye(4) + X + X @ X / 2 + X @ X @ X / 6\n"
     "    wh, vh = w / theta, v / theta\n    Wh = skew(wh)\n"
     "    G = np.eye(3) * theta + (1 - np.cos(theta)) * Wh + (theta - np.sin(theta)) * Wh @ Wh\n"
     "    T[:3, :3] = np.eye(3) + np.sin(theta) * Wh + (1 - np.cos(theta)) * Wh @ Wh\n"
     "    T[:3, 3] = G @ vh\n    return T\n"
     "    if theta < 1e-12:  # a pure translation (to rounding)\n"),
    ("    T = np.eye(4)\n    for i in range(S.shape[1]):\n        T = T @ _exp(S[:, i] * q[i])\n"
     "    return T @ M",
     "    T = M.copy()\n    for i in reversed(range(S.shape[1])):\n"
     "        T = _exp(S[:, i] * q[i]) @ T\n    return T"),
    ("        J[:, i] = Ad @ S[:, i]\n",
     "        X = np.zeros((4, 4))\n        X[:3, :3], X[:3, 3] = skew(S[3:, i]), S[:3, i]\n"
     "        Y = T @ X @ np.linalg.inv(T)\n"
     "        J[:, i] = [Y[0, 3], Y[1, 3], Y[2, 3], Y[2, 1], Y[0, 2], Y[1, 0]]\n"),
    ("        columns.append(adjoint(T) * S)",
     "        q_now = (T * sp.Matrix([-S[1], 0, 0, 1]))[:3, 0]  # where the axis passes now\n"
     "        columns.append(sp.Matrix.vstack(q_now.cross(z), z))"),
    (SJ3_RETURN, "    return sp.expand(sp.Matrix.hstack(*columns), trig=True)"),
    (W_RET, "    return float(np.prod(np.linalg.svd(J, compute_uv=False)))"),
    ("    U, s, Vt = np.linalg.svd(J)\n    if s[-1] >= tol * s[0]:\n        return None\n"
     "    return U[:, len(s) - 1]",
     "    lam, vec = np.linalg.eigh(J @ J.T)  # ascending: lam = sigma^2\n"
     "    if lam[0] >= (tol**2) * lam[-1]:\n        return None\n    return -vec[:, 0]"),
    ("        dq = J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(6), e)\n",
     "        dq = J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(6), e)\n"
     "        if np.linalg.norm(dq) > 0.5:\n            dq = dq * 0.5 / np.linalg.norm(dq)\n"),
    ("            return q, True", "            return list(q), np.bool_(True)"),
)


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """Every submission of this file graded in one run: the mistakes, then the alternatives."""
    tmp = tmp_path_factory.mktemp("a06")
    # the derivation's final tidying is left out (any form is right, and it costs 0.4 s a
    # submission; the solution as written is graded in test_grader.py)
    code = patched(solution_code(NAME), (SJ3_TIDY, SJ3_RETURN))
    subs = mistake_submissions(tmp, NAME, _isolated(code), TABLE, _right_copies(code))
    alt = write_notebook(tmp / "alt.ipynb", _right_copies(code), patched(_isolated(code), *ALT),
                         assignment=NAME)
    results = judge_notebooks([*subs, alt])
    return results[:-1], by_function(results[-1])


def test_differential_mistakes_are_diagnosed(graded):
    results, _ = graded
    wrong = misdiagnosed(results, TABLE)
    assert not wrong, wrong
    checks = [by_function(r) for r in results]
    # the joint outside its limits is named; a loop that never tries earns nothing
    limits = checks[0]["ik_with_limits"]["diagnoses"][0]["message"]
    assert "joint " in limits and "outside its limits" in limits
    never = checks[len(IK_MISTAKES) - 1]["ik_with_limits"]
    assert never["score"] == 0 and never["passed"] > 0
    assert any(d["key"] == "trivial" for d in never["diagnoses"])
    # a loop that always claims success loses only the unreachable targets
    claims = checks[1]["ik_with_limits"]
    unreachable = sum(not L._kind(c)[0] for c in
                      D.assignment().checks[-1].make_cases(0))
    assert claims["total"] - claims["passed"] == unreachable
    # rounding below zero happens: the unclipped square root fails a few singular cases
    negative = checks[4]["manipulability"]
    assert 1 <= negative["total"] - negative["passed"] <= 20
    # always None is right on every regular case but earns nothing for them
    none = checks[6]["lost_direction"]
    assert none["score"] == 0 and none["passed"] > 20
    assert top(checks[0]["exp_twist"]) == "rows"


def test_right_alternatives_are_accepted(graded):
    _, alt = graded
    for fn, check in alt.items():
        assert check["passed"] == check["total"], (fn, check["diagnoses"])
