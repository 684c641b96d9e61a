"""The singularity half of assignment 06 (differential kinematics): Yoshikawa's
manipulability ``√det(J Jᵀ)`` and the task-space direction a singular Jacobian loses (None
where it is not singular).

Every Jacobian here is m×n with m ≤ n (at least as many joints as task directions): a
robot's 6×6 or 6×7 Jacobian, the 3×3 position Jacobian of a 3-joint arm, the 2R arm's 2×2,
and matrices with chosen singular values. The singular configurations are exact: the
PUMA's and UR5's wrist (q5 = 0), the stretched and folded elbows, the Panda's joints 1, 3
and 5 on one line, and roots of det J found by bisection along one joint.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl

from .._checks import RIGHT, Check, Mistake, Verdict, as_numeric, close, fmt

__all__ = ["manipulability_check", "lost_direction_check", "singular_configurations",
           "with_singular_values", "lost_subspace", "manipulability_tolerance"]


def with_singular_values(rng, m: int, n: int, sigma) -> np.ndarray:
    """A random m×n matrix U diag(σ) Vᵀ with the given singular values (m ≤ n).

    >>> J = with_singular_values(np.random.default_rng(0), 2, 3, [2.0, 0.5])
    >>> J.shape, np.linalg.svd(J, compute_uv=False).round(12)
    ((2, 3), array([2. , 0.5]))
    """
    U, _ = np.linalg.qr(rng.normal(size=(m, m)))
    V, _ = np.linalg.qr(rng.normal(size=(n, n)))
    return U @ np.diag(np.asarray(sigma, dtype=float)) @ V[:, :m].T


def _robot(name):
    from kinlib import robots

    return {"planar_2r": lambda: robots.planar_2r(1.0, 0.7)}.get(name, getattr(robots, name,
                                                                               None))()


def _jac(robot, q, rows=slice(None)):
    return robot.jacobian(q)[rows]


def _bisect_det(f, a: float, b: float) -> float:
    """A root of f in [a, b] (f(a), f(b) of opposite signs), to the last bit."""
    fa = f(a)
    for _ in range(80):
        c = 0.5 * (a + b)
        if c in (a, b):
            break
        fc = f(c)
        if fc == 0:
            return c
        if (fc < 0) == (fa < 0):
            a, fa = c, fc
        else:
            b = c
    return 0.5 * (a + b)


def _det_root(rng, robot, joint: int, rows=slice(None)):
    """A configuration where det J = 0 along ``joint`` (the others random), or None."""
    for _ in range(20):
        q = rng.uniform(-np.pi, np.pi, robot.dof)

        def f(t, q=q):
            x = q.copy()
            x[joint] = t
            return float(np.linalg.det(_jac(robot, x, rows)))
        grid = np.linspace(-np.pi, np.pi, 25)
        values = [f(t) for t in grid]
        for a, b, fa, fb in zip(grid, grid[1:], values, values[1:], strict=False):
            if fa * fb < 0:
                q[joint] = _bisect_det(f, a, b)
                return q
    return None


def singular_configurations(rng) -> list[tuple]:
    """``(J, q, robot name)`` at exact singularities of kinlib's robots."""
    out = []
    puma, ur5, panda, arm, two = (_robot(n) for n in ("puma560", "ur5", "panda",
                                                      "three_dof_arm", "planar_2r"))
    for robot, k in ((puma, 2), (ur5, 2)):  # the wrist: q5 = 0
        for _ in range(k):
            q = rng.uniform(-np.pi, np.pi, 6)
            q[4] = 0.0
            out.append((_jac(robot, q), q, robot.name))
    for robot, joint in ((puma, 2), (puma, 1), (ur5, 1), (ur5, 2)):  # elbow and shoulder
        q = _det_root(rng, robot, joint)
        if q is not None:
            out.append((_jac(robot, q), q, robot.name))
    for _ in range(2):  # the Panda stretched: joints 1, 3 and 5 on one line
        q = rng.uniform(-2.0, 2.0, 7)
        q[1] = q[3] = 0.0
        out.append((_jac(panda, q), q, panda.name))
    for t2 in (0.0, np.pi):  # the 2R arm stretched and folded; the 3-joint arm likewise
        q = np.array([rng.uniform(-np.pi, np.pi), t2])
        out.append((_jac(two, q)[:2], q, two.name))
        q = np.array([*rng.uniform(-np.pi, np.pi, 2), t2])
        out.append((_jac(arm, q)[:3], q, arm.name))
    return out


# -- manipulability -------------------------------------------------------------------------
def _square_det(J):
    if J.shape[0] != J.shape[1]:
        raise ValueError("only for a square J")
    return np.linalg.det(J)


def _jtj(J):
    if J.shape[0] == J.shape[1]:
        raise ValueError("the same as J Jᵀ for a square J")
    return np.sqrt(abs(np.linalg.det(J.T @ J)))


MANIP_MISTAKES = [
    Mistake("sign", "your w is negative: for a square J, √det(J Jᵀ) = |det J|; det J itself "
                    "changes sign with the configuration (the elbow's side, say)", _square_det),
    Mistake("squared", "you returned det(J Jᵀ), the square of the manipulability: "
                       "w = √det(J Jᵀ)", lambda J: np.linalg.det(J @ J.T)),
    Mistake("JTJ", "you used Jᵀ J (n×n): for n > m it has rank at most m and determinant 0; "
                   "the manipulability is √det(J Jᵀ), with the m×m product", _jtj),
    Mistake("smallest", "you returned the smallest singular value σ_min (how far J is from "
                        "the nearest singular matrix); the manipulability is their product, "
                        "w = σ1 σ2 ⋯ σm = √det(J Jᵀ)",
            lambda J: np.linalg.svd(J, compute_uv=False)[-1]),
]


def manipulability_tolerance(J) -> float:
    """How far a right w may be from kinlib's: 1e-6 relative, plus what rounding does to
    det(J Jᵀ) near a singularity, where √det magnifies it (1e-6 σ_1 σ_2 ⋯ σ_{m−1})."""
    s = np.linalg.svd(J, compute_uv=False)
    w = float(np.prod(s))
    return 1e-6 * (1.0 + w) + 1e-6 * float(s[0] * np.prod(s[:-1]))


def _judge_manip(args, got):
    (J,) = args
    expected = float(kl.manipulability(J))
    a, bad = as_numeric(got, ())
    if a is None:
        if bad.key == "nan" and expected < 1e-6:
            return Verdict(False, "negative", "NaN at a singular configuration: there "
                                              "det(J Jᵀ) is 0, and rounding can make it a hair "
                                              "negative (−1e-17), whose square root is NaN; "
                                              "clip it at 0 first (or multiply the singular "
                                              "values)", expected)
        return Verdict(bad.ok, bad.key, bad.message, expected)
    tol = manipulability_tolerance(J)
    if abs(float(a) - expected) <= tol:
        return RIGHT
    for m in MANIP_MISTAKES:
        try:
            wrong = float(m.model(J))
        except Exception:  # a model that does not apply to this J
            continue
        if abs(float(a) - wrong) <= tol and abs(wrong - expected) > tol:
            return Verdict(False, m.key, m.message, expected)
    return Verdict(False, "wrong", f"differs from √det(J Jᵀ) = {expected:.6g} by "
                                   f"{abs(float(a) - expected):.3g}", expected)


def _manip_hint(args, error: str):
    J = args[0]
    if "square" in error and J.shape[0] != J.shape[1]:
        return (f"J is {J.shape[0]}×{J.shape[1]}, not square: det J does not exist; "
                "w = √det(J Jᵀ) uses the square m×m matrix J Jᵀ")
    return None


def _manip_cases(rng):
    from kinlib import planar_2r_jacobian

    out = [np.eye(2), np.array([[3.0, 0.0], [0.0, -4.0]]), np.array([[1.0, 2.0, 2.0]]),
           planar_2r_jacobian(0.3, np.pi / 2, 1.0, 0.8)[:2]]
    puma, ur5, panda, arm, two = (_robot(n) for n in ("puma560", "ur5", "panda",
                                                      "three_dof_arm", "planar_2r"))
    for robot, k, rows in ((puma, 5, slice(None)), (ur5, 5, slice(None)),
                           (panda, 5, slice(None)), (arm, 4, slice(0, 3)),
                           (puma, 3, slice(0, 3)), (panda, 2, slice(0, 3)),
                           (two, 5, slice(0, 2))):
        for _ in range(k):
            out.append(_jac(robot, rng.uniform(-np.pi, np.pi, robot.dof), rows))
    for name in ("puma560", "ur5"):  # the space Jacobian (the same w: det Ad = 1)
        S, _ = kl.screw_axes(_robot(name))
        out += [kl.space_jacobian(S, rng.uniform(-np.pi, np.pi, 6)) for _ in range(2)]
    out += [J for J, _, _ in singular_configurations(rng)]
    for m, n in ((2, 3), (3, 4), (4, 6), (5, 7), (6, 6), (3, 3), (2, 2), (1, 4), (6, 7),
                 (3, 6)):  # chosen singular values, some exactly singular
        sigma = np.sort(rng.uniform(0.2, 2.0, m))[::-1] * 10.0 ** rng.uniform(-1, 1)
        out.append(with_singular_values(rng, m, n, sigma))
        sigma[-1] = 0.0
        out.append(with_singular_values(rng, m, n, sigma))
    return [(np.asarray(J, dtype=float),) for J in out]


def manipulability_check(points: float) -> Check:
    return Check("manipulability", points, "Yoshikawa's w = √det(J Jᵀ)", _manip_cases,
                 judge=_judge_manip, on_error=_manip_hint)


# -- the lost direction ---------------------------------------------------------------------
def lost_subspace(J, tol) -> np.ndarray:
    """The columns u_i of U (J = U Σ Vᵀ) with σ_i < tol σ_1: an orthonormal basis of the
    task-space directions J loses (none: shape (m, 0)).

    >>> lost_subspace(np.diag([2.0, 1e-9]), 1e-6).T
    array([[0., 1.]])
    >>> lost_subspace(np.diag([2.0, 1e-3]), 1e-6).shape
    (2, 0)
    """
    U, s, _ = np.linalg.svd(np.asarray(J, dtype=float))
    return U[:, : len(s)][:, s < tol * s[0]]


def _parallel(a, b) -> bool:
    return close(a, b, 1e-6) or close(a, -b, 1e-6)


def _judge_lost(args, got):
    J, tol = args
    m, n = J.shape
    U, s, _ = np.linalg.svd(J)
    ratio = float(s[-1] / s[0])
    lost = lost_subspace(J, tol)
    stated = f"σ_min/σ_max = {ratio:.3g}, tol = {tol:g}"
    absolute = (s[-1] < tol) != (ratio < tol)
    if lost.shape[1] == 0:
        if got is None:
            return RIGHT
        if absolute:
            return Verdict(False, "absolute", f"J is not singular ({stated}), but σ_min = "
                                              f"{s[-1]:.3g} < tol: the test is relative, "
                                              "σ_min < tol·σ_max (so the units of J do not "
                                              "matter)", None)
        return Verdict(False, "phantom", f"J is not singular here ({stated}): return None",
                       None)
    expected = lost[:, -1]
    if got is None:
        if absolute:
            return Verdict(False, "absolute", f"J is singular ({stated}), but σ_min = "
                                              f"{s[-1]:.3g} ≥ tol: the test is relative, "
                                              "σ_min < tol·σ_max (J in millimetres is as "
                                              "singular as in metres)", expected)
        return Verdict(False, "missed", f"J is singular ({stated}): return a unit vector u "
                                        "(m entries) with Jᵀu ≈ 0", expected)
    u, bad = as_numeric(got, (m,), "a unit vector")
    if u is None:
        if bad.key == "shape" and np.shape(got) == (n,) and n != m:
            return Verdict(False, "joint space", f"you returned {n} numbers, one per joint: "
                                                 "that is a joint velocity (a row of Vᵀ); the "
                                                 f"lost direction is in task space ({m} "
                                                 "entries), a column of U", expected)
        return Verdict(bad.ok, bad.key, bad.message, expected)
    size = float(np.linalg.norm(u))
    if abs(size - 1.0) > 1e-6:
        return Verdict(False, "unit", f"your vector has length {size:.6g}: return a unit "
                                      "vector (if several directions are lost, any unit vector "
                                      "among them, e.g. one column of U)", expected)
    if np.linalg.norm(u - lost @ (lost.T @ u)) <= 1e-6:
        return RIGHT
    if m == n and np.linalg.norm(J @ u) <= 1e-6 * s[0]:
        return Verdict(False, "joint space", "J u ≈ 0: your u is the joint motion that does "
                                             "nothing (a right singular vector, a row of Vᵀ); "
                                             "the lost task-space direction u has Jᵀu ≈ 0, a "
                                             "column of U", expected)
    if _parallel(u, U[:, 0]):
        return Verdict(False, "largest", "that is the direction the end effector moves "
                                         "fastest (σ_max): numpy sorts the singular values "
                                         "largest first, so the lost one is the last column, "
                                         "U[:, -1]", expected)
    if _parallel(u, U[-1, :]):
        return Verdict(False, "row", "that is the last row of U: the singular vectors are its "
                                     "columns, U[:, -1]", expected)
    return Verdict(False, "wrong", f"|Jᵀu| = {np.linalg.norm(J.T @ u):.3g} (σ_max = "
                                   f"{s[0]:.3g}): the end effector can still move along your "
                                   f"u; the lost direction has Jᵀu ≈ 0 ({fmt(expected)})",
                   expected)


def _margin_ok(J, tol) -> bool:
    """No singular value within a factor 1.5 of tol·σ_max (a clear answer either way)."""
    s = np.linalg.svd(J, compute_uv=False)
    r = s / s[0]
    return bool(np.all((r < tol / 1.5) | (r > tol * 1.5)))


def _tol_for(J, factor) -> float:
    """The tol at which σ_min/σ_max = factor·tol."""
    s = np.linalg.svd(J, compute_uv=False)
    return float(s[-1] / s[0] / factor)


def _lost_cases(rng):
    from kinlib import planar_2r_jacobian

    tols = (1e-6, 1e-4, 1e-3, 1e-2)
    out = [(planar_2r_jacobian(0.4, 0.0, 1.0, 0.8)[:2], 1e-6),  # stretched: along the arm
           (planar_2r_jacobian(0.4, np.pi / 2, 1.0, 0.8)[:2], 1e-6), (np.eye(3), 0.1)]
    for J, _, _ in singular_configurations(rng):  # exact: singular for any tol
        out.append((J, tols[int(rng.integers(4))]))
    two, ur5, puma, arm = (_robot(n) for n in ("planar_2r", "ur5", "puma560",
                                               "three_dof_arm"))
    for k, factor in enumerate((0.3, 0.5, 2.0, 3.0, 5.0, 0.2, 10.0, 0.4)):  # near ones
        q = rng.uniform(-np.pi, np.pi, 6)
        q[4] = 10.0 ** rng.uniform(-5, -2) * rng.choice([-1, 1])
        J = _jac((ur5, puma)[k % 2], q)
        out.append((J, _tol_for(J, factor)))
        t2 = 10.0 ** rng.uniform(-5, -2) + (np.pi if k % 3 == 0 else 0.0)
        J = planar_2r_jacobian(rng.uniform(-np.pi, np.pi), t2, 1.0, 0.8)[:2]
        out.append((J, _tol_for(J, factor)))
    for robot, rows, k in ((ur5, slice(None), 4), (puma, slice(None), 4),
                           (arm, slice(0, 3), 3), (two, slice(0, 2), 3)):  # regular
        for _ in range(k):
            J = _jac(robot, rng.uniform(-np.pi, np.pi, robot.dof), rows)
            out.append((J, float(np.clip(_tol_for(J, 1.0) / rng.uniform(3, 30), 1e-7, 1e-2))))
    for scale, singular in ((1e3, True), (1e3, True), (1e-3, False), (1e-3, False)):  # units
        J = planar_2r_jacobian(rng.uniform(-np.pi, np.pi), rng.uniform(0.01, 0.05), 0.6,
                               0.5)[:2] * scale  # millimetres or kilometres
        out.append((J, _tol_for(J, 3.0 if not singular else 0.3)))
    for m, n, lost in ((2, 2, 1), (3, 3, 1), (3, 5, 1), (4, 4, 2), (6, 6, 1), (6, 7, 2),
                       (2, 4, 1), (6, 6, 2), (3, 3, 0), (6, 7, 0), (4, 6, 0), (6, 6, 3),
                       (5, 5, 2), (2, 3, 0)):  # chosen singular values, 0 to 3 of them lost
        tol = tols[int(rng.integers(4))]
        big = rng.uniform(0.2, 2.0, m - lost)
        small = big.max() * tol * rng.choice([0.0, 1e-3, 0.1, 0.5], lost)
        sigma = np.sort(np.concatenate([big, small]))[::-1] * 10.0 ** rng.uniform(-2, 2)
        J = with_singular_values(rng, m, n, sigma)
        out.append((J, tol))
    cases = [(np.asarray(J, dtype=float), float(tol)) for J, tol in out]
    return [c for c in cases if _margin_ok(*c)]


def _is_regular(args) -> bool:
    return lost_subspace(*args).shape[1] == 0


def lost_direction_check(points: float) -> Check:
    return Check("lost_direction", points, "the task direction a singular J loses (None if "
                 "σ_min ≥ tol·σ_max)", _lost_cases, judge=_judge_lost, is_trivial=_is_regular,
                 trivial="of None where J is not singular")
