"""Self-check: a student grades their own notebook where they work, as practice.

On the course hub or a laptop there may be no bubblewrap, and a student running their own
code needs no protection from it; so a self-check runs the grader without the sandbox
(``unsandboxed=True``: the code still runs in a child process of its own, with the same
deadlines, so an endless loop stops), on the public cases (seed 0), with no secret. Its
result says so: ``"practice": true`` and a ``"note"`` in place of the unsandboxed warning
an instructor's result would carry, and :func:`~kinlib.grade.format_report` starts with
that note.
"""

from __future__ import annotations

from ..errors import KinlibError
from ._grader import UNSANDBOXED, GradeResult, grade

__all__ = ["PRACTICE", "self_check", "as_practice"]

PRACTICE = ("your own code, run on this machine without a sandbox, on the public cases; "
            "your instructor grades on hidden cases")


def as_practice(result: dict) -> dict:
    """Mark ``result`` (of a grading with ``unsandboxed=True`` on the public cases) as a
    self-check: ``"practice": True`` and the :data:`PRACTICE` note, in place of the warning
    that the submission ran without the sandbox. Returns ``result`` itself.

    >>> r = as_practice({"submission": "a.ipynb", "warning": UNSANDBOXED})
    >>> r["practice"], "warning" in r
    (True, False)
    """
    if result.get("warning") == UNSANDBOXED:
        del result["warning"]
    result["practice"] = True
    result["note"] = PRACTICE
    return result


def self_check(submission, assignment: str | None = None, *, cell_timeout: float = 60.0,
               memory_mb: int = 4096, **limits) -> GradeResult:
    """Grade your own notebook on the public cases, here, as practice.

    Parameters
    ----------
    submission : str or Path
        The notebook (``.ipynb``) to check. Save it first: the file is what is graded,
        not the cells as they are in a running kernel.
    assignment : str, optional
        Which assignment (default: the notebook's metadata, else its file name).
    cell_timeout, memory_mb, **limits
        The grader's limits, as for :func:`~kinlib.grade.grade` (``submission_timeout``).

    Returns
    -------
    GradeResult
        The result :func:`~kinlib.grade.grade` gives, on the public cases (seed 0), with
        ``"practice": True`` and a ``"note"`` saying what it is; no secret is read, and no
        sandbox is needed. ``print(format_report(result))`` shows it.

    Examples
    --------
    >>> from kinlib.grade import format_report, self_check
    >>> result = self_check("01_rotations.ipynb")          # doctest: +SKIP
    >>> print(format_report(result).splitlines()[0])       # doctest: +SKIP
    PRACTICE: your own code, run on this machine without a sandbox, on the public cases; ...
    """
    odd = sorted(set(limits) - {"submission_timeout"})
    if odd:
        raise KinlibError(f"self_check: expected only the grader's limits (cell_timeout, "
                          f"memory_mb, submission_timeout), got {odd}: a self-check always "
                          "runs the public cases, without a secret or a sandbox")
    result = grade(submission, assignment, seed=0, secret=None, cell_timeout=cell_timeout,
                   memory_mb=memory_mb, unsandboxed=True, **limits)
    return as_practice(result)
