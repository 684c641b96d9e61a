"""A student's first calls: fk, jacobian, ik, batched fk and batched ik in a fresh process.

Run with ``make bench`` (or ``python bench/bench_first_call.py [--runs R]``).

Each run starts a new Python process that imports kinlib, builds the PUMA 560 and times,
one after another: ``fk(q)``, ``jacobian(q)``, ``ik(T)``, ``fk`` of 5,000 configurations
and ``ik`` of 10 targets. First with an empty numba cache (``NUMBA_CACHE_DIR`` a new empty
folder: a student's very first run, every kernel compiled), then again with the cache that
run filled (every later session). Goals: the sum at most 6 s with the empty cache, 2 s
with the cache filled. The first calls do not wait for numba: they take the numpy path
while the kernels are prepared in the background (``kinlib._background``); the script
also prints when the kernels of fk, jacobian and ik were ready (seconds after the first
call began), how many of the five calls found theirs ready, and the same calls once they
are. ``--compiled`` first makes each call wait for its kernel (``compiled=True``, what
every first call did before the background preparation): the cost of the compile itself.
With ``--numpy`` the same calls run on the numpy path (``KINLIB_NUMBA=0``) for comparison.

The machine is noisy: the runs are printed one by one, with their spread.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

FIRST_CALLS = r"""
import json, sys, time
import numpy as np
t0 = time.perf_counter()
import kinlib
from kinlib.robots import puma560
robot = puma560()
times = {"import": time.perf_counter() - t0}
q = np.array([0.3, -0.6, 1.2, 0.2, 0.5, -0.4])
rng = np.random.default_rng(0)
Q = rng.uniform(-1, 1, (5000, 6))
# the target from the numpy path: the timed calls below are the first ones
from kinlib.kinematics import _fk, ik
from kinlib._background import peek
T = _fk._chain_numpy(robot.chain_table(None), (q + 0.1)[None])[0]
T10 = _fk._chain_numpy(robot.chain_table(None), Q[:10])
wait = sys.argv[1] == "compiled" or None
calls = [("fk", lambda: _fk.run_chain(robot.chain_table(None), q[None], compiled=wait),
          "_fk_numba.chain"),
         ("jacobian", lambda: _fk.run_chain_jacobian(robot.chain_table(None), q[None],
                                                     compiled=wait), "_fk_numba.chain_jacobian"),
         ("ik", lambda: ik.solve_ik(robot, T, compiled=wait), "_ik_numba.ik_lm"),
         ("batched fk", lambda: _fk.run_chain(robot.chain_table(None), Q, compiled=wait),
          "_fk_numba.chain"),
         ("batched ik", lambda: ik.solve_ik(robot, T10, q0=Q[:10] + 0.05, compiled=wait),
          "_ik_numba.ik_lm")]
start, times["ready at call"] = time.perf_counter(), 0
for name, call, key in calls:
    times["ready at call"] += peek(key) is not None
    t = time.perf_counter()
    call()
    times[name] = time.perf_counter() - t
kinlib.prepare_kernels(["fk", "jacobian", "ik"])
times["ready after"] = time.perf_counter() - start
for name, call, key in calls:
    t = time.perf_counter()
    call()
    times[name + " again"] = time.perf_counter() - t
json.dump(times, sys.stdout)
"""

CALLS = ("fk", "jacobian", "ik", "batched fk", "batched ik")


def first_calls(cache: str, numpy: bool = False, compiled: bool = False) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    env.pop("KINLIB_NUMBA", None)
    if numpy:
        env["KINLIB_NUMBA"] = "0"
    out = subprocess.run([sys.executable, "-c", FIRST_CALLS,
                          "compiled" if compiled else "ready"],
                         env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def show(label: str, t: dict) -> float:
    total = sum(t[c] for c in CALLS)
    parts = ", ".join(f"{c} {t[c]:.2f}" for c in CALLS)
    print(f"  {label:<13} {total:6.2f} s   ({parts}; import {t['import']:.2f} s, not counted)")
    again = sum(t[c + " again"] for c in CALLS)
    print(f"  {'':<13} kernels ready {t['ready after']:.2f} s after the first call began "
          f"(ready at {t['ready at call']} of the 5 calls); the 5 calls again: {again:.3f} s")
    return total


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--numpy", action="store_true", help="also time the numpy path")
    ap.add_argument("--compiled", action="store_true",
                    help="also time first calls that wait for their kernels")
    args = ap.parse_args(argv)
    cold, warm = [], []
    print("PUMA 560, first fk + jacobian + ik + batched fk (5,000) + batched ik (10), "
          "fresh process each")
    for _ in range(args.runs):
        with tempfile.TemporaryDirectory(prefix="kinlib-numba-") as cache:
            cold.append(show("empty cache", first_calls(cache)))
            warm.append(show("cache filled", first_calls(cache)))
    if args.compiled:
        with tempfile.TemporaryDirectory(prefix="kinlib-numba-") as cache:
            show("waiting, empty", first_calls(cache, compiled=True))
            show("waiting, filled", first_calls(cache, compiled=True))
    if args.numpy:
        with tempfile.TemporaryDirectory(prefix="kinlib-numba-") as cache:
            show("numpy path", first_calls(cache, numpy=True))
    print(f"empty cache: {min(cold):.2f}-{max(cold):.2f} s (goal <= 6 s); cache filled: "
          f"{min(warm):.2f}-{max(warm):.2f} s (goal <= 2 s)")


if __name__ == "__main__":
    main()
