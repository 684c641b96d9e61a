"""Compiling kinlib's kernels now, instead of in the background on first use.

With numba installed (the ``fast`` extra), kinlib's batched kinematics and a few batched
conversions run compiled kernels. The first call that could use one never waits for it:
it takes the numpy path (the same results) while numba compiles the kernel, or loads it
from its on-disk cache, in a background thread (:mod:`kinlib._background`); later calls
use the kernel. :func:`prepare_kernels` does that work now and waits for it: for a
benchmark that must time the compiled kernels from its first call, or to fill numba's
cache once where many will use the same installation (a JupyterHub or Docker image: run it
in the image's build, where the package folder is writable).
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .._accel import MIN_BATCH, numba_disabled
from .._accel import kernel as _conversion
from .._background import peek
from ..errors import KinlibError
from . import _fk, ik
from .robot import Robot

__all__ = ["KERNELS", "prepare_kernels"]

#: what :func:`prepare_kernels` can prepare: name → what uses it
KERNELS = {
    "fk": "Robot.fk of one or many configurations (and IK's start ranking)",
    "jacobian": "Robot.jacobian and Robot.fk_and_jacobian",
    "link_poses": "Robot.link_poses",
    "ik": "Robot.ik's Levenberg–Marquardt loop",
    "conversions": f"matrix_from_quat, quat_from_matrix and is_rotation on batches of "
                   f"{MIN_BATCH} or more",
}


def _two_joints() -> Robot:
    """A small arm: its tables have the types every robot's have (so the kernels compile
    for the signature every later call uses)."""
    return Robot.from_dh([{"a": 0.3, "alpha": 0.5}, {"a": 0.2, "alpha": 0.0}], name="warm")


def prepare_kernels(names=None, *, wait: bool = True) -> dict[str, bool]:
    """Compile kinlib's kernels now (or load them from numba's cache); which are ready.

    ``names``: some of :data:`KERNELS` (default: all). ``wait=False`` only starts their
    preparation in the background, as a first call would. Returns name → whether its
    kernels are ready (all False without numba or with ``KINLIB_NUMBA=0``: the numpy paths
    are used then).

    >>> ready = prepare_kernels(["fk"])
    >>> sorted(ready)
    ['fk']
    """
    chosen = list(KERNELS) if names is None else names
    if not isinstance(chosen, str) and isinstance(chosen, Iterable):
        chosen = list(chosen)
    if not isinstance(chosen, list) or not all(isinstance(n, str) and n in KERNELS
                                               for n in chosen):
        raise KinlibError(f"prepare_kernels: expected a list of names from {list(KERNELS)}, "
                          f"got {names!r}")
    if numba_disabled():
        return dict.fromkeys(chosen, False)
    robot, compiled = _two_joints(), True if wait else None
    chain = robot.chain_table(None)
    q = np.zeros((1, robot.dof))
    rots, quats = np.zeros((0, 3, 3)), np.zeros((0, 4))
    for name in chosen:
        if name == "fk":
            _fk.run_chain(chain, q, compiled=compiled)
        elif name == "jacobian":
            _fk.run_chain_jacobian(chain, q, compiled=compiled)
        elif name == "link_poses":
            _fk.run(robot._table, q, robot._all, compiled=compiled)
        elif name == "ik":
            target = _fk._chain_numpy(chain, q)[0]  # (numpy: "ik" prepares the IK loop only)
            ik.solve_ik(robot, target, q[0], restarts=0, compiled=compiled)
        else:
            _conversion("matrix_from_quat", lambda: (quats, rots), wait=wait)
            _conversion("quat_from_matrix", lambda: (rots, quats), wait=wait)
            _conversion("rotation_errors", lambda: (rots, np.zeros(0), np.zeros(0)),
                        wait=wait)
    return {name: all(peek(key) is not None for key in _KEYS[name]) for name in chosen}


#: the kernels behind each name (their keys in :mod:`kinlib._background`)
_KEYS = {"fk": ["_fk_numba.chain"], "jacobian": ["_fk_numba.chain_jacobian"],
         "link_poses": ["_fk_numba.tree"], "ik": ["_ik_numba.ik_lm"],
         "conversions": ["_accel.matrix_from_quat", "_accel.quat_from_matrix",
                         "_accel.rotation_errors"]}
