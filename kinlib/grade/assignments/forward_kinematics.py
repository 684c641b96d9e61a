"""Assignment 02 · forward kinematics: the standard DH matrix, the pose of a DH table's last
frame, and the recursive matrix stack over a URDF-like joint tree (seed 000).

The references are kinlib: :func:`kinlib.dh_transform` (the DH table's product of them,
which is :meth:`kinlib.Robot.from_dh`'s forward kinematics), and
:meth:`kinlib.Robot.link_poses` of a robot built from the joint dict. The mistake models of
the matrix stack share one traversal (:func:`stack`) with a right joint transform swapped for
a wrong one, so each names exactly one mistake.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from functools import reduce

import numpy as np

import kinlib as kl
from kinlib.model import Joint, Link, origin_from_xyz_rpy
from kinlib.robots.autorob import urdf_path

from .._checks import RIGHT, Assignment, Check, Mistake, Verdict, as_numeric, close, fmt
from .._wire import Odd
from .common import DEGREES

MOVABLE = ("revolute", "continuous", "prismatic")
CRAIG = ("this is Craig's modified DH, A = Rx(α) Tx(a) Rz(θ) Tz(d) (the same as multiplying "
         "the four factors in reverse order): standard DH, used here, is "
         "A = Rz(θ) Tz(d) Tx(a) Rx(α), first about and along z, then along and about the new x")


# -- the DH matrix --------------------------------------------------------------------------
def dh(theta, d, a, alpha) -> np.ndarray:
    return kl.dh_transform(theta=theta, d=d, a=a, alpha=alpha)


def _rot_transposed(T) -> np.ndarray:
    T = np.array(T, dtype=float)
    T[:3, :3] = T[:3, :3].T.copy()
    return T


def _with_p(T, p) -> np.ndarray:
    T = np.array(T, dtype=float)
    T[:3, 3] = p
    return T


DH_MISTAKES = [  # (key, message, model(theta, d, a, alpha))
    ("modified", CRAIG, lambda t, d, a, al: kl.mdh_transform(theta=t, d=d, a=a, alpha=al)),
    ("transposed", "the rotation part is transposed (Rᵀ: the frames are mixed up, or the "
                   "signs of the sines swapped): R = Rz(θ) Rx(α), whose first column is "
                   "(cos θ, sin θ, 0) and third row (0, sin α, cos α)",
     lambda t, d, a, al: _rot_transposed(dh(t, d, a, al))),
    ("layout", "you returned the transpose of the whole 4×4: the translation "
               "(a cos θ, a sin θ, d) is the last column, and the last row is [0, 0, 0, 1]",
     lambda t, d, a, al: dh(t, d, a, al).T),
    ("degrees", DEGREES.message, lambda t, d, a, al: dh(np.deg2rad(t), d, a, np.deg2rad(al))),
    ("theta sign", "the signs of sin θ are flipped (you built Rz(−θ)): Rz(θ)'s first column "
                   "is (cos θ, sin θ, 0) and the translation is (a cos θ, a sin θ, d)",
     lambda t, d, a, al: dh(-t, d, a, al)),
    ("theta sign", "the signs of sin θ in the rotation part are flipped (Rz(−θ)): Rz(θ)'s "
                   "first column is (cos θ, sin θ, 0)",
     lambda t, d, a, al: _with_p(dh(-t, d, a, al), dh(t, d, a, al)[:3, 3])),
    ("alpha sign", "the signs of sin α are flipped (you built Rx(−α)): the third row of A is "
                   "(0, sin α, cos α, d), the second (sin θ, cos θ cos α, −cos θ sin α, a sin θ)",
     lambda t, d, a, al: dh(t, d, a, -al)),
    ("translation", "a cos θ and a sin θ are swapped: the translation is "
                    "(a cos θ, a sin θ, d), the point a along the x axis turned by θ",
     lambda t, d, a, al: _with_p(dh(t, d, a, al), [a * np.sin(t), a * np.cos(t), d])),
    ("translation", "the translation must be (a cos θ, a sin θ, d): the length a is measured "
                    "along the x axis after the rotation by θ about z, not before it",
     lambda t, d, a, al: _with_p(dh(t, d, a, al), [a, 0.0, d])),
    ("d axis", "d and a are swapped: d is the offset along z (the translation's third entry), "
               "a the length along the turned x axis", lambda t, d, a, al: dh(t, a, d, al)),
    ("d axis", "d slides along the old z axis, before the twist α: A = Rz(θ) Tz(d) Tx(a) "
               "Rx(α), so the translation is (a cos θ, a sin θ, d), not along the twisted z",
     lambda t, d, a, al: dh(t, 0.0, a, al) @ dh(0.0, d, 0.0, 0.0)),
]


def _dh_cases(rng):
    h = np.pi / 2
    fixed = [(0.0, 0.0, 0.0, 0.0), (h, 0.0, 2.0, 0.0), (0.0, 0.5, 1.0, h), (h, 0.3, 0.0, -h),
             (np.pi, 1.0, 1.0, np.pi), (0.3, 0.2, 0.1, 0.5), (-1.0, 0.0, 0.4318, 0.0),
             (0.0, 0.14909, 0.0, -h), (2.5, -0.7, -0.3, 1.2), (-h, 0.2, 0.6, h)]
    out = list(fixed)
    for _ in range(80):
        t, d, a = rng.uniform(-np.pi, np.pi), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)
        al = rng.choice([0.0, h, -h, np.pi]) if rng.random() < 0.3 else rng.uniform(-np.pi,
                                                                                   np.pi)
        out.append(tuple(float(x) for x in (t, d, a, al)))
    return out


# -- forward kinematics of a DH table -------------------------------------------------------
def _row_params(row, qi) -> tuple:
    """(θ, d, a, α) of one row at joint value qi."""
    if row["type"] == "prismatic":
        return row["theta"], qi + row["d"], row["a"], row["alpha"]
    return qi + row["theta"], row["d"], row["a"], row["alpha"]


def _chain(table, q, link: Callable, params: Callable = _row_params, reverse=False):
    mats = [link(*params(row, float(qi))) for row, qi in zip(table, q, strict=True)]
    return reduce(np.matmul, mats[::-1] if reverse else mats, np.eye(4))


def fk_dh_reference(table, q) -> np.ndarray:
    """T_0n = A_1(q_1) … A_n(q_n), standard DH."""
    return _chain(table, q, dh)


def _no_offsets(row, qi):
    if row["type"] == "prismatic":
        return row["theta"], qi, row["a"], row["alpha"]
    return qi, row["d"], row["a"], row["alpha"]


def _all_revolute(row, qi):
    return qi + row["theta"], row["d"], row["a"], row["alpha"]


def _fk_mistakes():
    out = [
        Mistake("order", "you multiplied in reverse order, A_n … A_1: the pose of the last "
                         "frame is T_0n = A_1(q_1) A_2(q_2) … A_n(q_n), the base's transform "
                         "leftmost", lambda tb, q: _chain(tb, q, dh, reverse=True)),
        Mistake("offsets", "the table's constants were dropped for the joint variable: "
                           "a revolute row has θ = q_i + theta (d from the table), a "
                           "prismatic row d = q_i + d (θ from the table)",
                lambda tb, q: _chain(tb, q, dh, _no_offsets)),
        Mistake("prismatic", "the prismatic rows were treated as revolute: for "
                             "type 'prismatic' q_i moves d (d = q_i + d), and θ is the "
                             "table's constant", lambda tb, q: _chain(tb, q, dh, _all_revolute)),
        Mistake("modified", "each A_i is " + CRAIG,
                lambda tb, q: _chain(tb, q, lambda *p: kl.mdh_transform(*p))),
        Mistake("transposed", "each row's matrix has its rotation part transposed: build "
                              "A_i = Rz(θ) Tz(d) Tx(a) Rx(α) as in dh_matrix",
                lambda tb, q: _chain(tb, q, lambda *p: _rot_transposed(dh(*p)))),
        Mistake("transposed", "each row's 4×4 matrix is transposed: the translation is the "
                              "last column of A_i, the last row is [0, 0, 0, 1]",
                lambda tb, q: _chain(tb, q, lambda *p: dh(*p).T)),
        Mistake("degrees", DEGREES.message,
                lambda tb, q: _chain(tb, q, lambda t, d, a, al: dh(np.deg2rad(t), d, a,
                                                                   np.deg2rad(al)))),
    ]
    for key, _, model in DH_MISTAKES[4:]:  # the sign and translation slips of dh_matrix
        out.append(Mistake("dh_matrix", f"each A_i has the mistake '{key}' of dh_matrix: "
                                        "make dh_matrix right first and build every A_i "
                                        "with it", lambda tb, q, m=model: _chain(tb, q, m)))
    return out


def _row(rtype, a, alpha, d, theta) -> dict:
    return {"a": float(a), "alpha": float(alpha), "d": float(d), "theta": float(theta),
            "type": rtype}


def dh_table_of(robot) -> list[dict]:
    """A kinlib DH robot's rows as the assignment's dicts (offset → theta or d)."""
    out = []
    for r in robot.dh_rows:
        pris = r.joint == "prismatic"
        out.append(_row(r.joint, r.a, r.alpha, r.offset if pris else r.d,
                        r.theta if pris else r.offset + r.theta))
    return out


def _random_table(rng, n):
    rows = []
    for _ in range(n):
        pris = rng.random() < 0.3
        alpha = rng.choice([0.0, np.pi / 2, -np.pi / 2]) if rng.random() < 0.4 \
            else rng.uniform(-np.pi, np.pi)
        a = 0.0 if rng.random() < 0.2 else rng.uniform(-1.0, 1.0)
        theta = rng.uniform(-np.pi, np.pi) if rng.random() < 0.8 else 0.0
        d = rng.uniform(-0.8, 0.8) if rng.random() < 0.8 else 0.0
        rows.append(_row("prismatic" if pris else "revolute", a, alpha, d, theta))
    return rows


def _random_q(rng, table):
    return np.array([rng.uniform(-1.0, 1.0) if r["type"] == "prismatic"
                     else rng.uniform(-np.pi, np.pi) for r in table])


def _fk_dh_cases(rng):
    from kinlib.robots import planar_2r, puma560

    puma = puma560()
    table = dh_table_of(puma)
    lo, hi = puma.limits.T
    out = [(table, np.array(puma.poses[k])) for k in ("zero", "table", "ready")]
    out += [(table, rng.uniform(lo, hi)) for _ in range(9)]
    for _ in range(8):
        l1, l2 = rng.uniform(0.3, 1.5, 2)
        out.append((dh_table_of(planar_2r(float(l1), float(l2))),
                    rng.uniform(-np.pi, np.pi, 2)))
    out.append(([_row("prismatic", 0.2, 0.0, 0.3, 0.5)], np.array([0.4])))
    out.append(([_row("revolute", 0.5, np.pi / 2, 0.2, 0.3),
                 _row("prismatic", 0.0, 0.0, 0.1, -np.pi / 2)], np.array([0.0, 0.0])))
    for i in range(80):
        tb = _random_table(rng, 2 + i % 5)
        if i % 4 == 0 and all(r["type"] == "revolute" for r in tb):
            tb[int(rng.integers(len(tb)))]["type"] = "prismatic"
        out.append((tb, _random_q(rng, tb)))
    return out


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
    """The joint dict as a kinlib Robot (axes normalised by :class:`kinlib.model.Joint`)."""
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
    """Seed 000's test_robot as the assignment's dict, values as written in the URDF."""
    root = ET.parse(str(urdf_path())).getroot()

    def nums(el, attr):
        return [float(x) for x in el.get(attr, "0 0 0").split()]
    joints = []
    for j in root.iter("joint"):
        o = j.find("origin")
        joints.append({"name": j.get("name"), "type": j.get("type"),
                       "parent": j.find("parent").get("link"),
                       "child": j.find("child").get("link"),
                       "xyz": nums(o, "xyz"), "rpy": nums(o, "rpy"),
                       "axis": nums(j.find("axis"), "xyz")})
    children = {j["child"] for j in joints}
    (base,) = [lk.get("name") for lk in root.iter("link") if lk.get("name") not in children]
    return {"root": base, "joints": joints}


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
        Check("dh_matrix", 8, "standard DH link transform A = Rz(θ) Tz(d) Tx(a) Rx(α)",
              _dh_cases, dh, [Mistake(k, m, f) for k, m, f in DH_MISTAKES]),
        Check("fk_dh", 12, "pose of the last frame of a DH table, T_0n = A_1 … A_n",
              _fk_dh_cases, fk_dh_reference, _fk_mistakes()),
        Check("fk_matrix_stack", 14, "every link's pose by the recursive matrix stack",
              _stack_cases, judge=_judge_stack, on_error=_stack_error_hint),
    ]
    return Assignment("02_forward_kinematics", "Forward kinematics", checks)
