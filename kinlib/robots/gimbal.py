"""A Z-Y-X gimbal as a robot: three revolute joints through one point.

The joints turn about ``z``, then the new ``y``, then the newer ``x``, so the joint values
``q = (α, β, γ)`` are Z-Y-X Euler angles and the last link's orientation is
``R = Rz(α) Ry(β) Rx(γ)`` (``kl.matrix_from_euler(q, "ZYX")``). At ``β = ±π/2`` the first
and third joint axes line up: gimbal lock, seen as two of the viewer's joint-axis
cylinders lying on one line. The last link carries a flat box with a fin (a little
aircraft), so its orientation can be read in 3-D.
"""

from __future__ import annotations

import numpy as np

from ..kinematics.robot import load_urdf

__all__ = ["gimbal_zyx"]

_URDF = """<?xml version="1.0"?>
<robot name="gimbal_zyx">
  <link name="frame"/>
  <link name="yaw_ring"/>
  <link name="pitch_ring"/>
  <link name="body">
    <visual><geometry><box size="0.6 0.3 0.06"/></geometry>
      <material name="grey"><color rgba="0.75 0.75 0.8 1"/></material></visual>
    <visual><origin xyz="-0.22 0 0.08"/><geometry><box size="0.14 0.02 0.16"/></geometry>
      <material name="red"><color rgba="0.85 0.2 0.2 1"/></material></visual>
  </link>
  <joint name="alpha_z" type="continuous">
    <parent link="frame"/><child link="yaw_ring"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="beta_y" type="revolute">
    <parent link="yaw_ring"/><child link="pitch_ring"/><axis xyz="0 1 0"/>
    <limit lower="-1.5707963267948966" upper="1.5707963267948966" effort="1" velocity="1"/>
  </joint>
  <joint name="gamma_x" type="continuous">
    <parent link="pitch_ring"/><child link="body"/><axis xyz="1 0 0"/>
  </joint>
</robot>
"""


def gimbal_zyx():
    """The Z-Y-X gimbal: joints ``alpha_z``, ``beta_y`` (limited to ±π/2), ``gamma_x``.

    >>> import kinlib as kl
    >>> g = gimbal_zyx()
    >>> q = [0.3, -0.5, 1.1]
    >>> bool(np.allclose(g.fk(q)[:3, :3], kl.matrix_from_euler(q, "ZYX")))
    True
    """
    robot = load_urdf(_URDF)
    robot.poses.update({"zero": np.zeros(3), "locked": np.array([0.35, np.pi / 2, -0.5])})
    robot.reference = "Z-Y-X Euler angles as joints (notebook 04); Craig, sec. 2.8"
    return robot
