"""Distances between points and segments in the plane, vectorised (private to
:mod:`kinlib.planning.cspace`).

>>> p, a, b = np.array([[0.0, 1.0], [-1.0, 0.0], [1.0, 0.0]])
>>> float(point_segment_distance(p, a, b))
1.0
>>> float(segment_segment_distance(*np.array([[0, 0], [2, 2], [0, 2], [2, 0]], dtype=float)))
0.0
"""

from __future__ import annotations

import numpy as np

__all__ = ["point_segment_distance", "segment_segment_distance"]


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def point_segment_distance(p, a, b):
    """Distance from points ``p`` to segments ``a→b`` (broadcasting over leading axes)."""
    ab, ap = b - a, p - a
    den = _dot(ab, ab)
    t = np.clip(_dot(ap, ab) / np.where(den > 0, den, 1.0), 0.0, 1.0)
    d = ap - t[..., None] * ab
    return np.hypot(d[..., 0], d[..., 1])


def _orient(o, a, b):
    """z-component of ``(a − o) × (b − o)``: > 0 when o, a, b turn counter-clockwise."""
    return (a[..., 0] - o[..., 0]) * (b[..., 1] - o[..., 1]) - (a[..., 1] - o[..., 1]) * (
        b[..., 0] - o[..., 0]
    )


def segment_segment_distance(a, b, c, d):
    """Distance between segments ``a→b`` and ``c→d``: 0 when they cross or touch.

    Segments that do not cross properly are at the smallest of the four endpoint-to-segment
    distances (which is 0 when they merely touch or overlap).
    """
    d1, d2 = _orient(c, d, a), _orient(c, d, b)
    d3, d4 = _orient(a, b, c), _orient(a, b, d)
    crossing = (d1 * d2 < 0) & (d3 * d4 < 0)
    near = np.minimum(
        np.minimum(point_segment_distance(a, c, d), point_segment_distance(b, c, d)),
        np.minimum(point_segment_distance(c, a, b), point_segment_distance(d, a, b)),
    )
    return np.where(crossing, 0.0, near)
