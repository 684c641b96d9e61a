"""kinlib: the course workbook library for robot kinematics.

The numeric core needs only numpy; sympy, matplotlib and meshcat load on first use.
Conventions (frames, quaternion order, Euler sequences, ...) are stated once in
:mod:`kinlib.conventions`.
"""

from .errors import KinlibError, URDFError
from .kinematics.ik import IKResult, dls_step, pose_error
from .kinematics.kernels import prepare_kernels
from .kinematics.planar import Planar2RIK, planar_2r_fk, planar_2r_ik, planar_2r_jacobian
from .kinematics.poe import body_jacobian, poe_fk, screw_axes, space_jacobian
from .kinematics.robot import Robot, load_urdf
from .kinematics.singularity import (
    condition_number,
    is_near_singular,
    manipulability,
    singular_values,
    velocity_ellipsoid,
)
from .models.dh import DHRow, dh_transform, mdh_transform
from .models.tree import Joint, Link, Mimic, Visual
from .planning.astar import PlanResult, astar, cost_to_go
from .planning.cspace import Circle, CSpaceGrid, Polygon, planar_2r_cspace, planar_2r_metric
from .spatial.axis_angle import (
    axis_angle_from_matrix,
    exp_so3,
    log_so3,
    matrix_from_axis_angle,
    rodrigues_rotate,
)
from .spatial.cayley import cayley_from_matrix, matrix_from_cayley
from .spatial.dual_quaternions import (
    dual_quat_conjugate,
    dual_quat_from_screw,
    dual_quat_from_transform,
    dual_quat_multiply,
    dual_quat_sclerp,
    dual_quat_transform_point,
    screw_from_dual_quat,
    transform_from_dual_quat,
)
from .spatial.euler import EULER_SEQUENCES, euler_from_matrix, euler_gimbal_lock, matrix_from_euler
from .spatial.quaternions import (
    axis_angle_from_quat,
    matrix_from_quat,
    quat_conjugate,
    quat_from_axis_angle,
    quat_from_matrix,
    quat_inverse,
    quat_multiply,
    quat_normalize,
    quat_rotate,
    quat_slerp,
    quat_wxyz_from_xyzw,
    quat_xyzw_from_wxyz,
)
from .spatial.rotations import (
    check_rotation,
    is_rotation,
    nearest_rotation,
    rotx,
    roty,
    rotz,
    skew,
    vee,
)
from .spatial.se3 import adjoint, exp_se3, hat_se3, log_se3, vee_se3
from .spatial.transforms import (
    check_transform,
    transform,
    transform_inverse,
    transform_points,
    transform_vectors,
)
from .spatial.velocity import (
    add_angular_velocities,
    angular_velocity,
    euler_rate_matrix,
    euler_rates_singular,
    point_velocity,
    rotation_derivative,
)

__version__ = "0.1.0"

_SUBMODULES = ("plot", "robots", "symbolic", "viz")


def __getattr__(name):
    """``kl.symbolic``, ``kl.plot``, ``kl.viz``, ``kl.robots`` import on first use."""
    if name in _SUBMODULES:
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'kinlib' has no attribute {name!r}")


__all__ = [
    "adjoint",
    "body_jacobian",
    "exp_se3",
    "hat_se3",
    "log_se3",
    "poe_fk",
    "prepare_kernels",
    "screw_axes",
    "space_jacobian",
    "vee_se3",
    "add_angular_velocities",
    "angular_velocity",
    "condition_number",
    "euler_rate_matrix",
    "euler_rates_singular",
    "is_near_singular",
    "manipulability",
    "point_velocity",
    "rotation_derivative",
    "singular_values",
    "velocity_ellipsoid",
    "CSpaceGrid",
    "Circle",
    "DHRow",
    "IKResult",
    "pose_error",
    "dls_step",
    "EULER_SEQUENCES",
    "Joint",
    "Link",
    "Mimic",
    "Planar2RIK",
    "PlanResult",
    "Polygon",
    "Robot",
    "Visual",
    "KinlibError",
    "URDFError",
    "axis_angle_from_matrix",
    "axis_angle_from_quat",
    "cayley_from_matrix",
    "dh_transform",
    "load_urdf",
    "mdh_transform",
    "planar_2r_cspace",
    "planar_2r_fk",
    "planar_2r_ik",
    "planar_2r_jacobian",
    "planar_2r_metric",
    "astar",
    "cost_to_go",
    "check_rotation",
    "check_transform",
    "dual_quat_conjugate",
    "dual_quat_from_screw",
    "dual_quat_from_transform",
    "dual_quat_multiply",
    "dual_quat_sclerp",
    "dual_quat_transform_point",
    "euler_from_matrix",
    "euler_gimbal_lock",
    "exp_so3",
    "is_rotation",
    "log_so3",
    "matrix_from_axis_angle",
    "matrix_from_cayley",
    "matrix_from_euler",
    "matrix_from_quat",
    "nearest_rotation",
    "quat_conjugate",
    "quat_from_axis_angle",
    "quat_from_matrix",
    "quat_inverse",
    "quat_multiply",
    "quat_normalize",
    "quat_rotate",
    "quat_slerp",
    "quat_wxyz_from_xyzw",
    "quat_xyzw_from_wxyz",
    "rodrigues_rotate",
    "rotx",
    "roty",
    "rotz",
    "screw_from_dual_quat",
    "skew",
    "transform",
    "transform_from_dual_quat",
    "transform_inverse",
    "transform_points",
    "transform_vectors",
    "vee",
]
