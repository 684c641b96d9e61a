"""Graded derivations: sympy values on the wire both ways, hostile ones refused with a clear
message (never a crash or a hang of the grader), the bounded symbolic judge, and assignment
01's derivation graded for real (those of 02–04 are in their assignments' test files).

The references of the judge's tests are sympy's own (identities written out here, sympy's
lambdify for the evaluator), never the judge's output.
"""

import json

import numpy as np
import pytest
import sympy as sp
from grading_helpers import ROOT, by_function, judge_notebooks, patched, top, write_notebook

import kinlib as kl
from kinlib.grade._symbolic import _exact, _Points, sym_tree, symbolic_judge
from kinlib.grade._wire import MAX_SYM_NODES, Odd, Sym, WireError, decode, dumps, encode, loads

A, B, G = sp.symbols("alpha beta gamma", real=True)
T1, T2 = sp.symbols("theta1 theta2", real=True)
L1, L2 = sp.symbols("l1 l2", positive=True)


def wire(value, **kwargs):
    """``value`` through one message line, as the grader would read it."""
    return decode(loads(dumps({"v": encode(value, **kwargs)}))["v"])


# -- the wire ---------------------------------------------------------------------------------
def test_sympy_values_go_both_ways():
    q, s = sp.symbols("q s")
    args = (A, sp.pi / 2, q + s, sp.Rational(3, 10), L1)
    sent = decode(loads(dumps({"v": encode(args, exact=True)}))["v"], sympy=True)
    assert sent == args and sent[4].is_positive and sent[0].is_real  # (the worker's side)
    R = kl.matrix_from_euler([A, B, G], "ZYX")
    got = wire(R)
    assert isinstance(got, Sym) and got.shape == (3, 3)
    assert got.names == {n: ("real",) for n in ("alpha", "beta", "gamma")}
    assert repr(got).startswith("<sympy 3×3 Matrix Matrix([[cos(alpha)*cos(beta)")
    assert decode(encode(R), sympy=True) == R
    # numbers stay numbers (the numeric checks see what they always saw), unless exact
    assert isinstance(wire(sp.Matrix([[1, 2], [3, 4]])), np.ndarray)
    assert isinstance(wire(sp.pi / 2), np.ndarray) and isinstance(wire(sp.pi / 2, exact=True), Sym)
    # sympy inside an object array or a list
    assert wire(np.array([[sp.cos(A), 0], [1.5, sp.sin(A)]], dtype=object)).shape == (2, 2)
    assert [type(x) for x in wire([sp.cos(A), 2.0])] == [Sym, float]
    assert wire(np.array([[1, [2]]], dtype=object)).why == "not a numeric array"  # as before


S = ["s", "x", []]
BAD = {  # malformed trees, each a WireError with a reason
    "no value": ({"t": "sym"}, "malformed"),
    "unknown kind": ({"t": "sym", "v": ["eval", "__import__('os').system('x')"]}, "unknown"),
    "text": ({"t": "sym", "v": "cos(x)"}, "malformed"),
    "empty name": ({"t": "sym", "v": ["s", "", []]}, "name"),
    "escape in a name": ({"t": "sym", "v": ["s", "x\x1b[2K total: 38", []]}, "name"),
    "bidi override": ({"t": "sym", "v": ["s", "x\u202e", []]}, "name"),
    "long name": ({"t": "sym", "v": ["s", "x" * 65, []]}, "name"),
    "unknown assumption": ({"t": "sym", "v": ["s", "x", ["evil"]]}, "assumptions"),
    "twice an assumption": ({"t": "sym", "v": ["s", "x", ["real", "real"]]}, "assumptions"),
    "huge integer": ({"t": "sym", "v": ["i", 10**61]}, "60 digits"),
    "bool as integer": ({"t": "sym", "v": ["i", True]}, "60 digits"),
    "huge exponent": ({"t": "sym", "v": ["^", ["i", 10], ["i", 10**9]]}, "exponent"),
    "huge root": ({"t": "sym", "v": ["^", S, ["q", 1, 10**9]]}, "exponent"),
    "NaN": ({"t": "sym", "v": ["f", float("nan")]}, "Float"),
    "unknown constant": ({"t": "sym", "v": ["c", "os"]}, "constant"),
    "arity": ({"t": "sym", "v": ["atan2", S]}, "number of arguments"),
    "sum of one": ({"t": "sym", "v": ["+", S]}, "number of arguments"),
    "shape": ({"t": "sym", "shape": [2, 2], "v": [S]}, "shape"),
    "huge matrix": ({"t": "sym", "shape": [17, 17], "v": [S] * 289}, "at most 256"),
    "node bomb": ({"t": "sym", "v": ["+", *[S] * (MAX_SYM_NODES + 5)]}, "nodes"),
}
deep = S
for _ in range(70):
    deep = ["sin", deep]
BAD["deep"] = ({"t": "sym", "v": deep}, "nested")


@pytest.mark.parametrize("kind", BAD)
def test_malformed_trees_are_wire_errors(kind):
    message, why = BAD[kind]
    with pytest.raises(WireError, match=why):
        decode(json.loads(json.dumps(message)))


def test_inconsistent_assumptions_are_refused_where_sympy_builds_them():
    tree = {"t": "sym", "v": ["s", "x", ["positive", "negative"]]}
    assert isinstance(decode(tree), Sym)  # the grader builds nothing
    with pytest.raises(WireError, match="InconsistentAssumptions"):
        decode(tree, sympy=True)


def test_hostile_sympy_objects_are_refused_by_name():
    """The student's side never calls a sympy object's repr, never follows a subclass's
    args, and stops at the node budget: each is an odd value saying why."""
    called = []

    class Loud(sp.Symbol):
        def __repr__(self):
            called.append("repr")
            raise RuntimeError("hostile repr")

        @property
        def args(self):
            called.append("args")
            raise RuntimeError("hostile args")

    bomb = A
    for _ in range(80):  # 160 nodes shared, 2**80 written out
        bomb = bomb * bomb + bomb
    cases = {
        "Loud": sp.Matrix(2, 2, [Loud("x"), 0, 0, A]),
        "too large": bomb,
        "exponent": sp.Mul(sp.Pow(10, 10**9, evaluate=False), A, evaluate=False),
        "60 digits": sp.Integer(10) ** 80 * A,
        "name": sp.Symbol("x\x1b[2K"),
        "Derivative": sp.Derivative(sp.Function("f")(A), A),
    }
    judge = symbolic_judge(lambda a: a * sp.eye(2), names=("a",))
    for why, obj in cases.items():
        sent = encode(obj)
        assert sent["t"] == "odd" and why in sent["why"] and sent["repr"] == "", (why, sent)
        v = judge((A,), wire(obj))
        assert v.key == "type" and "cannot read" in v.message and why in v.message, v
    assert called == []


# -- the judge --------------------------------------------------------------------------------
def det_2r(t1, t2, l1, l2):
    p = sp.Matrix([l1 * sp.cos(t1) + l2 * sp.cos(t1 + t2), l1 * sp.sin(t1) + l2 * sp.sin(t1 + t2)])
    return p.jacobian([t1, t2]).det()


def test_other_algebraic_forms_are_right():
    det = symbolic_judge(det_2r, names=("t1", "t2", "l1", "l2"))
    args = (T1, T2, L1, L2)
    for form in (L1 * L2 * sp.sin(T2), det_2r(*args), sp.expand(det_2r(*args)),
                 L1 * L2 * (sp.sin(T1 + T2) * sp.cos(T1) - sp.cos(T1 + T2) * sp.sin(T1)),
                 2 * L1 * L2 * sp.sin(T2 / 2) * sp.cos(T2 / 2),
                 sp.Matrix([[L1 * L2 * sp.sin(T2)]])):
        assert det(args, wire(form)).ok, form
    zyx = symbolic_judge(lambda a, b, g: kl.matrix_from_euler([a, b, g], "ZYX"),
                         names=("alpha", "beta", "gamma"))
    R = kl.rotz(A) * kl.roty(B) * kl.rotx(G)
    a, b, g = sp.symbols("a b g")  # no assumptions: other symbols of the same names
    for form in (R, sp.simplify(R), R.tolist(), np.array(R), sp.ImmutableMatrix(R)):
        assert zyx((A, B, G), wire(form)).ok
    assert zyx((a, b, g), wire(kl.rotz(a) * kl.roty(b) * kl.rotx(g))).ok
    lock = (A, sp.pi / 2, G)  # exact numbers in the arguments
    assert zyx(lock, wire(sp.simplify(kl.rotz(A) * kl.roty(sp.pi / 2) * kl.rotx(G)))).ok


def test_near_misses_are_named():
    R = lambda a, b, g: kl.rotz(a) * kl.roty(b) * kl.rotx(g)  # noqa: E731
    zyx = symbolic_judge(lambda a, b, g: kl.matrix_from_euler([a, b, g], "ZYX"),
                         names=("alpha", "beta", "gamma"), swaps=[(0, 2)])
    args = (A, B, G)
    right = R(*args)
    wrong_entry = right.copy()
    wrong_entry[1, 2] += A
    x = sp.Symbol("x")
    for got, key in [(-right, "sign"), (right.T, "transposed"), (R(G, B, A), "swapped"),
                     (wrong_entry, "entries"), (R(x, B, G), "symbols"),
                     (2 * right, "wrong"), (np.eye(3), "numbers"),
                     (0.5, "numbers"), (None, "none"), ("Rz*Ry*Rx", "type"), ({}, "type"),
                     (right[:, :2], "shape"), (right[:2, :], "shape"),
                     (sp.cos(A), "type"), (Odd("set", "{1}"), "type")]:
        v = zyx(args, wire(got) if isinstance(got, sp.Basic | sp.MatrixBase) else got)
        assert v.key == key, (key, v)
    assert "alpha and gamma are swapped" in zyx(args, wire(R(G, B, A))).message
    assert "[1, 2]" in zyx(args, wire(wrong_entry)).message
    scalar = symbolic_judge(lambda t: sp.sin(t), names=("t",))
    assert scalar((A,), [wire(sp.sin(A))]).key == "type"  # a list of one: solve's habit
    wide = symbolic_judge(lambda t: sp.Matrix([[t, 0, 1]]), names=("t",))
    assert wide((A,), wire(sp.Matrix([A, 0, 1]))).key == "transposed"
    zero = sp.Mul(A, sp.Pow(sp.Integer(0), -1, evaluate=False), evaluate=False)
    assert scalar((A,), wire(zero)).key == "undefined"


def test_the_judge_stays_bounded_on_trees_made_for_it():
    """Trees the decoder accepts but that no sympy call could finish with: the judge gives
    a verdict anyway (towers of powers, the sine of a huge number, a sum at the node limit)."""
    judge = symbolic_judge(lambda t: sp.sin(t), names=("t",))
    t = ["s", "t", ["real"]]
    tower = t
    for _ in range(50):
        tower = ["^", ["i", 1000], tower]
    trees = [["sin", tower], ["^", t, tower], ["exp", ["exp", ["exp", ["*", ["i", 10**59], t]]]],
             ["+", *[["sin", ["*", ["i", k], t]] for k in range(1, MAX_SYM_NODES // 4)]],
             ["log", ["+", t, ["*", ["i", -1], t]]]]
    for tree in trees:
        v = judge((sp.Symbol("t", real=True),), decode({"t": "sym", "v": tree}))
        assert v.key in ("undefined", "wrong"), v


def test_the_evaluator_agrees_with_sympy():
    """At each of the judge's points, its values are those of sympy's lambdify (doubles)."""
    x, y = sp.symbols("x y", real=True)
    exprs = [sp.sin(x) * sp.cos(y) ** 2 - sp.Rational(3, 7) * sp.tan(x + y),
             sp.sqrt(x**2 + y**2) + sp.atan2(y, x) * sp.exp(x / 3) - sp.log(sp.Abs(y) + 1),
             sp.pi * x**-2 + sp.E * sp.asin(sp.sin(y) / 2) + sp.acos(sp.cos(x) / 3) * sp.cot(y),
             (x + sp.I * y) ** sp.Rational(3, 2) + 1.25 * x]
    at = _Points({"x": ("real",), "y": ("real",)})
    for e in exprs:
        f = sp.lambdify((x, y), e, "numpy")
        values = at.values(sym_tree(e))
        for env, v in zip(at.points, values, strict=True):
            want = complex(f(float(env["x"]), float(env["y"])))
            assert v is not None and abs(complex(v[0]) - want) <= 1e-10 * max(1, abs(want)), e


def test_the_exact_decision_and_its_domain():
    t = sp.Symbol("t", real=True)
    tree = sym_tree
    assert _exact(tree(sp.sin(2 * t) + t), tree(2 * sp.sin(t) * sp.cos(t) + t)) is True
    assert _exact(tree(sp.sin(t) + t), tree(sp.cos(t) + t)) is False
    assert _exact(tree(sp.Abs(t) + 1), tree(sp.Abs(t) + 1)) is None  # outside the domain
    assert _exact(tree(t * 1.5), tree(t * 1.5)) is None  # Floats: the points decide
    big = sum(sp.symbols("u0:9")) + t
    assert _exact(tree(big**16), tree(big**16)) is None  # too many terms to expand


# -- assignment 01's derivation, graded for real ------------------------------------------------
ZYX = "return Rz * Ry * Rx"
MISTAKES_01 = [  # (edit or edits, diagnosis)
    ((ZYX, "return Rx * Ry * Rz"), "extrinsic"),
    (("Ry = sp.Matrix([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])",
      "Ry = sp.Matrix([[cb, 0, -sb], [0, 1, 0], [sb, 0, cb]])"), "sign"),
    ((ZYX, "return (Rz * Ry * Rx).T"), "transposed"),
    ((("ca, sa = sp.cos(alpha), sp.sin(alpha)", "ca, sa = sp.cos(gamma), sp.sin(gamma)"),
      ("cg, sg = sp.cos(gamma), sp.sin(gamma)", "cg, sg = sp.cos(alpha), sp.sin(alpha)")),
     "swapped"),
]


def test_the_zyx_derivation_graded_for_real(tmp_path):
    """Each mistake patched into the source's own function gets its diagnosis; the matrix
    simplified, as nested lists built with @, is right."""
    nb = json.loads((ROOT / "source" / "01_rotations.ipynb").read_text())
    (code,) = ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"
               and "".join(c["source"]).startswith("def euler_zyx_symbolic")]
    head = "import numpy as np\nimport sympy as sp"
    subs = []
    for k, (edit, _) in enumerate(MISTAKES_01):
        edits = [edit] if isinstance(edit[0], str) else list(edit)
        subs.append(write_notebook(tmp_path / f"m{k}.ipynb", head, patched(code, *edits),
                                   assignment="01_rotations"))
    alt = patched(code, (ZYX, "return sp.simplify(Rz @ Ry @ Rx).tolist()"))
    subs.append(write_notebook(tmp_path / "alt.ipynb", head, alt, assignment="01_rotations"))
    results = [by_function(r)["euler_zyx_symbolic"] for r in judge_notebooks(subs)]
    for (_, key), check in zip(MISTAKES_01, results, strict=False):
        assert check["passed"] < check["total"] and top(check) == key, (key, check["diagnoses"])
    assert "alpha and gamma" in results[3]["diagnoses"][0]["message"]
    assert results[-1]["passed"] == results[-1]["total"] == 4, results[-1]["diagnoses"]
