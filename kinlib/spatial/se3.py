r"""The Lie group SE(3) and its algebra se(3): twists, the exponential and logarithm maps,
and the adjoint.

A twist is the 6-vector :math:`\xi = [v;\ \omega]`, **linear part first**, the order of
the geometric Jacobian's rows (Modern Robotics writes :math:`[\omega;\ v]`). Its matrix
form is the element of se(3)

.. math:: [\xi] = \begin{bmatrix}[\omega]_\times & v\\ 0 & 0\end{bmatrix},

and :math:`e^{[\xi]}` is the rigid motion reached by moving along the twist for unit time:
with :math:`\theta = |\omega|` and :math:`W = [\omega]_\times`,

.. math:: e^{[\xi]} = \begin{bmatrix} e^{W} & V v\\ 0 & 1\end{bmatrix},\qquad
          V = I + \frac{1-\cos\theta}{\theta^2} W + \frac{\theta-\sin\theta}{\theta^3} W^2 .

If :math:`\dot T` is the time derivative of a pose, :math:`\dot T T^{-1}` (the spatial
twist) and :math:`T^{-1}\dot T` (the body twist) are elements of se(3); :math:`\dot T`
itself is not (its bottom-right entry is 0 but its top-left block is not skew).
"""

from __future__ import annotations

import numpy as np

from .._validate import as_array, is_symbolic, unit_rows
from ..conventions import SKEW_TOL
from ..errors import KinlibError
from .axis_angle import _rodrigues_matrix, log_so3
from .rotations import skew
from .transforms import check_transform

__all__ = ["hat_se3", "vee_se3", "exp_se3", "log_se3", "adjoint"]

_SMALL = 1e-3  # below this |ω| the coefficients use their Taylor series


def hat_se3(xi):
    r"""The 4×4 matrix :math:`[\xi]` of a twist ``xi = [v; ω]`` (batched ``(..., 6)``).

    >>> hat_se3([1.0, 2.0, 3.0, 0.0, 0.0, 1.0]) + 0.0
    array([[ 0., -1.,  0.,  1.],
           [ 1.,  0.,  0.,  2.],
           [ 0.,  0.,  0.,  3.],
           [ 0.,  0.,  0.,  0.]])
    """
    if is_symbolic(xi):
        import sympy as sp

        from ..symbolic import _sym

        x = _sym.vector(xi, "xi", 6)
        X = sp.zeros(4, 4)
        X[:3, :3] = _sym.skew(x[3:])
        X[:3, 3] = sp.Matrix(x[:3])
        return X
    a = as_array(xi, "xi", (6,))
    X = np.zeros(a.shape[:-1] + (4, 4))
    X[..., :3, :3] = skew(a[..., 3:])
    X[..., :3, 3] = a[..., :3]
    return X


def vee_se3(X, tol: float = SKEW_TOL):
    r"""The twist ``[v; ω]`` of a 4×4 se(3) matrix: the inverse of :func:`hat_se3`.

    Raises :class:`KinlibError` unless the top-left block is skew-symmetric and the bottom
    row is zero (within ``tol`` relative to the matrix's size): a pose or a :math:`\dot T`
    is not an element of se(3).

    >>> vee_se3(hat_se3([1.0, 2.0, 3.0, 0.4, 0.5, 0.6]))
    array([1. , 2. , 3. , 0.4, 0.5, 0.6])
    """
    if is_symbolic(X):
        import sympy as sp

        from ..symbolic import _sym

        M = _sym.matrix(X, (4, 4), "X")
        if any(sp.expand(e) != 0 for e in M[3, :]):
            raise KinlibError(f"X: the bottom row of an se(3) matrix must be 0, got "
                              f"{list(M[3, :])}")
        w = _sym.vee(M[:3, :3])
        return sp.Matrix([*M[:3, 3], *w])
    a = as_array(X, "X", (4, 4))
    scale = 1.0 + np.abs(a).max(axis=(-2, -1), initial=0.0)
    W = a[..., :3, :3]
    bad = (np.abs(W + np.swapaxes(W, -1, -2)).max(axis=(-2, -1)) > tol * scale) | \
          (np.abs(a[..., 3, :]).max(axis=-1) > tol * scale)
    if np.any(bad):
        raise KinlibError(
            "X: expected an se(3) matrix [[skew(ω), v], [0, 0]] (top-left block "
            "skew-symmetric, bottom row 0); a pose T or its derivative Ṫ is not one — "
            "Ṫ T⁻¹ and T⁻¹ Ṫ are")
    return np.concatenate([a[..., :3, 3], W[..., 2, 1:2], W[..., 0, 2:3], W[..., 1, 0:1]],
                          axis=-1)


def _coefficients(theta):
    """``(1 − cos θ)/θ², (θ − sin θ)/θ³`` without cancellation for small θ."""
    small = theta < _SMALL
    t = np.where(small, 1.0, theta)
    t2 = theta * theta
    b = np.where(small, 0.5 - t2 / 24.0 + t2 * t2 / 720.0, 2.0 * np.sin(0.5 * t) ** 2 / t**2)
    c = np.where(small, 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0, (t - np.sin(t)) / t**3)
    return b, c


def exp_se3(xi, theta=None):
    r"""The rigid motion :math:`e^{[\xi]}` of a twist ``xi = [v; ω]`` (``(..., 6)`` →
    ``(..., 4, 4)``).

    With ``theta`` given, ``xi`` is a screw axis ``S`` (unit ω, or ω = 0 and unit v) and
    the result is :math:`e^{[S]\theta}`: the motion of a joint with axis S turned by θ
    (the factors of the product of exponentials). Sympy input gives a ``sympy.Matrix``;
    with a numeric unit screw axis and a symbolic angle the result is as simple as
    Rodrigues' formula:

    .. math:: e^{[S]\theta} = \begin{bmatrix} I + \sin\theta W + (1-\cos\theta) W^2 &
              (I\theta + (1-\cos\theta) W + (\theta - \sin\theta) W^2) v\\ 0&1\end{bmatrix}.

    Accurate for tiny, zero and large rotations (the coefficients switch to their series
    below |ω| = 1e-3).

    >>> T = exp_se3([0.0, 0.0, 1.0, 0.0, 0.0, np.pi / 2])  # a screw along z
    >>> T.round(12) + 0.0
    array([[ 0., -1.,  0.,  0.],
           [ 1.,  0.,  0.,  0.],
           [ 0.,  0.,  1.,  1.],
           [ 0.,  0.,  0.,  1.]])
    """
    if is_symbolic(xi, theta):
        return _exp_sym(xi, theta)
    a = as_array(xi, "xi", (6,))
    if theta is not None:
        t = as_array(theta, "theta")
        try:
            a = a * t[..., None]
        except ValueError:
            raise KinlibError(f"exp_se3: xi of batch shape {a.shape[:-1]} and theta of shape "
                              f"{t.shape} do not broadcast") from None
    v, w = a[..., :3], a[..., 3:]
    u, th = unit_rows(w)
    u = np.where((th > 0)[..., None], u, [0.0, 0.0, 1.0])
    W = skew(w)
    b, c = _coefficients(th)
    V = np.eye(3) + b[..., None, None] * W + c[..., None, None] * (W @ W)
    T = np.zeros(a.shape[:-1] + (4, 4))
    T[..., :3, :3] = _rodrigues_matrix(u, th)
    T[..., :3, 3] = np.einsum("...ij,...j->...i", V, v)
    T[..., 3, 3] = 1.0
    return T


def _exp_sym(xi, theta):
    import sympy as sp

    from ..symbolic import _sym

    x = sp.Matrix(_sym.vector(xi, "xi", 6))
    v, w = x[:3, :], x[3:, :]
    W = _sym.skew(w)
    T = sp.eye(4)
    if theta is not None:
        t = _sym.scalar(theta, "theta")
        n2 = sp.simplify((w.T * w)[0])
        if n2 == 0:  # a prismatic axis: pure translation
            T[:3, 3] = v * t
            return T
        if n2 != 1:
            raise KinlibError(f"exp_se3: with theta given, xi must be a screw axis (|ω| = 1, "
                              f"or ω = 0), got |ω|² = {n2}")
        T[:3, :3] = sp.eye(3) + sp.sin(t) * W + (1 - sp.cos(t)) * W * W
        T[:3, 3] = (sp.eye(3) * t + (1 - sp.cos(t)) * W + (t - sp.sin(t)) * W * W) * v
        return T
    th = sp.sqrt((w.T * w)[0])
    if th == 0:
        T[:3, 3] = v
        return T
    T[:3, :3] = sp.eye(3) + sp.sin(th) / th * W + (1 - sp.cos(th)) / th**2 * W * W
    T[:3, 3] = (sp.eye(3) + (1 - sp.cos(th)) / th**2 * W + (th - sp.sin(th)) / th**3 * W * W) * v
    return T


def log_se3(T):
    r"""The twist ``xi = [v; ω]`` with ``exp_se3(xi) == T`` and :math:`|\omega| \le \pi`.

    :math:`\omega` is :func:`log_so3` of the rotation (accurate at θ = 0 and θ = π) and
    :math:`v = V^{-1} p` with

    .. math:: V^{-1} = I - \tfrac12 W + \frac{1}{\theta^2}\Bigl(1 - \frac{\theta}{2}
              \cot\frac{\theta}{2}\Bigr) W^2 ,

    whose last coefficient tends to 1/12 as θ → 0 (series there) and is 1/π² at θ = π.
    At θ = π, ω and −ω describe the same rotation; kinlib returns the one of
    :func:`log_so3`. Numeric input only.

    >>> xi = np.array([0.1, -0.2, 0.3, 0.4, 0.5, -0.6])
    >>> bool(np.allclose(log_se3(exp_se3(xi)), xi))
    True
    """
    if is_symbolic(T):
        raise KinlibError("log_se3: expected a numeric 4×4 transform; the logarithm of a "
                          "symbolic pose has no general closed form (use exp_se3 with "
                          "symbols and compare)")
    a = check_transform(T)
    w = log_so3(a[..., :3, :3])
    th = np.linalg.norm(w, axis=-1)
    small = th < _SMALL
    t = np.where(small, 1.0, th)
    half = 0.5 * t
    coef = np.where(small, 1.0 / 12.0 + th**2 / 720.0 + th**4 / 30240.0,
                    (1.0 - half * np.cos(half) / np.sin(half)) / t**2)
    W = skew(w)
    Vinv = np.eye(3) - 0.5 * W + coef[..., None, None] * (W @ W)
    v = np.einsum("...ij,...j->...i", Vinv, a[..., :3, 3])
    return np.concatenate([v, w], axis=-1)


def adjoint(T):
    r"""The 6×6 adjoint :math:`\mathrm{Ad}_T` mapping twists ``[v; ω]`` between frames:
    :math:`\xi_A = \mathrm{Ad}_{T_{AB}}\, \xi_B`, :math:`[\xi_A] = T [\xi_B] T^{-1}`.

    .. math:: \mathrm{Ad}_T = \begin{bmatrix} R & [p]_\times R\\ 0 & R\end{bmatrix}

    (Modern Robotics' :math:`\begin{bmatrix} R & 0\\ [p]R & R\end{bmatrix}` is the same map
    in its :math:`[\omega; v]` order.) Batched; sympy input gives a ``sympy.Matrix``.

    >>> from kinlib import rotz, transform
    >>> A = adjoint(transform(rotz(0.3), [1.0, 2.0, 3.0]))
    >>> A.shape, bool(np.allclose(A[3:, :3], 0))
    ((6, 6), True)
    """
    if is_symbolic(T):
        import sympy as sp

        from ..symbolic import _sym

        M = _sym.matrix(T, (4, 4), "T")
        R, p = M[:3, :3], M[:3, 3]
        A = sp.zeros(6, 6)
        A[:3, :3] = R
        A[3:, 3:] = R
        A[:3, 3:] = _sym.skew(p) * R
        return A
    a = check_transform(T)
    R, p = a[..., :3, :3], a[..., :3, 3]
    A = np.zeros(a.shape[:-2] + (6, 6))
    A[..., :3, :3] = R
    A[..., 3:, 3:] = R
    A[..., :3, 3:] = skew(p) @ R
    return A
