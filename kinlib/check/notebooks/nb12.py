"""Notebook 12 · differential kinematics I: angular velocity and the geometric Jacobian."""

from functools import cache

import numpy as np

from .._verdict import Mistake
from ..judges import choice_judge
from ..mistakes import DEGREES, FRAME, ORDER, ROWS, SIGN, TRANSPOSED
from ._make import expression, function, judged, value


# -- 12.1 · ω of the tilting turntable R(t) = Rx(γ(t)) Rz(α(t)) ----------------------------
def _table_symbols():
    import sympy as sp

    al, ga = sp.symbols("alpha gamma", real=True)
    ad, gd = sp.symbols(r"\dot{\alpha} \dot{\gamma}", real=True)
    return al, ga, ad, gd


def _omega_space():
    """ω = E(γ, α, 0) (γ̇, α̇, 0) with kinlib's XZY Euler-rate matrix: R = Rx(γ) Rz(α) Ry(0)."""
    import sympy as sp

    from ... import euler_rate_matrix

    al, ga, ad, gd = _table_symbols()
    return euler_rate_matrix([ga, al, 0], "XZY") * sp.Matrix([gd, ad, 0])


def _omega_body():
    """The body-frame angular velocity Rᵀω, R = Rx(γ) Rz(α): what vee(RᵀṘ) gives."""
    from ... import rotx, rotz
    from ...symbolic import simplify_rotation

    al, ga, _, _ = _table_symbols()
    return simplify_rotation((rotx(ga) * rotz(al)).T * _omega_space())


def _omega_other_order():
    """ω of Rz(α) Rx(γ), the product in the other order (a turn about the fixed z, then a
    tilt about the moving x)."""
    import sympy as sp

    from ... import euler_rate_matrix

    al, ga, ad, gd = _table_symbols()
    return euler_rate_matrix([al, 0, ga], "ZYX") * sp.Matrix([ad, 0, gd])


def _omega_unturned():
    """γ̇ x + α̇ z: the two rates added about the axes as they stand at rest."""
    import sympy as sp

    _, _, ad, gd = _table_symbols()
    return sp.Matrix([gd, 0, ad])


_OMEGA_MISTAKES = (  # tried in order, before the generic near misses
    FRAME.of(_omega_body,
             "this is the body angular velocity Rᵀω, the vector of Rᵀ Ṙ, expressed in the "
             "table's own frame (its last entry is the turn rate about the table's z axis): "
             "the fixed-frame ω is the vector of Ṙ Rᵀ"),
    ORDER.of(_omega_other_order,
             "this is the angular velocity of R_z(α) R_x(γ), the product in the other order: "
             "the table tilts about the fixed x axis and turns about its own z axis, "
             "R = R_x(γ) R_z(α) (the rotation about the moving axis stands on the right)"),
    Mistake("axis", "you added γ̇ x + α̇ z, both axes as they stand at rest: the table's z "
                    "axis tilts with γ, so α̇ turns about R_x(γ) z (section 3: add angular "
                    "velocities only once they are expressed in one frame)", _omega_unturned),
    SIGN.of(lambda: -_omega_space(),
            "right up to the sign: R Ṙᵀ = (Ṙ Rᵀ)ᵀ = −S(ω); the angular velocity is the vector "
            "of Ṙ Rᵀ, the derivative first"),
)


# -- 12.2 · the turntable and the wheel -----------------------------------------------------
W01, W12 = np.array([0.0, 0.0, 2.0]), np.array([5.0, 0.0, 0.0])   # ω01 (base), ω12 (turntable)


def _R01(angle=np.pi / 2):
    from ... import rotz

    return rotz(angle)


# -- 12.3 · one revolute column of the geometric Jacobian -----------------------------------
def _columns(z, o, o_n, **mistake):
    """[z × (o_n − o); z] through assignment 03's model of the Jacobian (and its mistakes)."""
    from ...grade.assignments.jacobian_ik import REVOLUTE, jacobian_columns

    return jacobian_columns([z], [o, o_n], [REVOLUTE], **mistake)[:, 0]


def _column_cases():
    rng = np.random.default_rng(1203)
    z = rng.normal(size=(10, 3))
    z /= np.linalg.norm(z, axis=1, keepdims=True)
    o, o_n = rng.uniform(-1.0, 1.0, (2, 10, 3))
    cases = [(np.array([0.0, 0.0, 1.0]), np.zeros(3), np.array([1.0, 0.0, 0.0])),
             (np.array([0.0, 1.0, 0.0]), np.array([0.2, 0.0, 0.4]), np.array([0.7, 0.3, 0.4]))]
    return cases + list(zip(z, o, o_n, strict=True))


# -- 12.4 · the SCARA's prismatic column ------------------------------------------------------
SCARA_OPTIONS = {"a": "[0, 0, 1; 0, 0, 0]: the tip moves up and does not turn",
                 "b": "[0, 0, −1; 0, 0, 0]: the tip moves down and does not turn",
                 "c": "[0, 0, 0; 0, 0, −1]: the tip turns about the vertical and does not move"}
_SCARA_COLUMNS = {"a": [0, 0, 1, 0, 0, 0], "b": [0, 0, -1, 0, 0, 0], "c": [0, 0, 0, 0, 0, -1]}
_SCARA_WRONG = {
    "a": (SIGN.key, "the slide moves along z₂, and α₂ = π turns frame 2 over about x₂: z₂ "
                    "points down, so q̇₃ = +1 moves the tip down, v = z₂ = (0, 0, −1)"),
    "c": ("prismatic", "that is the column a revolute joint about z₂ would have (its lever arm "
                       "o₄ − o₂ is vertical, so z₂ × (o₄ − o₂) = 0): a prismatic joint slides "
                       "along z₂ and turns nothing, its column is [z₂; 0]")}


@cache
def _scara_right() -> str:
    """The option that is the SCARA's column 3, from kinlib's Jacobian."""
    from ... import DHRow, Robot

    scara = Robot.from_dh([DHRow(a=0.4, alpha=0.0, d=0.35), DHRow(a=0.3, alpha=np.pi),
                           DHRow(a=0.0, alpha=0.0, joint="prismatic", limits=(0.0, 0.25)),
                           DHRow(a=0.0, alpha=0.0, d=0.05)], name="scara")
    column = scara.jacobian([0.4, -0.9, 0.12, 0.7])[:, 2]
    return next(k for k, c in _SCARA_COLUMNS.items() if np.allclose(column, c))


def _judge_scara(args, got):
    return choice_judge(SCARA_OPTIONS, _scara_right(), _SCARA_WRONG)(args, got)


EXERCISES = [
    expression("12.1", "ω of the tilting turntable from Ṙ Rᵀ", _omega_space, *_OMEGA_MISTAKES,
               what="a 3×1 sympy Matrix",
               explain="ω = γ̇ x + α̇ R_x(γ) z = (γ̇, −α̇ sin γ, α̇ cos γ): the tilt rate "
                       "about the fixed x axis plus the turn rate about the table's own axis, "
                       "as the tilt has turned it. Section 3 makes a rule of this: angular "
                       "velocities add once they are expressed in one frame"),
    value("12.2", "compute", "the wheel on the turntable: ω in the base frame",
          lambda: W01 + _R01() @ W12,
          FRAME.of(lambda: W01 + W12, "you added ω¹₁,₂ as it is, but it is expressed in the "
                                      "turntable's frame 1: turn it into the base frame first, "
                                      "ω⁰₀,₂ = ω⁰₀,₁ + R⁰₁ ω¹₁,₂"),
          TRANSPOSED.of(lambda: W01 + _R01().T @ W12,
                        "you turned ω¹₁,₂ with R⁰₁ᵀ = R¹₀, which maps base coordinates into "
                        "the turntable's: R⁰₁ takes the wheel's rate from frame 1 to frame 0"),
          DEGREES.of(lambda: W01 + _R01(90.0) @ W12,
                     "kl.rotz(90) turns by 90 radians: kinlib's angles are radians, π/2 is "
                     "90°"), what="a 3-vector",
          explain="ω⁰₀,₂ = ω⁰₀,₁ + R⁰₁ ω¹₁,₂ = (0, 0, 2) + R_z(π/2) (5, 0, 0) = (0, 5, 2) "
                  "rad/s: at this instant the turntable's x axis points along the base y "
                  "axis, and that is where the wheel's 5 rad/s point"),
    function("12.3", "a revolute joint's column [z × (o_n − o); z]", _column_cases(), _columns,
             ROWS.of(lambda z, o, o_n: np.roll(_columns(z, o, o_n), 3),
                     "your column is [z; z × (o_n − o)], rows [ω; v]: the course's Jacobian "
                     "stacks the linear velocity first, [v; ω] (Modern Robotics writes "
                     "[ω; v])"),
             SIGN.of(lambda z, o, o_n: _columns(z, o, o_n, linear=lambda a, on, oi: np.cross(
                 on - oi, a)),
                 "the linear part has the wrong sign: (o_n − o) × z is the cross product "
                 "reversed; a point at r from the axis moves with ω × r = z × (o_n − o)"),
             Mistake("lever arm", "the lever arm is missing o: z × o_n is the velocity for an "
                                  "axis through the base origin; the arm from the joint's axis "
                                  "to the tip is o_n − o",
                     lambda z, o, o_n: _columns(z, o, o_n, linear=lambda a, on, oi: np.cross(
                         a, on))),
             what="a 6-vector [v; ω]",
             explain="the tip, at r = o_n − o from a point of the axis, turns about the axis "
                     "at unit rate: v = z × r, and ω = z. Only the part of r perpendicular to "
                     "the axis counts, so any point o on the axis gives the same column"),
    judged("12.4", "predict", "the SCARA's prismatic column", _judge_scara,
           diagnoses=(SIGN.key, "prismatic"),
           explain="a slide moves the tip along its axis and turns nothing, [z₂; 0]; and "
                   "α₂ = π has turned z₂ over, so it points down"),
]
