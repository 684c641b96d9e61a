"""One way to say things (issue 19): Python scalars for one input, ``success`` on every
result, one wrap interval (−π, π], one argument order, named default tolerances.

Values are checked against independent computations (numpy's SVD and determinant, scipy,
closed forms), types against ``type(x) is bool`` / ``float`` (``np.float64`` subclasses
float, so ``isinstance`` would let it through).
"""

import inspect
import json
import math
import pickle

import numpy as np
import pytest
import scipy.linalg
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib import conventions
from kinlib._validate import py_scalar, wrap_angle
from kinlib.grade._grader import GradeResult, not_graded, to_json
from kinlib.kinematics.ik import _Limits
from kinlib.planning.cspace import Circle, planar_2r_cspace
from kinlib.robots import planar_2r, puma560

RNG_SEED = 19


# -- the helper: 0-d -> Python scalar ------------------------------------------------------

@pytest.mark.parametrize("value, expected", [
    (np.True_, True), (np.False_, False), (np.asarray(True), True), (np.float64(0.25), 0.25),
    (np.asarray(2.5), 2.5), (np.float32(0.5), 0.5), (np.int64(3), 3), (np.asarray(7), 7),
])
def test_py_scalar_turns_numpy_scalars_and_0d_arrays_into_python_ones(value, expected):
    out = py_scalar(value)
    assert type(out) is type(expected) and out == expected


def test_py_scalar_leaves_batches_and_python_values_alone():
    a = np.zeros((2, 3))
    assert py_scalar(a) is a
    one = np.ones(1)                      # a batch of one is still a batch
    assert py_scalar(one) is one
    for x in (True, 0.5, 3, "text", None):
        assert py_scalar(x) is x


# -- one wrap interval ---------------------------------------------------------------------

def test_wrap_angle_maps_minus_pi_to_pi_and_keeps_pi():
    assert float(wrap_angle(-np.pi)) == np.pi
    assert float(wrap_angle(np.pi)) == np.pi
    assert float(wrap_angle(-3 * np.pi)) == np.pi and float(wrap_angle(3 * np.pi)) == np.pi
    z = float(wrap_angle(-0.0))
    assert z == 0.0 and math.copysign(1.0, z) == 1.0
    assert np.isnan(wrap_angle(np.nan))


def test_wrap_angle_is_exact_inside_and_a_multiple_of_2pi_away_outside():
    rng = np.random.default_rng(RNG_SEED)
    inside = rng.uniform(-np.pi, np.pi, 2000)
    inside = inside[inside > -np.pi]
    np.testing.assert_array_equal(wrap_angle(inside), inside)       # bit for bit
    x = np.concatenate([rng.uniform(-60, 60, 5000), np.nextafter(np.pi, 10) + [0.0],
                        np.nextafter(-np.pi, -10) + [0.0], 2 * np.pi * np.arange(-5, 6)])
    w = wrap_angle(x)
    assert ((w > -np.pi) & (w <= np.pi)).all()
    turns = (x - w) / (2 * np.pi)
    np.testing.assert_allclose(turns, np.round(turns), atol=1e-12)
    # the same point on the circle, by an independent route (math.remainder: IEEE, [−π, π])
    ref = np.array([math.remainder(v, 2 * math.pi) for v in x])
    np.testing.assert_allclose(np.cos(w), np.cos(ref), atol=1e-12)
    np.testing.assert_allclose(np.sin(w), np.sin(ref), atol=1e-12)


def test_planar_2r_ik_wraps_into_minus_pi_pi_closed_at_pi():
    # a target on the negative x axis with y = −0.0: atan2 gives −π, kinlib returns π
    # stretched (on the rim, beyond it) and folded (l1 ≠ l2, inside the inner circle)
    for l1, l2, x in ((1.0, 1.0, -2.0), (1.0, 0.5, -1.5), (1.0, 0.5, -5.0), (1.0, 0.5, -0.2)):
        sol = kl.planar_2r_ik(x, -0.0, l1, l2)
        assert sol.theta1 == np.pi, (x, sol)
    batch = kl.planar_2r_ik(np.array([-2.0, 1.0]), np.array([-0.0, 1.0]), 1.0, 1.0)
    assert batch.theta1[0] == np.pi
    rng = np.random.default_rng(RNG_SEED)
    r, phi = rng.uniform(0.05, 1.95, 3000), rng.uniform(-np.pi, np.pi, 3000)
    x, y = r * np.cos(phi), r * np.sin(phi)
    for elbow in ("up", "down"):
        sol = kl.planar_2r_ik(x, y, 1.0, 1.0, elbow=elbow)
        for t in (sol.theta1, sol.theta2):
            assert ((t > -np.pi) & (t <= np.pi)).all()
        tip = kl.planar_2r_fk(sol.theta1, sol.theta2, 1.0, 1.0)[:, :2, 3]
        np.testing.assert_allclose(tip, np.stack([x, y], -1), atol=1e-9)


def test_euler_and_ik_wrap_the_same_way():
    angles = kl.euler_from_matrix(kl.rotz(np.pi), "ZYX")
    assert angles[0] == np.pi                                 # not −π
    limits = _Limits(planar_2r(1.0, 1.0))                     # two continuous joints
    np.testing.assert_array_equal(limits.project(np.array([-np.pi, np.pi])), [np.pi, np.pi])
    q = limits.project(np.array([3 * np.pi / 2, -7.0]))
    np.testing.assert_allclose(q, [-np.pi / 2, 2 * np.pi - 7.0], atol=1e-15)


# -- predicates: bool for one input, a bool array for a batch ------------------------------

def _jacobians(n=40, with_theta2=False):
    rng = np.random.default_rng(RNG_SEED)
    t2 = np.concatenate([rng.uniform(-np.pi, np.pi, n - 4), [0.0, np.pi, 1e-9, 1e-3]])
    J = kl.planar_2r_jacobian(rng.uniform(-np.pi, np.pi, n), t2, 1.0, 0.7)[:, :2]
    return (J, t2) if with_theta2 else J


def _one_and_many():
    rng = np.random.default_rng(RNG_SEED)
    Rs = Rotation.random(6, random_state=RNG_SEED).as_matrix()
    Rs[1] = np.diag([1.0, 1.0, -1.0])                        # a reflection
    Rs[2] = kl.matrix_from_euler([0.3, np.pi / 2, 0.2], "ZYX")  # gimbal lock
    angles = rng.uniform(-np.pi, np.pi, (6, 3))
    angles[0, 1] = np.pi / 2
    J = _jacobians()
    return [
        ("is_rotation", lambda x: kl.is_rotation(x), Rs),
        ("euler_gimbal_lock", lambda x: kl.euler_gimbal_lock(x, "ZYX"),
         np.stack([r for r in Rs if kl.is_rotation(r)])),
        ("is_near_singular", lambda x: kl.is_near_singular(x), J),
        ("euler_rates_singular", lambda x: kl.euler_rates_singular(x, "ZYX"), angles),
    ]


@pytest.mark.parametrize("name, f, batch", _one_and_many(), ids=lambda v: v
                         if isinstance(v, str) else "")
def test_predicates_return_python_bool_for_one_and_bool_array_for_a_batch(name, f, batch):
    many = f(batch)
    assert isinstance(many, np.ndarray) and many.dtype == bool and many.shape == batch.shape[:1]
    assert many.any() and not many.all(), f"{name}: the batch should mix True and False"
    for k, item in enumerate(batch):
        one = f(item)
        assert type(one) is bool and one == many[k]
    grid = f(batch[:4].reshape((2, 2) + batch.shape[1:]))
    assert grid.shape == (2, 2) and grid.dtype == bool


def test_predicate_values_against_independent_computations():
    J = _jacobians()
    s = np.array([scipy.linalg.svdvals(j) for j in J])
    np.testing.assert_array_equal(kl.is_near_singular(J), s[:, -1] < 1e-6 * s[:, 0])
    R = Rotation.random(50, random_state=RNG_SEED).as_matrix()
    assert kl.is_rotation(R).all()
    assert not kl.is_rotation(R * np.array([1.0, 1.0, -1.0])).any()   # det −1


@pytest.mark.parametrize("seq", ["ZYX", "xyz", "ZYZ", "yxy"])
def test_gimbal_lock_and_singular_rates_agree_under_the_default_tolerance(seq):
    """|det E| is the sine of the middle angle's distance to lock: one tolerance for both."""
    proper = seq[0].lower() == seq[2].lower()
    lock = 0.0 if proper else np.pi / 2
    for offset, locked in ((0.0, True), (1e-8, True), (3e-7, True), (1e-4, False),
                           (0.3, False)):
        angles = [0.4, lock + offset, -0.7]
        R = kl.matrix_from_euler(angles, seq)
        assert kl.euler_gimbal_lock(R, seq) is locked, offset
        assert kl.euler_rates_singular(angles, seq) is locked, offset
        # the determinant's closed form: sin of the distance to lock
        det = np.linalg.det(kl.euler_rate_matrix(angles, seq))
        assert abs(det) == pytest.approx(abs(np.sin(offset)), abs=1e-15)


# -- scalar-valued functions: float for one input, an array for a batch -------------------

def test_scalar_functions_return_python_float_for_one_and_arrays_for_a_batch():
    J, t2 = _jacobians(with_theta2=True)
    w, c = kl.manipulability(J), kl.condition_number(J)
    assert w.shape == c.shape == (len(J),)
    # independent: seed 001's closed form |l1 l2 sin θ2| and numpy's 2-norm condition number
    np.testing.assert_allclose(w, 1.0 * 0.7 * np.abs(np.sin(t2)), rtol=1e-9, atol=1e-15)
    finite = np.isfinite(c)
    np.testing.assert_allclose(c[finite], np.linalg.cond(J[finite]), rtol=1e-9)
    for k in (0, 5, len(J) - 4):
        one_w, one_c = kl.manipulability(J[k]), kl.condition_number(J[k])
        assert type(one_w) is float and one_w == w[k]
        assert type(one_c) is float and (one_c == c[k] or (math.isinf(one_c) and
                                                           math.isinf(c[k])))
    assert kl.condition_number(np.zeros((2, 2))) == math.inf
    assert type(kl.manipulability(np.zeros((6, 2)))) is float          # m > n: 0.0
    m = kl.planar_2r_metric([0.3, 0.4], [0.1, -0.2], 1.0, 0.7)
    J2 = kl.planar_2r_jacobian(0.3, 0.4, 1.0, 0.7)[:2]
    assert type(m) is float and m == pytest.approx(np.linalg.norm(J2 @ [0.1, -0.2]), abs=1e-15)
    assert kl.planar_2r_metric([[0.3, 0.4]] * 3, [0.1, -0.2], 1.0, 0.7).shape == (3,)


def test_angles_of_axis_angle_and_screws_are_python_floats_for_one_input():
    R = Rotation.random(5, random_state=RNG_SEED).as_matrix()
    _, angle = kl.axis_angle_from_matrix(R[0])
    assert type(angle) is float
    assert angle == pytest.approx(np.linalg.norm(Rotation.from_matrix(R[0]).as_rotvec()))
    assert kl.axis_angle_from_matrix(R)[1].shape == (5,)
    assert type(kl.axis_angle_from_quat([1.0, 0.0, 0.0, 0.0])[1]) is float
    np.testing.assert_allclose(kl.log_so3(R[0]), Rotation.from_matrix(R[0]).as_rotvec(),
                               atol=1e-12)
    T = kl.transform(kl.rotz(np.pi / 2), [1.0, -1.0, 0.5])
    _, _, theta, d = kl.screw_from_dual_quat(kl.dual_quat_from_transform(T))
    assert type(theta) is float and type(d) is float
    assert theta == pytest.approx(np.pi / 2) and d == pytest.approx(0.5)
    dq = kl.dual_quat_from_transform(np.stack([T, T]))
    assert kl.screw_from_dual_quat(dq)[2].shape == (2,)


# -- results: `success` everywhere ---------------------------------------------------------

def test_planar_2r_ik_success_and_types():
    sol = kl.planar_2r_ik(1.0, 1.0, 1.0, 1.0, elbow="down")
    assert type(sol.theta1) is float and type(sol.theta2) is float and sol.success is True
    assert not hasattr(sol, "reachable") and sol._fields == ("theta1", "theta2", "success")
    t1, t2, ok = kl.planar_2r_ik(3.0, 0.0, 1.0, 1.0)
    assert ok is False and (t1, t2) == (0.0, 0.0)           # stretched towards it
    x = np.array([[1.0, 3.0], [0.5, 0.0]])
    many = kl.planar_2r_ik(x, 0.2, 1.0, 1.0)
    assert many.success.dtype == bool and many.success.tolist() == [[True, False],
                                                                    [True, True]]
    assert many.theta1.shape == many.theta2.shape == (2, 2)
    # a batch from the lengths alone is a batch too
    assert kl.planar_2r_ik(1.0, 0.0, [0.5, 2.0], 1.0).success.tolist() == [True, True]
    # the annulus, by the law of cosines (independent of kinlib's half-angle form)
    rng = np.random.default_rng(RNG_SEED)
    p = rng.uniform(-2.5, 2.5, (500, 2))
    r = np.hypot(p[:, 0], p[:, 1])
    inside = (r > 0.3 + 1e-9) & (r < 1.7 - 1e-9)
    outside = (r < 0.3 - 1e-9) | (r > 1.7 + 1e-9)
    ok = kl.planar_2r_ik(p[:, 0], p[:, 1], 1.0, 0.7).success
    assert ok[inside].all() and not ok[outside].any()


def test_plan_and_cost_to_go_carry_success():
    grid = planar_2r_cspace(1.0, 1.0, [Circle((0.0, 1.5), 0.3)], n=32)
    plan = kl.astar(grid, [0.0, 0.0], [np.pi, 0.0])
    assert plan.success is True and type(plan.cost) is float
    blocked_goal = grid.q_of(np.argwhere(grid.occupied)[0])
    fail = kl.astar(grid, [0.0, 0.0], blocked_goal)
    assert fail.success is False and "occupied" in fail.message
    ctg = kl.cost_to_go(grid, [0.0, 0.0])
    assert ctg.success is True
    cost, step = ctg                                  # still unpacks as before
    assert cost.shape == grid.shape and step.shape == grid.shape + (2,)
    none = kl.cost_to_go(grid, blocked_goal)
    assert none.success is False and np.isinf(none.cost).all()


def test_grade_result_is_a_dict_with_success_and_to_json():
    r = not_graded("sub/a.ipynb", "01_rotations", "not a notebook", max_score=38.0)
    assert isinstance(r, dict) and isinstance(r, GradeResult)
    assert r.success is False and r["graded"] is False and r["max_score"] == 38.0
    assert "success" not in r                          # a property: the JSON is unchanged
    assert json.loads(r.to_json()) == dict(r)
    assert r.to_json() == json.dumps(dict(r), allow_nan=False, default=str) == to_json(r)
    r["graded"] = True
    assert r.success is True
    back = pickle.loads(pickle.dumps(r))
    assert type(back) is GradeResult and back == r and back.success
    r["score"] = float("nan")
    with pytest.raises(ValueError):
        r.to_json()                                    # NaN is refused, as before


# -- argument order -------------------------------------------------------------------------

@pytest.mark.parametrize("f, first", [(kl.check_rotation, "R"), (kl.check_transform, "T")])
def test_checkers_take_value_then_name_and_a_keyword_only_tol(f, first):
    params = inspect.signature(f).parameters
    assert list(params) == [first, "name", "tol"]
    assert params["name"].default == first
    assert params["tol"].kind is inspect.Parameter.KEYWORD_ONLY
    assert params["tol"].default is conventions.ROTATION_TOL
    bad = 2 * np.eye(3) if first == "R" else np.diag([2.0, 2.0, 2.0, 1.0])
    with pytest.raises(kl.KinlibError, match=r"^M_ee"):
        f(bad, "M_ee")
    with pytest.raises(TypeError):
        f(np.eye(3 if first == "R" else 4), "X", 1e-6)  # tol is not positional


def test_robot_functions_take_q_then_link_then_seq():
    for f in (kl.Robot.fk, kl.Robot.jacobian, kl.Robot.fk_and_jacobian,
              kl.Robot.analytic_jacobian):
        assert list(inspect.signature(f).parameters)[1:3] == ["q", "link"], f
    assert list(inspect.signature(kl.Robot.analytic_jacobian).parameters)[1:4] == \
        ["q", "link", "seq"]
    from kinlib.kinematics.analytic import analytic_jacobian
    assert list(inspect.signature(analytic_jacobian).parameters)[:4] == \
        ["robot", "q", "link", "seq"]
    robot = puma560()
    q = robot.poses["ready"]
    np.testing.assert_array_equal(robot.analytic_jacobian(q, "link6", "xyz"),
                                  robot.analytic_jacobian(q, seq="xyz"))


# -- default tolerances ---------------------------------------------------------------------

def _public_callables():
    for name in kl.__all__:
        obj = getattr(kl, name)
        if inspect.isclass(obj):
            for meth_name, meth in vars(obj).items():
                if not meth_name.startswith("_") and callable(meth):
                    yield f"{name}.{meth_name}", meth
        elif callable(obj):
            yield name, obj
    from kinlib.kinematics import analytic
    yield "analytic.analytic_jacobian", analytic.analytic_jacobian


EXPECTED = {
    "is_rotation": "ROTATION_TOL", "check_rotation": "ROTATION_TOL",
    "check_transform": "ROTATION_TOL", "euler_gimbal_lock": "GIMBAL_TOL",
    "euler_rates_singular": "GIMBAL_TOL", "analytic.analytic_jacobian": "GIMBAL_TOL",
    "Robot.analytic_jacobian": "GIMBAL_TOL", "euler_from_matrix": "ROUNDING_TOL",
    "is_near_singular": "SINGULAR_TOL", "vee": "SKEW_TOL", "vee_se3": "SKEW_TOL",
    "angular_velocity": "SKEW_TOL", "Robot.check_limits": "LIMIT_TOL",
    "Robot.ik": ("IK_POSITION_TOL", "IK_ROTATION_TOL"),
}


def test_every_public_tol_default_is_a_named_constant_of_conventions():
    constants = {name: getattr(conventions, name) for name in conventions.DEFAULT_TOLERANCES}
    found = {}
    for name, f in _public_callables():
        try:
            params = inspect.signature(f).parameters.values()
        except (TypeError, ValueError):
            continue
        for p in params:
            if p.name.startswith("tol") and p.default is not inspect.Parameter.empty:
                # identity, not equality: a literal 1e-6 typed elsewhere is another object
                assert any(p.default is c for c in constants.values()), (name, p.name)
                found.setdefault(name, []).append(p.default)
    assert set(found) == set(EXPECTED), set(found) ^ set(EXPECTED)
    for name, want in EXPECTED.items():
        want = want if isinstance(want, tuple) else (want,)
        assert found[name] == [constants[w] for w in want], name
    # every constant is some public function's default, and the docstring explains each
    used = {w for v in EXPECTED.values() for w in (v if isinstance(v, tuple) else (v,))}
    assert used == set(constants)
    for name in constants:
        assert f":data:`{name}`" in conventions.__doc__
    assert dict(conventions.DEFAULT_TOLERANCES) == constants
    with pytest.raises(TypeError):
        conventions.DEFAULT_TOLERANCES["ROTATION_TOL"] = 1.0   # no global mutable state


def test_the_tolerances_mean_what_their_docstrings_say():
    # ROTATION_TOL: a matrix 10x inside passes, 10x outside fails
    eps = conventions.ROTATION_TOL
    assert kl.is_rotation((1 + eps / 10) * np.eye(3))
    assert not kl.is_rotation((1 + 10 * eps) * np.eye(3))
    # SINGULAR_TOL: σ₂/σ₁ just below and above it
    s = conventions.SINGULAR_TOL
    assert kl.is_near_singular(np.diag([1.0, 0.5 * s]))
    assert not kl.is_near_singular(np.diag([1.0, 2.0 * s]))
    # SKEW_TOL: vee accepts a skew matrix with asymmetry below it, refuses above
    S = kl.skew([1.0, 2.0, 3.0])
    kl.vee(S + np.diag([0.0, 0.0, 0.5 * conventions.SKEW_TOL]))
    with pytest.raises(kl.KinlibError, match="skew"):
        kl.vee(S + np.diag([0.0, 0.0, 10.0 * conventions.SKEW_TOL]))
    # LIMIT_TOL: the slack of check_limits, in radians
    robot = puma560()
    lo = robot.limits[:, 0].copy()
    robot.check_limits(lo - 0.5 * conventions.LIMIT_TOL)
    with pytest.raises(kl.KinlibError):
        robot.check_limits(lo - 10 * conventions.LIMIT_TOL)
