"""Bad input to every public kinlib function raises :class:`kinlib.KinlibError`.

Never an IndexError, TypeError, numpy LinAlgError, a plain ValueError, a warning, a NaN
result or a hang; and the message names the argument and says what was expected.

The tables below list each array argument of each public function ("slots") and cross them
with wrong shapes, NaN/inf, and things that are not real numbers at all.
"""

import signal

import numpy as np
import pytest
import sympy as sp

import kinlib as kl

# --------------------------------------------------------------------------- good inputs

_c, _s = np.cos(0.3), np.sin(0.3)
R_OK = np.array([[_c, -_s, 0.0], [_s, _c, 0.0], [0.0, 0.0, 1.0]])  # 0.3 rad about z
Q_OK = np.array([0.9, 0.1, 0.2, 0.3]) / np.linalg.norm([0.9, 0.1, 0.2, 0.3])
V_OK = np.array([1.0, 2.0, 3.0])
T_OK = np.eye(4)
T_OK[:3, :3], T_OK[:3, 3] = R_OK, V_OK
DQ_OK = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.5])  # pure translation by (1, 2, 3)
L_OK, M_OK = np.array([0.0, 0.0, 1.0]), np.array([0.0, -1.0, 0.0])

GOOD = {(3, 3): R_OK, (4,): Q_OK, (3,): V_OK, (4, 4): T_OK, (8,): DQ_OK, (): 0.5,
        (2,): np.array([0.1, 0.2]), (6,): np.array([0.1, -0.2, 0.3, 0.4, 0.5, -0.6])}
S_OK = np.array([[0.0, -3.0, 2.0], [3.0, 0.0, -1.0], [-2.0, 1.0, 0.0]])  # skew([1, 2, 3])


SPECIAL_GOOD = {("vee", "S"): S_OK, ("dual_quat_from_screw", "l"): L_OK,
                ("dual_quat_from_screw", "m"): M_OK,
                ("angular_velocity", "R_dot"): S_OK @ R_OK,  # Ṙ = S(ω) R
                ("vee_se3", "X"): kl.hat_se3([0.1, -0.2, 0.3, 0.4, 0.5, -0.6])}


def good_for(slot):
    return SPECIAL_GOOD.get((slot[0], slot[1]), GOOD[slot[2]])


def shape_text(tail):
    return "(..., " + ", ".join(map(str, tail)) + ")"


# --------------------------------------------------------------------------- the slots

# (function, argument name as in the message, expected trailing shape, call with x in that
# slot and good values elsewhere)
SLOTS = [
    ("rotx", "theta", (), lambda x: kl.rotx(x)),
    ("roty", "theta", (), lambda x: kl.roty(x)),
    ("rotz", "theta", (), lambda x: kl.rotz(x)),
    ("skew", "v", (3,), lambda x: kl.skew(x)),
    ("vee", "S", (3, 3), lambda x: kl.vee(x)),
    ("is_rotation", "R", (3, 3), lambda x: kl.is_rotation(x)),
    ("check_rotation", "R", (3, 3), lambda x: kl.check_rotation(x)),
    ("nearest_rotation", "M", (3, 3), lambda x: kl.nearest_rotation(x)),
    ("matrix_from_euler", "angles", (3,), lambda x: kl.matrix_from_euler(x, "ZYX")),
    ("euler_from_matrix", "R", (3, 3), lambda x: kl.euler_from_matrix(x, "ZYX")),
    ("euler_gimbal_lock", "R", (3, 3), lambda x: kl.euler_gimbal_lock(x, "ZYX")),
    ("matrix_from_axis_angle", "axis", (3,), lambda x: kl.matrix_from_axis_angle(x, 0.5)),
    ("matrix_from_axis_angle", "angle", (), lambda x: kl.matrix_from_axis_angle(V_OK, x)),
    ("axis_angle_from_matrix", "R", (3, 3), lambda x: kl.axis_angle_from_matrix(x)),
    ("rodrigues_rotate", "v", (3,), lambda x: kl.rodrigues_rotate(x, V_OK, 0.5)),
    ("rodrigues_rotate", "axis", (3,), lambda x: kl.rodrigues_rotate(V_OK, x, 0.5)),
    ("rodrigues_rotate", "angle", (), lambda x: kl.rodrigues_rotate(V_OK, V_OK, x)),
    ("exp_so3", "w", (3,), lambda x: kl.exp_so3(x)),
    ("log_so3", "R", (3, 3), lambda x: kl.log_so3(x)),
    ("matrix_from_cayley", "s", (3,), lambda x: kl.matrix_from_cayley(x)),
    ("cayley_from_matrix", "R", (3, 3), lambda x: kl.cayley_from_matrix(x)),
    ("quat_multiply", "p", (4,), lambda x: kl.quat_multiply(x, Q_OK)),
    ("quat_multiply", "q", (4,), lambda x: kl.quat_multiply(Q_OK, x)),
    ("quat_conjugate", "q", (4,), lambda x: kl.quat_conjugate(x)),
    ("quat_inverse", "q", (4,), lambda x: kl.quat_inverse(x)),
    ("quat_normalize", "q", (4,), lambda x: kl.quat_normalize(x)),
    ("quat_rotate", "q", (4,), lambda x: kl.quat_rotate(x, V_OK)),
    ("quat_rotate", "v", (3,), lambda x: kl.quat_rotate(Q_OK, x)),
    ("quat_from_axis_angle", "axis", (3,), lambda x: kl.quat_from_axis_angle(x, 0.5)),
    ("quat_from_axis_angle", "angle", (), lambda x: kl.quat_from_axis_angle(V_OK, x)),
    ("axis_angle_from_quat", "q", (4,), lambda x: kl.axis_angle_from_quat(x)),
    ("matrix_from_quat", "q", (4,), lambda x: kl.matrix_from_quat(x)),
    ("quat_from_matrix", "R", (3, 3), lambda x: kl.quat_from_matrix(x)),
    ("quat_slerp", "q0", (4,), lambda x: kl.quat_slerp(x, Q_OK, 0.5)),
    ("quat_slerp", "q1", (4,), lambda x: kl.quat_slerp(Q_OK, x, 0.5)),
    ("quat_slerp", "t", (), lambda x: kl.quat_slerp(Q_OK, Q_OK, x)),
    ("quat_xyzw_from_wxyz", "q", (4,), lambda x: kl.quat_xyzw_from_wxyz(x)),
    ("quat_wxyz_from_xyzw", "q", (4,), lambda x: kl.quat_wxyz_from_xyzw(x)),
    ("transform", "R", (3, 3), lambda x: kl.transform(x, V_OK)),
    ("transform", "p", (3,), lambda x: kl.transform(R_OK, x)),
    ("check_transform", "T", (4, 4), lambda x: kl.check_transform(x)),
    ("transform_inverse", "T", (4, 4), lambda x: kl.transform_inverse(x)),
    ("transform_points", "T", (4, 4), lambda x: kl.transform_points(x, V_OK)),
    ("transform_points", "P", (3,), lambda x: kl.transform_points(T_OK, x)),
    ("transform_vectors", "T", (4, 4), lambda x: kl.transform_vectors(x, V_OK)),
    ("transform_vectors", "V", (3,), lambda x: kl.transform_vectors(T_OK, x)),
    ("dual_quat_from_transform", "T", (4, 4), lambda x: kl.dual_quat_from_transform(x)),
    ("transform_from_dual_quat", "dq", (8,), lambda x: kl.transform_from_dual_quat(x)),
    ("dual_quat_multiply", "a", (8,), lambda x: kl.dual_quat_multiply(x, DQ_OK)),
    ("dual_quat_multiply", "b", (8,), lambda x: kl.dual_quat_multiply(DQ_OK, x)),
    ("dual_quat_conjugate", "dq", (8,), lambda x: kl.dual_quat_conjugate(x)),
    ("dual_quat_transform_point", "dq", (8,), lambda x: kl.dual_quat_transform_point(x, V_OK)),
    ("dual_quat_transform_point", "p", (3,), lambda x: kl.dual_quat_transform_point(DQ_OK, x)),
    ("screw_from_dual_quat", "dq", (8,), lambda x: kl.screw_from_dual_quat(x)),
    ("dual_quat_from_screw", "l", (3,), lambda x: kl.dual_quat_from_screw(x, M_OK, 0.5, 1.0)),
    ("dual_quat_from_screw", "m", (3,), lambda x: kl.dual_quat_from_screw(L_OK, x, 0.5, 1.0)),
    ("dual_quat_from_screw", "theta", (), lambda x: kl.dual_quat_from_screw(L_OK, M_OK, x, 1.0)),
    ("dual_quat_from_screw", "d", (), lambda x: kl.dual_quat_from_screw(L_OK, M_OK, 0.5, x)),
    ("dual_quat_sclerp", "dq0", (8,), lambda x: kl.dual_quat_sclerp(x, DQ_OK, 0.5)),
    ("dual_quat_sclerp", "dq1", (8,), lambda x: kl.dual_quat_sclerp(DQ_OK, x, 0.5)),
    ("dual_quat_sclerp", "t", (), lambda x: kl.dual_quat_sclerp(DQ_OK, DQ_OK, x)),
    ("dh_transform", "theta", (), lambda x: kl.dh_transform(theta=x, d=0.1, a=0.2, alpha=0.3)),
    ("dh_transform", "d", (), lambda x: kl.dh_transform(theta=0.1, d=x, a=0.2, alpha=0.3)),
    ("dh_transform", "a", (), lambda x: kl.dh_transform(theta=0.1, d=0.1, a=x, alpha=0.3)),
    ("dh_transform", "alpha", (), lambda x: kl.dh_transform(theta=0.1, d=0.1, a=0.2, alpha=x)),
    ("mdh_transform", "theta", (), lambda x: kl.mdh_transform(theta=x, d=0.1, a=0.2, alpha=0.3)),
    ("mdh_transform", "d", (), lambda x: kl.mdh_transform(theta=0.1, d=x, a=0.2, alpha=0.3)),
    ("mdh_transform", "a", (), lambda x: kl.mdh_transform(theta=0.1, d=0.1, a=x, alpha=0.3)),
    ("mdh_transform", "alpha", (), lambda x: kl.mdh_transform(theta=0.1, d=0.1, a=0.2, alpha=x)),
    ("planar_2r_fk", "theta1", (), lambda x: kl.planar_2r_fk(x, 0.2, 1.0, 0.5)),
    ("planar_2r_fk", "theta2", (), lambda x: kl.planar_2r_fk(0.1, x, 1.0, 0.5)),
    ("planar_2r_fk", "l1", (), lambda x: kl.planar_2r_fk(0.1, 0.2, x, 0.5)),
    ("planar_2r_fk", "l2", (), lambda x: kl.planar_2r_fk(0.1, 0.2, 1.0, x)),
    ("planar_2r_jacobian", "theta1", (), lambda x: kl.planar_2r_jacobian(x, 0.2, 1.0, 0.5)),
    ("planar_2r_jacobian", "theta2", (), lambda x: kl.planar_2r_jacobian(0.1, x, 1.0, 0.5)),
    ("planar_2r_jacobian", "l1", (), lambda x: kl.planar_2r_jacobian(0.1, 0.2, x, 0.5)),
    ("planar_2r_jacobian", "l2", (), lambda x: kl.planar_2r_jacobian(0.1, 0.2, 1.0, x)),
    ("planar_2r_ik", "x", (), lambda x: kl.planar_2r_ik(x, 0.2, 1.0, 0.5)),
    ("planar_2r_ik", "y", (), lambda x: kl.planar_2r_ik(0.1, x, 1.0, 0.5)),
    ("planar_2r_ik", "l1", (), lambda x: kl.planar_2r_ik(0.1, 0.2, x, 0.5)),
    ("planar_2r_ik", "l2", (), lambda x: kl.planar_2r_ik(0.1, 0.2, 1.0, x)),
    ("planar_2r_metric", "theta", (2,), lambda x: kl.planar_2r_metric(x, [0.3, -0.4], 1.0, 0.5)),
    ("planar_2r_metric", "dtheta", (2,), lambda x: kl.planar_2r_metric([0.1, 0.2], x, 1.0, 0.5)),
    ("planar_2r_metric", "l1", (), lambda x: kl.planar_2r_metric([0.1, 0.2], [0.3, -0.4], x, 0.5)),
    ("planar_2r_metric", "l2", (), lambda x: kl.planar_2r_metric([0.1, 0.2], [0.3, -0.4], 1.0, x)),
    ("angular_velocity", "R", (3, 3), lambda x: kl.angular_velocity(x, S_OK @ R_OK)),
    ("angular_velocity", "R_dot", (3, 3), lambda x: kl.angular_velocity(R_OK, x)),
    ("rotation_derivative", "R", (3, 3), lambda x: kl.rotation_derivative(x, V_OK)),
    ("rotation_derivative", "omega", (3,), lambda x: kl.rotation_derivative(R_OK, x)),
    ("point_velocity", "R", (3, 3), lambda x: kl.point_velocity(x, V_OK, V_OK, V_OK)),
    ("point_velocity", "p_dot", (3,), lambda x: kl.point_velocity(R_OK, x, V_OK, V_OK)),
    ("point_velocity", "omega", (3,), lambda x: kl.point_velocity(R_OK, V_OK, x, V_OK)),
    ("point_velocity", "p_local", (3,), lambda x: kl.point_velocity(R_OK, V_OK, V_OK, x)),
    ("euler_rate_matrix", "angles", (3,), lambda x: kl.euler_rate_matrix(x, "ZYX")),
    ("euler_rates_singular", "angles", (3,), lambda x: kl.euler_rates_singular(x, "ZYX")),
    ("pose_error", "T", (4, 4), lambda x: kl.pose_error(x, T_OK)),
    ("hat_se3", "xi", (6,), lambda x: kl.hat_se3(x)),
    ("vee_se3", "X", (4, 4), lambda x: kl.vee_se3(x)),
    ("exp_se3", "xi", (6,), lambda x: kl.exp_se3(x)),
    ("exp_se3", "theta", (), lambda x: kl.exp_se3(GOOD[(6,)], x)),
    ("log_se3", "T", (4, 4), lambda x: kl.log_se3(x)),
    ("adjoint", "T", (4, 4), lambda x: kl.adjoint(x)),
    ("pose_error", "T_target", (4, 4), lambda x: kl.pose_error(T_OK, x)),
]
# Public callables whose input is not an array: tested in their own modules
# (load_urdf: tests/test_urdf_errors.py; Robot methods: tests/test_robot.py).
# (planar_2r_cspace, astar, cost_to_go: tests/test_planning.py).
# add_angular_velocities takes stacks (..., n, 3, 3) and the singularity tools and dls_step
# any (..., m, n) matrix: their bad input is tested in tests/test_velocity.py,
# tests/test_singularity.py and tests/test_ik.py; the product-of-exponentials functions take
# a robot or (6, n) screw axes with q of length n: tests/test_poe.py.
NOT_ARRAY_FUNCTIONS = {"load_urdf", "add_angular_velocities", "singular_values",
                       "manipulability", "condition_number", "velocity_ellipsoid",
                       "is_near_singular", "planar_2r_cspace", "astar", "cost_to_go",
                       "dls_step", "screw_axes", "poe_fk", "space_jacobian",
                       "body_jacobian", "prepare_kernels"}

# None means "the default" here
NONE_OK = {("transform", "R"), ("transform", "p"), ("exp_se3", "theta")}
# is_rotation answers False for NaN/inf (documented) instead of raising
NONFINITE_OK = {("is_rotation", "R")}

BAD_SHAPES = {
    (3, 3): [(2,), (3,), (3, 4), (4, 3), (2, 2, 2), ()],
    (4, 4): [(3, 3), (4,), (4, 3), (2, 2, 2), ()],
    (4,): [(3,), (5,), (2, 3), (4, 2), ()],
    (3,): [(2,), (4,), (3, 2), (2, 2, 2), ()],
    (8,): [(7,), (4,), (8, 2), ()],
    (2,): [(3,), (1,), (2, 3), ()],
    (6,): [(3,), (5,), (6, 2), ()],
}


def _ids(slot):
    return f"{slot[0]}-{slot[1]}"


def _params(slot, values):
    return [pytest.param(slot, v, id=f"{_ids(slot)}-{i}") for i, v in enumerate(values)]


def assert_names(msg, slot, prefix):
    """The message starts with the argument's name."""
    assert msg.startswith(prefix), msg


def raises_kinlib(call, x):
    """Call and return the KinlibError message (any other exception fails the test)."""
    with pytest.raises(kl.KinlibError) as info:
        call(x)
    assert isinstance(info.value, ValueError)
    return str(info.value)


@pytest.fixture(autouse=True)
def _no_hang():
    """Fail (instead of hanging) when a single test takes more than 20 s."""

    def alarm(signum, frame):
        raise TimeoutError("more than 20 s: kinlib hangs on this input")

    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, 20.0)
    yield
    signal.setitimer(signal.ITIMER_REAL, 0.0)
    signal.signal(signal.SIGALRM, old)


# --------------------------------------------------------------------------- basics


def test_exception_hierarchy():
    assert issubclass(kl.KinlibError, ValueError)
    assert issubclass(kl.URDFError, kl.KinlibError)


def test_every_public_function_is_in_the_table():
    public = {
        name
        for name in kl.__all__
        if callable(getattr(kl, name)) and not isinstance(getattr(kl, name), type)
    }
    covered = {slot[0] for slot in SLOTS} | NOT_ARRAY_FUNCTIONS
    assert public - covered == set()
    assert covered - public == set()


@pytest.mark.parametrize("slot", SLOTS, ids=_ids)
def test_the_good_inputs_are_good(slot):
    # the baseline every bad case modifies: the call succeeds and gives finite numbers
    out = slot[3](good_for(slot))
    for part in out if isinstance(out, tuple) else (out,):
        assert np.all(np.isfinite(part))


# --------------------------------------------------------------------------- wrong shapes

SHAPE_CASES = [
    p for slot in SLOTS if slot[2] for p in _params(slot, BAD_SHAPES[slot[2]])
]


@pytest.mark.parametrize(("slot", "shape"), SHAPE_CASES)
def test_wrong_shapes(slot, shape):
    _, name, tail, call = slot
    msg = raises_kinlib(call, np.full(shape, 0.25))
    assert_names(msg, slot, f"{name}:")
    assert "expected" in msg and shape_text(tail) in msg, msg
    assert f"got shape {shape}" in msg, msg


# --------------------------------------------------------------------------- NaN and inf

NONFINITE = [np.nan, np.inf, -np.inf]
NONFINITE_CASES = [
    p
    for slot in SLOTS
    if (slot[0], slot[1]) not in NONFINITE_OK
    for p in _params(slot, NONFINITE)
]


@pytest.mark.parametrize(("slot", "bad"), NONFINITE_CASES)
def test_nan_and_inf(slot, bad):
    _, name, _, call = slot
    good = good_for(slot)
    x = np.array(good, dtype=float)
    x.flat[x.size // 2] = bad
    msg = raises_kinlib(call, x)
    assert_names(msg, slot, f"{name}:")
    assert "NaN or infinity" in msg, msg
    # in a batch, the message says which member
    batch = np.stack([good, x, good])
    msg = raises_kinlib(call, batch)
    assert_names(msg, slot, f"{name}[1]:")
    assert "NaN or infinity" in msg, msg


def test_is_rotation_is_false_for_nan_and_inf():
    for bad in NONFINITE:
        R = R_OK.copy()
        R[1, 1] = bad
        assert kl.is_rotation(R) is False
        np.testing.assert_array_equal(kl.is_rotation(np.stack([R_OK, R])), [True, False])


# --------------------------------------------------------------------------- not numbers


def junk_for(slot):
    good = np.asarray(good_for(slot), dtype=float)
    return [
        "abc",
        b"xyz",
        None,
        object(),
        {"a": 1},
        [1.0, [2.0, 3.0]],  # ragged
        [[1.0, 2.0, 3.0], [4.0, 5.0]],  # ragged
        good * (1 + 1j),  # complex array
        (good + 0j).tolist(),  # complex list
        good.astype(str).tolist(),  # numbers written as text
        np.array(good.astype(str)),
        np.full(good.shape, np.datetime64("2024-01-01")),
        np.array(good.astype(str), dtype=object),  # text in an object array
        10**400,  # too large for a float
    ]


def _junk_params():
    out = []
    for slot in SLOTS:
        values = junk_for(slot)
        if (slot[0], slot[1]) in NONE_OK:
            values = [v for v in values if v is not None]
        out += _params(slot, values)
    return out


@pytest.mark.parametrize(("slot", "bad"), _junk_params())
def test_not_real_numbers(slot, bad):
    _, name, _, call = slot
    msg = raises_kinlib(call, bad)
    assert_names(msg, slot, f"{name}:")
    assert "expected" in msg, msg


SLERP_QUATS = [s for s in SLOTS if s[0] == "quat_slerp" and s[1] in ("q0", "q1")]


@pytest.mark.parametrize("slot", SLERP_QUATS, ids=_ids)
def test_slerp_names_its_arguments(slot):
    msg = raises_kinlib(slot[3], [1.0, 2.0, 3.0])
    assert msg.startswith(f"{slot[1]}:"), msg


def test_object_arrays_of_numbers_are_fine():
    # not junk: numbers in an object array convert cleanly
    np.testing.assert_allclose(
        kl.transform_points(T_OK, np.array([1.0, 2.0, 3.0], dtype=object)),
        R_OK @ V_OK + V_OK,
        atol=1e-15,
    )
    np.testing.assert_allclose(kl.rotz(np.array(0.3, dtype=object)), R_OK, atol=1e-15)


# --------------------------------------------------------------------------- zero axis

ZERO_AXIS = [
    ("matrix_from_axis_angle", "axis", lambda a: kl.matrix_from_axis_angle(a, 0.5)),
    ("quat_from_axis_angle", "axis", lambda a: kl.quat_from_axis_angle(a, 0.5)),
    ("rodrigues_rotate", "axis", lambda a: kl.rodrigues_rotate(V_OK, a, 0.5)),
    ("dual_quat_from_screw", "l", lambda a: kl.dual_quat_from_screw(a, [0.0, 0, 0], 0.5, 1.0)),
]


@pytest.mark.parametrize(("func", "name", "call"), ZERO_AXIS, ids=[z[0] for z in ZERO_AXIS])
@pytest.mark.parametrize("axis", [[0.0, 0.0, 0.0], [1e-14, 0.0, -1e-14], [-0.0, 0.0, 0.0]])
def test_zero_axis(func, name, call, axis):
    msg = raises_kinlib(call, axis)
    assert msg.startswith(name) and "non-zero" in msg, msg


@pytest.mark.parametrize(("func", "name", "call"), ZERO_AXIS, ids=[z[0] for z in ZERO_AXIS])
def test_zero_axis_in_a_batch_is_named(func, name, call):
    msg = raises_kinlib(call, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]])
    assert msg.startswith(f"{name}[2]") and "non-zero" in msg, msg


@pytest.mark.parametrize("scale", [1e-6, 1.0, 1e100, 1e200, 1e300])
def test_axis_length_does_not_matter(scale):
    # a huge axis is still a direction: its squares must not overflow into a zero axis
    u = np.array([1.0, 2.0, 2.0])
    expected = kl.matrix_from_axis_angle(u / 3.0, 0.5)
    np.testing.assert_allclose(kl.matrix_from_axis_angle(scale * u, 0.5), expected, atol=1e-15)
    np.testing.assert_allclose(
        kl.rodrigues_rotate(V_OK, scale * u, 0.5), expected @ V_OK, atol=1e-14
    )
    np.testing.assert_allclose(
        kl.quat_from_axis_angle(scale * u, 0.5)[1:], np.sin(0.25) * u / 3.0, atol=1e-15
    )


# --------------------------------------------------------------------------- zero quaternion

ZERO_QUAT = [
    ("quat_normalize", lambda q: kl.quat_normalize(q)),
    ("quat_inverse", lambda q: kl.quat_inverse(q)),
    ("matrix_from_quat", lambda q: kl.matrix_from_quat(q)),
    ("quat_rotate", lambda q: kl.quat_rotate(q, V_OK)),
    ("axis_angle_from_quat", lambda q: kl.axis_angle_from_quat(q)),
    ("quat_slerp q0", lambda q: kl.quat_slerp(q, Q_OK, 0.5)),
    ("quat_slerp q1", lambda q: kl.quat_slerp(Q_OK, q, 0.5)),
]


@pytest.mark.parametrize(("func", "call"), ZERO_QUAT, ids=[z[0] for z in ZERO_QUAT])
@pytest.mark.parametrize("q", [[0.0, 0.0, 0.0, 0.0], [1e-15, 0.0, -1e-15, 0.0]])
def test_zero_quaternion(func, call, q):
    msg = raises_kinlib(call, q)
    assert "zero quaternion" in msg and "expected" in msg, msg


@pytest.mark.parametrize("n", [3, 3000])  # 3000: the compiled batch path, where present
def test_zero_quaternion_in_a_batch_is_named(n):
    q = np.tile(Q_OK, (n, 1))
    q[1] = 0.0
    for f in (kl.matrix_from_quat, kl.quat_normalize, kl.axis_angle_from_quat):
        msg = raises_kinlib(f, q)
        assert msg.startswith("q[1]") and "zero quaternion" in msg, msg


# --------------------------------------------------------------------------- not rotations

NEEDS_ROTATION = [
    ("euler_from_matrix", lambda R: kl.euler_from_matrix(R, "XYZ")),
    ("euler_gimbal_lock", lambda R: kl.euler_gimbal_lock(R, "XYZ")),
    ("quat_from_matrix", kl.quat_from_matrix),
    ("axis_angle_from_matrix", kl.axis_angle_from_matrix),
    ("log_so3", kl.log_so3),
    ("cayley_from_matrix", kl.cayley_from_matrix),
    ("check_rotation", kl.check_rotation),
    ("transform", lambda R: kl.transform(R, V_OK)),
]

NOT_ROTATIONS = [
    ("scaled", 2.0 * R_OK, ["orthonormal"]),
    ("slightly scaled", 1.001 * R_OK, ["orthonormal"]),
    ("reflection", np.diag([1.0, 1.0, -1.0]), ["det", "reflection"]),
    ("minus a rotation", -R_OK, ["det", "reflection"]),
    ("shear", np.array([[1.0, 0.3, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), ["orthonormal"]),
    ("zero", np.zeros((3, 3)), ["orthonormal"]),
    ("ones", np.ones((3, 3)), ["orthonormal"]),
]


@pytest.mark.parametrize(("func", "call"), NEEDS_ROTATION, ids=[n[0] for n in NEEDS_ROTATION])
@pytest.mark.parametrize(("kind", "M", "words"), NOT_ROTATIONS, ids=[n[0] for n in NOT_ROTATIONS])
def test_not_a_rotation(func, call, kind, M, words):
    msg = raises_kinlib(call, M)
    assert msg.startswith("R") and "not a rotation matrix" in msg, msg
    for w in words:
        assert w in msg, msg
    assert kl.is_rotation(M) is False


@pytest.mark.parametrize(("func", "call"), NEEDS_ROTATION, ids=[n[0] for n in NEEDS_ROTATION])
@pytest.mark.parametrize("n", [4, 3000])  # 3000: the compiled batch path, where present
def test_not_a_rotation_in_a_batch_is_named(func, call, n):
    R = np.tile(R_OK, (n, 1, 1))
    R[2] = np.diag([1.0, -1.0, 1.0])
    msg = raises_kinlib(call, R)
    assert msg.startswith("R[2]") and "reflection" in msg, msg


def test_vee_needs_a_skew_matrix():
    msg = raises_kinlib(kl.vee, np.eye(3))
    assert msg.startswith("S") and "skew-symmetric" in msg, msg


# --------------------------------------------------------------------------- sequences

SEQ_FUNCS = [
    ("matrix_from_euler", lambda s: kl.matrix_from_euler([0.1, 0.2, 0.3], s)),
    ("euler_from_matrix", lambda s: kl.euler_from_matrix(R_OK, s)),
    ("euler_gimbal_lock", lambda s: kl.euler_gimbal_lock(R_OK, s)),
]

BAD_SEQUENCES = [
    ("XYx", "mixes cases"),
    ("xYz", "mixes cases"),
    ("Zyx", "mixes cases"),
    ("XXY", "same axis twice"),
    ("xxy", "same axis twice"),
    ("ZZX", "same axis twice"),
    ("XYY", "same axis twice"),
    ("zzz", "same axis twice"),
    ("abc", "letters other than x, y, z"),
    ("XYW", "letters other than x, y, z"),
    ("123", "letters other than x, y, z"),
    ("x y", "letters other than x, y, z"),
    ("XY", "three axis letters"),
    ("XYZW", "three axis letters"),
    ("", "three axis letters"),
    (123, "three axis letters"),
    (None, "three axis letters"),
    (b"XYZ", "three axis letters"),
    (["X", "Y", "Z"], "three axis letters"),
]


@pytest.mark.parametrize(("func", "call"), SEQ_FUNCS, ids=[f[0] for f in SEQ_FUNCS])
@pytest.mark.parametrize(("seq", "what"), BAD_SEQUENCES, ids=[repr(b[0]) for b in BAD_SEQUENCES])
def test_bad_sequences(func, call, seq, what):
    msg = raises_kinlib(call, seq)
    assert msg.startswith("seq:") and what in msg, msg
    assert repr(seq) in msg, msg  # says what was given


def test_sequence_messages_suggest_the_fix():
    msg = raises_kinlib(lambda s: kl.matrix_from_euler([0, 0, 0], s), "XYx")
    assert "UPPERCASE" in msg and "lowercase" in msg and "intrinsic" in msg
    msg = raises_kinlib(lambda s: kl.matrix_from_euler([0, 0, 0], s), "XXY")
    assert "consecutive axes must differ" in msg


def test_symbolic_euler_with_a_bad_sequence():
    a, b, g = sp.symbols("a b g")
    msg = raises_kinlib(lambda s: kl.matrix_from_euler([a, b, g], s), "XXY")
    assert "same axis twice" in msg


# --------------------------------------------------------------------------- slerp t


@pytest.mark.parametrize("t", [-0.1, 1.1, -1e-12, 1.0 + 1e-12, 5.0, [0.5, 2.0], [[0.0], [-1.0]]])
def test_slerp_t_outside_unit_interval(t):
    msg = raises_kinlib(lambda x: kl.quat_slerp(Q_OK, [1.0, 0.0, 0.0, 0.0], x), t)
    assert msg.startswith("t") and "[0, 1]" in msg and "expected" in msg, msg
    if np.ndim(t):
        assert msg.startswith("t[1"), msg


def test_slerp_t_at_the_ends_is_fine():
    q1 = np.array([1.0, 0.0, 0.0, 0.0])
    np.testing.assert_allclose(kl.quat_slerp(Q_OK, q1, 0.0), Q_OK, atol=1e-15)
    np.testing.assert_allclose(kl.quat_slerp(Q_OK, q1, 1.0), q1, atol=1e-15)


# --------------------------------------------------------------------------- batches

R2, R3 = np.tile(R_OK, (2, 1, 1)), np.tile(R_OK, (3, 1, 1))
V2, V3 = np.tile(V_OK, (2, 1)), np.tile(V_OK, (3, 1))
Q2, Q3 = np.tile(Q_OK, (2, 1)), np.tile(Q_OK, (3, 1))
T2 = np.tile(T_OK, (2, 1, 1))
DQ2, DQ3 = np.tile(DQ_OK, (2, 1)), np.tile(DQ_OK, (3, 1))
L2 = np.tile(L_OK, (2, 1))

NO_BROADCAST = [
    ("transform", lambda: kl.transform(R2, V3)),
    ("transform_points", lambda: kl.transform_points(T2, V3)),
    ("transform_vectors", lambda: kl.transform_vectors(T2, V3)),
    ("matrix_from_axis_angle", lambda: kl.matrix_from_axis_angle(V2, [0.1, 0.2, 0.3])),
    ("rodrigues_rotate v/axis", lambda: kl.rodrigues_rotate(V2, V3, 0.5)),
    ("rodrigues_rotate v/angle", lambda: kl.rodrigues_rotate(V2, V_OK, [0.1, 0.2, 0.3])),
    ("quat_multiply", lambda: kl.quat_multiply(Q2, Q3)),
    ("quat_rotate", lambda: kl.quat_rotate(Q2, V3)),
    ("quat_from_axis_angle", lambda: kl.quat_from_axis_angle(V2, [0.1, 0.2, 0.3])),
    ("quat_slerp q0/q1", lambda: kl.quat_slerp(Q2, Q3, 0.5)),
    ("quat_slerp q/t", lambda: kl.quat_slerp(Q2, Q2, [0.1, 0.2, 0.3])),
    ("dual_quat_multiply", lambda: kl.dual_quat_multiply(DQ2, DQ3)),
    ("dual_quat_transform_point", lambda: kl.dual_quat_transform_point(DQ2, V3)),
    ("dual_quat_from_screw l/m", lambda: kl.dual_quat_from_screw(L2, np.zeros((3, 3)), 0.5, 1.0)),
    ("dual_quat_from_screw l/theta", lambda: kl.dual_quat_from_screw(L2, M_OK, [1, 2, 3], 1.0)),
    ("dual_quat_from_screw theta/d", lambda: kl.dual_quat_from_screw(L_OK, M_OK, [1, 2], V_OK)),
    ("dual_quat_sclerp dq0/dq1", lambda: kl.dual_quat_sclerp(DQ2, DQ3, 0.5)),
    ("dual_quat_sclerp dq/t", lambda: kl.dual_quat_sclerp(DQ2, DQ2, [0.1, 0.2, 0.3])),
]


@pytest.mark.parametrize("call", [b[1] for b in NO_BROADCAST], ids=[b[0] for b in NO_BROADCAST])
def test_batches_that_do_not_broadcast(call):
    msg = raises_kinlib(lambda _: call(), None)
    assert "do not broadcast" in msg and "(2,)" in msg and "(3,)" in msg, msg


# --------------------------------------------------------------------------- transforms & dq


@pytest.mark.parametrize(
    "call",
    [
        kl.check_transform,
        kl.transform_inverse,
        kl.dual_quat_from_transform,
        lambda T: kl.transform_points(T, V_OK),
        lambda T: kl.transform_vectors(T, V_OK),
    ],
    ids=["check_transform", "transform_inverse", "dual_quat_from_transform", "points", "vectors"],
)
def test_not_a_rigid_transform(call):
    T = T_OK.copy()
    T[3, 2] = 1.0
    msg = raises_kinlib(call, T)
    assert msg.startswith("T") and "bottom row" in msg and "[0, 0, 0, 1]" in msg, msg
    T = T_OK.copy()
    T[:3, :3] *= 2.0
    msg = raises_kinlib(call, T)
    assert "T[:3, :3]" in msg and "not a rotation matrix" in msg, msg


@pytest.mark.parametrize(
    "call",
    [
        kl.transform_from_dual_quat,
        kl.screw_from_dual_quat,
        lambda dq: kl.dual_quat_transform_point(dq, V_OK),
    ],
    ids=["transform_from_dual_quat", "screw_from_dual_quat", "dual_quat_transform_point"],
)
@pytest.mark.parametrize("dq", [2 * DQ_OK, np.zeros(8), np.r_[1.0, 0, 0, 0, 1.0, 0, 0, 0]])
def test_not_a_unit_dual_quaternion(call, dq):
    msg = raises_kinlib(call, dq)
    assert msg.startswith("dq") and "expected a unit dual quaternion" in msg, msg


def test_screw_moment_not_perpendicular():
    msg = raises_kinlib(lambda m: kl.dual_quat_from_screw(L_OK, m, 0.5, 1.0), [0.0, 0.0, 1.0])
    assert msg.startswith("m") and "perpendicular" in msg, msg


# --------------------------------------------------------------------------- symbolic input

x, y, z, t = sp.symbols("x y z t")

SYMBOLIC = [
    ("skew 2", lambda: kl.skew([x, y]), "v"),
    ("skew 4", lambda: kl.skew([x, y, z, t]), "v"),
    ("skew text", lambda: kl.skew([x, y, "z"]), "v"),
    ("rotx matrix", lambda: kl.rotx(sp.Matrix([x, y])), "theta"),
    ("rotz list", lambda: kl.rotz([x, y]), "theta"),
    ("axis-angle 2", lambda: kl.matrix_from_axis_angle([x, y], t), "axis"),
    ("axis-angle nested", lambda: kl.matrix_from_axis_angle([[x, y, z]], t), "axis"),
    ("axis-angle zero", lambda: kl.matrix_from_axis_angle([0, 0, 0], t), "axis"),
    ("axis-angle angle", lambda: kl.matrix_from_axis_angle([x, y, z], [t, t]), "angle"),
    ("euler 2 angles", lambda: kl.matrix_from_euler([x, y], "XYZ"), "angles"),
    ("transform R 2x2", lambda: kl.transform(sp.eye(2), [x, y, z]), "R"),
    ("transform p 2", lambda: kl.transform(None, [x, y]), "p"),
    ("transform p text", lambda: kl.transform(None, [x, y, "a"]), "p"),
    ("transform_inverse 3x3", lambda: kl.transform_inverse(sp.Matrix(3, 3, [x] * 9)), "T"),
    ("cayley 2", lambda: kl.matrix_from_cayley([x, y]), ""),
]


@pytest.mark.parametrize(("call", "name"), [s[1:] for s in SYMBOLIC], ids=[s[0] for s in SYMBOLIC])
def test_bad_symbolic_input(call, name):
    msg = raises_kinlib(lambda _: call(), None)
    assert msg.startswith(name) and "expected" in msg, msg


def test_bad_symbolic_transform_bottom_row():
    T = sp.Matrix(4, 4, [x] * 12 + [0, 0, 1, 1])
    msg = raises_kinlib(kl.transform_inverse, T)
    assert msg.startswith("T") and "bottom row" in msg and "[0, 0, 0, 1]" in msg, msg


# --- regressions: huge magnitudes and tolerance arguments --------------------------------


def test_huge_quaternions_normalise_without_overflow():
    q = [1e200, 1e200, 0.0, 0.0]  # a quarter turn about x, scaled absurdly
    h = np.sqrt(0.5)
    np.testing.assert_allclose(kl.quat_normalize(q), [h, h, 0.0, 0.0], atol=1e-15)
    R = kl.matrix_from_quat(q)
    np.testing.assert_allclose(R, [[1, 0, 0], [0, 0, -1], [0, 1, 0]], atol=1e-15)
    big = np.tile(q, (5000, 1))  # the compiled path too
    np.testing.assert_allclose(kl.matrix_from_quat(big)[-1], R, atol=1e-15)


def test_huge_rotation_vector_gives_a_rotation():
    w = np.array([1e154, 1e154, 0.0])
    R = kl.exp_so3(w)
    assert kl.is_rotation(R, tol=1e-12)
    u = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    np.testing.assert_allclose(R @ u, u, atol=1e-12)  # the axis is fixed


@pytest.mark.parametrize("tol", ["a", np.nan, -1.0, [1e-6, 1e-6], None])
@pytest.mark.parametrize(
    "call",
    [
        lambda tol: kl.check_rotation(np.eye(3), tol=tol),
        lambda tol: kl.is_rotation(np.eye(3), tol=tol),
        lambda tol: kl.vee(np.zeros((3, 3)), tol=tol),
        lambda tol: kl.euler_from_matrix(np.eye(3), "ZYX", tol=tol),
        lambda tol: kl.euler_gimbal_lock(np.eye(3), "ZYX", tol=tol),
        lambda tol: kl.check_transform(np.eye(4), tol=tol),
    ],
    ids=["check_rotation", "is_rotation", "vee", "euler_from_matrix", "euler_gimbal_lock",
         "check_transform"],
)
def test_bad_tolerances_are_rejected(call, tol):
    with pytest.raises(kl.KinlibError, match=r"^tol"):
        call(tol)
