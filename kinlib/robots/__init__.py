"""The robots of the course, each as data (a DH table or a URDF file), named poses and a
reference for its numbers.

=========================  ====================================================
``planar_2r(l1, l2)``      the planar RR arm of seed 001 (Dorst, fig. 5.4/5.5)
``three_dof_arm(...)``     the 3-DOF DH example of the lecture notes (RRR, d1, a2, a3)
``puma560()``              the PUMA 560, seed 001's table (Fu, Gonzalez & Lee), metres
``ur5()``                  Universal Robots UR5, the manufacturer's DH parameters
``panda()``                Franka Emika Panda, the manufacturer's (modified) DH parameters
``autorob_test_robot()``   seed 000's ``test_robot`` URDF: a branched tree
``gimbal_zyx()``           a Z-Y-X gimbal: three joints through one point (04)
=========================  ====================================================

Each function builds a fresh :class:`~kinlib.Robot`; models do no work at import.
"""

from .autorob import autorob_test_robot
from .gimbal import gimbal_zyx
from .industrial import panda, ur5
from .planar import planar_2r, three_dof_arm
from .puma560 import puma560

__all__ = ["planar_2r", "three_dof_arm", "puma560", "ur5", "panda", "autorob_test_robot",
           "gimbal_zyx"]
