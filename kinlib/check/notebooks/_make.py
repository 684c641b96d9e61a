"""Short constructors for the exercises of the notebook modules."""

from __future__ import annotations

from .._exercise import Exercise
from .._symbolic import expression_judge
from .._verdict import Rule
from ..judges import choice_judge

__all__ = ["value", "function", "choice", "expression", "judged"]


def _keys(mistakes) -> tuple:
    return tuple(dict.fromkeys(m.key for m in mistakes))


def value(id, kind, title, reference, *mistakes, accept=None, atol=1e-6, what="an array",
          explain=""):
    """A number or an array, compared with ``reference()``."""
    return Exercise(id, kind, title, Rule(reference, mistakes, accept, atol=atol, what=what,
                                          returned=False), diagnoses=_keys(mistakes),
                    explain=explain)


def function(id, title, cases, reference, *mistakes, accept=None, atol=1e-6,
             what="an array", on_error=None, explain=""):
    """A function the student writes: called on each case, compared with ``reference``."""
    return Exercise(id, "implement", title, Rule(reference, mistakes, accept, atol=atol,
                                                 what=what), cases, on_error=on_error,
                    diagnoses=_keys(mistakes), explain=explain)


def choice(id, kind, title, options, right, wrong=None, explain=""):
    """Multiple choice: ``options`` maps keys to texts, ``wrong`` keys to (key, diagnosis)."""
    keys = tuple(dict.fromkeys(k for k, _ in (wrong or {}).values()))
    return Exercise(id, kind, title, Rule(judge=choice_judge(options, right, wrong)),
                    diagnoses=keys, explain=explain)


def expression(id, title, expected, *mistakes, unit=None, swaps=None,
               what="a sympy expression", diagnoses=(), explain=""):
    """A derivation: a sympy expression or matrix equal to ``expected()``. ``mistakes``:
    its own near misses (``Mistake`` whose model is the wrong expression); ``diagnoses``:
    the generic ones (sign, transposed, swapped) its tests produce."""
    judge = expression_judge(expected, unit=unit, swaps=swaps, what=what, mistakes=mistakes)
    return Exercise(id, "derive", title, Rule(judge=judge),
                    diagnoses=tuple(dict.fromkeys((*_keys(mistakes), *diagnoses))),
                    explain=explain)


def judged(id, kind, title, judge, cases=(), on_error=None, diagnoses=(), explain=""):
    """An answer judged by ``judge(args, got)`` (for a function: on each case);
    ``diagnoses``: the keys of the mistakes the judge names."""
    return Exercise(id, kind, title, Rule(judge=judge), cases, on_error=on_error,
                    diagnoses=tuple(diagnoses), explain=explain)
