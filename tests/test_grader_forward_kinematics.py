"""Assignment 02 (forward kinematics): the grader's references agree with kinlib's robots,
its cases cover what they must, each classic mistake gets its diagnosis, and other right
answers (lists, another product, an iterative stack) are accepted.

Submissions are built from the source notebook's own code with one mistake patched in per
function; ``fk_dh`` calls a right copy ``_dh`` of ``dh_matrix`` so that each function
carries exactly its own mistake. ``dh_symbolic`` (the DH matrix derived with sympy) is
judged symbolically: see also ``test_grader_symbolic.py``.
"""

import numpy as np
import pytest
import sympy as sp
from grading_helpers import (
    by_function,
    judge_notebooks,
    misdiagnosed,
    mistake_submissions,
    patched,
    solution_code,
    top,
    write_notebook,
)

import kinlib as kl
from kinlib.grade.assignments import forward_kinematics as F
from kinlib.robots import autorob_test_robot, puma560

NAME = "02_forward_kinematics"


def _check(function):
    return next(c for c in F.assignment().checks if c.function == function)


# -- the references -------------------------------------------------------------------------
def _dh_rows(table):
    """The assignment's rows as kinlib DHRows (the constant goes to offset)."""
    return [kl.DHRow(a=r["a"], alpha=r["alpha"], offset=r["d"], theta=r["theta"],
                     joint="prismatic") if r["type"] == "prismatic" else
            kl.DHRow(a=r["a"], alpha=r["alpha"], d=r["d"], offset=r["theta"])
            for r in table]


def test_dh_reference_is_the_product_of_the_four_factors():
    rng = np.random.default_rng(7)
    for t, d, a, al in rng.uniform(-3, 3, (20, 4)):
        Rz, Rx = np.eye(4), np.eye(4)
        Rz[:3, :3], Rx[:3, :3] = kl.rotz(t), kl.rotx(al)
        Tz, Tx = kl.transform(p=[0, 0, d]), kl.transform(p=[a, 0, 0])
        assert np.allclose(F.dh(t, d, a, al), Rz @ Tz @ Tx @ Rx, atol=1e-14)
        # Craig's matrix is the reverse product of the same four factors (Rz, Tz commute)
        assert np.allclose(kl.mdh_transform(theta=t, d=d, a=a, alpha=al), Rx @ Tx @ Tz @ Rz)


def test_fk_dh_reference_is_kinlibs_dh_robot():
    for table, q in _check("fk_dh").make_cases(0):
        robot = kl.Robot.from_dh(_dh_rows(table))
        assert np.allclose(F.fk_dh_reference(table, q), robot.fk(q), atol=1e-12)
    puma = puma560()
    for key, q in puma.poses.items():
        assert np.allclose(F.fk_dh_reference(F.dh_table_of(puma), q), puma.fk(q)), key


def _urdf(robot) -> str:
    def v(x):
        return " ".join(repr(float(c)) for c in x)
    links = {robot["root"]} | {j["child"] for j in robot["joints"]}
    out = ['<robot name="t">'] + [f'<link name="{n}"/>' for n in sorted(links)]
    for j in robot["joints"]:
        limit = '<limit lower="-9" upper="9" effort="1" velocity="1"/>' \
            if j["type"] in ("revolute", "prismatic") else ""
        out.append(f'<joint name="{j["name"]}" type="{j["type"]}"><parent link="{j["parent"]}"/>'
                   f'<child link="{j["child"]}"/><origin xyz="{v(j["xyz"])}" '
                   f'rpy="{v(j["rpy"])}"/><axis xyz="{v(j["axis"])}"/>{limit}</joint>')
    return "\n".join(out + ["</robot>"])


def _by_hand(robot, q):
    """The matrix stack written out independently: fixed-axis rpy, unit axis, Rodrigues."""
    def rot(u, t):
        K = kl.skew(u)
        return np.eye(3) + np.sin(t) * K + (1 - np.cos(t)) * K @ K
    out = {robot["root"]: np.eye(4)}
    todo = list(robot["joints"])
    while todo:  # joints whose parent is known, in any order
        j = next(j for j in todo if j["parent"] in out)
        todo.remove(j)
        r, p, y = j["rpy"]
        O = kl.transform(rot([0, 0, 1], y) @ rot([0, 1, 0], p) @ rot([1, 0, 0], r), j["xyz"])
        u = np.asarray(j["axis"]) / np.linalg.norm(j["axis"])
        Mo = np.eye(4)
        if j["type"] == "prismatic":
            Mo[:3, 3] = q[j["name"]] * u
        elif j["type"] != "fixed":
            Mo[:3, :3] = rot(u, q[j["name"]])
        out[j["child"]] = out[j["parent"]] @ O @ Mo
    return out


def test_stack_reference_is_kinlibs_urdf_robot_and_the_hand_written_stack():
    for robot, q in _check("fk_matrix_stack").make_cases(0):
        ref = F.stack_reference(robot, q)
        loaded = kl.load_urdf(_urdf(robot)).link_poses(q)
        hand, model = _by_hand(robot, q), F.stack(robot, q)
        assert set(ref) == set(loaded) == set(hand) == set(model)
        for n in ref:
            for other in (loaded, hand, model):
                assert np.allclose(ref[n], other[n], atol=1e-12), n
    auto = autorob_test_robot()
    for key, q in auto.poses.items():
        named = dict(zip(auto.joint_names, q, strict=True))
        ref = F.stack_reference(F.autorob_dict(), named)
        for n, T in auto.link_poses(q).items():
            assert np.allclose(ref[n], T), (key, n)


def test_dh_symbolic_reference_is_the_product_of_the_four_factors():
    """kinlib's symbolic A (the reference of dh_symbolic) is Rz Tz Tx Rx written out here,
    and at numbers it is the numeric reference; on every case, with θ, d, a, α as given."""
    for t, d, a, al in _check("dh_symbolic").make_cases(0):
        c, s = sp.cos, sp.sin
        Rz = sp.Matrix([[c(t), -s(t), 0, 0], [s(t), c(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
        Rx = sp.Matrix([[1, 0, 0, 0], [0, c(al), -s(al), 0], [0, s(al), c(al), 0],
                        [0, 0, 0, 1]])
        Tz, Tx = sp.eye(4), sp.eye(4)
        Tz[2, 3], Tx[0, 3] = d, a
        A = kl.dh_transform(theta=t, d=d, a=a, alpha=al)
        assert sp.expand(A - Rz * Tz * Tx * Rx) == sp.zeros(4, 4)
        free = sorted(A.free_symbols, key=str)
        at = dict(zip(free, np.random.default_rng(1).uniform(-2, 2, len(free)), strict=True))
        num = [float(sp.sympify(x).subs(at)) for x in (t, d, a, al)]
        assert np.allclose(np.array(A.subs(at), dtype=float), F.dh(*num), atol=1e-12)


# -- the cases ------------------------------------------------------------------------------
def test_cases_cover_what_they_must():
    spec = F.assignment()
    cases = {c.function: c.make_cases(0) for c in spec.checks}
    assert [c.points for c in spec.checks] == [5, 3, 12, 14]
    assert sum(map(len, cases.values())) >= 300
    assert all(len(c) >= 90 for f, c in cases.items() if f != "dh_symbolic")
    derivation = cases["dh_symbolic"]  # symbols under two names, an exact twist, a slider
    assert len(derivation) == 4 and all(isinstance(x, sp.Basic | int) for c in derivation
                                        for x in c)
    assert {str(c[0]) for c in derivation[:2]} == {"theta", "theta_6"}
    assert derivation[2][3] in (sp.pi / 2, -sp.pi / 2) and derivation[3][2] == 0
    dh = np.array(cases["dh_matrix"])
    assert (np.abs(dh[:, 3]) > 0.1).sum() > 60 and (dh[:, 3] == 0).sum() >= 5
    tables = [t for t, _ in cases["fk_dh"]]
    puma = F.dh_table_of(puma560())
    assert sum(t == puma for t in tables) >= 10
    assert sum(len(t) == 2 and all(r["alpha"] == r["d"] == 0 for r in t) for t in tables) >= 8
    assert {len(t) for t in tables} >= {1, 2, 3, 4, 5, 6}
    with_p = [t for t in tables if any(r["type"] == "prismatic" for r in t)]
    assert len(with_p) >= 40
    assert sum(any(r["theta"] != 0 for r in t if r["type"] == "revolute") for t in tables) >= 60
    assert sum(any(r["d"] != 0 for r in t if r["type"] == "prismatic") for t in with_p) >= 30
    trees = cases["fk_matrix_stack"]
    kinds = set()
    shuffled = 0
    for robot, q in trees:
        joints = robot["joints"]
        kinds |= {j["type"] for j in joints}
        parents = [j["parent"] for j in joints]
        assert len(set(parents)) < len(parents), "every tree branches"
        assert set(q) == {j["name"] for j in joints if j["type"] != "fixed"}
        seen = {robot["root"]}
        for j in joints:
            shuffled += j["parent"] not in seen
            seen.add(j["child"])
    assert kinds == {"revolute", "continuous", "prismatic", "fixed"}
    assert shuffled >= 30
    assert sum(r == F.autorob_dict() for r, _ in trees) >= 10
    axes = [np.linalg.norm(j["axis"]) for r, _ in trees for j in r["joints"]]
    assert sum(abs(n - 1) > 0.1 for n in axes) > 0.8 * len(axes)
    depths = []  # joints between the root and the deepest link
    for robot, _ in trees:
        parent = {j["child"]: j["parent"] for j in robot["joints"]}
        depths.append(max(_depth(n, parent) for n in parent))
    assert min(depths) >= 2 and sum(d >= 3 for d in depths) >= 30


def _depth(link, parent):
    return 0 if link not in parent else 1 + _depth(parent[link], parent)


# -- the judge of fk_matrix_stack, on answers made by hand ----------------------------------
def test_stack_judge_on_hand_made_answers():
    robot, q = F.autorob_dict(), {"joint1": 0.5, "joint2": -0.8, "joint3": 1.2}
    ref = F.stack_reference(robot, q)
    judge = F._judge_stack
    assert judge((robot, q), ref).ok
    assert judge((robot, q), {k: v.tolist() for k, v in ref.items()}).ok
    assert judge((robot, q), None).key == "none"
    assert judge((robot, q), [ref["link2"]]).key == "type"
    no_root = {k: v for k, v in ref.items() if k != "link1"}
    v = judge((robot, q), no_root)
    assert v.key == "links" and "root" in v.message and "'link1'" in v.message
    v = judge((robot, q), {**ref, "joint1": np.eye(4)})
    assert v.key == "links" and "joint1" in v.message
    v = judge((robot, q), {**ref, "link3": np.eye(3)})
    assert v.key == "shape" and "'link3'" in v.message
    bad = {**ref, "link4": ref["link4"] + 0.1}
    bad["link4"][3] = [0, 0, 0, 1]
    v = judge((robot, q), bad)
    assert v.key == "wrong" and "'link4'" in v.message and "'joint3'" in v.message
    assert judge((robot, q), {**ref, "link1": 2 * np.eye(4)}).key == "root"
    v = judge((robot, q), F.stack(robot, q, from_root=True))
    assert v.key == "no stack" and "first wrong link: 'link4'" in v.message


# -- classic mistakes, graded for real ------------------------------------------------------
DH_RET = ("return np.array([[ct, -st * ca, st * sa, a * ct],\n"
          "                     [st, ct * ca, -ct * sa, a * st],\n"
          "                     [0.0, sa, ca, d],\n"
          "                     [0.0, 0.0, 0.0, 1.0]])")
CRAIG_RET = ("return np.array([[ct, -st, 0.0, a], [st * ca, ct * ca, -sa, -sa * d],\n"
             "                     [st * sa, ct * sa, ca, ca * d], [0.0, 0.0, 0.0, 1.0]])")
DH_MISTAKES = [  # (edit or tuple of edits, diagnosis)
    ((DH_RET, CRAIG_RET), "modified"),
    ((DH_RET, "return np.array([[ct, st, 0.0, a * ct], [-st * ca, ct * ca, sa, a * st],\n"
              "                     [st * sa, -ct * sa, ca, d], [0.0, 0.0, 0.0, 1.0]])"),
     "transposed"),
    (("[0.0, 0.0, 0.0, 1.0]])", "[0.0, 0.0, 0.0, 1.0]]).T"), "layout"),
    (("ct, st = np.cos(theta), np.sin(theta)\n    ca, sa = np.cos(alpha), np.sin(alpha)",
      "theta, alpha = np.deg2rad(theta), np.deg2rad(alpha)\n"
      "    ct, st = np.cos(theta), np.sin(theta)\n    ca, sa = np.cos(alpha), np.sin(alpha)"),
     "degrees"),
    (("ct, st = np.cos(theta), np.sin(theta)", "ct, st = np.cos(theta), -np.sin(theta)"),
     "theta sign"),
    (("ca, sa = np.cos(alpha), np.sin(alpha)", "ca, sa = np.cos(alpha), -np.sin(alpha)"),
     "alpha sign"),
    ((("st * sa, a * ct]", "st * sa, a * st]"), ("-ct * sa, a * st]", "-ct * sa, a * ct]")),
     "translation"),
    ((DH_RET, DH_RET.replace("a *", "d *").replace("ca, d]", "ca, a]")), "d axis"),
    # the rotation's sin θ flipped only (the translation right): the second 'theta sign' model
    ((DH_RET, DH_RET.replace("[ct, -st * ca, st * sa", "[ct, st * ca, -st * sa")
      .replace("[st, ct * ca", "[-st, ct * ca")), "theta sign"),
    # Tx(a) before Rz(θ): the second 'translation' model
    ((("st * sa, a * ct]", "st * sa, a]"), ("-ct * sa, a * st]", "-ct * sa, 0.0]")),
     "translation"),
    # d along the twisted z: Rz(θ) Tx(a) Rx(α) Tz(d), the second 'd axis' model
    ((DH_RET, DH_RET.replace("a * ct]", "a * ct + d * st * sa]")
      .replace("a * st]", "a * st - d * ct * sa]").replace("ca, d]", "ca, d * ca]")),
     "d axis"),
]
FK_CALL = "T = T @ _dh(theta, d, row[\"a\"], row[\"alpha\"])"
FK_MISTAKES = [
    ((FK_CALL, "T = _dh(theta, d, row[\"a\"], row[\"alpha\"]) @ T"), "order"),
    ((("d = d + qi", "d = qi"), ("theta = theta + qi", "theta = qi")), "offsets"),
    (("if row[\"type\"] == \"prismatic\":", "if False:"), "prismatic"),
    ((FK_CALL, "T = T @ _dh(0.0, 0.0, row[\"a\"], row[\"alpha\"]) @ _dh(theta, d, 0.0, 0.0)"),
     "modified"),
    ((FK_CALL, FK_CALL + ".T"), "transposed"),
    ((FK_CALL, "T = T @ _dh(np.deg2rad(theta), d, row[\"a\"], np.deg2rad(row[\"alpha\"]))"),
     "degrees"),
    ((FK_CALL, FK_CALL.replace("_dh(theta", "_dh(-theta")), "dh_matrix"),
    ((FK_CALL, "A = _dh(theta, d, row[\"a\"], row[\"alpha\"])\n"
               "        A[:3, :3] = A[:3, :3].T.copy()\n        T = T @ A"), "transposed"),
]
RPY = ("T[:3, :3] = (rotation(np.array([0.0, 0.0, 1.0]), yaw)\n"
       "                     @ rotation(np.array([0.0, 1.0, 0.0]), pitch)\n"
       "                     @ rotation(np.array([1.0, 0.0, 0.0]), roll))")
DOWN = "visit(joint[\"child\"], T @ origin(joint) @ motion(joint, value))"
STACK_MISTAKES = [
    ((RPY, "T[:3, :3] = (rotation(np.array([1.0, 0.0, 0.0]), roll)\n"
           "                     @ rotation(np.array([0.0, 1.0, 0.0]), pitch)\n"
           "                     @ rotation(np.array([0.0, 0.0, 1.0]), yaw))"), "rpy"),
    ((DOWN, "visit(joint[\"child\"], T @ motion(joint, value) @ origin(joint))"),
     "motion first"),
    (("u = u / np.linalg.norm(u)", "u = u"), "axis"),
    (("visit(robot[\"root\"], np.eye(4))\n    return poses",
      "poses[robot[\"root\"]] = np.eye(4)\n    for joint in robot[\"joints\"]:\n"
      "        poses[joint[\"child\"]] = (origin(joint)\n"
      "                                 @ motion(joint, q.get(joint[\"name\"], 0.0)))\n"
      "    return poses"), "no stack"),
    ((("poses = {}\n", "poses = {}\n    top = [np.eye(4)]\n"),
      (DOWN, "top[0] = top[0] @ origin(joint) @ motion(joint, value)\n"
             "            visit(joint[\"child\"], top[0])")), "pop"),
    (("np.sin(angle) * K", "np.sin(angle) * K.T"), "transposed"),
    (("T[:3, :3] = rotation(u, value)", "T[:3, :3] = rotation(u, -value)"), "sign"),
    (("roll, pitch, yaw = joint[\"rpy\"]", "yaw, pitch, roll = joint[\"rpy\"]"), "rpy"),
]


DHS_RET = "return Rz * Tz * Tx * Rx"
DHS_RZ = "Rz = sp.Matrix([[ct, -st, 0, 0], [st, ct, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])"
DHS_RX = "Rx = sp.Matrix([[1, 0, 0, 0], [0, ca, -sa, 0], [0, sa, ca, 0], [0, 0, 0, 1]])"
RZ_FLIPPED = DHS_RZ.replace("[[ct, -st, 0, 0], [st, ct", "[[ct, st, 0, 0], [-st, ct")
RX_FLIPPED = DHS_RX.replace("[0, ca, -sa, 0], [0, sa, ca", "[0, ca, sa, 0], [0, -sa, ca")
DHS_MISTAKES = [  # the DH matrix derived with sympy
    ((DHS_RET, "return Rx * Tx * Rz * Tz"), "modified"),
    (((DHS_RZ, RZ_FLIPPED), (DHS_RX, RX_FLIPPED)), "transposed"),
    ((DHS_RET, "return (Rz * Tz * Tx * Rx).T"), "layout"),
    ((DHS_RZ, RZ_FLIPPED), "theta sign"),
    ((DHS_RX, RX_FLIPPED), "alpha sign"),
    (("ct, st = sp.cos(theta), sp.sin(theta)\n    ca, sa = sp.cos(alpha), sp.sin(alpha)",
      "ct, st = sp.cos(alpha), sp.sin(alpha)\n    ca, sa = sp.cos(theta), sp.sin(theta)"),
     "swapped"),
    (("Tz[2, 3], Tx[0, 3] = d, a", "Tz[2, 3], Tx[0, 3] = a, d"), "swapped"),
    ((DHS_RET, "return np.eye(4)  # (to do)"), "numbers"),
]
TABLE = (("dh_matrix", DH_MISTAKES), ("dh_symbolic", DHS_MISTAKES), ("fk_dh", FK_MISTAKES),
         ("fk_matrix_stack", STACK_MISTAKES))


def test_forward_kinematics_mistakes_are_diagnosed(tmp_path):
    right = solution_code(NAME) + "\n\n_dh = dh_matrix\n"
    code = patched(solution_code(NAME), ("T = T @ dh_matrix(", "T = T @ _dh("))
    graded = judge_notebooks(mistake_submissions(tmp_path, NAME, code, TABLE, right))
    wrong = misdiagnosed(graded, TABLE)
    results = [by_function(r) for r in graded]
    assert not wrong, wrong
    # the second model of a key says what differs (see also test_each_model_its_message)
    assert "intrinsic" in results[0]["fk_matrix_stack"]["diagnoses"][0]["message"]
    assert "roll about z" in results[7]["fk_matrix_stack"]["diagnoses"][0]["message"]
    assert "4×4" in results[4]["fk_dh"]["diagnoses"][0]["message"]
    assert "rotation part" in results[7]["fk_dh"]["diagnoses"][0]["message"]
    assert "first wrong link" in results[3]["fk_matrix_stack"]["diagnoses"][0]["message"]
    swapped = [results[n]["dh_symbolic"]["diagnoses"][0]["message"] for n in (5, 6)]
    assert "theta and alpha" in swapped[0] and "d and a" in swapped[1], swapped


def test_each_model_its_message():
    """On a generic case every model of dh_matrix and fk_dh is diagnosed with its own
    message (on special cases, a = 0 say, two models of one key may coincide)."""
    spec = F.assignment()
    generic = {"dh_matrix": (0.7, 0.3, 0.5, 0.4),
               "fk_dh": ([F._row("revolute", 0.4, 0.3, 0.2, 0.5),
                          F._row("prismatic", 0.3, -1.1, 0.4, 0.8),
                          F._row("revolute", -0.2, 0.7, 0.1, -0.6)], np.array([0.3, 0.2, 0.9]))}
    for check in (c for c in spec.checks if c.function in generic):
        args = generic[check.function]
        assert check.verdict(args, check.reference(*args)).ok
        for m in check.mistakes:
            v = check.verdict(args, m.model(*args))
            assert (v.key, v.message) == (m.key, m.message), (check.function, m.key)
    robot = F.random_tree(np.random.default_rng(3), 6, shuffle=True)
    q = F.random_joint_values(np.random.default_rng(4), robot)
    for key, message, model in F.STACK_MISTAKES:
        v = F._judge_stack((robot, q), model(robot, q))
        assert v.key == key and v.message.startswith(message), key


def test_more_stack_mistakes(tmp_path):
    """The rotation of each factor transposed (not its elementary rotations), the 4×4s
    transposed, and joints taken in list order (a KeyError on the shuffled trees)."""
    code = solution_code(NAME)
    subs = [
        write_notebook(tmp_path / "a.ipynb", patched(
            code, ("T[:3, :3] = rotation(u, value)", "T[:3, :3] = rotation(u, value).T"),
            ("T[:3, 3] = joint[\"xyz\"]\n        return T",
             "T[:3, :3] = T[:3, :3].T.copy()\n        T[:3, 3] = joint[\"xyz\"]\n"
             "        return T")), assignment=NAME),
        write_notebook(tmp_path / "b.ipynb", patched(
            code, (DOWN, "visit(joint[\"child\"], T @ origin(joint).T @ motion(joint, value).T)")),
            assignment=NAME),
        write_notebook(tmp_path / "c.ipynb", patched(
            code, ("visit(robot[\"root\"], np.eye(4))\n    return poses",
                   "poses[robot[\"root\"]] = np.eye(4)\n    for joint in robot[\"joints\"]:\n"
                   "        poses[joint[\"child\"]] = (poses[joint[\"parent\"]] @ origin(joint)\n"
                   "                                 @ motion(joint, q.get(joint[\"name\"],"
                   " 0.0)))\n    return poses")), assignment=NAME),
    ]
    a, b, c = (by_function(r)["fk_matrix_stack"] for r in judge_notebooks(subs))
    assert top(a) == "transposed" and "the origin's and the joint motion's" in \
        a["diagnoses"][0]["message"]
    assert top(b) == "transposed" and "4×4" in b["diagnoses"][0]["message"]
    assert top(c) == "raised" and "KeyError" in c["diagnoses"][0]["message"]
    assert 40 <= c["passed"] < c["total"]  # right wherever the list happens to be in order


def test_other_right_answers_are_accepted(tmp_path):
    """dh_matrix as the product of its four factors, returning nested lists; dh_symbolic as
    the product written out entry by entry, simplified, as an immutable Matrix; fk_dh with
    the row's matrix from a closure and multi_dot; the stack as an iterative loop that waits
    for each parent, returning lists."""
    code = patched(
        solution_code(NAME),
        (DH_RET, "Rz = np.array([[ct, -st, 0, 0], [st, ct, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
                 "    Rx = np.array([[1, 0, 0, 0], [0, ca, -sa, 0], [0, sa, ca, 0],"
                 " [0, 0, 0, 1]])\n"
                 "    Tzx = np.eye(4)\n    Tzx[0, 3], Tzx[2, 3] = a, d\n"
                 "    return (Rz @ Tzx @ Rx).tolist()"),
        (DHS_RET, "return sp.ImmutableMatrix(sp.simplify(sp.Matrix([\n"
                  "        [ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],\n"
                  "        [0, sa, ca, d], [0, 0, 0, 1]])))"),
        ("    T = np.eye(4)\n    for row, qi in zip(table, q, strict=True):",
         "    mats = [np.eye(4), np.eye(4)]\n    for row, qi in zip(table, q, strict=True):"),
        ("T = T @ dh_matrix(theta, d, row[\"a\"], row[\"alpha\"])\n    return T",
         "mats.append(np.array(dh_matrix(theta, d, row[\"a\"], row[\"alpha\"])))\n"
         "    return np.linalg.multi_dot(mats)"),
        ("visit(robot[\"root\"], np.eye(4))\n    return poses",
         "poses[robot[\"root\"]] = np.eye(4)\n    todo = list(robot[\"joints\"])\n"
         "    while todo:\n"
         "        joint = next(j for j in todo if j[\"parent\"] in poses)\n"
         "        todo.remove(joint)\n"
         "        poses[joint[\"child\"]] = (poses[joint[\"parent\"]] @ origin(joint)\n"
         "                                 @ motion(joint, q.get(joint[\"name\"], 0.0)))\n"
         "    return {k: v.tolist() for k, v in poses.items()}"))
    sub = write_notebook(tmp_path / "alt.ipynb", code, assignment=NAME)
    result = by_function(judge_notebooks([sub])[0])
    for fn, check in result.items():
        assert check["passed"] == check["total"], (fn, check["diagnoses"])


@pytest.mark.parametrize("seed", [1])
def test_mistake_models_differ_from_the_reference_on_most_cases(seed):
    """Each model is a real mistake on the cases (it differs from the right answer), so a
    submission with it loses points."""
    spec = F.assignment()
    for check in (c for c in spec.checks if c.function in ("dh_matrix", "fk_dh")):
        cases = check.make_cases(seed)
        for m in check.mistakes:
            differs = sum(not np.allclose(m.model(*c), check.reference(*c), atol=1e-6)
                          for c in cases)
            assert differs >= 0.5 * len(cases), (check.function, m.key, differs)
    cases = _check("fk_matrix_stack").make_cases(seed)
    for key, _, model in F.STACK_MISTAKES:
        differs = 0
        for robot, q in cases:
            ref, wrong = F.stack_reference(robot, q), model(robot, q)
            differs += any(not np.allclose(wrong[n], ref[n], atol=1e-6) for n in ref)
        assert differs >= 0.85 * len(cases), (key, differs)
