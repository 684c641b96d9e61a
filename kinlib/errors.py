"""The exceptions kinlib raises for bad input."""

__all__ = ["KinlibError", "URDFError"]


class KinlibError(ValueError):
    """Bad input to a kinlib function: says what was expected, what was given, and where."""


class URDFError(KinlibError):
    """A robot description (URDF) that cannot be loaded; names the element and line when known."""
