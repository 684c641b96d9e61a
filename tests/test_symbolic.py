"""Symbolic input: the elementary constructors given sympy expressions return sympy matrices
that agree with the numeric results, and sympy proves the textbook identities about them.
Also: ``import kinlib`` itself must not import sympy, matplotlib or meshcat.

Expected symbolic matrices are typed here from the textbook; the numeric comparisons are
between kinlib's two independent code paths (sympy and numpy) and textbook matrices.
"""

import subprocess
import sys

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import kinlib as kl

# --------------------------------------------------------------------------- symbols, helpers

a, b, g, q, th, s = sp.symbols("alpha beta gamma q theta s", real=True)
x, y, z = sp.symbols("x y z", real=True)
s1, s2, s3 = sp.symbols("s1 s2 s3", real=True)
ux, uy, uz = sp.symbols("u_x u_y u_z", real=True)


def sym_rx(t):
    """R_x, R_y, R_z typed from the textbook, as sympy matrices."""
    return sp.Matrix([[1, 0, 0], [0, sp.cos(t), -sp.sin(t)], [0, sp.sin(t), sp.cos(t)]])


def sym_ry(t):
    return sp.Matrix([[sp.cos(t), 0, sp.sin(t)], [0, 1, 0], [-sp.sin(t), 0, sp.cos(t)]])


def sym_rz(t):
    return sp.Matrix([[sp.cos(t), -sp.sin(t), 0], [sp.sin(t), sp.cos(t), 0], [0, 0, 1]])


def is_zero_matrix(M):
    return sp.simplify(M) == sp.zeros(*M.shape)


def numeric(M, symbols, values):
    """Evaluate a sympy matrix at numbers via lambdify."""
    return np.array(sp.lambdify(symbols, M, "numpy")(*values), dtype=float)


angles = st.floats(-2 * np.pi, 2 * np.pi, allow_nan=False)
small = st.floats(-3.0, 3.0, allow_nan=False)

# The symbolic matrices are built (and lambdified) once.
ROT = {name: getattr(kl, name)(q) for name in ("rotx", "roty", "rotz")}
ROT_F = {name: sp.lambdify([q], M, "numpy") for name, M in ROT.items()}
EULER_SEQS = ["ZYX", "XYZ", "ZYZ", "xyz", "zxz", "YXY"]
EULER = {seq: kl.matrix_from_euler([a, b, g], seq) for seq in EULER_SEQS}
EULER_F = {seq: sp.lambdify([a, b, g], M, "numpy") for seq, M in EULER.items()}
AXIS_ANGLE = kl.matrix_from_axis_angle([ux, uy, uz], th)
AXIS_ANGLE_F = sp.lambdify([ux, uy, uz, th], AXIS_ANGLE, "numpy")
CAYLEY = kl.matrix_from_cayley([s1, s2, s3])
CAYLEY_F = sp.lambdify([s1, s2, s3], CAYLEY, "numpy")
SKEW = kl.skew([x, y, z])
TRANSFORM = kl.transform(kl.rotz(q), [x, y, z])
TRANSFORM_INV = kl.transform_inverse(TRANSFORM)
TRANSFORM_INV_F = sp.lambdify([q, x, y, z], TRANSFORM_INV, "numpy")

TOL = 1e-12


# --------------------------------------------------------------------------- types


def test_constructors_return_sympy_matrices():
    cases = {
        "rotx": (ROT["rotx"], (3, 3)),
        "roty": (ROT["roty"], (3, 3)),
        "rotz": (ROT["rotz"], (3, 3)),
        "skew": (SKEW, (3, 3)),
        "matrix_from_axis_angle": (AXIS_ANGLE, (3, 3)),
        "matrix_from_axis_angle numeric axis": (kl.matrix_from_axis_angle([0, 0, 1], th), (3, 3)),
        "matrix_from_euler": (EULER["ZYX"], (3, 3)),
        "matrix_from_euler mixed": (kl.matrix_from_euler([a, 0.2, 0.3], "xyz"), (3, 3)),
        "transform": (TRANSFORM, (4, 4)),
        "transform numeric R": (kl.transform(np.eye(3), [x, 0, 0]), (4, 4)),
        "transform only R": (kl.transform(kl.rotx(q)), (4, 4)),
        "transform_inverse": (TRANSFORM_INV, (4, 4)),
        "matrix_from_cayley": (CAYLEY, (3, 3)),
    }
    for name, (M, shape) in cases.items():
        assert isinstance(M, sp.MatrixBase), name
        assert M.shape == shape, name
        assert M.free_symbols, name  # really symbolic, not numbers wrapped in a Matrix


def test_symbolic_rotations_are_the_textbook_matrices():
    assert ROT["rotx"] == sym_rx(q)
    assert ROT["roty"] == sym_ry(q)
    assert ROT["rotz"] == sym_rz(q)
    assert SKEW == sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    assert SKEW * sp.Matrix([1, 2, 3]) == sp.Matrix([x, y, z]).cross(sp.Matrix([1, 2, 3]))


# --------------------------------------------------------------------------- numbers in


@settings(max_examples=30, deadline=None)
@given(t=angles)
def test_elementary_rotations_substituted(t):
    c, sn = np.cos(t), np.sin(t)
    typed = {
        "rotx": [[1, 0, 0], [0, c, -sn], [0, sn, c]],
        "roty": [[c, 0, sn], [0, 1, 0], [-sn, 0, c]],
        "rotz": [[c, -sn, 0], [sn, c, 0], [0, 0, 1]],
    }
    for name, f in ROT_F.items():
        got = np.array(f(t), dtype=float)
        np.testing.assert_allclose(got, getattr(kl, name)(t), rtol=0, atol=TOL)
        np.testing.assert_allclose(got, typed[name], rtol=0, atol=TOL)
    # .subs + evalf gives the same as lambdify
    got = np.array(ROT["rotx"].subs(q, t).evalf(), dtype=float)
    np.testing.assert_allclose(got, typed["rotx"], rtol=0, atol=TOL)


@settings(max_examples=30, deadline=None)
@given(al=angles, be=angles, ga=angles)
def test_euler_substituted(al, be, ga):
    for seq, f in EULER_F.items():
        got = np.array(f(al, be, ga), dtype=float)
        np.testing.assert_allclose(got, kl.matrix_from_euler([al, be, ga], seq), rtol=0, atol=TOL)
    # and the ZYX one against scipy (intrinsic "ZYX" in scipy's upper-case convention)
    np.testing.assert_allclose(
        np.array(EULER_F["ZYX"](al, be, ga), dtype=float),
        Rotation.from_euler("ZYX", [al, be, ga]).as_matrix(),
        rtol=0,
        atol=TOL,
    )


@settings(max_examples=30, deadline=None)
@given(
    u=st.tuples(small, small, small).filter(lambda v: np.linalg.norm(v) > 1e-2).map(np.array),
    t=angles,
)
def test_axis_angle_substituted(u, t):
    u = u / np.linalg.norm(u)  # a symbolic axis is taken as unit: substitute a unit vector
    got = np.array(AXIS_ANGLE_F(*u, t), dtype=float)
    np.testing.assert_allclose(got, kl.matrix_from_axis_angle(u, t), rtol=0, atol=TOL)
    np.testing.assert_allclose(got, Rotation.from_rotvec(t * u).as_matrix(), rtol=0, atol=TOL)


def test_axis_angle_with_a_numeric_axis_is_normalised_exactly():
    R = kl.matrix_from_axis_angle([1, 2, 2], th)  # |(1, 2, 2)| = 3
    assert R.free_symbols == {th}
    for t in (0.3, -2.0, np.pi):
        got = np.array(R.subs(th, t).evalf(), dtype=float)
        expected = Rotation.from_rotvec(t * np.array([1.0, 2.0, 2.0]) / 3.0).as_matrix()
        np.testing.assert_allclose(got, expected, rtol=0, atol=TOL)


@settings(max_examples=30, deadline=None)
@given(v=st.tuples(small, small, small))
def test_cayley_and_skew_substituted(v):
    got = np.array(CAYLEY_F(*v), dtype=float)
    np.testing.assert_allclose(got, kl.matrix_from_cayley(v), rtol=0, atol=TOL)
    S = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    np.testing.assert_allclose(got, np.linalg.solve(np.eye(3) - S, np.eye(3) + S), atol=1e-10)
    np.testing.assert_allclose(
        np.array(SKEW.subs(dict(zip((x, y, z), v, strict=True))), dtype=float), S, atol=0
    )


@settings(max_examples=30, deadline=None)
@given(t=angles, p=st.tuples(small, small, small))
def test_transform_and_inverse_substituted(t, p):
    T_num = kl.transform(kl.rotz(t), p)
    np.testing.assert_allclose(
        np.array(TRANSFORM.subs({q: t, x: p[0], y: p[1], z: p[2]}).evalf(), dtype=float),
        T_num,
        rtol=0,
        atol=TOL,
    )
    got = np.array(TRANSFORM_INV_F(t, *p), dtype=float)
    np.testing.assert_allclose(got, np.linalg.inv(T_num), rtol=0, atol=TOL)
    np.testing.assert_allclose(got, kl.transform_inverse(T_num), rtol=0, atol=TOL)


# --------------------------------------------------------------------------- identities


def test_sympy_proves_orthonormality():
    for R in (ROT["rotx"], EULER["ZYX"]):
        assert is_zero_matrix(R.T * R - sp.eye(3))
        assert sp.simplify(R.det()) == 1


def test_sympy_proves_det_one():
    for R in (ROT["roty"], ROT["rotz"], kl.matrix_from_axis_angle([1, 2, 2], th)):
        assert sp.simplify(R.det()) == 1
    R = kl.matrix_from_axis_angle([1, 2, 2], th)
    assert is_zero_matrix(R.T * R - sp.eye(3))
    assert sp.simplify(CAYLEY.det()) == 1
    assert is_zero_matrix(CAYLEY.T * CAYLEY - sp.eye(3))


def test_gimbal_lock_only_alpha_plus_gamma_matters():
    # seed 000 "Gimbal Lock": at β = π/2, R_x(α) R_y(β) R_z(γ) depends on α + γ only.
    R = sp.trigsimp(kl.matrix_from_euler([a, sp.pi / 2, s - a], "XYZ"))  # γ = s − α
    assert all(a not in e.free_symbols for e in R)
    expected = sp.Matrix([[0, 0, 1], [sp.sin(s), sp.cos(s), 0], [-sp.cos(s), sp.sin(s), 0]])
    assert is_zero_matrix(R - expected)
    # while away from the lock α and γ are separate degrees of freedom
    R = sp.trigsimp(kl.matrix_from_euler([a, sp.pi / 3, s - a], "XYZ"))
    assert any(a in e.free_symbols for e in R)


def test_rodrigues_about_z_is_rotz():
    R = kl.matrix_from_axis_angle([0, 0, 1], th)
    assert is_zero_matrix(R - sym_rz(th))
    assert is_zero_matrix(R - kl.rotz(th))
    R = kl.matrix_from_axis_angle([0, 0, 5], th)  # normalised exactly
    assert is_zero_matrix(R - sym_rz(th))


def test_zyx_euler_is_the_product_of_elementary_rotations():
    assert is_zero_matrix(EULER["ZYX"] - sym_rz(a) * sym_ry(b) * sym_rx(g))
    assert is_zero_matrix(EULER["ZYZ"] - sym_rz(a) * sym_ry(b) * sym_rz(g))
    assert is_zero_matrix(EULER["xyz"] - sym_rz(g) * sym_ry(b) * sym_rx(a))
    # fixed angles xyz (γ, β, α) are the same matrix as Euler ZYX (α, β, γ)
    assert is_zero_matrix(EULER["ZYX"] - kl.matrix_from_euler([g, b, a], "xyz"))


def test_sympy_proves_the_closed_form_inverse():
    assert is_zero_matrix(TRANSFORM_INV * TRANSFORM - sp.eye(4))
    assert is_zero_matrix(TRANSFORM * TRANSFORM_INV - sp.eye(4))


# --------------------------------------------------------------------------- lazy imports


@pytest.mark.parametrize("code", ["import kinlib", "import kinlib; kinlib.rotx(0.3)"])
def test_import_kinlib_does_not_import_heavy_modules(code):
    heavy = ["sympy", "matplotlib", "meshcat", "ipywidgets"]
    script = (
        f"{code}\nimport sys\n"
        f"loaded = [m for m in {heavy!r} if m in sys.modules]\n"
        "print(','.join(loaded))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, timeout=60
    )
    assert out.stdout.strip() == "", f"`{code}` imported: {out.stdout.strip()}"


def test_symbolic_input_does_import_sympy_lazily():
    # the check above is meaningful: the same subprocess sees sympy once it is used
    script = (
        "import sys, kinlib\nassert 'sympy' not in sys.modules\n"
        "import sympy\nkinlib.rotx(sympy.Symbol('q'))\n"
        "print('kinlib.symbolic._sym' in sys.modules)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, timeout=60
    )
    assert out.stdout.strip() == "True"


def test_functions_of_time_are_symbolic_input():
    """``Function("theta")(t)`` has a class made on the fly (``__module__`` is None)."""
    t = sp.symbols("t", real=True)
    th = sp.Function("theta")(t)
    R = kl.rotz(th)
    assert isinstance(R, sp.Matrix) and R[0, 1] == -sp.sin(th)
    E = kl.matrix_from_euler([th, 0, th**2], "ZYX")
    assert E.has(th) and isinstance(E, sp.Matrix)
    # Ṙ Rᵀ for a rotation about z is S(θ̇ z): vee by hand (the entries) and by kl.vee
    W = (R.diff(t) * R.T).applyfunc(sp.simplify)
    assert (W[1, 0], W[0, 2], W[2, 1]) == (th.diff(t), 0, 0)
    assert kl.vee(W) == sp.Matrix([0, 0, th.diff(t)])


def test_symbolic_vee_inverts_skew_and_rejects_non_skew():
    a, b, c = sp.symbols("a b c", real=True)
    assert kl.vee(kl.skew([a, b, c])) == sp.Matrix([a, b, c])
    al = sp.symbols("alpha", real=True)
    R = kl.rotx(al)
    S = (R * kl.skew([a, b, c]) * R.T)  # skew already as a polynomial: S + Sᵀ expands to 0
    assert sp.simplify(kl.vee(S) - R * sp.Matrix([a, b, c])) == sp.zeros(3, 1)
    with pytest.raises(kl.KinlibError, match="skew-symmetric"):
        kl.vee(sp.Matrix([[0, a, 0], [a, 0, 0], [0, 0, 0]]))
    with pytest.raises(kl.KinlibError, match="3×3"):
        kl.vee(sp.Matrix([[0, a], [-a, 0]]))


def test_symbolic_vee_proves_skewness_by_trig_reduce_only():
    # Ṙ Rᵀ of R = Rz(α) Ry(β) is skew only after sin² + cos² = 1: vee proves it with
    # trig_reduce (expand alone does not), and reads off ω = α̇ z + β̇ Rz(α) y (typed)
    t = sp.symbols("t", real=True)
    al, be = sp.Function("alpha")(t), sp.Function("beta")(t)
    ad, bd, A, B = sp.symbols("alpha_dot beta_dot alpha beta", real=True)
    R = kl.rotz(al) * kl.roty(be)
    W = (R.diff(t) * R.T).subs({al.diff(t): ad, be.diff(t): bd}).subs({al: A, be: B})
    assert sp.expand(W + W.T) != sp.zeros(3, 3)
    omega = sp.Matrix([-sp.sin(A) * bd, sp.cos(A) * bd, ad])
    assert sp.expand(kl.vee(W) - omega) != sp.zeros(3, 1)  # equal only after the reduction
    assert kl.symbolic.trig_reduce(kl.vee(W) - omega) == sp.zeros(3, 1)
    # skew only under a constraint trig_reduce is not told (a unit axis), or by an identity
    # outside its rules (cosh² - sinh² = 1, which sympy.simplify would find): refused, the
    # entry named, no simplify() search
    kx, ky, kz = sp.symbols("k_x k_y k_z", real=True)
    off_unit = kl.skew([kx, ky, kz]) + (kx**2 + ky**2 + kz**2 - 1) * sp.diag(0, 1, 0)
    assert kl.vee(kl.symbolic.trig_reduce(off_unit, unit=[kx, ky, kz])) == sp.Matrix([kx, ky, kz])
    with pytest.raises(kl.KinlibError, match=r"S\[1, 1\] \+ S\[1, 1\] = .*unit=") as info:
        kl.vee(off_unit)
    assert "k_x**2" in str(info.value)
    hyper = kl.skew([x, y, z])
    hyper[0, 1] = (sp.cosh(x) ** 2 - sp.sinh(x) ** 2) * hyper[0, 1]
    assert sp.simplify(hyper + hyper.T) == sp.zeros(3, 3)
    with pytest.raises(kl.KinlibError, match=r"S\[0, 1\] \+ S\[1, 0\]"):
        kl.vee(hyper)
