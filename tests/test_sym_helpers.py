"""kinlib.symbolic: canonical trigonometric reduction, readable simplification, batched lambdify.

Soundness is checked numerically (a reduced expression evaluates to the same numbers as the
input at random points), completeness on textbook identities (each typed here, must reduce to
exactly 0), determinism across interpreter runs with different hash seeds, and the batched
functions against kinlib's numeric constructors and robots.

The products and chains below are a few chosen ones, not random draws: together they take
every path of the reduction (three axes, one angle on two axes, a double angle, a half angle
next to its full angle, tan and cot, a denominator, unit vectors) and of the folding (sums,
differences, a chain of four, irrational cofactors, equal coefficients that must not fold).
"""

import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

import kinlib as kl
import kinlib.robots
from kinlib.symbolic import lambdify_batched, simplify_rotation, sym_equal, trig_reduce

t, t1, t2, t3 = sp.symbols("theta theta1 theta2 theta3", real=True)
a, b, g = sp.symbols("alpha beta gamma", real=True)
l1, l2 = sp.symbols("l1 l2", positive=True)
kx, ky, kz = sp.symbols("k_x k_y k_z", real=True)
w, x, y, z = sp.symbols("w x y z", real=True)


def numeric(expr, symbols, values):
    f = sp.lambdify(symbols, expr, "numpy")
    return np.array(f(*values), dtype=float)


def same_values(got, want, symbols, points):
    """``got`` and ``want`` evaluate to the same numbers at each row of ``points``."""
    for p in points:
        np.testing.assert_allclose(numeric(got, symbols, p), numeric(want, symbols, p),
                                   atol=1e-12)


# --------------------------------------------------------------------------- identities → 0

IDENTITIES = [
    sp.sin(t) ** 2 + sp.cos(t) ** 2 - 1,
    sp.sin(2 * t) - 2 * sp.sin(t) * sp.cos(t),
    sp.cos(2 * t) - (1 - 2 * sp.sin(t) ** 2),
    sp.sin(t) - 2 * sp.sin(t / 2) * sp.cos(t / 2),
    sp.cos(t) - (sp.cos(t / 2) ** 2 - sp.sin(t / 2) ** 2),
    sp.cos(t1 + t2) - (sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2)),
    sp.sin(t1 - t2) - (sp.sin(t1) * sp.cos(t2) - sp.cos(t1) * sp.sin(t2)),
    sp.sin(3 * t) - (3 * sp.sin(t) - 4 * sp.sin(t) ** 3),
    sp.tan(t) * sp.cos(t) - sp.sin(t),
    sp.tan(t / 2) - sp.sin(t) / (1 + sp.cos(t)),
    (1 - sp.tan(t / 2) ** 2) / (1 + sp.tan(t / 2) ** 2) - sp.cos(t),
    sp.cos(t) ** 4 - sp.sin(t) ** 4 - sp.cos(2 * t),
    sp.sin(t1 + t2 + t3) - (
        sp.sin(t1) * sp.cos(t2 + t3) + sp.cos(t1) * sp.sin(t2 + t3)
    ),
]


@pytest.mark.parametrize("expr", IDENTITIES, ids=range(len(IDENTITIES)))
def test_identities_reduce_to_exactly_zero(expr):
    assert trig_reduce(expr) == 0
    assert sym_equal(expr, 0)


def test_unit_vector_identities():
    k = sp.Matrix([kx, ky, kz])
    R = kl.matrix_from_axis_angle([kx, ky, kz], t)  # symbolic axis: taken as unit
    assert trig_reduce(k.dot(k), unit=[kx, ky, kz]) == 1
    assert sym_equal(R.T * R, sp.eye(3), unit=[kx, ky, kz])
    assert sym_equal(R * k, k, unit=[kx, ky, kz])  # the axis is fixed
    assert sym_equal(R.det(), 1, unit=[kx, ky, kz])
    # without the constraint these are not identities
    assert not sym_equal(R.T * R, sp.eye(3))


def test_two_unit_vectors_at_once():
    expr = (kx**2 + ky**2 + kz**2) * (w**2 + x**2 + y**2 + z**2)
    assert trig_reduce(expr, unit=[[kx, ky, kz], [w, x, y, z]]) == 1
    assert trig_reduce(expr, unit=[kx, ky, kz]) == w**2 + x**2 + y**2 + z**2


def test_quaternion_rotation_is_rodrigues():
    # seed 000: q = (cos θ/2, k sin θ/2) rotates v like Rodrigues' formula; sympy's own
    # Quaternion class does the conjugation q v q*
    q = sp.Quaternion(sp.cos(t / 2), *(sp.sin(t / 2) * e for e in (kx, ky, kz)))
    v = sp.Quaternion(0, x, y, z)
    r = q * v * q.conjugate()
    R = sp.Matrix([r.b, r.c, r.d]).jacobian([x, y, z])
    rodrigues = sp.cos(t) * sp.eye(3) + sp.sin(t) * kl.skew([kx, ky, kz]) + (
        1 - sp.cos(t)) * sp.Matrix([kx, ky, kz]) * sp.Matrix([[kx, ky, kz]])
    assert sym_equal(R, rodrigues, unit=[kx, ky, kz])


PRODUCTS = {
    # three axes, z twice (not adjacent), alpha on two axes, a double angle
    "zyxz": kl.rotz(a) * kl.roty(2 * b) * kl.rotx(a) * kl.rotz(g),
    # a half angle next to its full angle: rescaled to beta = 2 beta_2 first
    "half": kl.rotx(b / 2) * kl.roty(b) * kl.rotz(a),
}


@pytest.mark.parametrize("name", PRODUCTS)
def test_rotation_products_are_orthonormal(name):
    M = PRODUCTS[name]
    assert sp.expand(M.T * M) != sp.eye(3)  # an identity only after the reduction
    assert trig_reduce(M.T * M) == sp.eye(3)
    assert trig_reduce(M.det()) == 1


# --------------------------------------------------------------------------- soundness


SOUNDNESS = {
    # one angle on two axes, a double angle and a half angle of it, lengths
    "product": kl.rotz(a) * kl.roty(2 * b) * kl.rotx(a) * sp.Matrix([l1, l2 * sp.sin(b / 2), 1]),
    # tan and cot rewritten, a denominator left after the reduction
    "rational": sp.Matrix([sp.tan(a / 2) * l1 + l2 / (2 + sp.cos(b)),
                           sp.cot(a) * sp.sin(a + b) / (1 + sp.sin(a) ** 2)]),
}


@pytest.mark.parametrize("name", SOUNDNESS)
def test_reduction_keeps_the_value(name):
    M, rng = SOUNDNESS[name], np.random.default_rng(100)
    R = trig_reduce(M)
    assert R != sp.expand(M)  # the reduction did something
    points = np.column_stack([rng.uniform(0.2, 2.9, (5, 2)), rng.uniform(0.1, 2, (5, 2))])
    same_values(R, M, [a, b, l1, l2], points)


Q = sp.symbols("q1:5", real=True)
CHAINS = {  # a chain and the sum of angles it folds into
    # the typical use: elementary rotations and translations, one angle each; two z
    # rotations in a row fold, offsets of both signs, and equal ones (2, 2) that do not
    "mixed": (kl.transform(kl.rotz(Q[0]), [1, -2, 0]) * kl.transform(kl.rotz(Q[1]), [0, 1, 2])
              * kl.transform(kl.rotx(Q[2]), [-1, 0, 1]) * kl.transform(kl.roty(Q[3]), [2, 2, -1]),
              Q[0] + Q[1]),
    # twists of 45° and 60°: sqrt(2)/2 and sqrt(3)/2 are cofactors, kept, also of folds
    "twists": (kl.dh_transform(theta=Q[0], d=1, a=2, alpha=sp.pi / 4)
               * kl.dh_transform(theta=Q[1], d=0, a=1, alpha=0)
               * kl.dh_transform(theta=Q[2], d=0, a=1, alpha=sp.pi / 3), Q[1] + Q[2]),
}


@pytest.mark.parametrize("name", CHAINS)
def test_simplified_chains_keep_the_value(name):
    T, folded = CHAINS[name]
    S = simplify_rotation(T)
    assert S[:3, :3].has(sp.cos(folded), sp.sin(folded))
    assert sp.count_ops(S) <= sp.count_ops(sp.expand(T))  # never longer than expanded
    same_values(S, T, Q, np.random.default_rng(200).uniform(-np.pi, np.pi, (5, 4)))


def test_folds_that_sympys_tr10i_does_not_make():
    """Why kinlib keeps its own folding (kinlib/_trig_fold.py) rather than sympy's
    ``sympy.simplify.fu.TR10i`` of the expanded entry, which agrees on the PUMA 560, UR5 and
    Panda (sympy 1.14): with four parallel joints TR10i's greedy pairing stops at products
    such as cos(q2) cos(q4) cos(q1 + q3), and it writes sin q + cos q as sqrt(2) sin(q + pi/4)."""
    L = sp.symbols("l1:5", positive=True)
    T = sp.eye(4)
    for qi, li in zip(Q, L, strict=True):
        T = T * kl.dh_transform(theta=qi, d=0, a=li, alpha=0)
    S = simplify_rotation(T)  # the planar 4R arm, typed
    partial = [sum(Q[:k]) for k in range(1, 5)]
    assert S[0, 0] == sp.cos(sum(Q))
    assert S[0, 3] == sum(li * sp.cos(p) for li, p in zip(L, partial, strict=True))
    assert S[1, 3] == sum(li * sp.sin(p) for li, p in zip(L, partial, strict=True))
    p = simplify_rotation(kl.rotz(Q[0]) * sp.Matrix([1, 1, 0]))
    assert p == sp.Matrix([sp.cos(Q[0]) - sp.sin(Q[0]), sp.sin(Q[0]) + sp.cos(Q[0]), 0])


def test_reduce_poly_needs_one_pass():
    _reduce_poly = kl.symbolic._reduce_poly
    # high powers under both kinds of rule; the remainder typed: s**7 = s (1 - c²)³,
    # kz**5 = kz (1 - kx² - ky²)², c**4 stays
    c, s_ = sp.symbols("c s", real=True)
    rules = {s_: 1 - c**2, kz: 1 - kx**2 - ky**2}
    got = _reduce_poly(sp.expand(s_**7 * c**4 + kz**5 * s_**2), rules)
    want = s_ * (1 - c**2) ** 3 * c**4 + kz * (1 - kx**2 - ky**2) ** 2 * (1 - c**2)
    assert sp.expand(got - want) == 0
    assert not [p for p in got.atoms(sp.Pow) if p.base in rules]
    # rules whose right-hand sides hold a replaced symbol would need more passes: refused
    with pytest.raises(kl.KinlibError, match="itself replaced"):
        _reduce_poly(s_**2, {s_: 1 - c**2, c: 1 - s_**2})


def test_non_identities_are_not_zero():
    assert not sym_equal(sp.cos(t), sp.sin(t))
    assert not sym_equal(sp.sin(t / 2), sp.sin(t) / 2)
    assert not sym_equal(kl.rotz(a) * kl.roty(b), kl.roty(b) * kl.rotz(a))
    assert trig_reduce(sp.cos(t1 + t2) - sp.cos(t1) * sp.cos(t2)) != 0


def test_canonical_equal_inputs_give_identical_outputs():
    e1 = sp.cos(t1 + t2)
    e2 = sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2)
    e3 = 1 - 2 * sp.sin((t1 + t2) / 2) ** 2
    assert trig_reduce(e1) == trig_reduce(e2)  # same angle scale: the same polynomial
    assert sym_equal(e1, e3) and sym_equal(e2, e3)  # a half angle: equal after rescaling
    assert simplify_rotation(e2) == simplify_rotation(e3) == sp.cos(t1 + t2)


# --------------------------------------------------------------------------- readable output


def test_planar_2r_fk_is_eq_5_4():
    T = kl.dh_transform(theta=t1, d=0, a=l1, alpha=0) * kl.dh_transform(
        theta=t2, d=0, a=l2, alpha=0)
    S = simplify_rotation(T)
    # seed 001, eq. 5.4, typed here
    expected = sp.Matrix([
        [sp.cos(t1 + t2), -sp.sin(t1 + t2), 0, l1 * sp.cos(t1) + l2 * sp.cos(t1 + t2)],
        [sp.sin(t1 + t2), sp.cos(t1 + t2), 0, l1 * sp.sin(t1) + l2 * sp.sin(t1 + t2)],
        [0, 0, 1, 0],
        [0, 0, 0, 1],
    ])
    assert S == expected  # structurally, not just numerically


def test_puma_position_is_craigs_closed_form():
    # Craig, Introduction to Robotics, eq. 3.14 (PUMA 560, modified DH)
    q = sp.symbols("q1:7", real=True)
    a2, a3, d3, d4 = sp.symbols("a2 a3 d3 d4", real=True)
    rows = [(0, 0, 0), (-sp.pi / 2, 0, 0), (0, a2, d3), (-sp.pi / 2, a3, d4),
            (sp.pi / 2, 0, 0), (-sp.pi / 2, 0, 0)]
    T = sp.eye(4)
    for qi, (alpha, a_, d) in zip(q, rows, strict=False):
        T = T * kl.mdh_transform(theta=qi, d=d, a=a_, alpha=alpha)
    c1, s1 = sp.cos(q[0]), sp.sin(q[0])
    c2, s2 = sp.cos(q[1]), sp.sin(q[1])
    c23, s23 = sp.cos(q[1] + q[2]), sp.sin(q[1] + q[2])
    px = c1 * (a2 * c2 + a3 * c23 - d4 * s23) - d3 * s1
    py = s1 * (a2 * c2 + a3 * c23 - d4 * s23) + d3 * c1
    pz = -a3 * s23 - a2 * s2 - d4 * c23
    assert sym_equal(T[:3, 3], sp.Matrix([px, py, pz]))
    S = simplify_rotation(T[:3, 3])
    assert sym_equal(S, sp.Matrix([px, py, pz]))
    # readable: sums of angles recombined, no longer than the expanded textbook form
    assert S[2].has(sp.sin(q[1] + q[2])) and S[2].has(sp.cos(q[1] + q[2]))
    for got, book in zip(S, (px, py, pz), strict=False):
        assert sp.count_ops(got) <= sp.count_ops(sp.expand(book))


def test_deterministic_across_hash_seeds():
    # another interpreter, with a hash seed other than this one's, prints the same: a half
    # angle next to its full angle (rescaling, dummies, trigsimp, lowering) and folds into
    # cos(alpha + beta) and sin(alpha + 3 beta/2)
    code = (
        "import sympy as sp, kinlib as kl\n"
        "from kinlib.symbolic import simplify_rotation\n"
        "a, b = sp.symbols('alpha beta', real=True)\n"
        "print(sp.srepr(simplify_rotation(kl.rotz(a) * kl.rotz(b) * kl.rotx(b / 2))))\n"
    )
    seed = "2" if os.environ.get("PYTHONHASHSEED") == "1" else "1"
    other = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True, env=dict(os.environ, PYTHONHASHSEED=seed)).stdout
    printed = []
    exec(code, {"print": printed.append})
    assert other.splitlines() == printed


# --------------------------------------------------------------------------- lambdify_batched


def test_lambdify_matches_numeric_rotations_batched():
    f = lambdify_batched([a, b, g], kl.rotz(a) * kl.roty(b) * kl.rotx(g))
    rng = np.random.default_rng(1)
    ang = rng.uniform(-3, 3, (50, 3))
    out = f(ang[:, 0], ang[:, 1], ang[:, 2])
    assert out.shape == (50, 3, 3)
    np.testing.assert_allclose(out, kl.matrix_from_euler(ang, "ZYX"), atol=1e-14)


def test_lambdify_vector_argument_against_robot_fk():
    rob = kl.robots.planar_2r(0.7, 0.4)
    q1, q2 = sp.symbols("q1 q2", real=True)
    T = kl.dh_transform(theta=q1, d=0, a=l1, alpha=0) * kl.dh_transform(
        theta=q2, d=0, a=l2, alpha=0)
    f = lambdify_batched([[q1, q2], l1, l2], T)
    qs = np.random.default_rng(2).uniform(-3, 3, (4, 5, 2))
    out = f(qs, 0.7, 0.4)
    assert out.shape == (4, 5, 4, 4)
    np.testing.assert_allclose(out, rob.fk(qs), atol=1e-14)
    np.testing.assert_array_equal(out[..., 3, :], np.broadcast_to([0, 0, 0, 1.0], (4, 5, 4)))


def test_lambdify_scalar_and_broadcasting():
    f = lambdify_batched([t, l1], l1 * sp.cos(t))
    assert f(0.0, 2.0).shape == ()
    out = f(np.array([0.0, np.pi]), np.array([[1.0], [2.0]]))
    np.testing.assert_allclose(out, [[1.0, -1.0], [2.0, -2.0]], atol=1e-15)
    const = lambdify_batched([t], sp.Matrix([[1, 0], [0, 2]]))
    assert const(np.zeros(3)).shape == (3, 2, 2)
    # a column vector comes out as (..., n), a row vector as (..., 1, n)
    col = lambdify_batched([t], sp.Matrix([sp.cos(t), sp.sin(t), 0]))
    np.testing.assert_allclose(col(np.array([0.0, np.pi / 2])), [[1, 0, 0], [0, 1, 0]], atol=1e-15)
    assert lambdify_batched([t], sp.Matrix([[sp.cos(t), 0]]))(np.zeros(5)).shape == (5, 1, 2)


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda: lambdify_batched([t], l1 * sp.cos(t)), "l1"),
        (lambda: lambdify_batched(t, sp.cos(t)), "args"),
        (lambda: lambdify_batched([t, t], sp.cos(t)), "twice"),
        (lambda: lambdify_batched(["t"], sp.cos(t)), "args[0]"),
        (lambda: lambdify_batched([t], "cos(t)"), "expr"),
        (lambda: lambdify_batched([t], sp.cos(t))(1.0, 2.0), "expected 1 input"),
        (lambda: lambdify_batched([t, l1], sp.cos(t) * l1)(np.zeros(2), np.zeros(3)),
         "do not broadcast"),
        (lambda: lambdify_batched([[t1, t2]], sp.cos(t1))(np.zeros(3)), "(..., 2)"),
        (lambda: lambdify_batched([t], sp.cos(t))("x"), "theta"),
        (lambda: lambdify_batched([t], sp.cos(t))(np.nan), "theta"),
        (lambda: lambdify_batched([t], 1 / sp.sin(t))(np.array([1.0, 0.0])), "not finite"),
        (lambda: lambdify_batched([t], sp.sqrt(t))(-1.0), "not finite"),
        (lambda: trig_reduce(sp.cos(t), unit=[kx]), "unit"),
        (lambda: trig_reduce(sp.cos(t), unit=["kx", "ky"]), "unit"),
        (lambda: trig_reduce(sp.cos(t), unit=[[kx, ky], [ky, kz]]), "two unit vectors"),
        (lambda: trig_reduce(None), "expr"),
        (lambda: sym_equal(sp.eye(3), sp.eye(4)), "cannot compare"),
    ],
)
def test_bad_input(call, words):
    with pytest.raises(kl.KinlibError) as info:
        call()
    assert words in str(info.value), str(info.value)


def test_not_finite_names_the_batch_index():
    f = lambdify_batched([t], sp.Matrix([sp.cos(t), 1 / sp.sin(t)]))
    with pytest.raises(kl.KinlibError, match=r"entry 1 .*\[2\]"):
        f(np.array([1.0, 2.0, 0.0]))


def test_submodules_load_on_first_use():
    code = (
        "import sys, kinlib as kl\n"
        "assert 'sympy' not in sys.modules\n"
        "assert kl.symbolic.sym_equal is not None and 'sympy' in sys.modules\n"
        "assert kl.robots.puma560().dof == 6\n"
        "try:\n    kl.no_such_thing\nexcept AttributeError as e:\n    print(e)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "no attribute 'no_such_thing'" in out.stdout


def test_sum_and_difference_patterns_fold_exactly():
    # rotations about one axis add: Rz(α) Rz(β)ᵀ = Rz(α − β), Rx(α) Rx(β) Rx(γ) = Rx(α + β + γ)
    assert simplify_rotation(kl.rotz(a) * kl.rotz(b).T) == kl.rotz(a - b)
    assert simplify_rotation(kl.rotx(a) * kl.rotx(b) * kl.rotx(g)) == kl.rotx(a + b + g)
    # a product that has no sum in it stays a product
    assert simplify_rotation(kl.rotz(a) * kl.roty(b)) == kl.rotz(a) * kl.roty(b)
    # unequal coefficients must not fold
    e = 2 * sp.cos(a) * sp.cos(b) - sp.sin(a) * sp.sin(b)
    assert sym_equal(simplify_rotation(e), e) and not simplify_rotation(e).has(sp.cos(a + b))


def test_puma_full_transform_orientation():
    # Craig eq. 3.13-3.14 (modified DH PUMA): r13, r23, r33 and the wrist entries, typed here
    q = sp.symbols("q1:7", real=True)
    rows = [(0, 0, 0), (-sp.pi / 2, 0, 0), (0, 1, 0), (-sp.pi / 2, 0, 0),
            (sp.pi / 2, 0, 0), (-sp.pi / 2, 0, 0)]
    T = sp.eye(4)
    for qi, (alpha, a_, d) in zip(q, rows, strict=True):
        T = T * kl.mdh_transform(theta=qi, d=d, a=a_, alpha=alpha)
    S = simplify_rotation(T)
    c = [sp.cos(x) for x in q]
    s_ = [sp.sin(x) for x in q]
    c23, s23 = sp.cos(q[1] + q[2]), sp.sin(q[1] + q[2])
    r33 = s23 * c[3] * s_[4] - c23 * c[4]
    r13 = -c[0] * (c23 * c[3] * s_[4] + s23 * c[4]) - s_[0] * s_[3] * s_[4]
    assert sym_equal(S[2, 2], r33) and sym_equal(S[0, 2], r13)
    assert S[2, 2] == sp.expand(r33)  # folded to the textbook's c23 and s23


def test_half_angles_come_back_as_rodrigues():
    # the quaternion matrix with q = (cos θ/2, u sin θ/2) simplifies to Rodrigues' terms in θ
    q0, q1, q2, q3 = sp.cos(t / 2), kx * sp.sin(t / 2), ky * sp.sin(t / 2), kz * sp.sin(t / 2)
    R = sp.Matrix([
        [1 - 2 * (q2**2 + q3**2), 2 * (q1 * q2 - q0 * q3), 2 * (q0 * q2 + q1 * q3)],
        [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1**2 + q3**2), 2 * (q2 * q3 - q0 * q1)],
        [2 * (q1 * q3 - q0 * q2), 2 * (q0 * q1 + q2 * q3), 1 - 2 * (q1**2 + q2**2)],
    ])
    S = simplify_rotation(R, unit=[kx, ky, kz])
    assert not S.has(t / 2)
    c, s_ = sp.cos(t), sp.sin(t)
    assert sp.expand(S[0, 1] - (kx * ky * (1 - c) - kz * s_)) == 0  # eq. 4.64, typed
    assert sp.expand(S[2, 2] - (kz**2 * (1 - c) + c).subs(kz**2, 1 - kx**2 - ky**2)) == 0
