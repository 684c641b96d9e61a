"""Notebook 11 · inverse kinematics II, numerical IK: the pose error and one damped
least-squares step (judged with assignment 03's references, cases and mistake models), the
PUMA 560's eight solutions, warm versus cold starts along a path."""

import numpy as np

from .._verdict import Rule
from ..mistakes import FRAME, ROWS
from ._make import choice, judged

# --- 11.1 · the pose error [p_t − p; log(R_t Rᵀ)^∨] ------------------------------------------

_MESSAGES = {
    ROWS.key: "your error is stacked [ω; v]: the course stacks it like the Jacobian's rows, "
              "position first, [p_target − p; log(R_target Rᵀ)^∨] (Modern Robotics writes "
              "twists [ω; v])",
}


def _pose_rule():
    from ...grade.assignments._numerical_ik import (
        POSE_MISTAKES,
        _accept_pose,
        pose_error_reference,
    )

    rekey = {"order": ROWS, "frame": FRAME}  # assignment 03's keys → the catalogue's
    mistakes = [rekey[m.key].of(m.model, _MESSAGES.get(rekey[m.key].key, m.message))
                if m.key in rekey else m for m in POSE_MISTAKES]
    return Rule(pose_error_reference, mistakes, _accept_pose, what="a 6-vector [p_t − p; ω]")


def _pose_judge():
    from ...grade.assignments._numerical_ik import _judge_pose

    rule = _pose_rule()

    def judge(args, got):
        verdict = rule.verdict(args, got)
        if verdict.ok or verdict.key not in ("wrong", "nan"):
            return verdict
        return _judge_pose(args, got)  # the angles near 0 and π, diagnosed
    return judge


def _pose_cases():
    from ...grade.assignments._numerical_ik import _pose_cases as cases

    return cases(np.random.default_rng(11))


# --- 11.2 · one damped least-squares step ----------------------------------------------------


def _dls_judge(args, got):
    from ...grade.assignments._numerical_ik import _judge_dls

    return _judge_dls(args, got)


def _dls_cases():
    from ...grade.assignments._numerical_ik import _dls_cases as cases

    return cases(np.random.default_rng(11))


# --- 11.3 · how many solutions the PUMA 560 has at most --------------------------------------

_COUNTS = {"a": 2, "b": 4, "c": 8, "d": 64, "e": np.inf}
_SHOULDER, _ELBOW, _WRIST_FLIP = 2, 2, 2  # the arm positions the wrist centre, the wrist turns


def _most() -> str:
    return next(k for k, n in _COUNTS.items() if n == _SHOULDER * _ELBOW * _WRIST_FLIP)


_SOLUTIONS = {k: ("infinitely many" if np.isinf(n) else str(n)) for k, n in _COUNTS.items()}

# --- 11.4 · warm or cold starts along a path -------------------------------------------------

_SMOOTH = {"a": "both", "b": "the warm-started one", "c": "the cold one", "d": "neither"}

EXERCISES = [
    judged("11.1", "implement", "the pose error [p_t − p; log(R_t Rᵀ)^∨]", _pose_judge(),
           cases=_pose_cases(), diagnoses=("sign", "rotation sign", "frame", "rows", "sin"),
           explain="e = 0 exactly when T = T_target, and at θ = π both ±k are right (the same "
                   "rotation). kinlib's `kl.pose_error(T, T_target)` is this function, for "
                   "batches of poses too; the rest of the notebook uses it"),
    judged("11.2", "implement", "one damped least-squares step", _dls_judge, cases=_dls_cases(),
           diagnoses=("lambda", "sign", "undamped", "inverse", "transpose"),
           explain="with λ = 0 and a square, invertible J this is Newton's step J⁻¹ e; a λ > 0 "
                   "keeps it short where J is nearly singular. kinlib's "
                   "`kl.dls_step(J, e, damping)` is this function, with damping = λ"),
    choice("11.3", "predict", "the most solutions the PUMA 560 has for one pose", _SOLUTIONS,
           _most(),
           {"a": ("elbow only", "the elbow up or down, as for the 2R arm, yes — but the PUMA "
                                "also reaches with its shoulder left or right (joint 1 turned "
                                "by about π, reaching backwards), and its wrist can flip "
                                "(q4 + π, −q5, q6 + π): 2 × 2 × 2"),
            "b": ("wrist flip", "shoulder left/right × elbow up/down place the wrist centre; "
                                "then the spherical wrist has two ways to give the orientation, "
                                "q5 and −q5 (with q4 + π and q6 + π): twice 4"),
            "d": ("per joint", "not every joint has a choice of its own: the position fixes the "
                               "first three joints up to shoulder × elbow (4 ways), the "
                               "orientation fixes the wrist up to its flip (2 ways): 8"),
            "e": ("finite", "six joints for the six numbers of a pose (3 for the position, 3 "
                            "for the orientation) leave no freedom: a general pose has "
                            "isolated solutions. Whole families appear only at singular poses "
                            "or for a redundant arm, with seven joints or more")},
           explain="2 shoulders × 2 elbows place the wrist centre, and the spherical wrist "
                   "gives the orientation in 2 ways (its flip): 8"),
    choice("11.4", "predict", "warm or cold starts along a straight line", _SMOOTH, "b",
           {"a": ("branches", "close poses have close solutions on each of the up to eight "
                              "branches, but a solve started far away picks its branch by "
                              "where it starts: neighbouring samples may land on different "
                              "branches"),
            "c": ("carried error", "each solve converges to the tolerance from wherever it "
                                   "starts, so no error is carried along; the warm start only "
                                   "chooses the branch — the one of the previous sample"),
            "d": ("continuous", "away from singularities each solution changes continuously "
                                "with the pose (J is invertible there: a small change of pose "
                                "needs only a small change Δq = J⁻¹ e)")},
           explain="a warm start stays on the branch of the previous sample, and each branch "
                   "changes continuously with the pose away from singularities"),
]
