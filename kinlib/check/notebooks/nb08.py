"""Notebook 08 · URDF and the matrix stack: joint origins, the product on the stack,
the joint motion, joint limits, drawing a joint axis with the cross product."""

import numpy as np

from .._verdict import RIGHT, Mistake, Verdict, as_numeric, close, fmt
from ..mistakes import DEGREES, EXTRINSIC, ORDER, SEQUENCE, TRANSPOSED
from ._make import choice, function, judged, value

# ---- 08.1: a joint origin from xyz and rpy --------------------------------------------


def _origin(xyz, rpy, seq="xyz", order="DR"):
    from ... import matrix_from_euler, transform

    R = matrix_from_euler(np.asarray(rpy, dtype=float), seq)
    p = np.asarray(xyz, dtype=float)
    return transform(R, R @ p if order == "RD" else p)


def _origin_cases():
    rng = np.random.default_rng(8)
    cases = [([0.119525, 0.0, 0.34858], [0.0, 0.0, 0.0]),          # seed 000's shoulder pan
             ([0.0, 0.0, 0.2], [np.pi / 2, 0.0, 0.0]),
             ([0.1, 0.0, 0.0], [0.0, 0.0, np.pi / 2])]
    for _ in range(9):
        cases.append((rng.uniform(-1, 1, 3).round(3), rng.uniform(-np.pi, np.pi, 3).round(3)))
    return [(np.asarray(x, dtype=float), np.asarray(r, dtype=float)) for x, r in cases]


# ---- 08.2 and 08.4: products on the stack -----------------------------------------------

Q_LINK4 = np.array([0.6, 0.9, -0.4])
Q_SLIDE = 0.7


def _robot():
    from ...robots import autorob_test_robot

    return autorob_test_robot()


def _rot(jt, q):
    from ... import matrix_from_axis_angle, transform

    return transform(matrix_from_axis_angle(jt.axis, q))


def _stack(*names, q=Q_LINK4, motion_first=False):
    """The product origin · motion (or motion · origin) over the joints ``names``, in that
    order (joint k takes q[k−1])."""
    robot, T = _robot(), np.eye(4)
    for name in names:
        jt = robot.joint(name)
        M = _rot(jt, q[robot.joint_names.index(name)])
        T = T @ (M @ jt.origin if motion_first else jt.origin @ M)
    return T


def _base():
    from ... import rotz, transform

    return transform(rotz(0.3), [1.0, 2.0, 0.0])


def _slide(axis=None):
    from ... import transform

    jt = _robot().joint("joint1")
    u = jt.axis if axis is None else np.asarray(axis, dtype=float)
    return transform(p=Q_SLIDE * u)


def _link2():
    return _base() @ _robot().joint("joint1").origin @ _slide()


# ---- 08.6: a three.js cylinder (along y) turned onto a joint axis ------------------------

_E_Y = np.array([0.0, 1.0, 0.0])


def _axis_cases():
    """The test robot's three axes as the file writes them (not unit vectors), the z axis,
    two axes below the x-z plane (obtuse angles), and u along +y and along −y."""
    axes = ([-0.9, 0.15, 0.0], [-0.707, 0.707, 0.0], [0.707, -0.707, 0.0], [0.0, 0.0, 1.0],
            [0.3, -0.9, 0.2], [2.0, 1.0, -2.0], [0.0, 2.0, 0.0], [0.0, -1.0, 0.0])
    return [(np.array(u),) for u in axes]


def _turn(axis, angle):
    from ... import matrix_from_axis_angle

    return matrix_from_axis_angle(axis, angle)


def _shortest_turn(u):
    """The rotation about e_y × û by the angle between them (a half turn about x for
    û = −e_y): one of the right answers, shown in a message."""
    u_hat = u / np.linalg.norm(u)
    k = np.cross(_E_Y, u_hat)
    if np.linalg.norm(k) < 1e-12:
        return np.eye(3) if u_hat[1] > 0 else np.diag([1.0, -1.0, -1.0])
    return _turn(k, np.arctan2(np.linalg.norm(k), u_hat[1]))


def _axis_judge(args, got):
    """Right: any rotation R with R e_y = u/|u| (the cylinder is round about its own y)."""
    from ... import is_rotation

    (u,) = args
    u_hat = u / np.linalg.norm(u)
    along_y = np.linalg.norm(np.cross(_E_Y, u_hat)) < 1e-12
    expected = _shortest_turn(u)
    R, bad = as_numeric(got, (3, 3), "a 3×3 rotation matrix")
    if R is None:
        if bad.key == "nan" and along_y:
            return Verdict(False, "parallel", "NaN for u along y: there e_y × û = 0 and "
                                              "normalising it divides by zero. Handle u ∥ y "
                                              "first: no turn for +y, a half turn about x for "
                                              "−y", expected)
        return Verdict(bad.ok, bad.key, bad.message, expected)
    image = R @ _E_Y
    if is_rotation(R) and close(image, u_hat, 1e-6):
        return RIGHT
    if along_y and u_hat[1] < 0 and close(image, _E_Y, 1e-6):
        return Verdict(False, "antiparallel", "for u along −y the cross product vanishes "
                                              "too, but the cylinder must be turned upside "
                                              "down: a half turn about an axis perpendicular "
                                              "to y, e.g. kl.rotx(np.pi)", expected)
    if not is_rotation(R):
        return Verdict(False, "rotation", "your matrix is not a rotation (RᵀR ≠ I or det R ≠ 1): "
                                          "if you wrote Rodrigues' formula yourself, its axis "
                                          "must be a unit vector, and e_y × û has length "
                                          "sin θ", expected)
    if close(R.T @ _E_Y, u_hat, 1e-6):
        return Verdict(False, "transposed", "you turned the wrong way: that R turns û onto "
                                            "e_y. The axis from e_y towards û is e_y × û (not "
                                            "û × e_y), turned by +θ", expected)
    k = np.cross(_E_Y, u)
    if np.linalg.norm(k) > 1e-12:
        for key, angle, message in (
                ("unit", np.arccos(np.clip(u[1], -1.0, 1.0)),
                 "normalise u first: the file's axes are not unit vectors, so e_y · u is not "
                 "cos θ"),
                ("arcsin", np.arcsin(np.clip(np.linalg.norm(np.cross(_E_Y, u_hat)), 0.0, 1.0)),
                 "arcsin |e_y × û| is at most 90°: for an axis below the x-z plane (u_y < 0) "
                 "the angle is obtuse. Take θ from both sin θ = |e_y × û| and cos θ = e_y · û: "
                 "atan2, or arccos(e_y · û)")):
            wrong = _turn(k, angle) @ _E_Y
            if close(image, wrong, 1e-6) and not close(wrong, u_hat, 1e-6):
                return Verdict(False, key, message, expected)
    return Verdict(False, "wrong", f"R e_y = {fmt(image)}, not û = u/|u| = {fmt(u_hat)}",
                   expected)


def _axis_error_hint(case, text):
    (u,) = case
    if np.linalg.norm(np.cross(_E_Y, u)) < 1e-12:
        return ("for u along y, e_y × u = 0 gives no axis to turn about: handle that case "
                "first (no turn for +y, a half turn about x for −y)")
    return None


EXERCISES = [
    function("08.1", "a joint's origin from xyz and rpy", _origin_cases(), _origin,
             EXTRINSIC.of(lambda x, r: _origin(x, r, "XYZ"),
                          "this is Rx(roll) Ry(pitch) Rz(yaw), the product for rotations "
                          "about the moving axes; URDF's roll, pitch and yaw turn about the "
                          "parent's fixed axes, so the first rotation stands on the right: "
                          "R = Rz(yaw) Ry(pitch) Rx(roll)"),
             SEQUENCE.of(lambda x, r: _origin(x, r, "ZYX"),
                         "the angles turn about the wrong axes: roll (the first number) is "
                         "about x, pitch about y, yaw (the last) about z, R = Rz(yaw) "
                         "Ry(pitch) Rx(roll)"),
             DEGREES.of(lambda x, r: _origin(x, np.deg2rad(r)),
                        "URDF's rpy is in radians already: converting it with np.deg2rad "
                        "(or π/180) turns every angle into almost nothing"),
             ORDER.of(lambda x, r: _origin(x, r, order="RD"),
                      "you rotated first and then translated in the rotated frame (R D): "
                      "xyz is the child's origin in the parent's coordinates, so "
                      "T = D(xyz) R(rpy), whose last column is xyz itself"),
             TRANSPOSED.of(lambda x, r: _origin(x, r).T,
                           "your 4×4 matrix is transposed: the translation belongs in the "
                           "last column, [R xyz; 0 0 0 1]"),
             TRANSPOSED.of(lambda x, r: np.block([[_origin(x, r)[:3, :3].T, _origin(x, r)[:3, 3:]],
                                                  [np.zeros((1, 3)), np.ones((1, 1))]]),
                           "the rotation block is transposed: that is the parent's axes in "
                           "the child frame, R(rpy)ᵀ; the columns of R are the child's axes "
                           "written in the parent"),
             what="a 4×4 matrix",
             explain="URDF's roll, pitch and yaw turn about the parent's fixed axes, so the "
                     "first turn stands on the right: R = Rz(yaw) Ry(pitch) Rx(roll), which "
                     "is `kl.matrix_from_euler(rpy, \"xyz\")` (lowercase: extrinsic). xyz is "
                     "measured in the parent, so R does not turn it: T = D(xyz) R(rpy) = "
                     "[R xyz; 0 0 0 1], translate first, then rotate about the new origin "
                     "(the other order, R D, would put the origin at R·xyz)."),
    value("08.2", "compute", "T_link4 as the product on the stack",
          lambda: _stack("joint2", "joint3"),
          ORDER.of(lambda: _stack("joint2", "joint3", motion_first=True),
                   "each joint's motion stands before its origin: on the stack a joint "
                   "contributes its origin first, then its motion, D R R_u(q), because the "
                   "axis is written in the joint (child) frame that the origin reaches"),
          ORDER.of(lambda: _stack("joint3", "joint2"),
                   "the product runs from link4 back to link1: on the stack the factors "
                   "come in the order the joints are entered, from the root outwards: "
                   "joint2's, then joint3's"),
          ORDER.of(lambda: _stack("joint3", "joint2", motion_first=True),
                   "the whole product is reversed: the transform entered first (joint2's "
                   "origin) stands on the left, the last (joint3's motion) on the right"),
          Mistake("branch", "joint1 is on the other branch: it carries link2, not link3 or "
                            "link4, so neither its origin nor its motion belongs in link4's "
                            "product; pop it off the stack before entering joint2",
                  lambda: _stack("joint1", "joint2", "joint3")),
          what="a 4×4 matrix",
          explain="with link4 on top the stack holds D^1_3 R^1_3 R_u2(q2) D^3_4 R^3_4 "
                  "R_u3(q3) (times the base pose, here I): joint1 was popped before joint2 "
                  "was entered, so q1 does not appear, and each joint puts its origin "
                  "before its motion because its axis is written in the frame the origin "
                  "reaches."),
    choice("08.3", "predict", "what accounts for a prismatic joint's motion",
           {"a": "a rotation R_u1(q1) about the unit axis u1, right after joint1's origin",
            "b": "a translation D_u1(q1) by q1·u1 along the unit axis, right after joint1's "
                 "origin",
            "c": "a translation D_u1(q1), multiplied on the left of the base pose"}, "b",
           {"a": ("revolute", "a rotation about the axis is the motion of a revolute (or "
                              "continuous) joint; a prismatic joint slides along its axis: "
                              "D_u(q), the translation by q u"),
            "c": ("order", "on the left of D^w_1 R^w_1 the translation would act in world "
                           "coordinates and carry the whole robot, link1 and the other branch "
                           "included; the motion stands right after the joint's origin, so it "
                           "moves the outboard chain only, along the axis in the joint frame")}),
    value("08.4", "compute", "link2's world pose with joint1 prismatic", _link2,
          Mistake("unit axis", "the axis in the file, (−0.9, 0.15, 0), is not a unit vector: "
                               "normalise it first (robot.joint('joint1').axis is), or the "
                               "link slides q·|axis| instead of q",
                  lambda: _base() @ _robot().joint("joint1").origin
                  @ _slide([-0.9, 0.15, 0.0])),
          Mistake("revolute", "that is a rotation by q1 about the axis: joint1 is prismatic "
                              "now, its motion is the translation D_u1(q1) = Tr(q1 u1)",
                  lambda: _base() @ _robot().joint("joint1").origin
                  @ _rot(_robot().joint("joint1"), Q_SLIDE)),
          ORDER.of(lambda: _slide() @ _base() @ _robot().joint("joint1").origin,
                   "the translation was applied in world coordinates (on the left of the "
                   "base pose): the axis is written in the joint frame, so D_u1(q1) comes "
                   "after the base and the origin, where the base's rotation turns it"),
          Mistake("base", "the base pose is missing: that is link2 in link1's frame; the "
                          "world pose starts from D^w_1 R^w_1 = base",
                  lambda: _robot().joint("joint1").origin @ _slide()),
          what="a 4×4 matrix",
          explain="T_link2 = base · D^1_2 R^1_2 · D_u1(q1): the slide by q1·u1 is along the "
                  "axis written in joint1's frame, so the base's turn by 0.3 rad about z "
                  "turns it too: in the world, link2 moved by 0.7 · Rz(0.3) u1 from where "
                  "it stands at q1 = 0."),
    choice("08.5", "predict", "can a joint move infinitely far?",
           {"a": "yes, every joint: q is just a number in R_u(q) or D_u(q)",
            "b": "a continuous joint turns forever (q and q + 2π give the same pose); a "
                 "revolute or prismatic joint stops at its <limit lower upper>",
            "c": "no joint: a continuous joint is limited to [−π, π] too"}, "b",
           {"a": ("limits", "the matrices accept any q, but the robot does not: a revolute or "
                            "prismatic joint has a range, URDF's <limit lower=… upper=…> "
                            "(required for those types); a slider would leave its rail"),
            "c": ("continuous", "a continuous joint (a wheel, an endless wrist) has no limits: "
                                "q may grow without bound, q and q + 2π give the same pose, "
                                "and robot.limits holds ±∞ for it")}),
    judged("08.6", "implement", "a cylinder along y turned onto a joint axis", _axis_judge,
           cases=_axis_cases(), on_error=_axis_error_hint,
           diagnoses=("transposed", "unit", "arcsin", "antiparallel", "rotation",
                      "parallel"),
           explain="e_y × û is the axis of the shortest turn and θ = atan2(|e_y × û|, e_y · û) "
                   "its angle, in [0, π]; along ±y the cross product vanishes and names no "
                   "axis, so those two cases are handled apart. Any turn about û afterwards "
                   "is right too: the cylinder is round."),
]
