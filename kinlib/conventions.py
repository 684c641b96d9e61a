r"""The conventions kinlib follows, stated once.

Units
    SI everywhere in the API: metres and radians. Degrees appear only in helpers
    (use ``np.deg2rad``).

Frames and transforms
    Right-handed frames, active rotations, column vectors. ``T_AB`` is the pose of frame
    B in frame A, so ``T_AC = T_AB @ T_BC`` and ``p_A = T_AB @ p_B``. A rotation matrix's
    columns are the unit axes of B written in A (direction cosines).

Quaternions
    Hamilton algebra (i² = j² = k² = ijk = −1), scalar first: ``[w, x, y, z]``, with
    ``q = (cos θ/2, u sin θ/2)`` for a rotation of θ about the unit axis u.
    ``quat_from_matrix`` returns the quaternion with ``w >= 0`` (q and −q are the same
    rotation). ``quat_xyzw_from_wxyz`` / ``quat_wxyz_from_xyzw`` convert to and from the
    scalar-last order of ROS, scipy and Eigen's coefficient storage.

Euler and fixed angles
    A sequence is three letters. UPPERCASE = intrinsic (rotations about the axes of the
    moving frame: "Euler angles"); lowercase = extrinsic (rotations about the fixed axes:
    "fixed angles"); mixing cases is an error, as is the same axis twice in a row. The
    angles are given in the order of the letters, so::

        matrix_from_euler([a, b, g], "ZYX") == rotz(a) @ roty(b) @ rotx(g)
                                            == matrix_from_euler([g, b, a], "xyz")

    (roll-pitch-yaw; URDF's ``rpy`` is ``"xyz"``). All 24 sequences are supported: 12
    Tait–Bryan (three different axes) and 12 proper Euler (first axis = last).

    ``euler_from_matrix`` returns the middle angle in [−π/2, π/2] for Tait–Bryan sequences
    and in [0, π] for proper Euler sequences, the outer two in (−π, π]. At gimbal lock the
    middle angle is at its singular value (±π/2, or 0/π) and only the sum or difference of
    the outer angles is defined: kinlib then sets the *first* angle (first in the letter
    order, for extrinsic sequences too) to 0 and lets the third carry the whole rotation
    (Craig's convention). ``euler_from_matrix(R, seq, tol=ROUNDING_TOL)`` treats the matrix
    as locked when the middle angle is within ``tol`` of its singular value; the default
    only absorbs rounding, so a matrix *near* lock gets its exact (ill-conditioned) outer
    angles, which still reproduce R to rounding. ``euler_gimbal_lock(R, seq,
    tol=GIMBAL_TOL)`` tells whether the middle angle is within ``tol`` radians of its
    singular value; pass the same ``tol`` to ``euler_from_matrix`` to apply the convention
    over that whole band. ``euler_rates_singular(angles, seq, tol=GIMBAL_TOL)`` tests
    ``|det E| < tol``, and ``|det E|`` is the sine of that same distance, so the two agree.
    Angles that kinlib wraps (Euler angles, ``planar_2r_ik``, continuous joints in IK) lie
    in (−π, π]: −π is returned as π.

Axis-angle and Cayley
    ``axis_angle_from_matrix`` returns the angle in [0, π]. ``exp_so3(w)`` takes the rotation
    vector ``w = θ u``; ``log_so3(R)`` returns it. Cayley's formula is
    ``R = (I − S)⁻¹ (I + S)`` with ``S = skew(s)``, so ``s = tan(θ/2) u``; it is undefined
    at θ = π.

Dual quaternions (Daniilidis 1999)
    ``dq = q_r + ε q_d`` stored as 8 numbers: real part wxyz, then dual part wxyz, with
    ``q_d = ½ t q_r``. A screw is ``(l, m, θ, d)``: unit axis direction l, moment
    ``m = c × l`` for any point c on the axis, rotation angle θ about it and translation d
    along it.

Twists and SE(3)
    A twist is ``xi = [v; ω]``, linear part first, the order of the geometric Jacobian's
    rows (Modern Robotics writes ``[ω; v]``: reorder where the two meet). ``hat_se3(xi)`` is
    the 4×4 se(3) matrix ``[[skew(ω), v], [0, 0]]``, ``vee_se3`` its inverse;
    ``exp_se3(xi)`` / ``log_se3(T)`` map between them and SE(3) (``|ω| <= π`` from log).
    ``adjoint(T)`` is ``[[R, skew(p) R], [0, R]]``: ``xi_A = adjoint(T_AB) @ xi_B``. The
    spatial twist of a moving pose is ``vee_se3(Ṫ T⁻¹)``, the body twist ``vee_se3(T⁻¹ Ṫ)``.
    Product of exponentials: ``screw_axes(robot, link)`` gives ``(S, M)``, S (6×dof) the
    joints' screw axes in the base frame at q = 0 (``frame="body"``: in the link's frame),
    M the home pose, so ``robot.fk(q) == poe_fk(M, S, q)``; ``space_jacobian(S, q)`` and
    ``body_jacobian(B, q)`` give those twists from q̇.

Robots
    URDF: a joint's axis is expressed in the joint frame, which is the child link's frame:
    ``T_world_child = T_world_parent @ T_origin(xyz, rpy) @ motion(axis, q)`` (the matrix
    stack); ``rpy`` means ``matrix_from_euler(rpy, "xyz")`` = ``Rz(yaw) Ry(pitch) Rx(roll)``.
    A fixed joint's axis is ignored, as urdfdom does. The order of q is
    ``robot.joint_names``: the movable joints that do not mimic another, in document order
    (DH: row order). Poses are in the root link's frame.
    Denavit–Hartenberg: standard ``A_i = Rz(θ) Tz(d) Tx(a) Rx(α)``; modified (Craig,
    ``Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)``) only when asked. The joint variable
    replaces θ (revolute) or d (prismatic), plus the row's ``offset``. Link ``i`` of a DH
    robot is DH frame ``i``; ``link0`` is the base. The geometric Jacobian is 6×n with rows
    ``[v; ω]`` in the base frame.

Batches and symbols
    Every numeric function accepts leading batch dimensions — ``(..., 3, 3)``, ``(..., 4)``,
    ``(N, n_joints)`` — and returns the matching batch. The elementary constructors
    (``rotx``, ``roty``, ``rotz``, ``skew``, ``matrix_from_axis_angle``,
    ``matrix_from_euler``, ``transform``, ``dh_transform``, ``mdh_transform``) given sympy
    expressions return ``sympy.Matrix``.

Bad input
    Raises :class:`kinlib.KinlibError` (a ``ValueError``) saying what was expected, what
    was given and where. Results that may be unreachable (IK, planning) come back as
    result objects with ``success=False`` instead. ``success`` is the one flag name of
    every result (``IKResult``, ``Planar2RIK``, ``PlanResult``, ``CostToGo``, the grader's).

One input, one answer
    Predicates (``is_rotation``, ``euler_gimbal_lock``, ``is_near_singular``,
    ``euler_rates_singular``) return a Python ``bool`` for one input and a bool ndarray for
    a batch; scalar-valued functions (``manipulability``, ``condition_number``,
    ``planar_2r_metric``, the angle of ``axis_angle_from_matrix``, ...) a Python ``float``
    for one input and an ndarray for a batch.

Argument order
    A robot function takes ``q`` first, then ``link``, then ``seq`` (``robot.fk(q, link)``,
    ``robot.jacobian(q, link)``, ``robot.analytic_jacobian(q, link, seq)``). A checker takes
    the value, then its ``name``; tolerances are keyword-only there
    (``check_rotation(R, name="R", *, tol=ROTATION_TOL)``, ``check_transform`` alike).

Default tolerances
    One constant per meaning, defined below and used as the default everywhere:
    :data:`ROTATION_TOL`, :data:`GIMBAL_TOL`, :data:`SINGULAR_TOL`, :data:`SKEW_TOL`,
    :data:`LIMIT_TOL`, :data:`ROUNDING_TOL`, :data:`IK_POSITION_TOL`, :data:`IK_ROTATION_TOL`.
"""

from types import MappingProxyType

__all__ = ["ROTATION_TOL", "GIMBAL_TOL", "SINGULAR_TOL", "SKEW_TOL", "LIMIT_TOL",
           "ROUNDING_TOL", "IK_POSITION_TOL", "IK_ROTATION_TOL", "DEFAULT_TOLERANCES"]

#: Accepting a matrix as a rotation (``is_rotation``, ``check_rotation``, the rotation
#: block of ``check_transform``, unit dual quaternions): max |RᵀR − I| and |det R − 1|.
ROTATION_TOL = 1e-6

#: Gimbal lock (``euler_gimbal_lock``, ``euler_rates_singular``, ``analytic_jacobian``):
#: the middle Euler angle within this many radians of its singular value (|det E| below it).
GIMBAL_TOL = 1e-6

#: A Jacobian near a singularity (``is_near_singular``): smallest over largest singular
#: value, σ_k / σ₁, below this (relative, so units do not matter).
SINGULAR_TOL = 1e-6

#: A matrix taken as skew-symmetric (``vee``, ``vee_se3``, ``angular_velocity``'s Ṙ Rᵀ):
#: ``max |W + Wᵀ|`` relative to the matrix's size (its largest entry, at least 1).
SKEW_TOL = 1e-8

#: Joint limits (``Robot.check_limits``): how far (rad or m) q may lie outside them.
LIMIT_TOL = 1e-9

#: Floating-point rounding only (``euler_from_matrix``'s lock test, the rim of
#: ``planar_2r_ik``'s workspace): a case counts as exact within this.
ROUNDING_TOL = 1e-12

#: Numerical IK's success (``Robot.ik``'s ``tol_position``): position error in metres.
IK_POSITION_TOL = 1e-6

#: Numerical IK's success (``Robot.ik``'s ``tol_rotation``): rotation error in radians.
IK_ROTATION_TOL = 1e-6

#: Every default tolerance above, by name (a test checks each ``tol`` default is one).
DEFAULT_TOLERANCES = MappingProxyType({name: globals()[name] for name in __all__[:-1]})


