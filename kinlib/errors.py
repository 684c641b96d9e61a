"""The exceptions kinlib raises for bad input."""

__all__ = ["KinlibError", "TreeError", "URDFError"]


class KinlibError(ValueError):
    """Bad input to a kinlib function: says what was expected, what was given, and where."""


class URDFError(KinlibError):
    """A robot description (URDF) that cannot be loaded; names the element and line when known."""


class TreeError(KinlibError):
    """Links and joints that do not form one kinematic tree (a duplicate name, a missing
    link, a cycle, a second root, a bad mimic rule).

    ``element`` names the element at fault, ``("link" | "joint", name)``, or is None when no
    single one is (a robot without links); ``nth`` is which element of that name, in the
    order given (0: the first; a duplicate name is reported at its second use, ``nth=1``).
    A URDF reader turns these into :class:`URDFError` with the element's line.
    """

    def __init__(self, message: str, element: tuple[str, str] | None = None, nth: int = 0):
        super().__init__(message)
        self.element = element
        self.nth = nth
