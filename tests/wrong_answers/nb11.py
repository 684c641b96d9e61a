"""Notebook 11: wrong answers a student would write."""

import numpy as np

import kinlib as kl


def error_backwards(T, T_target):          # "current minus target", as in a residual
    return np.concatenate([T[:3, 3] - T_target[:3, 3],
                           kl.log_so3(T_target[:3, :3] @ T[:3, :3].T)])


def error_negated(T, T_target):            # the error of T_target → T
    return -np.concatenate([T_target[:3, 3] - T[:3, 3],
                            kl.log_so3(T_target[:3, :3] @ T[:3, :3].T)])


def error_body(T, T_target):               # Rᵀ R_t: the rotation still to go, in the tool frame
    return np.concatenate([T_target[:3, 3] - T[:3, 3],
                           kl.log_so3(T[:3, :3].T @ T_target[:3, :3])])


def error_rows(T, T_target):               # Modern Robotics' twist order
    omega = kl.log_so3(T_target[:3, :3] @ T[:3, :3].T)
    return np.concatenate([omega, T_target[:3, 3] - T[:3, 3]])


def error_turned_back(T, T_target):        # R R_tᵀ: from the target to the current orientation
    return np.concatenate([T_target[:3, 3] - T[:3, 3],
                           kl.log_so3(T[:3, :3] @ T_target[:3, :3].T)])


def error_skew(T, T_target):               # "the rotation vector is the skew part of R_err"
    Re = T_target[:3, :3] @ T[:3, :3].T
    return np.concatenate([T_target[:3, 3] - T[:3, 3], kl.vee((Re - Re.T) / 2)])


def dls_lambda(J, e, lam):                 # λ I where the formula has λ² I
    return J.T @ np.linalg.solve(J @ J.T + lam * np.eye(len(J)), e)


def dls_sign(J, e, lam):
    return -J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(len(J)), e)


def dls_pinv(J, e, lam):                   # the undamped pseudo-inverse
    return np.linalg.pinv(J) @ e


def dls_multiplied(J, e, lam):             # multiplied where it should solve
    return J.T @ (J @ J.T + lam**2 * np.eye(len(J))) @ e


def dls_transpose(J, e, lam):              # the Jacobian-transpose (gradient) step
    return 0.5 * J.T @ e


WRONG = {
    "11.1": [(error_backwards, "sign"), (error_negated, "sign"), (error_body, "frame"),
             (error_rows, "rows"), (error_turned_back, "rotation sign"), (error_skew, "sin")],
    "11.2": [(dls_lambda, "lambda"), (dls_sign, "sign"), (dls_pinv, "undamped"),
             (dls_multiplied, "inverse"), (dls_transpose, "transpose")],
    "11.3": [("a", "elbow only"), ("b", "wrist flip"), ("d", "per joint"), ("e", "finite")],
    "11.4": [("a", "branches"), ("c", "carried error"), ("d", "continuous")],
}
