"""The grader's throughput with the sandbox, and what the sandbox itself costs.

In one run, on this machine:

1. a student process started and answering its first request, in the bubblewrap sandbox
   and as a plain child process (best of ``--repeat``, interleaved): the sandbox's own
   overhead per process (a normal submission uses one);
2. each assignment's solution graded in this process, sandboxed and unsandboxed,
   interleaved (best of ``--repeat``): seconds per submission and the difference;
3. a batch of ``--batch`` submissions of assignment 02 (the solution and the student
   edition, alternating) graded by the command line with ``--jobs`` workers, as an
   instructor runs it, sandboxed then unsandboxed: wall-clock seconds per submission.

Run: ``.venv/bin/python bench/bench_grader.py`` (about two minutes). Figures are of one
run; compare the sandboxed and unsandboxed columns of the same run, never times across runs.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from timing import best_time

from kinlib.grade import assignment_names, grade
from kinlib.grade._bwrap import find_sandbox
from kinlib.grade._sandbox import BLOCKED, Worker

ROOT = Path(__file__).resolve().parents[1]


def start_and_answer(sandbox) -> None:
    with Worker(sandbox=sandbox) as w:
        w.request({"op": "cells", "cells": [[0, "x = 1"]]})
        while w.receive(60)["ev"] != "cells_done":
            pass


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--batch", type=int, default=100)
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    t0 = time.perf_counter()
    sandbox = find_sandbox(BLOCKED)
    print(f"sandbox: {sandbox.describe()} ({sandbox.bwrap}); first use (build and trial "
          f"run) {time.perf_counter() - t0:.2f} s")

    # 1. one process
    boxed = plain = float("inf")
    for _ in range(args.repeat * 4):
        boxed = min(boxed, best_time(lambda: start_and_answer(sandbox), 1))
        plain = min(plain, best_time(lambda: start_and_answer(None), 1))
    print(f"\nstart a student process and get its first answer (best of {args.repeat * 4})")
    print(f"  sandboxed {boxed * 1e3:7.1f} ms   unsandboxed {plain * 1e3:7.1f} ms   "
          f"sandbox overhead {(boxed - plain) * 1e3:+.1f} ms per process")

    # 2. each assignment's solution
    print(f"\none submission (the solution), graded in this process (best of {args.repeat})")
    print(f"  {'assignment':<24} {'sandboxed':>10} {'unsandboxed':>12} {'overhead':>9}")
    for name in assignment_names():
        nb = ROOT / "assignments" / "source" / f"{name}.ipynb"
        assert grade(nb)["score"] == grade(nb, unsandboxed=True)["score"] > 0
        s = u = float("inf")
        for _ in range(args.repeat):
            s = min(s, best_time(lambda nb=nb: grade(nb), 1))
            u = min(u, best_time(lambda nb=nb: grade(nb, unsandboxed=True), 1))
        print(f"  {name:<24} {s:9.2f}s {u:11.2f}s {s - u:+8.2f}s")

    # 3. a batch by the command line
    with tempfile.TemporaryDirectory() as tmp:
        subs = []
        for k in range(args.batch):
            edition = ("source", "release")[k % 2]
            path = Path(tmp) / f"02_forward_kinematics_{k:03d}.ipynb"
            shutil.copy(ROOT / "assignments" / edition / "02_forward_kinematics.ipynb", path)
            subs.append(str(path))
        print(f"\n{args.batch} submissions of 02_forward_kinematics (solution and student "
              f"edition alternating), python -m kinlib.grade -j {args.jobs}")
        for flag in ([], ["--unsandboxed"]):
            t = time.perf_counter()
            out = subprocess.run([sys.executable, "-m", "kinlib.grade", "--no-write", "-j",
                                  str(args.jobs), *flag, *subs], capture_output=True, text=True)
            wall = time.perf_counter() - t
            assert out.returncode == 0, out.stderr
            assert f"graded {args.batch} of {args.batch}" in out.stdout
            label = "unsandboxed" if flag else "sandboxed"
            print(f"  {label:<12} {wall:7.1f} s in all, {wall / args.batch:.3f} s per "
                  f"submission ({args.batch / wall * 60:.0f} per minute)")


if __name__ == "__main__":
    main()
