"""Small arms of the lecture notes, as DH tables."""

from __future__ import annotations

import numpy as np

from ..kinematics.robot import Robot
from ..models.dh import DHRow

__all__ = ["planar_2r", "three_dof_arm"]


def planar_2r(l1: float = 1.0, l2: float = 1.0):
    """The planar RR arm of seed 001 (Dorst, fig. 5.4 and the DH table of fig. 5.5).

    Rows ``(θ_i, d_i, a_i, α_i) = (θ1, 0, l1, 0), (θ2, 0, l2, 0)``; both joints are
    continuous (unlimited), as the configuration-space planning lecture assumes.

    >>> arm = planar_2r(2.0, 1.0)
    >>> arm.fk([0.0, np.pi / 2])[:2, 3].round(12)
    array([2., 1.])
    """
    return Robot.from_dh(
        [DHRow(a=l1, alpha=0.0), DHRow(a=l2, alpha=0.0)],
        name="planar_2r",
        poses={"zero": [0.0, 0.0], "elbow_up": [0.0, np.pi / 2],
               "folded": [0.0, np.pi]},
        reference="Leo Dorst, 'Poses and Kinematics' (seed 001), fig. 5.4/5.5, eq. 5.4",
    )


def three_dof_arm(d1: float = 0.4, a2: float = 0.5, a3: float = 0.4):
    """The 3-DOF DH exercise of the lecture notes ("convert these parameters").

    Rows ``(θ1, d1, 0, 90°), (θ2, 0, a2, 0), (θ3, 0, a3, 0)``: a base yaw joint and a
    planar 2R arm on top. The notes leave d1, a2, a3 symbolic; the defaults are a
    desk-sized arm in metres. Joints are revolute with ±170° range.

    >>> arm = three_dof_arm()
    >>> arm.fk([0.0, 0.0, 0.0])[:3, 3].round(12)
    array([0.9, 0. , 0.4])
    """
    lim = (-np.deg2rad(170.0), np.deg2rad(170.0))
    return Robot.from_dh(
        [DHRow(d=d1, a=0.0, alpha=np.pi / 2, limits=lim),
         DHRow(a=a2, alpha=0.0, limits=lim),
         DHRow(a=a3, alpha=0.0, limits=lim)],
        name="three_dof_arm",
        poses={"zero": [0.0, 0.0, 0.0], "reach_up": [0.0, np.pi / 2, -np.pi / 2]},
        reference="AutoRob lecture 'Hierarchies of Transforms' (seed 000): DH example for "
                  "individual exploration, 3 DoF robot arm",
    )
