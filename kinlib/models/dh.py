r"""Denavit–Hartenberg link transforms and DH table rows.

Standard DH (Spong, Dorst, Fu; seed 001) is the default:

.. math:: A_i = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)
   = \begin{bmatrix} c\theta & -s\theta c\alpha & s\theta s\alpha & a c\theta \\
                     s\theta & c\theta c\alpha & -c\theta s\alpha & a s\theta \\
                     0 & s\alpha & c\alpha & d \\ 0 & 0 & 0 & 1 \end{bmatrix}

Modified DH (Craig) is used only when asked for:

.. math:: {}^{i-1}_{\;\;i}T = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)

In a modified table, row ``i`` holds ``a_{i-1}, α_{i-1}, d_i, θ_i`` as in Craig.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import as_array, as_limits, broadcast, is_symbolic
from ..errors import KinlibError

__all__ = ["DHRow", "dh_transform", "mdh_transform", "as_dh_row"]

JOINT_KINDS = ("revolute", "prismatic", "fixed")


def _params(theta, d, a, alpha):
    arrs = [as_array(x, n) for x, n in ((theta, "theta"), (d, "d"), (a, "a"), (alpha, "alpha"))]
    batch = broadcast(*((x, 0, n) for x, n in zip(arrs, ("theta", "d", "a", "alpha"),
                                                   strict=True)))
    return [np.broadcast_to(x, batch) for x in arrs], batch


def dh_transform(theta=0.0, d=0.0, a=0.0, alpha=0.0):
    r"""Standard DH link transform ``A = Rz(θ) Tz(d) Tx(a) Rx(α)``.

    Arguments broadcast against each other (batched result ``(..., 4, 4)``); sympy
    expressions give a ``sympy.Matrix``. Keyword use is recommended.

    The planar 2R arm of seed 001 (eq. 5.4), first link: a rotation by θ₁ and the link
    length l₁ along the new x axis.

    >>> dh_transform(theta=np.pi / 2, d=0.0, a=2.0, alpha=0.0).round(12) + 0.0
    array([[ 0., -1.,  0.,  0.],
           [ 1.,  0.,  0.,  2.],
           [ 0.,  0.,  1.,  0.],
           [ 0.,  0.,  0.,  1.]])
    >>> import sympy as sp
    >>> t, l = sp.symbols("theta l")
    >>> dh_transform(theta=t, a=l)[:2, 3].T
    Matrix([[l*cos(theta), l*sin(theta)]])
    """
    if is_symbolic(theta, d, a, alpha):
        from ..symbolic import _sym

        return _sym.dh(theta, d, a, alpha, modified=False)
    (th, d, a, al), batch = _params(theta, d, a, alpha)
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    T = np.zeros(batch + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 2], T[..., 0, 3] = ct, -st * ca, st * sa, a * ct
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st, ct * ca, -ct * sa, a * st
    T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = sa, ca, d
    T[..., 3, 3] = 1.0
    return T


def mdh_transform(theta=0.0, d=0.0, a=0.0, alpha=0.0):
    r"""Modified (Craig) DH link transform ``Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)``.

    ``a`` and ``alpha`` are the previous link's length and twist. Batched and symbolic like
    :func:`dh_transform`.

    >>> mdh_transform(theta=0.0, d=0.5, a=1.0, alpha=np.pi / 2).round(12) + 0.0
    array([[ 1. ,  0. ,  0. ,  1. ],
           [ 0. ,  0. , -1. , -0.5],
           [ 0. ,  1. ,  0. ,  0. ],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    if is_symbolic(theta, d, a, alpha):
        from ..symbolic import _sym

        return _sym.dh(theta, d, a, alpha, modified=True)
    (th, d, a, al), batch = _params(theta, d, a, alpha)
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    T = np.zeros(batch + (4, 4))
    T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = ct, -st, a
    T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st * ca, ct * ca, -sa, -sa * d
    T[..., 2, 0], T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = st * sa, ct * sa, ca, ca * d
    T[..., 3, 3] = 1.0
    return T


@dataclass(frozen=True)
class DHRow:
    """One row of a DH table.

    The joint variable ``q`` replaces θ for a revolute row (θ = q + offset) and d for a
    prismatic row (d = q + offset); a ``"fixed"`` row (a tool flange, say) has no variable.
    ``limits`` is ``(lower, upper)`` in radians or metres, ``None`` for unlimited.
    ``name`` names the joint (default ``joint{i}``).

    >>> DHRow(a=0.4318, alpha=0.0, d=0.14909, limits=(-3.93, 0.79)).joint
    'revolute'
    """

    a: float
    alpha: float
    d: float = 0.0
    theta: float = 0.0
    joint: str = "revolute"
    offset: float = 0.0
    limits: tuple[float, float] | None = None
    name: str | None = None

    def __post_init__(self):
        where = f"DHRow{'' if self.name is None else ' ' + repr(self.name)}"
        for field in ("a", "alpha", "d", "theta", "offset"):
            v = getattr(self, field)
            if isinstance(v, bool) or not isinstance(v, int | float | np.integer | np.floating):
                raise KinlibError(f"{where}: {field} must be a real number, got {v!r}")
            if not math.isfinite(v):
                raise KinlibError(f"{where}: {field} must be finite, got {v!r}")
            object.__setattr__(self, field, float(v))
        if self.joint not in JOINT_KINDS:
            raise KinlibError(
                f"{where}: joint must be one of {', '.join(JOINT_KINDS)}, got {self.joint!r}"
            )
        if self.limits is not None:
            limits = as_limits(self.limits, where)
            if self.joint == "fixed":
                raise KinlibError(f"{where}: a fixed row has no joint variable to limit")
            object.__setattr__(self, "limits", limits)
        if self.name is not None and (not isinstance(self.name, str) or not self.name):
            raise KinlibError(f"{where}: name must be a non-empty string, got {self.name!r}")


_ROW_KEYS = {"a", "alpha", "d", "theta", "joint", "offset", "limits", "name"}


def as_dh_row(row, i: int) -> DHRow:
    """A :class:`DHRow` from a DHRow or a dict with its keys (row index ``i`` for messages)."""
    if isinstance(row, DHRow):
        return row
    if isinstance(row, dict):
        unknown = set(row) - _ROW_KEYS
        if unknown:
            raise KinlibError(
                f"DH row {i}: unknown keys {sorted(unknown)}; expected some of "
                f"{sorted(_ROW_KEYS)}"
            )
        missing = {"a", "alpha"} - set(row)
        if missing:
            raise KinlibError(f"DH row {i}: missing {sorted(missing)}")
        try:
            return DHRow(**row)
        except KinlibError as exc:
            raise KinlibError(f"DH row {i}: {exc}") from None
    raise KinlibError(f"DH row {i}: expected a DHRow or a dict, got {type(row).__name__}")
