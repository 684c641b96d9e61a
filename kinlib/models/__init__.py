"""Kinematic models as data: links, joints and their checks (:mod:`.tree`), Denavit–Hartenberg
rows and transforms (:mod:`.dh`, :mod:`.dh_tree`), URDF reading and writing (:mod:`.urdf`,
:mod:`.urdf_write`). Builds on :mod:`kinlib.spatial`; knows nothing of kinematics.
"""
