"""The compiled kernels: each compiled once (one kernel, one signature, whatever the batch
size: large batches run the same kernel in threads), and cached on disk also where the
package's own folder is read-only (an installation a student cannot write to): numba then
keeps its cache in the user's cache folder, and the next process loads it."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kinlib
from kinlib.kinematics import _fk, ik
from kinlib.robots import panda, puma560

kernels = _fk._compiled()
pytestmark = pytest.mark.skipif(kernels is None, reason="numba is not installed")
PACKAGE = Path(kinlib.__file__).resolve().parent


def test_every_kernel_is_compiled_once_for_every_batch_size():
    for robot in (puma560(), panda()):
        rng = np.random.default_rng(0)
        for n in (1, 7, _fk.PARALLEL_MIN + 3):
            q = rng.uniform(-1, 1, (n, robot.dof))
            T, J = robot.fk(q), robot.jacobian(q)
            assert T.shape == (n, 4, 4) and J.shape == (n, 6, robot.dof)
        targets = robot.fk(rng.uniform(-1, 1, (9, robot.dof)))  # 9: in threads
        assert robot.ik(targets).success.mean() > 0.5 and robot.ik(targets[1]).success
        frozen = np.broadcast_to(q[0], (3, robot.dof))  # read-only: numba types it apart
        robot.fk(frozen), robot.jacobian(frozen), robot.link_poses(frozen)
        assert robot.ik(np.broadcast_to(targets[1], (2, 4, 4))).success.all()
    for kernel in (kernels.chain, kernels.chain_jacobian, kernels.tree,
                   ik._compiled_ik().ik_lm):
        assert len(kernel.signatures) == 1, (kernel, kernel.signatures)
    assert not [n for n in dir(kernels) if n.endswith("parallel")]


def test_threads_give_the_one_thread_answer(monkeypatch):
    robot = puma560()
    q = np.random.default_rng(1).uniform(-2, 2, (_fk.PARALLEL_MIN * 2 + 1, 6))
    T, J = robot.fk(q), robot.jacobian(q)
    targets = robot.fk(q[:20] * 0.4)
    sol = robot.ik(targets)  # before the monkeypatch: 20 targets in threads
    monkeypatch.setattr(_fk, "THREADS", 1)
    np.testing.assert_array_equal(robot.fk(q), T)
    np.testing.assert_array_equal(robot.jacobian(q), J)
    one = robot.ik(targets)
    np.testing.assert_array_equal(one.q, sol.q)
    np.testing.assert_array_equal(one.iterations, sol.iterations)
    assert sol.success.all()


SCRIPT = """
import json, sys
import numpy as np
import kinlib
from kinlib.kinematics import _fk
from kinlib.robots import puma560
T = puma560().fk(np.full(6, 0.3))
kinlib.prepare_kernels(["fk"])
print(json.dumps({"file": _fk.__file__, "T": T.tolist(),
                  "hits": sum(_fk._compiled().chain.stats.cache_hits.values()),
                  "misses": sum(_fk._compiled().chain.stats.cache_misses.values())}))
"""


def test_the_cache_works_where_the_package_folder_is_read_only(tmp_path):
    from kinlib.grade._bwrap import _bwrap_path

    bwrap = _bwrap_path()
    if bwrap is None:
        pytest.skip("needs bubblewrap for a read-only package folder")
    pkg, home = tmp_path / "pkg", tmp_path / "home"
    shutil.copytree(PACKAGE, pkg / "kinlib", ignore=shutil.ignore_patterns("__pycache__"))
    home.mkdir()
    cmd = [bwrap, "--ro-bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
           "--bind", str(home), str(home), "--setenv", "HOME", str(home),
           "--setenv", "PYTHONPATH", str(pkg), "--unsetenv", "NUMBA_CACHE_DIR",
           "--unshare-pid", "--die-with-parent", sys.executable, "-c", SCRIPT]
    runs = []
    for _ in range(2):
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=300, cwd=home)
        assert out.returncode == 0, out.stderr[-3000:]
        runs.append(json.loads(out.stdout.strip().splitlines()[-1]))
    first, second = runs
    assert first["file"].startswith(str(pkg)), first["file"]  # the read-only copy
    assert not list(pkg.rglob("*.nbi")), "numba wrote into the read-only package"
    assert first["misses"] >= 1 and list(home.rglob("*.nbi")), "nothing cached"
    assert second["hits"] >= 1 and second["misses"] == 0, second
    np.testing.assert_allclose(first["T"], puma560().fk(np.full(6, 0.3)), atol=0)
