"""Two modern arms from their manufacturers' published kinematic parameters."""

from __future__ import annotations

import numpy as np

from ..kinematics.robot import Robot
from ..models.dh import DHRow

__all__ = ["ur5", "panda"]


def ur5():
    """Universal Robots UR5 (CB3/e-Series kinematics), standard DH.

    ====  =========  ==========  =======
    i     d (m)      a (m)       α (rad)
    ====  =========  ==========  =======
    1     0.089159   0           π/2
    2     0          −0.425      0
    3     0          −0.39225    0
    4     0.10915    0           π/2
    5     0.09465    0           −π/2
    6     0.0823     0           0
    ====  =========  ==========  =======

    Every joint ranges over ±360°.

    >>> robot = ur5()
    >>> robot.fk(np.zeros(6))[:3, 3].round(5)
    array([-0.81725, -0.19145, -0.00549])
    """
    d = [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823]
    a = [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0]
    alpha = [np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0]
    lim = (-2 * np.pi, 2 * np.pi)
    return Robot.from_dh(
        [DHRow(a=a[i], alpha=alpha[i], d=d[i], limits=lim) for i in range(6)],
        name="ur5",
        poses={"zero": np.zeros(6),
               "home": np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0]),
               "ready": np.array([0.0, -np.pi / 2, np.pi / 2, -np.pi / 2, -np.pi / 2, 0.0])},
        reference="Universal Robots, 'DH parameters for calculations of kinematics and "
                  "dynamics' (UR5), universal-robots.com support article",
    )


def panda():
    """Franka Emika Panda, modified (Craig) DH, with the flange as a fixed last row.

    ======  ========  ======  =======
    row     a (m)     d (m)   α (rad)
    ======  ========  ======  =======
    1       0         0.333   0
    2       0         0       −π/2
    3       0         0.316   π/2
    4       0.0825    0       π/2
    5       −0.0825   0.384   −π/2
    6       0         0       π/2
    7       0.088     0       π/2
    flange  0         0.107   0
    ======  ========  ======  =======

    >>> robot = panda()
    >>> robot.dof, robot.tip
    (7, 'link8')
    >>> robot.fk(robot.poses["ready"])[:3, 3].round(4) + 0.0
    array([0.3069, 0.    , 0.5903])
    """
    a = [0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088]
    d = [0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0]
    alpha = [0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2]
    lims = [(-2.8973, 2.8973), (-1.7628, 1.7628), (-2.8973, 2.8973), (-3.0718, -0.0698),
            (-2.8973, 2.8973), (-0.0175, 3.7525), (-2.8973, 2.8973)]
    rows = [DHRow(a=a[i], alpha=alpha[i], d=d[i], limits=lims[i]) for i in range(7)]
    rows.append(DHRow(a=0.0, alpha=0.0, d=0.107, joint="fixed", name="flange"))
    return Robot.from_dh(
        rows,
        "modified",
        name="panda",
        poses={"zero": np.zeros(7),
               "ready": np.array([0.0, -np.pi / 4, 0.0, -3 * np.pi / 4, 0.0, np.pi / 2,
                                  np.pi / 4])},
        reference="Franka Emika, 'Robot and interface specifications': Denavit-Hartenberg "
                  "parameters (Craig's convention) and joint limits, frankaemika.github.io",
    )
