"""kinlib vs scipy.spatial.transform.Rotation on batches of 100,000 rotations.

Run with ``make bench`` (or ``python bench/bench_conversions.py [--n N] [--repeat R]``).
Both libraries are timed in the same run, interleaved, best of R repeats each, on the
same inputs; the table reports the kinlib/scipy time ratio (below 1.0: kinlib is faster).
scipy is timed on its default path, which validates its input (``from_matrix``
orthonormalises, ``from_quat`` normalises); kinlib validates too (rotation check,
finiteness), so the comparison is like for like. Absolute times are printed for
context only: this machine is noisy, compare ratios, never times from different runs.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from scipy.spatial.transform import Rotation
from timing import best_time  # bench/timing.py (the script's folder is on sys.path)

import kinlib as kl


def cases(n: int, seed: int = 0):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    q_xyzw = kl.quat_xyzw_from_wxyz(q)
    R = kl.matrix_from_quat(q)
    zyx = rng.uniform(-np.pi, np.pi, size=(n, 3))
    zyx[:, 1] /= 2.0
    return [
        (
            "matrix -> quaternion",
            lambda: kl.quat_from_matrix(R),
            lambda: Rotation.from_matrix(R).as_quat(),
        ),
        (
            "quaternion -> matrix",
            lambda: kl.matrix_from_quat(q),
            lambda: Rotation.from_quat(q_xyzw).as_matrix(),
        ),
        (
            "matrix -> ZYX",
            lambda: kl.euler_from_matrix(R, "ZYX"),
            lambda: Rotation.from_matrix(R).as_euler("ZYX"),
        ),
        (
            "ZYX -> matrix",
            lambda: kl.matrix_from_euler(zyx, "ZYX"),
            lambda: Rotation.from_euler("ZYX", zyx).as_matrix(),
        ),
    ]


def check_agreement(n: int = 1000) -> None:
    """The benchmarked pairs compute the same thing (up to q ↔ −q)."""
    rng = np.random.default_rng(1)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    R = kl.matrix_from_quat(q)
    assert np.allclose(R, Rotation.from_quat(kl.quat_xyzw_from_wxyz(q)).as_matrix(), atol=1e-12)
    qk = kl.quat_from_matrix(R)
    qs = kl.quat_wxyz_from_xyzw(Rotation.from_matrix(R).as_quat())
    assert np.allclose(np.abs(np.sum(qk * qs, axis=1)), 1.0, atol=1e-12)
    ek = kl.euler_from_matrix(R, "ZYX")
    es = Rotation.from_matrix(R).as_euler("ZYX")
    assert np.allclose(kl.matrix_from_euler(ek, "ZYX"), kl.matrix_from_euler(es, "ZYX"), atol=1e-12)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100_000, help="batch size (default 100000)")
    ap.add_argument("--repeat", type=int, default=15, help="repeats, best taken (default 15)")
    args = ap.parse_args(argv)
    kl.prepare_kernels()  # compiled kernels from the first timed call (bench_first_call)
    check_agreement()
    import scipy

    print(f"kinlib {kl.__version__} vs scipy {scipy.__version__} Rotation, numpy {np.__version__}")
    print(f"batch of {args.n:,}, best of {args.repeat} interleaved runs\n")
    print(f"{'conversion':<22}{'kinlib ms':>11}{'scipy ms':>11}{'ratio':>8}")
    worst = 0.0
    for name, ours, theirs in cases(args.n):
        ours(), theirs()  # warm up
        tk = ts = np.inf
        for _ in range(args.repeat):
            tk = min(tk, best_time(ours, 1))
            ts = min(ts, best_time(theirs, 1))
        ratio = tk / ts
        worst = max(worst, ratio)
        print(f"{name:<22}{tk * 1e3:>11.2f}{ts * 1e3:>11.2f}{ratio:>8.2f}")
    print(f"\nworst kinlib/scipy ratio: {worst:.2f} (target <= 1.0)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
