"""Input checks shared by kinlib's functions (private).

Every public function turns its inputs into clean float64 arrays here, so that bad input
is reported as a :class:`KinlibError` that says what was expected, what was given and
where, instead of failing deep inside numpy.
"""

from __future__ import annotations

import sys

import numpy as np

from .errors import KinlibError

__all__ = [
    "as_array",
    "as_limits",
    "as_tol",
    "as_unit_vectors",
    "unit_rows",
    "broadcast",
    "fmt_index",
    "is_symbolic",
    "parse_seq",
    "py_scalar",
    "wrap_angle",
]


def _shape_text(tail: tuple[int, ...]) -> str:
    if not tail:
        return "scalars (any shape)"
    return "shape (..., " + ", ".join(str(n) for n in tail) + ")"


def fmt_index(batch_shape: tuple[int, ...], mask: np.ndarray) -> str:
    """Describe where ``mask`` is true in a batch: ``""`` for a single item, else ``"[i, j]"``.

    Adds how many others are affected, e.g. ``"[3] (and 4 more of 100)"``.
    """
    if not batch_shape:
        return ""
    bad = np.argwhere(mask)
    first = "[" + ", ".join(str(int(i)) for i in bad[0]) + "]"
    more = len(bad) - 1
    total = int(np.prod(batch_shape))
    return first + (f" (and {more} more of {total})" if more else "")


def as_array(x, name: str, tail: tuple[int, ...] = (), *, finite: bool = True) -> np.ndarray:
    """``x`` as a float64 array whose shape ends in ``tail``, checked for NaN/inf."""
    if isinstance(x, str | bytes) or x is None:
        raise KinlibError(f"{name}: expected numbers of {_shape_text(tail)}, got {x!r}")
    try:
        raw = np.asarray(x)
    except (TypeError, ValueError, OverflowError) as exc:  # ragged nesting, ...
        raise KinlibError(
            f"{name}: expected real numbers of {_shape_text(tail)}, got "
            f"{type(x).__name__} that numpy cannot read as float ({exc})"
        ) from None
    # numpy would parse text ("1.5") and drop imaginary parts with only a warning
    kind = raw.dtype.kind
    if kind in "USVMmc" or (
        kind == "O" and any(isinstance(e, str | bytes | complex) for e in raw.flat)
    ):
        what = "complex numbers" if kind == "c" else f"data of dtype {raw.dtype}"
        raise KinlibError(
            f"{name}: expected real numbers of {_shape_text(tail)}, got {what}: {_short(x)}"
        )
    try:
        a = np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError, OverflowError) as exc:
        raise KinlibError(
            f"{name}: expected real numbers of {_shape_text(tail)}, got "
            f"{type(x).__name__} that numpy cannot read as float ({exc})"
        ) from None
    n = len(tail)
    if a.ndim < n or a.shape[a.ndim - n :] != tail:
        raise KinlibError(f"{name}: expected {_shape_text(tail)}, got shape {a.shape}")
    if finite and a.size and not np.isfinite(a).all():
        bad = ~np.isfinite(a)
        if n:
            bad = bad.reshape(a.shape[: a.ndim - n] + (-1,)).any(axis=-1)
        where = fmt_index(a.shape[: a.ndim - n], bad)
        raise KinlibError(f"{name}{where}: contains NaN or infinity: {_preview(x)}")
    return a


def _short(x) -> str:
    text = repr(x).replace("\n", " ")
    return text if len(text) <= 80 else text[:77] + "..."


def _preview(x) -> str:
    text = np.array2string(np.asarray(x, dtype=float), threshold=12, precision=4)
    return text.replace("\n", " ")


def as_tol(tol, name: str = "tol") -> float:
    """A tolerance: one finite number >= 0."""
    a = as_array(tol, name)
    if a.ndim or a < 0:
        raise KinlibError(f"{name}: expected one number >= 0, got {_short(tol)}")
    return float(a)


def py_scalar(x):
    """A result for one input as a Python scalar; a batch (an ndarray with ndim >= 1) unchanged.

    ``np.True_``, ``np.float64(0.5)`` and 0-d arrays become ``True``, ``0.5`` (Python
    ``bool`` / ``float`` / ``int``, whatever ``.item()`` gives); everything else is returned
    as it is. The one rule for kinlib's predicates and scalar-valued functions: a Python
    scalar for one input, an ndarray for a batch.

    >>> py_scalar(np.asarray(True)), py_scalar(np.float64(0.5)), py_scalar(np.zeros(2))
    (True, 0.5, array([0., 0.]))
    """
    if isinstance(x, np.generic) or (isinstance(x, np.ndarray) and x.ndim == 0):
        return x.item()
    return x


def wrap_angle(x):
    """Angles (radians) wrapped into (−π, π]: −π becomes π; ``-0.0`` becomes ``0.0``.

    Angles already in (−π, π] come back bit for bit (no ``(x + π) % 2π − π`` rounding);
    the others are shifted by a multiple of 2π. Returns an ndarray (0-d for one angle).

    >>> wrap_angle([-np.pi, 0.5, 4.0]).round(6)
    array([ 3.141593,  0.5     , -2.283185])
    """
    a = np.asarray(x, dtype=np.float64)
    out = np.where((a > np.pi) | (a <= -np.pi), np.pi - np.mod(np.pi - a, 2.0 * np.pi), a)
    # np.mod may round up to exactly 2π (a just above π), which would give −π
    return np.where(out <= -np.pi, out + 2.0 * np.pi, out) + 0.0


def as_limits(limits, where: str) -> tuple[float, float]:
    """Joint limits ``(lower, upper)`` with ``lower <= upper`` (±inf allowed, NaN not)."""
    lim = as_array(limits, f"{where} limits", finite=False)
    if lim.shape != (2,) or np.isnan(lim).any() or lim[0] > lim[1]:
        raise KinlibError(
            f"{where}: limits must be (lower, upper) with lower <= upper, got {limits!r}"
        )
    return float(lim[0]), float(lim[1])


def unit_rows(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(a / |a|, |a|)`` along the last axis, without overflow or underflow.

    Each row is first scaled by its largest entry, so the squares of huge (1e200) or tiny
    entries stay representable. Zero rows give NaN directions; callers reject them first.
    """
    big = np.abs(a).max(axis=-1, initial=0.0)
    scale = np.where(big > 0, big, 1.0)[..., None]
    u = a / scale
    n = np.sqrt(np.einsum("...i,...i->...", u, u))
    with np.errstate(invalid="ignore", divide="ignore"):
        return u / n[..., None], n * scale[..., 0]


def as_unit_vectors(x, name: str = "axis", *, eps: float = 1e-12) -> np.ndarray:
    """``x`` as unit 3-vectors (normalised); a zero (or near-zero) vector is an error."""
    a = as_array(x, name, (3,))
    if a.ndim == 1:  # one vector (a joint axis): the same scaling, without batch overhead
        x0, x1, x2 = a.tolist()
        big = max(abs(x0), abs(x1), abs(x2))
        if big > 0:
            u0, u1, u2 = x0 / big, x1 / big, x2 / big
            n = (u0 * u0 + u1 * u1 + u2 * u2) ** 0.5
            if n * big > eps:
                return np.array([u0 / n, u1 / n, u2 / n])
    u, norm = unit_rows(a)
    small = norm <= eps
    if np.any(small):
        where = fmt_index(a.shape[:-1], small)
        raise KinlibError(
            f"{name}{where}: expected a non-zero 3-vector (it is normalised), got "
            f"{_preview(a[small][0])} with norm {norm[small].flat[0]:.3g}"
        )
    return u


def broadcast(*arrays_with_tails: tuple[np.ndarray, int, str]) -> tuple[int, ...]:
    """The common batch shape of arrays whose last ``tail`` dimensions are not batch dims."""
    shapes = [a.shape[: a.ndim - t] for a, t, _ in arrays_with_tails]
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        described = ", ".join(
            f"{name} batch {s}" for (_, _, name), s in zip(arrays_with_tails, shapes, strict=True)
        )
        raise KinlibError(f"batch shapes do not broadcast: {described}") from None


def _sympy_basic(x) -> bool:
    """A sympy object whose class lives in no sympy module (e.g. an applied undefined
    function ``Function("theta")(t)``, whose class is made on the fly)."""
    # getattr: another thread may be importing sympy right now (half made in sys.modules);
    # then x cannot be a sympy object yet (making one waits for the import to finish)
    basic = getattr(sys.modules.get("sympy"), "Basic", None)
    return basic is not None and isinstance(x, basic)


def _is_sym(x) -> bool:
    if (type(x).__module__ or "").startswith("sympy") or _sympy_basic(x):
        return True
    if isinstance(x, list | tuple):
        return any(_is_sym(e) for e in x)
    if isinstance(x, np.ndarray) and x.dtype == object:
        return any(_is_sym(e) for e in x.flat)
    return False


def is_symbolic(*xs) -> bool:
    """True when any argument is (or contains) a sympy object: then sympy is used."""
    return any(_is_sym(x) for x in xs)


_AXES = "xyz"


def parse_seq(seq) -> tuple[tuple[int, int, int], bool]:
    """Parse an Euler/fixed-angle sequence: ``(axis indices, intrinsic?)``.

    UPPERCASE = intrinsic (moving axes), lowercase = extrinsic (fixed axes).
    """
    if not isinstance(seq, str) or len(seq) != 3:
        raise KinlibError(
            f"seq: expected three axis letters such as 'ZYX' (intrinsic) or 'xyz' "
            f"(extrinsic), got {seq!r}"
        )
    low = seq.lower()
    if any(c not in _AXES for c in low):  # before the case check: '123' mixes no cases
        raise KinlibError(f"seq: {seq!r} has letters other than x, y, z")
    if seq.isupper():
        intrinsic = True
    elif seq.islower():
        intrinsic = False
    else:
        raise KinlibError(
            f"seq: {seq!r} mixes cases; use UPPERCASE for intrinsic (rotating axes) or "
            f"lowercase for extrinsic (fixed axes), e.g. 'ZYX' or 'xyz'"
        )
    if low[0] == low[1] or low[1] == low[2]:
        raise KinlibError(
            f"seq: {seq!r} turns about the same axis twice in a row, which is one rotation, "
            f"not two; consecutive axes must differ (e.g. 'ZYZ' or 'ZYX')"
        )
    return tuple(_AXES.index(c) for c in low), intrinsic
