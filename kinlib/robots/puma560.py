"""The PUMA 560 from seed 001's DH table, in metres."""

from __future__ import annotations

import numpy as np

from ..kinematics.robot import Robot
from ..models.dh import DHRow

__all__ = ["puma560", "PUMA560_TABLE"]

# seed 001, "PUMA robot arm link coordinate parameters" (Fu, Gonzalez & Lee, Robotics:
# Control, Sensing, Vision and Intelligence, 1987, table 2.2):
#   joint  θ (deg)  α (deg)   a (mm)    d (mm)   range (deg)
PUMA560_TABLE = (
    (1, 90.0, -90.0, 0.0, 0.0, (-160.0, 160.0)),
    (2, 0.0, 0.0, 431.8, 149.09, (-225.0, 45.0)),
    (3, 90.0, 90.0, -20.32, 0.0, (-45.0, 225.0)),
    (4, 0.0, -90.0, 0.0, 433.07, (-110.0, 170.0)),
    (5, 0.0, 90.0, 0.0, 0.0, (-100.0, 100.0)),
    (6, 0.0, 0.0, 0.0, 56.25, (-266.0, 266.0)),
)


def puma560():
    """The PUMA 560 arm: standard DH, seed 001's table converted to metres and radians.

    The table's θ column is the configuration drawn in the book, not an offset: it is
    the named pose ``"table"``. ``q = 0`` puts every θ at 0.

    >>> robot = puma560()
    >>> robot.dof, np.rad2deg(robot.limits[1]).round(6)
    (6, array([-225.,   45.]))
    >>> robot.fk(robot.poses["zero"])[:3, 3].round(5)
    array([0.41148, 0.14909, 0.48932])
    """
    rows = [DHRow(a=a_mm / 1000.0, alpha=np.deg2rad(alpha), d=d_mm / 1000.0,
                  limits=tuple(np.deg2rad(rng)), name=f"joint{i}")
            for i, _theta, alpha, a_mm, d_mm, rng in PUMA560_TABLE]
    table_pose = np.deg2rad([row[1] for row in PUMA560_TABLE])
    return Robot.from_dh(
        rows,
        name="puma560",
        poses={"zero": np.zeros(6), "table": table_pose,
               "ready": np.deg2rad([0.0, -45.0, 135.0, 0.0, 45.0, 0.0])},
        reference="Seed 001 (Dorst, 'Poses and Kinematics'): PUMA robot arm link coordinate "
                  "parameters, from K. S. Fu, R. C. Gonzalez, C. S. G. Lee, Robotics: "
                  "Control, Sensing, Vision and Intelligence, McGraw-Hill 1987, table 2.2",
    )
