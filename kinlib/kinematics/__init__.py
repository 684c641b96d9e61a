"""Kinematics of a model: :class:`~kinlib.Robot` (forward kinematics, Jacobians, IK), the
planar 2R arm, singularities, the product of exponentials and the holonomic base. Builds on
:mod:`kinlib.models` and :mod:`kinlib.spatial`.
"""
