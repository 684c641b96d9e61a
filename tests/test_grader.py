"""The grader: solutions score full marks, student versions score 0, classic mistakes get
their diagnosis, and hostile submissions cannot crash it, hang it or raise their score.

Submissions are built here from the source notebook's own code with one mistake patched in
per function, so every expected diagnosis is decided by the test, not by the grader.
"""

import json
import subprocess
import sys

import nbformat
import numpy as np
import pytest
from grading_helpers import ROOT, by_function, patched, solution_code, top, write_notebook

import kinlib as kl
from kinlib.assign import main as assign_main
from kinlib.assign import release_source
from kinlib.grade import format_report, grade, grade_many

SOURCES = sorted((ROOT / "source").glob("*.ipynb"))
NAMES = [s.stem for s in SOURCES]


# -- solutions and student versions ---------------------------------------------------------
@pytest.mark.parametrize("name", NAMES)
def test_solution_scores_full_marks(name):
    result = grade(ROOT / "source" / f"{name}.ipynb")
    assert result["graded"] and result["assignment"] == name
    assert result["score"] == result["max_score"] > 0, format_report(result)
    assert result["cells"] == []
    total = sum(c["total"] for c in result["checks"])
    assert total >= 300, f"only {total} cases"


@pytest.mark.parametrize("name", NAMES)
def test_student_version_scores_zero_and_says_why(name):
    result = grade(ROOT / "release" / f"{name}.ipynb")
    assert result["graded"] and result["score"] == 0 and result["max_score"] > 0
    for check in result["checks"]:
        assert check["passed"] == 0 and top(check) == "raised", check
        assert "NotImplementedError" in check["diagnoses"][0]["message"]


def test_releases_are_generated_and_current(tmp_path):
    assert NAMES, "no assignments"
    assert assign_main(["--root", str(ROOT.parent), "--check"]) == 0, \
        "run `python -m kinlib.assign`"
    for src in SOURCES:
        student = nbformat.read(ROOT / "release" / src.name, as_version=4)
        source = nbformat.read(src, as_version=4)
        assert len(student.cells) == len(source.cells)
        for a, b in zip(source.cells, student.cells, strict=True):
            assert a.cell_type == b.cell_type
            if a.cell_type == "markdown":
                assert a.source == b.source
            elif "### BEGIN SOLUTION" in a.source:
                assert "raise NotImplementedError" in b.source and "BEGIN" not in b.source
            else:
                assert a.source == b.source
    # a stale release is caught, and regenerating fixes it
    root = tmp_path  # a repository with one assignment
    (root / "assignments" / "source").mkdir(parents=True)
    (root / "assignments" / "source" / "x.ipynb").write_text(SOURCES[0].read_text())
    assert assign_main(["--root", str(root), "--check"]) == 1
    assert assign_main(["--root", str(root)]) == 0
    assert assign_main(["--root", str(root), "--check"]) == 0


def test_release_source_markers():
    src = "def f():\n    x = 1\n    ### BEGIN SOLUTION\n    return x\n    ### END SOLUTION\n"
    assert release_source(src) == "def f():\n    x = 1\n    raise NotImplementedError\n"
    for bad in ("### BEGIN SOLUTION\n", "### END SOLUTION\n",
                "### BEGIN SOLUTION\n### BEGIN SOLUTION\n### END SOLUTION\n"):
        with pytest.raises(kl.KinlibError, match="SOLUTION"):
            release_source(bad)


# -- classic mistakes -----------------------------------------------------------------------
ROTATION_MISTAKES = {
    # function: (edit, expected diagnosis)
    "rotx": (("[0.0, c, -s], [0.0, s, c]]", "[0.0, c, s], [0.0, -s, c]]"), "transposed"),
    "roty": (("c, s = np.cos(theta), np.sin(theta)\n    return np.array([[c, 0.0, s]",
              "c, s = np.cos(np.deg2rad(theta)), np.sin(np.deg2rad(theta))\n"
              "    return np.array([[c, 0.0, s]"), "degrees"),
    "euler_zyx_to_matrix": (("return rotz(alpha) @ roty(beta) @ rotx(gamma)",
                             "return rotx(gamma) @ roty(beta) @ rotz(alpha)"), "extrinsic"),
    "matrix_to_euler_zyx": (("if cb < 1e-9:", "if False:"), "gimbal"),
    "axis_angle_to_matrix": (("np.sin(angle) * K", "np.sin(angle) * K.T"), "transposed"),
    "matrix_to_axis_angle": (("k = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], "
                              "R[1, 0] - R[0, 1]])",
                              "k = np.array([R[1, 2] - R[2, 1], R[2, 0] - R[0, 2], "
                              "R[0, 1] - R[1, 0]])"), "axis sign"),
    "quat_multiply": (("np.cross(p[1:], q[1:])", "np.cross(q[1:], p[1:])"), "order"),
    "quat_to_matrix": (("w, x, y, z = np.asarray(q, dtype=float)",
                        "x, y, z, w = np.asarray(q, dtype=float)"), "xyzw"),
    "matrix_to_quat": (("    return q / np.linalg.norm(q)",
                        "    return np.roll(q / np.linalg.norm(q), -1)"), "xyzw"),
}


def test_rotation_mistakes_are_diagnosed(tmp_path):
    # the Euler functions call right copies _rx, _ry, _rz (made in an earlier cell), so that
    # each function carries exactly one mistake
    right = solution_code("01_rotations") + "\n\n_rx, _ry, _rz = rotx, roty, rotz\n"
    code = solution_code("01_rotations").replace(
        "return rotz(alpha) @ roty(beta) @ rotx(gamma)",
        "return _rz(alpha) @ _ry(beta) @ _rx(gamma)")
    edits = [e for e, _ in ROTATION_MISTAKES.values()]
    edits[2] = ("return _rz(alpha) @ _ry(beta) @ _rx(gamma)",
                "return _rx(gamma) @ _ry(beta) @ _rz(alpha)")
    sub = write_notebook(tmp_path / "mistakes.ipynb", right, patched(code, *edits),
                         assignment="01_rotations")
    result = by_function(grade(sub))
    for fn, (_, key) in ROTATION_MISTAKES.items():
        check = result[fn]
        assert check["passed"] < check["total"], fn
        assert top(check) == key, (fn, check["diagnoses"])
    assert result["rotz"]["passed"] == result["rotz"]["total"]


def test_more_rotation_mistakes(tmp_path):
    code = solution_code("01_rotations")
    sub = write_notebook(tmp_path / "more.ipynb", patched(
        code,
        ("def rotz(theta):\n    \"\"\"Rotation about z by theta (radians): a 3x3 array.\"\"\"\n"
         "    ### BEGIN SOLUTION",
         "def rotz(theta):\n    \"\"\"Rotation about z by theta (radians): a 3x3 array.\"\"\"\n"
         "    return rotx(theta)\n    ### BEGIN SOLUTION"),
        ("return rotz(alpha) @ roty(beta) @ rotx(gamma)",
         "return rotx(alpha) @ roty(beta) @ np.array([[np.cos(gamma), -np.sin(gamma), 0], "
         "[np.sin(gamma), np.cos(gamma), 0], [0, 0, 1]])"),  # XYZ (its own right rotz)
        ("return np.array([1.0, 0.0, 0.0]), 0.0", "return np.array([0.0, 0.0, 0.0]), 0.0"),
        ("w = p[0] * q[0] - p[1:] @ q[1:]\n    v = p[0] * q[1:] + q[0] * p[1:] + "
         "np.cross(p[1:], q[1:])\n    return np.concatenate([[w], v])",
         "p, q = np.roll(p, 1), np.roll(q, 1)\n    w = p[0] * q[0] - p[1:] @ q[1:]\n"
         "    v = p[0] * q[1:] + q[0] * p[1:] + np.cross(p[1:], q[1:])\n"
         "    return np.roll(np.concatenate([[w], v]), -1)"),
    ), assignment="01_rotations")
    result = by_function(grade(sub))
    assert top(result["rotz"]) == "axis"
    assert top(result["euler_zyx_to_matrix"]) == "sequence"
    assert "XYZ" in result["euler_zyx_to_matrix"]["diagnoses"][0]["message"]
    assert top(result["matrix_to_axis_angle"]) == "unit"
    assert top(result["quat_multiply"]) == "xyzw"


def test_q_and_minus_q_and_other_valid_answers_are_accepted(tmp_path):
    code = solution_code("01_rotations")
    sub = write_notebook(tmp_path / "alt.ipynb", patched(
        code,
        # the other ZYX solution: beta' = pi - beta, alpha' = alpha + pi, gamma' = gamma + pi
        ("    return alpha, beta, gamma\n",
         "    return alpha + np.pi, np.pi - beta, gamma + np.pi\n"),
        # quat_to_matrix of -q is the same matrix
        ("w, x, y, z = np.asarray(q, dtype=float)", "w, x, y, z = -np.asarray(q, dtype=float)"),
        # and -q is as good an answer as q (the w >= 0 choice is not required)
        ("    return q / np.linalg.norm(q)", "    return -q / np.linalg.norm(q)"),
    ), assignment="01_rotations")
    result = by_function(grade(sub))
    for fn in ("matrix_to_euler_zyx", "quat_to_matrix", "matrix_to_quat"):
        assert result[fn]["passed"] == result[fn]["total"], result[fn]


# -- hostile submissions --------------------------------------------------------------------
HOSTILE = {  # kind: (a cell run before the right solution, a cell that overrides a function)
    "prints": ("print('x' * 10_000_000)\nimport sys; sys.stderr.write('y' * 1_000_000)",
               "_right = quat_to_matrix\n"
               "def quat_to_matrix(q):\n    print('noise ' * 1000)\n    return _right(q)"),
    "exits_in_cell": ("import sys\nsys.exit(0)", None),
    "os_exit_in_cell": ("import os\nos._exit(3)", None),
    "raises_on_import": ("import this_module_does_not_exist", None),
    "loops_in_cell": ("while True:\n    pass", None),
    "loops_in_function": (None, "def quat_to_matrix(q):\n    while True:\n        pass"),
    "exits_in_function": (None, "def quat_to_matrix(q):\n    import os\n    os._exit(0)"),
    "patches_numpy": ("np.allclose = lambda *a, **k: True\nnp.isclose = lambda *a, **k: True\n"
                      "np.testing.assert_allclose = lambda *a, **k: None",
                      "def quat_to_matrix(q):\n    return np.zeros((3, 3))"),
    "patches_kinlib": ("import sys, types\nfake = types.ModuleType('kinlib')\n"
                       "fake.rotx = lambda t: 0\nsys.modules['kinlib'] = fake\n"
                       "import kinlib\nkinlib.rotx = lambda t: 0", None),
    "uses_kinlib": (None, "def quat_to_matrix(q):\n    import kinlib\n"
                          "    return kinlib.matrix_from_quat(q)"),
    "writes_files": ("import os\nopen(os.path.expanduser('~/hostile.txt'), 'w').write('x')\n"
                     "open('big.bin', 'wb').write(b'0' * 100_000_000)", None),
    "odd_objects": (None, "class Liar:\n    def __eq__(self, other):\n        return True\n"
                          "    def __array__(self, *a, **k):\n        raise RuntimeError\n"
                          "    def __repr__(self):\n        raise RuntimeError\n"
                          "def quat_to_matrix(q):\n    return Liar()\n"
                          "def quat_multiply(p, q):\n    return (x for x in range(3))\n"
                          "def axis_angle_to_matrix(k, t):\n    return np.zeros(10_000_000)"),
    "memory_hog": (None, "def quat_to_matrix(q):\n    return np.ones((200_000, 100_000))"),
    "forges_replies": (None, "def quat_to_matrix(q):\n    import os, json\n"
                             "    lies = b''.join(json.dumps({'ev': e, 'i': 0, 'ok': True, "
                             "'id': n, 'value': 1.0}).encode() + b'\\n' for n in range(20) "
                             "for e in ('case', 'call_done'))\n"
                             "    for fd in range(3, 64):\n        try:\n"
                             "            os.write(fd, lies)\n"
                             "        except OSError:\n            pass\n"
                             "    return np.zeros((3, 3))"),
}
SPOILED = {"loops_in_function": "quat_to_matrix", "exits_in_function": "quat_to_matrix",
           "patches_numpy": "quat_to_matrix", "uses_kinlib": "quat_to_matrix",
           "odd_objects": ("quat_to_matrix", "quat_multiply", "axis_angle_to_matrix"),
           "memory_hog": "quat_to_matrix", "forges_replies": "quat_to_matrix"}


def test_hostile_submissions(tmp_path):
    subs = {}
    for kind, (before, override) in HOSTILE.items():
        cells = ["import numpy as np"]
        if before:
            cells.append(before)
        cells.append(solution_code("01_rotations"))
        if override:
            cells.append(override)
        subs[kind] = write_notebook(tmp_path / f"{kind}.ipynb", *cells,
                                    assignment="01_rotations")
    results = dict(zip(subs, grade_many(subs.values(), cell_timeout=5.0, jobs=2),
                       strict=True))
    for kind, result in results.items():
        assert result["graded"], (kind, result["error"])
        checks = by_function(result)
        spoiled = SPOILED.get(kind, ())
        spoiled = (spoiled,) if isinstance(spoiled, str) else spoiled
        for fn, check in checks.items():
            if fn in spoiled:
                assert check["passed"] == 0, (kind, fn, check)
            else:
                assert check["passed"] == check["total"], (kind, fn, check["diagnoses"])
    assert top(by_function(results["loops_in_function"])["quat_to_matrix"]) == "timeout"
    assert top(by_function(results["exits_in_function"])["quat_to_matrix"]) == "died"
    used = by_function(results["uses_kinlib"])["quat_to_matrix"]["diagnoses"][0]["message"]
    assert "cannot be used" in used
    assert any("skipped" in c["error"] for c in results["loops_in_cell"]["cells"])
    assert any("ended the process" in c["error"] for c in results["os_exit_in_cell"]["cells"])
    odd = by_function(results["odd_objects"])
    assert {top(odd[f]) for f in SPOILED["odd_objects"]} <= {"type", "shape"}
    # the grader's own kinlib and numpy were never touched
    assert np.allclose(kl.rotx(np.pi / 2) @ [0, 1, 0], [0, 0, 1])
    assert not np.allclose(np.zeros(3), np.ones(3))


def test_command_line_json_parallel_and_exit_status(tmp_path):
    good = tmp_path / "01_rotations_alice.ipynb"
    good.write_text((ROOT / "source" / "01_rotations.ipynb").read_text())
    empty = tmp_path / "01_rotations_bob.ipynb"
    empty.write_text((ROOT / "release" / "01_rotations.ipynb").read_text())
    # a submission that writes a fake result file where the grader writes its own
    forger = write_notebook(
        tmp_path / "01_rotations_eve.ipynb", "import json\n"
        f"open({str(tmp_path / '01_rotations_eve.grade.json')!r}, 'w').write("
        "json.dumps({'score': 1000}))", assignment="01_rotations")
    out = subprocess.run([sys.executable, "-m", "kinlib.grade", "--json", "-j", "2",
                          str(good), str(empty), str(forger)],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    rows = {json.loads(line)["submission"]: json.loads(line) for line in out.stdout.splitlines()}
    assert len(rows) == 3, out.stdout  # one line each, in the order they were graded
    rows = [rows[str(p)] for p in (good, empty, forger)]
    assert "graded 3 of 3 submission(s)" in out.stderr
    for r in rows:
        assert {"submission", "score", "max_score", "checks"} <= set(r)
    assert rows[0]["score"] == rows[0]["max_score"] and rows[1]["score"] == 0
    saved = json.loads((tmp_path / "01_rotations_eve.grade.json").read_text())
    assert saved["score"] == 0 and saved["max_score"] == rows[0]["max_score"]
    # the text report, and a file that cannot be graded: exit status 2
    bad = tmp_path / "notes.ipynb"
    bad.write_text("not a notebook")
    out = subprocess.run([sys.executable, "-m", "kinlib.grade", "--no-write", str(good),
                          str(bad)], capture_output=True, text=True, timeout=300)
    assert out.returncode == 2
    assert f"total: {rows[0]['max_score']:g} / {rows[0]['max_score']:g}" in out.stdout
    assert "NOT GRADED" in out.stdout


def test_exceptions_get_the_checks_hint(tmp_path):
    ik = patched(solution_code("03_jacobian_and_ik"),
                 ("        return None\n    c2 = min(", "        raise ValueError('unreachable')\n"
                                                      "    c2 = min("))
    stack = patched(solution_code("02_forward_kinematics"),
                    ("    children = {}\n    for joint in robot[\"joints\"]:\n"
                     "        children.setdefault(joint[\"parent\"], []).append(joint)\n"
                     "    poses = {}\n",
                     "    poses = {robot['root']: np.eye(4)}\n"
                     "    for joint in robot['joints']:  # list order: parents may come later\n"
                     "        T = poses[joint['parent']] @ origin(joint) @ "
                     "motion(joint, q.get(joint['name'], 0.0))\n"
                     "        poses[joint['child']] = T\n    return poses\n"
                     "    children = {}\n"))
    results = grade_many([write_notebook(tmp_path / "ik.ipynb", ik,
                                         assignment="03_jacobian_and_ik"),
                          write_notebook(tmp_path / "fk.ipynb", stack,
                                         assignment="02_forward_kinematics")], jobs=2)
    ik_check = by_function(results[0])["ik_2r"]
    raised = [d for d in ik_check["diagnoses"] if d["key"] == "raised"]
    assert raised and "return None for it instead of raising" in raised[0]["message"]
    assert 0 < ik_check["passed"] < ik_check["total"]
    fk_check = by_function(results[1])["fk_matrix_stack"]
    raised = [d for d in fk_check["diagnoses"] if d["key"] == "raised"]
    assert raised and "KeyError" in raised[0]["message"]
    assert "start at the root link" in raised[0]["message"]
    assert 0 < fk_check["passed"] < fk_check["total"]  # in-order lists still come out right


def test_shape_messages(tmp_path):
    from kinlib.grade._checks import as_numeric

    _, bad = as_numeric(np.zeros((6, 2)), (2, 6))
    assert bad.key == "shape" and "transpose" in bad.message
    _, bad = as_numeric(np.zeros((3, 4)), (2, 6))
    assert bad.key == "shape" and "reshape it to (2, 6)" in bad.message
    code = patched(solution_code("01_rotations"),
                   ("    return np.concatenate([[w], v])",
                    "    return np.concatenate([[w], v])[:, None]"))  # (4, 1)
    result = by_function(grade(write_notebook(tmp_path / "t.ipynb", code,
                                              assignment="01_rotations")))
    assert top(result["quat_multiply"]) == "shape"
    assert "reshape it to (4,)" in result["quat_multiply"]["diagnoses"][0]["message"]


def test_quaternion_from_matrix_mistakes(tmp_path):
    start = "    R = np.asarray(R, dtype=float)\n    ### BEGIN SOLUTION\n    sq = np.array("
    naive = ("    R = np.asarray(R, dtype=float)\n    w = np.sqrt(1 + np.trace(R)) / 2\n"
             "    return np.array([w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w),"
             " (R[1, 0] - R[0, 1]) / (4 * w)])\n    ### BEGIN SOLUTION\n    sq = np.array(")
    conj = ("    R = np.asarray(R, dtype=float).T\n    ### BEGIN SOLUTION\n    sq = np.array(")
    code = solution_code("01_rotations")
    subs = [write_notebook(tmp_path / f"{k}.ipynb", patched(code, (start, v)),
                           assignment="01_rotations") for k, v in (("naive", naive),
                                                                   ("conj", conj))]
    naive_r, conj_r = (by_function(r)["matrix_to_quat"] for r in grade_many(subs, jobs=2))
    # dividing by 4w: right except at half turns, where it is NaN or raises (w = 0)
    assert 0 < naive_r["passed"] < naive_r["total"]
    keys = {d["key"] for d in naive_r["diagnoses"]}
    assert keys <= {"nan", "raised", "wrong"} and keys & {"nan", "raised"}, naive_r
    assert top(conj_r) == "conjugate"


def test_the_documented_result_of_assignment_01_has_its_real_maximum():
    import kinlib.grade
    from kinlib.grade import load_assignment

    points = {c.function: c.points for c in load_assignment("01_rotations").checks}
    assert sum(points.values()) == 38  # 3 × 2 (rotx, roty, rotz) + 7 functions of 4 or 6
    assert '"max_score": 38.0' in kinlib.grade.__doc__
