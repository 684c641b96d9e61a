"""Notebook 15 · SE(3), twists and the product of exponentials: Ṫ and se(3), a point's
velocity in a moving frame, e^{[S]θ} of a revolute joint, a screw axis, PoE forward
kinematics, what the body Jacobian depends on."""

from functools import cache

import numpy as np

from .._verdict import Mistake
from ..judges import choice_judge
from ..mistakes import FRAME, ORDER, ROWS, SIGN
from ._make import expression, function, judged, value

# -- 15.1 · is Ṫ an element of se(3)? ---------------------------------------------------------
#: T(t) = [[Rz(t), (t, 0, 0)], [0, 1]]: the frame turns about z and slides along x
TDOT_OPTIONS = {
    "a": "Ṫ only, as seed 004 labels it",
    "b": "Ṫ T⁻¹ and T⁻¹ Ṫ, but not Ṫ",
    "c": "all three: Ṫ, Ṫ T⁻¹ and T⁻¹ Ṫ",
    "d": "none of them: the frame translates",
}
_NOT_TDOT = ("a zero bottom row is not enough: the top-left block of an element of se(3) "
             "must be skew-symmetric, and Ṫ's is Ṙ = S(ω) R, skew only in special poses "
             "(R = I, say). Ṫ lies in the tangent space at T; se(3) is the tangent space at "
             "I, and Ṫ T⁻¹, T⁻¹ Ṫ carry Ṫ there")
_TDOT_WRONG = {
    "a": ("seed 004", "that is seed 004's slip: " + _NOT_TDOT + " — they are the ones in se(3)"),
    "c": ("zero row", "Ṫ T⁻¹ and T⁻¹ Ṫ are, Ṫ is not: " + _NOT_TDOT),
    "d": ("translation", "the translation is no obstacle: ḋ goes into the last column, which "
                         "an element of se(3) leaves free. Ṫ T⁻¹ = [[S(ω), ḋ − ω × d], [0, 0]] "
                         "is in se(3) for every motion; only Ṫ itself is not"),
}


def _T_of(t):
    from ... import rotz, transform

    return transform(rotz(t), [t, 0.0, 0.0])


@cache
def _tdot_right() -> str:
    """The option kinlib confirms at t = 1: vee_se3 refuses Ṫ and accepts Ṫ T⁻¹, T⁻¹ Ṫ."""
    from ... import KinlibError, transform_inverse, vee_se3

    h, T = 1e-6, _T_of(1.0)
    Td = (_T_of(1.0 + h) - _T_of(1.0 - h)) / (2 * h)

    def in_se3(X):
        try:
            vee_se3(X, tol=1e-6)
        except KinlibError:
            return False
        return True

    Ti = transform_inverse(T)
    pattern = {(True, False, False): "a", (False, True, True): "b", (True, True, True): "c",
               (False, False, False): "d"}
    return pattern[in_se3(Td), in_se3(Td @ Ti), in_se3(Ti @ Td)]


def _judge_tdot(args, got):
    return choice_judge(TDOT_OPTIONS, _tdot_right(), _TDOT_WRONG)(args, got)


# -- 15.2 · a bead on a turntable on a conveyor -------------------------------------------------
PHI, OMEGA = 0.6, np.array([0.0, 0.0, 0.5])           # R = Rz(φ), ω (rad/s, frame 0)
D, D_DOT = np.array([1.2, 0.4, 0.3]), np.array([0.2, 0.0, 0.0])   # the table's centre, m/s
P1, P1_DOT = np.array([0.3, 0.0, 0.1]), np.array([0.1, 0.0, 0.0])  # the bead in frame 1


def _bead(carried=True, sliding=True, lever=None, slide=None):
    """ṗ0 = ω × (R p1) + ḋ + R ṗ1, or one of its wrong variants."""
    from ... import rotz

    R = rotz(PHI)
    arm = R @ P1 if lever is None else lever(R)
    out = np.cross(OMEGA, arm)
    if carried:
        out = out + D_DOT
    if sliding:
        out = out + (R @ P1_DOT if slide is None else slide(R))
    return out


def _bead_right():
    from ... import point_velocity, rotz

    return point_velocity(rotz(PHI), D_DOT, OMEGA, P1) + rotz(PHI) @ P1_DOT


# -- 15.3 · e^{[S]θ} of a revolute joint about the vertical line through (a, b, 0) ----------
def _rev_symbols():
    import sympy as sp

    return sp.symbols("a b theta", real=True)


def _rev_about(point_sign=1, translation=None):
    """The rotation by θ about the vertical line through ±(a, b, 0): Trans(q) Rz(θ) Trans(−q)
    (a rotation about a line off the origin, notebook 07), or a variant's translation."""
    import sympy as sp

    from ... import rotz, transform

    a, b, th = _rev_symbols()
    q = point_sign * sp.Matrix([a, b, 0])
    R = rotz(th)
    p = (sp.eye(3) - R) * q if translation is None else translation(R, th)
    return transform(R, p)


def _rev_no_V():
    import sympy as sp

    a, b, _ = _rev_symbols()
    return _rev_about(translation=lambda R, th: th * sp.Matrix([b, -a, 0]))


def _rev_origin():
    import sympy as sp

    return _rev_about(translation=lambda R, th: sp.zeros(3, 1))


# -- 15.4 · the UR5's fifth screw axis at home -------------------------------------------------
@cache
def _ur5_home():
    from ...robots import ur5

    robot = ur5()
    return robot, robot.link_poses(np.zeros(robot.dof))


def _axis_from(frame, kind="right"):
    """S of a joint turning about z of ``frame`` through its origin (standard DH: joint i
    turns about z_{i-1}), or a wrong variant."""
    _, poses = _ur5_home()
    F = poses[frame]
    w, q = F[:3, 2], F[:3, 3]
    v = {"right": -np.cross(w, q), "sign": np.cross(w, q), "point": q}[kind]
    return np.r_[v, w]


def _s5_body():
    from ... import adjoint, transform_inverse

    robot, poses = _ur5_home()
    return adjoint(transform_inverse(poses[robot.tip])) @ _axis_from("link4")


# -- 15.5 · PoE forward kinematics ---------------------------------------------------------------
def _poe_cases():
    from ... import screw_axes
    from ...robots import puma560, ur5

    rng = np.random.default_rng(1505)
    cases = []
    for robot in (puma560(), ur5()):
        S, M = screw_axes(robot)
        cases.append((M, S, np.zeros(6)))
        cases += [(M, S, q) for q in rng.uniform(-np.pi, np.pi, (3, 6))]
    for _ in range(3):  # random chains: five revolute joints and one slide
        w = rng.normal(size=(6, 3))
        w /= np.linalg.norm(w, axis=1, keepdims=True)
        S = np.vstack([-np.cross(w, rng.uniform(-1, 1, (6, 3))).T, w.T])
        S[:, 2] = np.r_[w[2], 0.0, 0.0, 0.0]
        M = _random_pose(rng)
        cases.append((M, S, rng.uniform(-2, 2, 6)))
    return cases


def _random_pose(rng):
    from ... import exp_so3, transform

    return transform(exp_so3(rng.normal(size=3)), rng.uniform(-1, 1, 3))


def _product(S, q, order=1, column=None):
    from ... import exp_se3

    column = column or (lambda S, i: S[:, i])
    T = np.eye(4)
    for i in range(len(q))[::order]:
        T = T @ exp_se3(column(S, i) * q[i])
    return T


def _poe_right(M, S, q):
    from ... import poe_fk

    return poe_fk(M, S, q)


# -- 15.6 · which columns of the body Jacobian move with joint 1? ------------------------------
Q_JB = np.array([0.4, -1.1, 1.3, -0.7, 0.9, 0.2])
JB_OPTIONS = {"a": "all six columns", "b": "columns 2 to 6 (column 1 stays)", "c": "none",
              "d": "column 1 only"}
_JB_WRONG = {
    "a": ("all", "J_b is the arm's velocity seen from its own tool frame; turning joint 1 "
                 "turns the whole arm, tool frame included, rigidly about axis 1: in the "
                 "tool's frame nothing has changed, so no column changes"),
    "b": ("space", "that is the space Jacobian: J_s's column 1 is S₁ for ever, and the "
                   "others are carried by joint 1. J_b's column i depends only on the joints "
                   "after i, q_{i+1} … q_n — and joint 1 comes before all of them"),
    "d": ("column 1", "column 1 of J_b is B₁ carried back through joints 2 … 6: it depends on "
                      "q₂ … q₆, the joints between axis 1 and the tool, not on q₁ — and no "
                      "other column depends on q₁ either"),
}


@cache
def _jb_right() -> str:
    """The option kinlib's body Jacobian confirms: the columns that change with q1."""
    from ... import body_jacobian, screw_axes
    from ...robots import ur5

    B, _ = screw_axes(ur5(), frame="body")
    J0 = body_jacobian(B, Q_JB)
    J1 = body_jacobian(B, Q_JB + [0.8, 0, 0, 0, 0, 0])
    moved = tuple(bool(x) for x in np.abs(J1 - J0).max(axis=0) > 1e-9)
    pattern = {(True,) * 6: "a", (False,) + (True,) * 5: "b", (False,) * 6: "c",
               (True,) + (False,) * 5: "d"}
    return pattern[moved]


def _judge_jb(args, got):
    return choice_judge(JB_OPTIONS, _jb_right(), _JB_WRONG)(args, got)


EXERCISES = [
    judged("15.1", "predict", "is Ṫ an element of se(3)?", _judge_tdot,
           diagnoses=("seed 004", "zero row", "translation"),
           explain="se(3) is the set of matrices [[S(ω), v], [0, 0]] with S(ω) skew. Ṫ's "
                   "top-left block is Ṙ = S(ω) R; multiplying by T⁻¹ (on either side) turns "
                   "it into S(ω) or S(Rᵀω). Ṫ lives in the tangent space at T, "
                   "{[ξ] T : [ξ] ∈ se(3)}"),
    value("15.2", "compute", "the velocity of a bead on a turntable on a conveyor",
          _bead_right,
          Mistake("carried", "the term ḋ is missing: the turntable's centre moves too, and "
                             "every point of the table moves with it; ṗ0 = ω × (R p1) + ḋ "
                             "+ R ṗ1", lambda: _bead(carried=False)),
          Mistake("sliding", "the bead's own motion on the table is missing: it slides at "
                             "ṗ1 in frame 1, which adds R ṗ1", lambda: _bead(sliding=False)),
          FRAME.of(lambda: _bead(slide=lambda R: P1_DOT),
                   "you added ṗ1 as it is, in the table's frame 1: turn it into frame 0 "
                   "first, R ṗ1"),
          FRAME.of(lambda: _bead(lever=lambda R: P1),
                   "the lever arm ω × p1 uses p1 in the table's frame: the arm from the "
                   "table's centre to the bead, in frame 0, is R p1"),
          Mistake("lever arm", "ω × (R p1 + d) measures the lever arm from frame 0's origin; "
                               "the table turns about its own centre d, so the arm is R p1 "
                               "(p0 − d)", lambda: _bead(lever=lambda R: R @ P1 + D)),
          what="a 3-vector (m/s)",
          explain="ṗ0 = ω × (R p1) + ḋ + R ṗ1: the turn of the table carries the bead round "
                  "its centre, the conveyor carries the centre, and the bead slides on the "
                  "table. kl.point_velocity(R, ḋ, ω, p1) gives the first two"),
    expression("15.3", "e^{[S]θ} of a revolute joint about the vertical line through (a, b, 0)",
               _rev_about,
               Mistake("moment", "this turns about the line through −q = (−a, −b, 0), its "
                                 "translation is (R − I) q instead of (I − R) q: the screw "
                                 "axis of a joint through q is S = [−ω × q; ω] (v = q × ω); "
                                 "v = +ω × q belongs to the line through −q",
                       lambda: _rev_about(point_sign=-1)),
               Mistake("origin", "this is the rotation about the z axis through the origin: "
                                 "v = 0. A joint whose axis passes through q = (a, b, 0) has "
                                 "v = −ω × q", _rev_origin),
               Mistake("no V", "the translation θ v ignores that the point moves on a circle "
                               "while it turns: the top-right block of e^{[S]θ} is "
                               "(Iθ + (1 − cos θ) W + (θ − sin θ) W²) v", _rev_no_V),
               what="a 4×4 sympy Matrix",
               explain="e^{[S]θ} = [[R_z(θ), (I − R_z(θ)) q], [0, 1]] with q = (a, b, 0): "
                       "the points of the axis stay where they are, the rest turns about it "
                       "— Trans(q) R_z(θ) Trans(−q), the rotation about a line off the "
                       "origin of notebook 07"),
    value("15.4", "compute", "the UR5's fifth screw axis S₅ at home", lambda: _axis_from("link4"),
          ROWS.of(lambda: np.roll(_axis_from("link4"), 3),
                  "your axis is [ω; v], Modern Robotics' order: kinlib's twists stack the "
                  "linear part first, [v; ω]"),
          SIGN.of(lambda: _axis_from("link4", "sign"),
                  "the linear part has the wrong sign: v = −ω × q = q × ω (the velocity of "
                  "the body point at the base origin, turning about the axis through q)"),
          Mistake("point", "v is not the point q of the axis but its moment, −ω × q",
                  lambda: _axis_from("link4", "point")),
          Mistake("next frame", "joint 5 turns about z₄ through o₄ (standard DH: joint i "
                                "moves frame i about z_{i−1}); you used frame 5",
                  lambda: _axis_from("link5")),
          FRAME.of(_s5_body, "this is the body screw axis B₅ = Ad_{M⁻¹} S₅, written in the "
                             "tool's frame at home; S₅ is written in the base frame"),
          what="a 6-vector [v; ω]",
          explain="S₅ = [−ω × q; ω] with ω = z₄ and q = o₄ of the home pose: at home the "
                  "fifth axis is vertical, pointing down, ω = (0, 0, −1)"),
    function("15.5", "PoE forward kinematics e^{[S₁]q₁} ⋯ e^{[Sₙ]qₙ} M", _poe_cases(),
             _poe_right,
             ORDER.of(lambda M, S, q: _product(S, q, order=-1) @ M,
                      "the exponentials are multiplied in the reverse order: joint 1, "
                      "nearest the base, stands leftmost, e^{[S₁]q₁} e^{[S₂]q₂} ⋯ M"),
             Mistake("body form", "M stands on the left: M e^{[S₁]q₁} ⋯ is the body form, "
                                  "and it needs the body screw axes B = Ad_{M⁻¹} S; with the "
                                  "space axes S, M goes on the right",
                     lambda M, S, q: M @ _product(S, q)),
             Mistake("home", "M is missing: the product of the exponentials moves the home "
                             "pose M, T = e^{[S₁]q₁} ⋯ e^{[Sₙ]qₙ} M",
                     lambda M, S, q: _product(S, q)),
             ROWS.of(lambda M, S, q: _product(S, q, column=lambda S, i: np.roll(S[:, i], 3))
                     @ M, "you read each screw axis as [ω; v], Modern Robotics' order: "
                          "kinlib's columns are [v; ω], linear part first"),
             Mistake("columns", "S[i] is row i of S; the screw axis of joint i is column i, "
                                "S[:, i]", lambda M, S, q: _product(
                                    S, q, column=lambda S, i: S[i]) @ M),
             what="a 4×4 transform",
             explain="the last joint moves the home pose first, e^{[Sₙ]qₙ} M, then each "
                     "joint nearer the base moves everything beyond it about its own axis, "
                     "which the joints beyond it have not moved"),
    judged("15.6", "predict", "which columns of the body Jacobian move with joint 1",
           _judge_jb, diagnoses=("all", "space", "column 1"),
           explain="J_b's column i is B_i carried back through the joints after i, "
                   "Ad_{(e^{[B_{i+1}]q_{i+1}}⋯e^{[B_n]q_n})⁻¹} B_i: q₁ is in none of them. "
                   "J_s is the mirror image: its column i depends on q₁ … q_{i−1} only"),
]
