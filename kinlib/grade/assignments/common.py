"""Pieces shared by the assignments' checks: random inputs (the common mistakes are
:mod:`kinlib.check.mistakes`, shared with the notebooks), and the planar 2R arm's position
Jacobian in sympy, for the derivations of assignments 03 and 04."""

from __future__ import annotations

import numpy as np

import kinlib as kl
from kinlib.check.mistakes import DEGREES, TRANSPOSED, wxyz_read_as_xyzw

__all__ = ["DEGREES", "TRANSPOSED", "random_quats", "random_rotations",
           "random_unit_vectors", "wxyz_read_as_xyzw", "jacobian_2r", "symbolic_2r_cases"]


def random_unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def random_quats(rng: np.random.Generator, n: int) -> np.ndarray:
    """Unit quaternions [w, x, y, z], uniform on the sphere, w of either sign."""
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def random_rotations(rng: np.random.Generator, n: int) -> np.ndarray:
    return kl.matrix_from_quat(random_quats(rng, n))


def jacobian_2r(theta1, theta2, l1, l2, *, absolute: bool = False, turned: bool = False):
    """The 2×2 Jacobian ∂(x, y)/∂(θ1, θ2) of the planar 2R arm's tip, a sympy Matrix
    (``theta1``, ``theta2``: Symbols). The tip is the translation of kinlib's standard-DH
    product A1 A2; the keywords make mistakes: ``absolute``, θ2 measured from the x axis
    (link 2 at θ2, not θ1 + θ2); ``turned``, link 2 turned by a right angle (its tip at
    θ1 + θ2 + π/2)."""
    import sympy as sp

    t2 = theta2 - theta1 if absolute else theta2
    t2 = t2 + sp.pi / 2 if turned else t2
    T = kl.dh_transform(theta=theta1, d=0, a=l1, alpha=0) * \
        kl.dh_transform(theta=t2, d=0, a=l2, alpha=0)
    return T[:2, 3].jacobian([theta1, theta2])


def symbolic_2r_cases(rng: np.random.Generator) -> list[tuple]:
    """(θ1, θ2, l1, l2) for a derivation of the 2R arm: the angles are Symbols (the
    function differentiates by them); the lengths positive symbols, other names, exact
    numbers, or one symbol for both links."""
    import sympy as sp

    k = int(rng.integers(1, 10))
    t1, t2 = sp.symbols("theta1 theta2", real=True)
    q1, q2 = sp.symbols(f"q{k} q{k + 1}", real=True)
    l1, l2, length = sp.symbols(f"l1 l2 L{k}", positive=True)
    a, b = (sp.Rational(int(n), 10) for n in rng.choice(np.arange(3, 16), 2, replace=False))
    return [(t1, t2, l1, l2), (q1, q2, *sp.symbols(f"a{k} b{k}", positive=True)),
            (t1, t2, a, b), (q1, q2, length, length)]
