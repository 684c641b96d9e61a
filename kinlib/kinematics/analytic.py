"""The analytic Jacobian of a robot: the rates of the tip's Euler/fixed angles (seed 004),
from the geometric Jacobian and the Euler-rate map of :mod:`kinlib.spatial.velocity`."""

from __future__ import annotations

import numpy as np

from .._validate import as_tol, fmt_index, parse_seq
from ..conventions import GIMBAL_TOL
from ..errors import KinlibError
from ..spatial.euler import EULER_SEQUENCES, euler_from_matrix
from ..spatial.velocity import euler_rate_matrix

__all__ = ["analytic_jacobian"]


def analytic_jacobian(robot, q, link=None, seq: str = "ZYX", *, tol: float = GIMBAL_TOL):
    """The analytic Jacobian ``[ṗ; φ̇] = J_a(q) q̇`` for the Euler/fixed sequence ``seq``.

    ``J_a = [J_v; E(φ)⁻¹ J_ω]`` with the geometric Jacobian's rows ``[J_v; J_ω]`` and the
    rate map ``ω = E(φ) φ̇`` at ``φ = euler_from_matrix(R(q), seq)``. At gimbal lock E is
    singular (``|det E| < tol``) and the Euler rates do not exist: that raises
    :class:`~kinlib.KinlibError` — it is the representation's singularity, not the
    robot's; use the geometric Jacobian there. The arguments come in kinlib's order:
    ``q``, then ``link`` (default: the tip), then ``seq``.
    """
    if isinstance(link, str) and link in EULER_SEQUENCES and link not in robot.link_names:
        raise KinlibError(f"link: {link!r} is an Euler sequence, not a link of robot "
                          f"{robot.name!r}; the order is analytic_jacobian(q, link, seq), "
                          f"e.g. seq={link!r}")
    parse_seq(seq)

    T, J = robot.fk_and_jacobian(q, link)
    phi = euler_from_matrix(T[..., :3, :3], seq)
    E = euler_rate_matrix(phi, seq)
    det = np.linalg.det(E)
    bad = np.abs(det) < as_tol(tol)
    if bad.any():
        where = fmt_index(bad.shape, bad)
        raise KinlibError(f"q{where}: the {seq} angles are at gimbal lock (|det E| = "
                          f"{float(np.abs(det[bad]).flat[0]):.2g}): their rates are undefined "
                          f"here; use the geometric Jacobian")
    Ja = J.copy()
    Ja[..., 3:, :] = np.linalg.solve(E, J[..., 3:, :])
    return Ja
