"""Planar obstacles as 3-D solids (kinlib.viz.obstacles), checked by geometry: areas by
the shoelace formula, the prism's volume by the divergence theorem over its own faces
(which also proves every face points outwards), the cylinder's axis and centre."""

import numpy as np
import pytest
import umsgpack

from kinlib import Circle, KinlibError, Polygon
from kinlib.viz import Scene, draw_obstacles
from kinlib.viz.obstacles import prism, triangulate


def shoelace(v):
    v = np.asarray(v, float)
    w = np.roll(v, -1, axis=0)
    return 0.5 * float(np.sum(v[:, 0] * w[:, 1] - w[:, 0] * v[:, 1]))


def star(seed, n=9):
    rng = np.random.default_rng(seed)
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    radii = rng.uniform(0.3, 1.0, n)  # star-shaped about 0: simple, often non-convex
    return np.c_[radii * np.cos(angles), radii * np.sin(angles)]


@pytest.mark.parametrize("seed", range(20))
@pytest.mark.parametrize("flip", [False, True])
def test_triangles_cover_the_polygon(seed, flip):
    v = star(seed)[::-1] if flip else star(seed)  # either winding
    tri = triangulate(v)
    assert tri.shape == (len(v) - 2, 3)
    areas = [shoelace(v[t]) for t in tri]
    assert min(areas) > 0  # counter-clockwise, none flat
    assert sum(areas) == pytest.approx(abs(shoelace(v)), rel=1e-12)


@pytest.mark.parametrize("seed", range(10))
def test_prism_is_closed_and_outward(seed):
    v, h = star(seed), 0.3
    geom = prism(v, h)
    P, F = np.asarray(geom.vertices), np.asarray(geom.faces)
    a, b, c = P[F[:, 0]], P[F[:, 1]], P[F[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0  # > 0: faces outwards
    assert volume == pytest.approx(abs(shoelace(v)) * h, rel=1e-6)  # meshcat: float32
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 2).all()  # every edge shared by two faces: closed


def test_draw_obstacles_in_a_scene():
    scene = Scene()
    try:
        obs = [Circle((0.4, 1.45), 0.2), Polygon([(-1.7, -0.5), (-1.2, -0.5), (-1.2, 0.2)])]
        draw_obstacles(scene, obs, ["tab:red", "#00ff00"], height=0.2)
        cmds = [umsgpack.unpackb(c) for c in scene._commands]
        objects = {c["path"]: c["object"] for c in cmds if c["type"] == "set_object"}
        disc = objects["/meshcat/obstacles/0"]
        assert disc["geometries"][0]["type"] == "CylinderGeometry"
        assert disc["geometries"][0]["radiusTop"] == 0.2 and disc["geometries"][0]["height"] == 0.2
        assert disc["materials"][0]["color"] == 0xD62728  # matplotlib's tab:red
        k = scene._pose_paths.index("/meshcat/obstacles/0")
        T = np.frombuffer(scene._poses, np.float32).reshape(-1, 4, 4)[k].T
        np.testing.assert_allclose(T[:3, :3] @ [0, 1, 0], [0, 0, 1], atol=1e-7)  # y -> z
        np.testing.assert_allclose(T[:3, 3], [0.4, 1.45, 0.0], atol=1e-6)
        assert objects["/meshcat/obstacles/1"]["geometries"][0]["type"] == "BufferGeometry"
        draw_obstacles(scene, obs[:1])  # drawn again: replaced, not added
        paths = [c["path"] for c in map(umsgpack.unpackb, scene._commands)
                 if c["type"] == "set_object"]
        assert paths == ["/meshcat/obstacles/0"]
        with pytest.raises(KinlibError, match="colors"):
            draw_obstacles(scene, obs, ["red"])
        with pytest.raises(KinlibError, match="obstacles\\[0\\]"):
            draw_obstacles(scene, [(0.0, 0.0)])
        with pytest.raises(KinlibError, match="height"):
            draw_obstacles(scene, obs, height=0)
        with pytest.raises(KinlibError, match="RobotVisualizer or a Scene"):
            draw_obstacles("scene", obs)
    finally:
        scene.close()
