"""The optional compiled kernels agree with kinlib's numpy reference implementations."""

import subprocess
import sys

import numpy as np
import pytest

import kinlib as kl
from kinlib import _accel
from kinlib.spatial.quaternions import _matrix_from_quat_numpy

needs_numba = pytest.mark.skipif(_accel.kernels() is None, reason="numba not installed")


def _run(code: str, **env) -> str:
    import os

    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, **env},
    )
    return out.stdout.strip()


def test_numba_is_installed_by_the_project_environment():
    # make test installs the 'fast' extra; without it the benchmarks would measure the
    # numpy fallback, so a missing numba is an environment bug, not a skip.
    assert _accel.kernels() is not None


@needs_numba
@pytest.mark.parametrize("shape", [(_accel.MIN_BATCH,), (3, _accel.MIN_BATCH), (5000,)])
def test_matrix_from_quat_kernel_matches_numpy(shape):
    rng = np.random.default_rng(7)
    q = rng.normal(size=(*shape, 4)) * rng.uniform(0.1, 10.0, size=(*shape, 1))
    q[..., 0, :] = [0.0, 0.0, 0.0, 3.0]  # a half turn, non-unit
    fast = kl.matrix_from_quat(q)
    ref = _matrix_from_quat_numpy(q)
    assert fast.shape == (*shape, 3, 3)
    assert np.abs(fast - ref).max() < 1e-15 * 8
    assert np.all(kl.is_rotation(fast, tol=1e-12))


@needs_numba
def test_matrix_from_quat_kernel_reports_zero_quaternion_position():
    q = np.tile([1.0, 0.0, 0.0, 0.0], (4, _accel.MIN_BATCH, 1))
    q[2, 17] = 0.0
    with pytest.raises(kl.KinlibError, match=r"q\[2, 17\].*zero quaternion"):
        kl.matrix_from_quat(q)


def test_small_calls_and_import_do_not_load_numba():
    code = (
        "import sys, kinlib as kl; kl.matrix_from_quat([1.0, 0, 0, 0]);"
        "print('numba' in sys.modules)"
    )
    assert _run(code) == "False"


def test_kernels_can_be_disabled():
    code = (
        "import sys, numpy as np, kinlib as kl\n"
        "from kinlib import _accel\n"
        "R = kl.matrix_from_quat(np.tile([0.0, 0, 0, 1], (5000, 1)))\n"
        "print(_accel.kernels() is None, 'numba' in sys.modules, float(R[..., 0, 0].max()))"
    )
    assert _run(code, KINLIB_NUMBA="0") == "True False -1.0"


def _rotations(n, seed):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    R = kl.matrix_from_quat(q)
    # Every branch of Shepperd's method: near-identity, and half turns about x, y, z.
    R[:4] = [np.eye(3), kl.rotx(np.pi), kl.roty(np.pi), kl.rotz(np.pi)]
    R[4:8] = kl.matrix_from_axis_angle(np.eye(3)[[0, 1, 2, 0]], np.pi - 1e-9)
    return R


@needs_numba
def test_quat_from_matrix_kernel_matches_numpy():
    from kinlib.spatial.quaternions import _quat_from_matrix_numpy

    R = _rotations(3 * _accel.MIN_BATCH, 3).reshape(3, -1, 3, 3)
    fast = kl.quat_from_matrix(R)
    ref = _quat_from_matrix_numpy(R)
    assert fast.shape == (3, _accel.MIN_BATCH, 4)
    assert np.abs(fast - ref).max() < 1e-15 * 4
    assert np.all(fast[..., 0] >= 0)


@needs_numba
def test_rotation_errors_kernel_matches_numpy():
    from kinlib.spatial.rotations import _rotation_errors_numpy, rotation_errors

    rng = np.random.default_rng(5)
    M = _rotations(_accel.MIN_BATCH + 11, 4) + rng.normal(scale=1e-3, size=(1, 3, 3))
    M[7] = np.diag([1.0, 1.0, -1.0])
    err, det = rotation_errors(M)
    err0, det0 = _rotation_errors_numpy(M)
    assert np.abs(err - err0).max() < 1e-15 * 4
    assert np.abs(det - det0).max() < 1e-15 * 8
    assert det[7] == pytest.approx(-1.0)
    with pytest.raises(kl.KinlibError, match=r"R\[0\].*not orthonormal"):
        kl.check_rotation(M)
