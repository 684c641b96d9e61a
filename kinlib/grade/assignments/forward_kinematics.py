"""Assignment 02 · forward kinematics: the standard DH matrix (numerically, and derived with
sympy), the pose of a DH table's last frame, and the recursive matrix stack over a URDF-like
joint tree (seed 000).

The references are kinlib: :func:`kinlib.dh_transform` (the DH table's product of them,
which is :meth:`kinlib.Robot.from_dh`'s forward kinematics), and
:meth:`kinlib.Robot.link_poses` of a robot built from the joint dict. The mistake models of
the matrix stack share one traversal (:func:`stack`) with a right joint transform swapped for
a wrong one, so each names exactly one mistake.
"""

from __future__ import annotations

import numpy as np

import kinlib as kl
from kinlib.models.tree import Joint, Link, origin_from_xyz_rpy
from kinlib.models.urdf import joints_as_written
from kinlib.robots.autorob import autorob_test_robot, urdf_path

from .._checks import RIGHT, Assignment, Check, Mistake, Verdict, as_numeric, close, fmt
from .._wire import Odd
from ._fk_dh import (
    DH_MISTAKES,
    _dh_cases,
    _fk_dh_cases,
    _fk_mistakes,
    _rot_transposed,
    dh,
    dh_symbolic_check,
)
from ._fk_dh import _row as _row
from ._fk_dh import dh_table_of as dh_table_of
from ._fk_dh import fk_dh_reference as fk_dh_reference

MOVABLE = ("revolute", "continuous", "prismatic")


# -- the matrix stack -----------------------------------------------------------------------
def _rpy(rpy, seq="xyz") -> np.ndarray:
    return kl.matrix_from_euler(np.asarray(rpy, dtype=float), seq)


def _homog(R=None, p=None) -> np.ndarray:
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if p is not None:
        T[:3, 3] = p
    return T


def _rodrigues_raw(k, t) -> np.ndarray:
    """cos t I + sin t [k]× + (1 − cos t) k kᵀ, k as given (not normalised)."""
    k = np.asarray(k, dtype=float)
    return np.cos(t) * np.eye(3) + np.sin(t) * kl.skew(k) + (1 - np.cos(t)) * np.outer(k, k)


def origin(jt, seq="xyz") -> np.ndarray:
    return _homog(_rpy(jt["rpy"], seq), jt["xyz"])


def motion(jt, qj, normalise=True) -> np.ndarray:
    u = np.asarray(jt["axis"], dtype=float)
    if normalise:
        u = u / np.linalg.norm(u)
    if jt["type"] == "prismatic":
        return _homog(p=qj * u)
    if jt["type"] in ("revolute", "continuous"):
        return _homog(_rodrigues_raw(u, qj))
    return np.eye(4)


def right_local(jt, qj) -> np.ndarray:
    return origin(jt) @ motion(jt, qj)


def stack(robot, q, local=right_local, *, from_root=False, pop=True) -> dict:
    """Every link's pose by the matrix stack, with ``local(joint, q_j)`` each joint's
    transform; ``from_root``: no stack (each child gets its joint's own transform);
    ``pop=False``: the stack is never popped (one running matrix, children in list order)."""
    children: dict[str, list] = {}
    for jt in robot["joints"]:
        children.setdefault(jt["parent"], []).append(jt)
    poses = {robot["root"]: np.eye(4)}
    running = [np.eye(4)]

    def visit(link):
        for jt in children.get(link, []):
            L = local(jt, float(q.get(jt["name"], 0.0)))
            if from_root:
                poses[jt["child"]] = L
            elif pop:
                poses[jt["child"]] = poses[link] @ L
            else:
                running[0] = running[0] @ L
                poses[jt["child"]] = running[0]
            visit(jt["child"])
    visit(robot["root"])
    return poses


def kinlib_robot(robot) -> kl.Robot:
    """The joint dict as a kinlib Robot (axes normalised by :class:`kinlib.models.tree.Joint`)."""
    names = [robot["root"]] + [jt["child"] for jt in robot["joints"]]
    joints = [Joint(jt["name"], jt["type"], jt["parent"], jt["child"],
                    origin=origin_from_xyz_rpy(jt["xyz"], jt["rpy"]), axis=jt["axis"])
              for jt in robot["joints"]]
    return kl.Robot("assignment_tree", [Link(n) for n in names], joints)


def stack_reference(robot, q) -> dict:
    return kinlib_robot(robot).link_poses(dict(q))


def _transposed_factors(jt, qj, whole=False):
    def tr(T):
        return T.T if whole else _rot_transposed(T)
    return tr(origin(jt)) @ tr(motion(jt, qj))


def _back(jt, qj) -> float:
    return -qj if jt["type"] in ("revolute", "continuous") else qj


def _angles_negated(jt, qj):
    """Every elementary rotation by −angle: Rz(−y) Ry(−p) Rx(−r), then R_u(−q)."""
    return origin(dict(jt, rpy=[-x for x in jt["rpy"]])) @ motion(jt, _back(jt, qj))


STACK_MISTAKES = [  # (key, message, model(robot, q) -> dict)
    ("rpy", "the origin's rpy was applied as Rx(roll) Ry(pitch) Rz(yaw) (intrinsic XYZ): URDF "
            "rpy are fixed-axis angles, R = Rz(yaw) Ry(pitch) Rx(roll)",
     lambda r, q: stack(r, q, lambda jt, v: origin(jt, "XYZ") @ motion(jt, v))),
    ("rpy", "roll turns about x, pitch about y and yaw about z: rpy = [roll, pitch, yaw] gives "
            "R = Rz(yaw) Ry(pitch) Rx(roll); you turned by roll about z",
     lambda r, q: stack(r, q, lambda jt, v: origin(jt, "ZYX") @ motion(jt, v))),
    ("motion first", "the joint's motion comes after its origin: T_child = T_parent @ "
                     "T_origin(xyz, rpy) @ motion(axis, q), since the axis is expressed in "
                     "the joint (child) frame", lambda r, q: stack(
                         r, q, lambda jt, v: motion(jt, v) @ origin(jt))),
    ("axis", "the joint axis is not a unit vector here: normalise it, u = axis / |axis|, "
             "before Rodrigues' formula (revolute) or q·u (prismatic)",
     lambda r, q: stack(r, q, lambda jt, v: origin(jt) @ motion(jt, v, normalise=False))),
    ("no stack", "each link got only its own joint's transform, as if its parent were the "
                 "root: T_world_child = T_world_parent @ T_origin @ motion, recursively down "
                 "the tree (the matrix stack)", lambda r, q: stack(r, q, from_root=True)),
    ("pop", "a link's pose was built on top of its sibling's: after a child's subtree, go "
            "back to the parent's matrix (pop the stack; with recursion, pass T_world_parent "
            "down and never change it in place)", lambda r, q: stack(r, q, pop=False)),
    ("transposed", "each rotation (the origin's and the joint motion's) is transposed: check "
                   "the signs of the sines in Rz, Ry, Rx and in Rodrigues' sin q [u]× term",
     lambda r, q: stack(r, q, _transposed_factors)),
    ("transposed", "each elementary rotation is transposed (turns by −angle): "
                   "check the signs of the sines in Rz, Ry, Rx and in Rodrigues' sin q [u]× "
                   "term", lambda r, q: stack(r, q, _angles_negated)),
    ("transposed", "each 4×4 transform is transposed: the translation is the last column, "
                   "the last row is [0, 0, 0, 1]",
     lambda r, q: stack(r, q, lambda jt, v: _transposed_factors(jt, v, whole=True))),
    ("sign", "the revolute joints turn the wrong way (by −q): Rodrigues' formula is "
             "R = cos q I + sin q [u]× + (1 − cos q) u uᵀ",
     lambda r, q: stack(r, q, lambda jt, v: right_local(jt, _back(jt, v)))),
]


def _depth_first(robot) -> list[str]:
    children: dict[str, list] = {}
    for jt in robot["joints"]:
        children.setdefault(jt["parent"], []).append(jt["child"])
    out, todo = [], [robot["root"]]
    while todo:
        link = todo.pop()
        out.append(link)
        todo.extend(reversed(children.get(link, [])))
    return out


def _judge_stack(args, got):
    robot, q = args
    want = "a dict link name → 4×4 pose"
    if got is None:
        return Verdict(False, "none", f"returned None, expected {want}: is there a `return` "
                                      "at the end of your function?")
    if isinstance(got, Odd) or not isinstance(got, dict):
        what = got.type if isinstance(got, Odd) else type(got).__name__
        return Verdict(False, "type", f"returned a {what}, expected {want}")
    ref = stack_reference(robot, q)
    order = _depth_first(robot)
    missing = [n for n in order if n not in got]
    extra = [k for k in got if k not in ref]
    if missing or extra:
        msg = "the dict must have exactly one entry per link"
        if missing:
            root = " (the root's pose is the identity)" if robot["root"] in missing else ""
            msg += f"; missing {fmt(missing, 100)}{root}"
        if extra:
            msg += f"; not links of this robot: {fmt(extra, 100)}"
        return Verdict(False, "links", msg, sorted(ref))
    mats = {}
    for n in order:
        a, bad = as_numeric(got[n], (4, 4), "a 4×4 pose")
        if a is None:
            return Verdict(False, bad.key, f"link {n!r}: {bad.message}", {n: ref[n]})
        mats[n] = a
    wrong = [n for n in order if not close(mats[n], ref[n], 1e-6)]
    if not wrong:
        return RIGHT
    first = wrong[0]
    for key, message, model in STACK_MISTAKES:
        try:
            m = model(robot, q)
            hit = all(close(mats[n], m[n], 1e-6) for n in order)
        except Exception:
            continue
        if hit and not all(close(m[n], ref[n], 1e-6) for n in order):
            return Verdict(False, key, f"{message} (first wrong link: {first!r})",
                           {first: ref[first]})
    err = float(np.abs(mats[first] - ref[first]).max())
    if first == robot["root"]:
        return Verdict(False, "root", f"the root link {first!r} must have the identity pose",
                       {first: ref[first]})
    jt = next(j for j in robot["joints"] if j["child"] == first)
    return Verdict(False, "wrong", f"link {first!r} is off by up to {err:.3g} while its parent "
                                   f"{jt['parent']!r} is right: look at joint {jt['name']!r} "
                                   f"({jt['type']}): T_child = T_parent @ T_origin(xyz, rpy) "
                                   "@ motion(axis, q)", {first: ref[first]})


def autorob_dict() -> dict:
    """Seed 000's test_robot as the assignment's dict, values as written in the URDF (read
    by kinlib's URDF reader, which keeps them so: the axes are not normalised)."""
    robot, joints = autorob_test_robot(), joints_as_written(urdf_path())
    keys = ("name", "type", "parent", "child", "xyz", "rpy", "axis")
    return {"root": robot.root, "joints": [{k: j[k] for k in keys} for j in joints]}


def random_tree(rng, n: int, shuffle: bool) -> dict:
    """A branched tree of ``n`` joints (all four types, non-unit axes, non-zero rpy)."""
    kinds = ["revolute", "prismatic", "continuous", "fixed"][:min(n, 4)]
    kinds += list(rng.choice(MOVABLE + ("fixed",), n - len(kinds), p=[.3, .3, .25, .15]))
    kinds = [str(k) for k in rng.permutation(kinds)]
    names = [f"link_{c}" for c in rng.permutation(list("abcdefghijk"))[:n + 1]]
    # joint i joins link i + 1 to an earlier link: the root has two children, and link 3
    # hangs below link 1 or 2 (so every tree branches and is at least three links deep)
    parents = [0, 0, int(rng.integers(1, 3))] + [int(rng.integers(0, i + 1))
                                                 for i in range(3, n)]
    joints = []
    for i, kind in enumerate(kinds):
        axis = rng.normal(size=3)
        if rng.random() < 0.3:  # an axis along a coordinate axis, scaled
            axis = np.eye(3)[int(rng.integers(3))] * rng.choice([-1.0, 1.0])
        axis = axis / np.linalg.norm(axis) * rng.uniform(0.3, 2.5)
        joints.append({"name": f"j{i + 1}", "type": kind, "parent": names[parents[i]],
                       "child": names[i + 1],
                       "xyz": [float(x) for x in rng.uniform(-1.0, 1.0, 3)],
                       "rpy": [float(x) for x in rng.uniform(-np.pi, np.pi, 3)],
                       "axis": [float(x) for x in axis]})
    if shuffle:
        joints = [joints[i] for i in rng.permutation(n)]
    return {"root": names[0], "joints": joints}


def random_joint_values(rng, robot) -> dict:
    return {jt["name"]: float(rng.uniform(-1.0, 1.0) if jt["type"] == "prismatic"
                              else rng.uniform(-np.pi, np.pi))
            for jt in robot["joints"] if jt["type"] != "fixed"}


def _stack_cases(rng):
    auto = autorob_dict()
    out = [(auto, {"joint1": 0.0, "joint2": 0.0, "joint3": 0.0}),
           (auto, {"joint1": 0.5, "joint2": -0.8, "joint3": 1.2})]
    out += [(auto, random_joint_values(rng, auto)) for _ in range(8)]
    for i in range(100):
        tree = random_tree(rng, 3 + i % 6, shuffle=i % 2 == 1)
        out.append((tree, random_joint_values(rng, tree)))
    return out


def _stack_error_hint(args, error: str):
    if error.startswith("raised KeyError"):
        return ("The joints come in no particular order: start at the root link and visit "
                "the joints whose parent is the current link (recursively), instead of "
                "walking the list in order")
    return None


def assignment() -> Assignment:
    checks = [
        Check("dh_matrix", 5, "standard DH link transform A = Rz(θ) Tz(d) Tx(a) Rx(α)",
              _dh_cases, dh, [Mistake(k, m, f) for k, m, f in DH_MISTAKES]),
        dh_symbolic_check(),
        Check("fk_dh", 12, "pose of the last frame of a DH table, T_0n = A_1 … A_n",
              _fk_dh_cases, fk_dh_reference, _fk_mistakes()),
        Check("fk_matrix_stack", 14, "every link's pose by the recursive matrix stack",
              _stack_cases, judge=_judge_stack, on_error=_stack_error_hint),
    ]
    return Assignment("02_forward_kinematics", "Forward kinematics", checks)
