"""Readable forms of reduced trigonometric polynomials (private, used by kinlib.symbolic).

``combine_sums`` folds c1 c2 - s1 s2 into cos(θ1 + θ2) (and the three other sum and
difference patterns) exactly, term by term; ``lower_half_angles`` writes sin²(θ/2) as
(1 - cos θ)/2.

Why not sympy's ``sympy.simplify.fu.TR10i``, which folds the same patterns and gives the same
result on the PUMA 560, the UR5, the Panda and every expression the notebooks fold? Two cases
(both tested in tests/test_sym_helpers.py):

* four or more parallel joints: on the expanded cos(q1 + q2 + q3 + q4) (8 terms) TR10i pairs
  terms greedily, in its own order, and stops at products such as
  cos(q2) cos(q4) cos(q1 + q3) - ...; here the angles are merged pair by pair in a fixed order
  (q1 with q2 first), so a planar 4R arm comes out as l1 cos q1 + ... + l4 cos(q1 + ... + q4);
* ``sin q + cos q``: TR10i writes it as sqrt(2) sin(q + pi/4), an angle no joint has; here
  only equal rational coefficients fold, so a translation (1, 1, 0) stays readable.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["combine_sums", "lower_half_angles"]

# A term of the polynomial: ((trig dummy, exponent), ...), the rest of the product) mapped to
# its numeric coefficient. The rest keeps every other factor as it is (symbols, sqrt(2), pi):
# only terms with the same rest and equal or opposite coefficients fold.
_Terms = dict[tuple[tuple[tuple[sp.Dummy, int], ...], sp.Expr], sp.Number]

# (p1, p2, fn, sgn), p = (factor of angle i, factor of angle j): p1 + sgn p2 = fn(i + j) and
# p1 - sgn p2 = fn(i - j), i.e. cc - ss = cos(i + j), cc + ss = cos(i - j), sc + cs = sin(i + j),
# sc - cs = sin(i - j).
_RULES = ((("c", "c"), ("s", "s"), sp.cos, -1), (("s", "c"), ("c", "s"), sp.sin, 1))


class _Angles:
    """The cos/sin dummies of each angle, made on first use."""

    def __init__(self):
        self.cs: dict[sp.Expr, tuple[sp.Dummy, sp.Dummy]] = {}
        self.back: dict[sp.Dummy, sp.Expr] = {}

    def of(self, angle: sp.Expr) -> tuple[sp.Dummy, sp.Dummy]:
        if angle not in self.cs:
            c, s = sp.Dummy("c", real=True), sp.Dummy("s", real=True)
            self.cs[angle] = (c, s)
            self.back[c], self.back[s] = sp.cos(angle), sp.sin(angle)
        return self.cs[angle]

    def ordered(self) -> list[sp.Expr]:
        return sorted(self.cs, key=sp.default_sort_key)


def _terms(poly: sp.Expr, angles: _Angles) -> _Terms:
    """An expanded polynomial in the trig dummies as {(trig monomial, rest): coefficient}."""
    out: _Terms = {}
    for term in sp.Add.make_args(poly):
        coeff, product = term.as_coeff_Mul()
        trig, rest = [], []
        for f in sp.Mul.make_args(product):
            base, exp = f.as_base_exp()
            if base in angles.back and exp.is_Integer:
                trig.append((base, int(exp)))
            else:
                rest.append(f)
        _add(out, dict(trig), sp.Mul(*rest), coeff)
    return out


def _add(terms: _Terms, trig: dict, rest: sp.Expr, coeff) -> None:
    key = (tuple(sorted(trig.items(), key=lambda bx: sp.default_sort_key(bx[0]))), rest)
    new = terms.pop(key, 0) + coeff
    if new != 0:
        terms[key] = new


def _merge_pair(terms: _Terms, angles: _Angles, ai: sp.Expr, aj: sp.Expr) -> bool:
    """Fold every pattern of angles ``ai`` and ``aj``; True if any folded.

    Each fold replaces two terms by one, so the number of terms falls.
    """
    (ci, si), (cj, sj) = angles.of(ai), angles.of(aj)
    groups: dict[tuple, dict[tuple[str, str], tuple]] = {}
    for key, coeff in terms.items():
        trig = dict(key[0])
        pi_, pj_ = (trig.get(ci, 0), trig.get(si, 0)), (trig.get(cj, 0), trig.get(sj, 0))
        if sum(pi_) != 1 or sum(pj_) != 1:
            continue  # not linear in angle i and in angle j
        other = tuple(bx for bx in key[0] if bx[0] not in (ci, si, cj, sj))
        pattern = ("s" if pi_[1] else "c", "s" if pj_[1] else "c")
        groups.setdefault((other, key[1]), {})[pattern] = (key, coeff)
    merged = False
    # the groups are disjoint and a fold's new term holds neither angle: the order of the
    # groups does not change the result
    for (other, rest), g in groups.items():
        for p1, p2, fn, sgn in _RULES:
            if p1 not in g or p2 not in g:
                continue
            (k1, a1), (k2, a2) = g[p1], g[p2]
            if a2 not in (a1, -a1):
                continue
            angle = ai + aj if a2 == sgn * a1 else ai - aj
            if angle.could_extract_minus_sign():  # cos(-x) = cos x, sin(-x) = -sin x
                angle, a1 = -angle, (-a1 if fn is sp.sin else a1)
            del terms[k1], terms[k2]
            c, s = angles.of(angle)
            _add(terms, {**dict(other), (c if fn is sp.cos else s): 1}, rest, a1)
            merged = True
    return merged


def _merge_first_pair(terms: _Terms, angles: _Angles) -> bool:
    """Fold the first pair of angles, in sorted order, that has a pattern; True if any did."""
    order = angles.ordered()
    return any(_merge_pair(terms, angles, ai, aj)
               for i, ai in enumerate(order) for aj in order[i + 1:])


def combine_sums(e: sp.Expr) -> sp.Expr:
    r"""Fold :math:`c_i c_j \mp s_i s_j` into :math:`\cos(\theta_i \pm \theta_j)` and
    :math:`s_i c_j \pm c_i s_j` into :math:`\sin(\theta_i \pm \theta_j)`, exactly (same
    cofactor, equal or opposite rational coefficients), repeatedly, so chains give
    cos(θ1 + θ2 + θ3).

    The angle pairs are tried in sorted order and the search restarts after each pair that
    folded; every fold removes a term, so this ends after fewer folds than there are terms.

    >>> import sympy as sp
    >>> a, b, l = sp.symbols("alpha beta l", real=True)
    >>> combine_sums(l * sp.cos(a) * sp.cos(b) - l * sp.sin(a) * sp.sin(b) + sp.sin(a))
    l*cos(alpha + beta) + sin(alpha)
    """
    num, den = sp.fraction(e)
    if den != 1:
        return combine_sums(num) / combine_sums(den)
    trig = num.atoms(sp.sin, sp.cos)
    if len(trig) < 2:
        return num
    angles = _Angles()
    for a in sorted({f.args[0] for f in trig}, key=sp.default_sort_key):
        angles.of(a)
    sub = {f(a): cs[k] for a, cs in angles.cs.items() for k, f in enumerate((sp.cos, sp.sin))}
    terms = _terms(sp.expand(num.xreplace(sub)), angles)
    while _merge_first_pair(terms, angles):
        pass
    out = sp.Add(*[
        c * rest * sp.Mul(*[b**x for b, x in trig]) for (trig, rest), c in terms.items()
    ])
    return out.xreplace(angles.back)


def lower_half_angles(x: sp.Expr) -> sp.Expr:
    """sin²(θ/2) → (1 − cos θ)/2, cos²(θ/2) → (1 + cos θ)/2: Rodrigues' form, not the half angle."""

    def half(arg):
        return any(
            sp.expand(arg).coeff(v).is_Rational and sp.expand(arg).coeff(v).q % 2 == 0
            for v in arg.free_symbols
        )

    def lower(p):
        f, n = p.base, int(p.exp)
        a = f.args[0]
        c2 = sp.cos(2 * a)
        sq = (1 - c2) / 2 if f.func is sp.sin else (1 + c2) / 2
        return sq ** (n // 2) * f ** (n % 2)

    return x.replace(
        lambda p: p.is_Pow and p.base.func in (sp.sin, sp.cos) and p.exp.is_Integer
        and p.exp >= 2 and half(p.base.args[0]),
        lower,
    )
