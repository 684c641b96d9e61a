"""Readable forms of reduced trigonometric polynomials (private, used by kinlib.symbolic).

``combine_sums`` folds c1 c2 - s1 s2 into cos(θ1 + θ2) (and the three other sum and
difference patterns) exactly, term by term; ``lower_half_angles`` writes sin²(θ/2) as
(1 - cos θ)/2.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["combine_sums", "lower_half_angles"]


def _monomials(poly: sp.Expr) -> dict[tuple, sp.Expr]:
    """An expanded polynomial as {((symbol, exponent), ...): coefficient}."""
    out: dict[tuple, sp.Expr] = {}
    for m, c in poly.as_coefficients_dict().items():
        key = tuple(sorted(
            ((b, int(x)) for b, x in m.as_powers_dict().items() if b != 1),
            key=lambda bx: sp.default_sort_key(bx[0]),
        ))
        out[key] = out.get(key, 0) + c
    return {k: v for k, v in out.items() if v != 0}


def combine_sums(e: sp.Expr) -> sp.Expr:
    r"""Fold :math:`c_i c_j \mp s_i s_j` into :math:`\cos(\theta_i \pm \theta_j)` and
    :math:`s_i c_j \pm c_i s_j` into :math:`\sin(\theta_i \pm \theta_j)`, exactly (term by term,
    same cofactor and coefficient), repeatedly, so chains give cos(θ1 + θ2 + θ3)."""
    num, den = sp.fraction(e)
    if den != 1:
        return combine_sums(num) / combine_sums(den)
    trig = num.atoms(sp.sin, sp.cos)
    if len(trig) < 2:
        return num
    table: dict[sp.Expr, tuple[sp.Dummy, sp.Dummy]] = {}
    back: dict[sp.Dummy, sp.Expr] = {}

    def pair(angle):
        if angle not in table:
            c, s = sp.Dummy("c", real=True), sp.Dummy("s", real=True)
            table[angle] = (c, s)
            back[c], back[s] = sp.cos(angle), sp.sin(angle)
        return table[angle]

    for a in sorted({f.args[0] for f in trig}, key=sp.default_sort_key):
        pair(a)
    sub = {f(a): cs[k] for a, cs in table.items() for k, f in enumerate((sp.cos, sp.sin))}
    terms = _monomials(sp.expand(num.xreplace(sub)))

    def split(key, ci, si, cj, sj):
        """(pattern, cofactor) if the monomial is linear in angle i and in angle j."""
        d = dict(key)
        pi_ = (d.get(ci, 0), d.get(si, 0))
        pj_ = (d.get(cj, 0), d.get(sj, 0))
        if sum(pi_) != 1 or sum(pj_) != 1:
            return None, None
        rest = tuple(bx for bx in key if bx[0] not in (ci, si, cj, sj))
        return ("s" if pi_[1] else "c") + ("s" if pj_[1] else "c"), rest

    def add(key_d, coeff):
        key = tuple(sorted(key_d.items(), key=lambda bx: sp.default_sort_key(bx[0])))
        terms[key] = terms.get(key, 0) + coeff
        if terms[key] == 0:
            del terms[key]

    for _ in range(64):  # each pass merges at least one pair of angles
        angles = sorted(table, key=sp.default_sort_key)
        merged = False
        for i, ai in enumerate(angles):
            for aj in angles[i + 1:]:
                (ci, si), (cj, sj) = table[ai], table[aj]
                groups: dict[tuple, dict[str, tuple]] = {}
                for key, coeff in terms.items():
                    pat, rest = split(key, ci, si, cj, sj)
                    if pat:
                        groups.setdefault(rest, {})[pat] = (key, coeff)
                for rest, g in sorted(groups.items(), key=lambda kv: sp.default_sort_key(
                        sp.Mul(*[b**x for b, x in kv[0]]))):
                    for p1, p2, fn, sgn in (("cc", "ss", sp.cos, -1), ("sc", "cs", sp.sin, 1)):
                        if p1 not in g or p2 not in g:
                            continue
                        (k1, a1), (k2, a2) = g[p1], g[p2]
                        if a2 == sgn * a1:  # cos(i + j) or sin(i + j)
                            angle, coeff = ai + aj, a1
                        elif a2 == -sgn * a1:  # cos(i − j) or sin(i − j)
                            angle, coeff = ai - aj, a1
                        else:
                            continue
                        if angle.could_extract_minus_sign():
                            angle = -angle
                            coeff = -coeff if fn is sp.sin else coeff
                        del terms[k1], terms[k2]
                        c, s = pair(angle)
                        add({**dict(rest), (c if fn is sp.cos else s): 1}, coeff)
                        merged = True
                if merged:
                    break
            if merged:
                break
        if not merged:
            break
    out = sp.Add(*[c * sp.Mul(*[b**x for b, x in key]) for key, c in terms.items()])
    return out.xreplace(back)


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
