"""The compiled kernels are prepared in the background (kinlib/_background.py): a first
call never waits for numba, it takes the numpy path and gives the same answer; later calls
use the kernels (the numpy and compiled paths agree: tests/test_ik.py, test_jacobian.py,
test_robot.py). Checked in fresh processes with an empty numba cache (a student's very
first run), against the numpy path: a first call answers before its kernel is ready, and
the answer is the one the compiled kernel gives once it is; a big batch waits for its
kernel instead; a script that ends while a kernel compiles waits for it, so the next
process loads it from the cache; a child forked while a kernel compiles uses numpy and
does not hang; a preparation that fails is warned once and leaves the numpy path."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import kinlib
from kinlib import _background
from kinlib.kinematics import _fk

needs_numba = pytest.mark.skipif(_fk._compiled() is None, reason="numba is not installed")

FIRST = """
import json, os, sys
import numpy as np
import kinlib
from kinlib._background import peek
from kinlib.kinematics import _fk
from kinlib.robots import puma560

robot = puma560()
report = {}
Q = np.random.default_rng(0).uniform(-1, 1, (_fk.WAIT_MIN, 6))
report["big batch before"] = peek("_fk_numba.chain") is not None
T_big = robot.fk(Q)  # a batch this big waits for its kernel
report["big batch after"] = peek("_fk_numba.chain") is not None
report["big batch right"] = bool(np.allclose(T_big[:50], _fk._chain_numpy(
    robot.chain_table(None), Q[:50]), atol=1e-13))
q = Q[1]
report["jacobian before"] = peek("_fk_numba.chain_jacobian") is not None
J_first = robot.jacobian(q)  # starts the Jacobian's compile: numpy meanwhile
pid = os.fork()
if pid == 0:  # the child: the compile it was forked during is not its own
    J_child = robot.jacobian(q)
    ready = kinlib.prepare_kernels(["jacobian"])
    os._exit(0 if np.allclose(J_child, J_first, atol=1e-13) and ready == {"jacobian": False}
             else 3)
report["child status"] = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
report["J"] = J_first.tolist()
print(json.dumps(report))
"""  # the parent ends here, while the Jacobian compiles

NEXT = """
import json, threading
import numpy as np
import kinlib
from kinlib._background import peek
from kinlib.kinematics import _fk
from kinlib.robots import puma560

robot = puma560()
q = np.random.default_rng(0).uniform(-1, 1, (2, 6))[1]
report = {"ready before": peek("_fk_numba.chain_jacobian") is not None}
J = robot.jacobian(q)  # the first call: numpy (while the kernel loads)
report["threads"] = [t.name for t in threading.enumerate() if t.name == "kinlib-kernels"]
report["prepared"] = kinlib.prepare_kernels(["jacobian"])
stats = _fk._compiled().chain_jacobian.stats
report["jacobian cache"] = [sum(stats.cache_hits.values()), sum(stats.cache_misses.values())]
report["same J"] = bool(np.allclose(J, robot.jacobian(q), atol=1e-13))  # compiled
print(json.dumps(report))
"""


def _run(code: str, cache, **env) -> dict:
    environ = {k: v for k, v in os.environ.items() if k != "KINLIB_NUMBA"}
    environ.update(NUMBA_CACHE_DIR=str(cache), **env)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=environ, timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "Warning" not in out.stderr, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@needs_numba
def test_first_calls_take_the_numpy_path_and_the_kernels_follow(tmp_path):
    cache = tmp_path / "numba-cache"
    cache.mkdir()
    first = _run(FIRST, cache)
    assert first["big batch before"] is False and first["big batch after"] is True
    assert first["big batch right"]
    assert first["jacobian before"] is False
    assert first["child status"] == 0  # numpy in the child, no hang, nothing prepared
    # the first process ended while the Jacobian compiled: it waited, and cached it
    assert [p.name for p in cache.rglob("*chain_jacobian*.nbi")], list(cache.rglob("*"))

    nxt = _run(NEXT, cache)
    assert nxt["ready before"] is False
    assert nxt["threads"] == ["kinlib-kernels"]  # the first call started the preparation
    assert nxt["prepared"] == {"jacobian": True}
    hits, misses = nxt["jacobian cache"]
    assert hits >= 1 and misses == 0, nxt  # loaded from what the first process left
    assert nxt["same J"]
    robot = kinlib.robots.puma560()
    np.testing.assert_allclose(first["J"], robot.jacobian(
        np.random.default_rng(0).uniform(-1, 1, (2, 6))[1], ), atol=1e-13)


def test_disabled_kernels_start_nothing(tmp_path):
    code = ("import json, sys, threading, numpy as np, kinlib\n"
            "from kinlib.robots import puma560\n"
            "r = puma560(); r.fk(np.zeros((5, 6))); r.ik(r.fk(np.full(6, 0.2)))\n"
            "kinlib.matrix_from_quat(np.tile([1.0, 0, 0, 0], (5000, 1)))\n"
            "print(json.dumps([kinlib.prepare_kernels(), 'numba' in sys.modules,\n"
            "    [t.name for t in threading.enumerate() if t.name == 'kinlib-kernels']]))")
    ready, numba_loaded, threads = _run(code, tmp_path, KINLIB_NUMBA="0")
    assert ready == dict.fromkeys(kinlib.kinematics.kernels.KERNELS, False)
    assert not numba_loaded and threads == []


def test_a_preparation_that_fails_is_warned_once_and_numpy_stays():
    def broken():
        raise TypeError("no kernels here")

    key = f"test.broken.{os.getpid()}"
    assert _background.ready(key, broken) is None  # started, not waited for
    with pytest.warns(RuntimeWarning, match="could not be prepared.*TypeError: no kernels"):
        assert _background.ready(key, broken, wait=True) is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _background.ready(key, broken) is None  # once only
        assert _background.peek(key) is None


def test_a_ready_kernel_is_handed_out_and_nothing_is_prepared_twice():
    calls = []

    def prepare():
        calls.append(1)
        return np.cos

    key = f"test.cos.{os.getpid()}"
    assert _background.peek(key) is None
    assert _background.ready(key, prepare, wait=True) is np.cos
    assert _background.ready(key, prepare) is np.cos and _background.peek(key) is np.cos
    assert calls == [1]


def test_prepare_kernels_names_what_it_knows():
    for bad in (["fk", "nope"], "fk", 5, [None], [["fk"]]):
        with pytest.raises(kinlib.KinlibError, match=r"expected a list of names from \['fk'.*"
                                                     r"got " + repr(bad).replace("[", r"\[")):
            kinlib.prepare_kernels(bad)
