"""Seed 000's ``test_robot``: four links, three continuous joints, two branches."""

from __future__ import annotations

from importlib import resources

from ..kinematics.robot import load_urdf

__all__ = ["autorob_test_robot", "urdf_path"]


def urdf_path():
    """Path of the shipped ``autorob_test_robot.urdf`` (a context-free file path)."""
    return resources.files(__package__).joinpath("data", "autorob_test_robot.urdf")


def autorob_test_robot():
    """The ``test_robot`` URDF of seed 000 ("Hierarchies of Transforms", autorob.org).

    ``link1`` is the root; ``joint1`` and ``joint2`` both hang from it, so the tree has two
    leaves (``link2`` and ``link4``) and ``fk`` needs ``link=``. The axes in the file are not
    unit vectors; they are normalised on loading.

    >>> robot = autorob_test_robot()
    >>> robot.joint_names, robot.tip
    (['joint1', 'joint2', 'joint3'], None)
    >>> robot.fk([0, 0, 0], link="link2")[:3, 3]
    array([5., 3., 0.])
    """
    with resources.as_file(urdf_path()) as path:
        return load_urdf(
            path,
            poses={"zero": [0.0, 0.0, 0.0], "bent": [0.5, -0.8, 1.2]},
            reference="Chad Jenkins, AutoRob (Michigan Robotics 367/511), lecture "
                      "'Hierarchies of Transforms': the test_robot URDF (seed 000)",
        )
