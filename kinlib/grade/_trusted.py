"""Judge trusted functions in this process: an assignment's own tests of its diagnoses.

An assignment's checks are proved by its known mistakes: each mistake patched into the
solution must be diagnosed as itself. Those wrong versions are the instructor's code, not a
student's, and there are hundreds of them; :func:`judge_functions` judges them the way
:func:`~kinlib.grade.grade` judges a submission — the same cases from the same seed, the
same trip through the wire format both ways (arguments as the student process receives
them, answers as the grader reads them back), the same judges, hints and summary — but
calls the functions here, without a sandbox, a student process or deadlines.

Never give it a student's code: it runs with the grader's own rights. Submissions go to
:func:`~kinlib.grade.grade`, which runs them in the sandbox.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping

from ._checks import shared_cases
from ._grader import _judged, load_assignment, not_graded
from ._wire import WireError, decode, dumps, encode, loads
from ._worker import _error_text, _where

__all__ = ["judge_functions"]

TRUSTED = ("judged in this process (kinlib.grade._trusted), without the sandbox: for the "
           "instructor's own code only")


def _answer(fn: Callable, case) -> tuple[str, object]:
    """``fn`` on ``case`` as the student process would run it and the grader read it:
    ``("value", answer)`` or ``("error", text)``."""
    args = decode(loads(dumps({"a": encode(case, exact=True)}))["a"], sympy=True)
    try:
        with warnings.catch_warnings():  # as in the student process: a warning is not an error
            warnings.simplefilter("ignore")
            value = fn(*args)
    except Exception as exc:
        where = _where(exc)
        return "error", f"raised {_error_text(exc)[:400]}" + (f" ({where})" if where else "")
    try:
        return "value", decode(loads(dumps({"v": encode(value)}))["v"])
    except (WireError, TypeError, ValueError) as exc:
        return "error", f"the returned value could not be read ({exc})"


def judge_functions(functions: Mapping[str, Callable], assignment: str, *,
                    seed: int = 0) -> dict:
    """The result :func:`~kinlib.grade.grade` would give a submission defining
    ``functions`` (name → callable) for ``assignment``, on the public cases of ``seed``;
    marked ``"sandbox": None`` with a warning saying it was judged in process."""
    spec = load_assignment(assignment)
    result = not_graded("<in process>", assignment, None, spec.max_score)
    result.update(title=spec.title, cases=f"public (seed {seed})", sandbox=None,
                  warning=TRUSTED)
    for check in spec.checks:
        cases, memos = shared_cases(assignment, check, seed)
        fn = functions.get(check.function)
        if fn is None or not callable(fn):
            what = "not defined" if fn is None else f"a {type(fn).__name__}, not a function"
            answers = [("missing", what)] * len(cases)
        else:
            answers = [_answer(fn, c) for c in cases]
        result["checks"].append(_judged(check, cases, memos, answers))
    result["score"] = round(sum(c["score"] for c in result["checks"]), 2)
    result["graded"] = True
    return result
