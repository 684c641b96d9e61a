"""Spatial descriptions: rotations, Euler angles, axis-angle, Cayley, quaternions, dual
quaternions, homogeneous transforms, SE(3) and angular velocity. Depends only on kinlib's base
(errors, conventions, input checks) and :mod:`kinlib.symbolic`.
"""
