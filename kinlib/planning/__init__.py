"""Configuration-space planning: the planar 2R C-space grid with obstacles and A*. Builds on
:mod:`kinlib.kinematics`.
"""
