"""kinlib.plot.sequences: the frames of a three-angle sequence, one elementary turn at a
time, cross-checked against scipy's Euler angles and against the axis-angle of each step."""

import matplotlib.pyplot as plt
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kinlib as kl
from kinlib.plot.sequences import animate_rotation_sequences, rotation_steps

RNG = np.random.default_rng(7)


@pytest.mark.parametrize("seq", ["ZYX", "xyz", "ZYZ", "yxy", "XZY", "zxz"])
def test_each_stage_ends_where_scipy_puts_the_partial_sequence(seq):
    """After turn m the frame is the sequence of the first m + 1 angles (scipy agrees on
    the convention: UPPERCASE intrinsic, lowercase extrinsic, angles in letter order)."""
    angles = RNG.uniform(-2.5, 2.5, 3)
    R, axes, stage = rotation_steps(angles, seq, steps=5)
    assert R.shape == (16, 3, 3) and axes.shape == (16, 3) and stage.shape == (16,)
    np.testing.assert_allclose(R[0], np.eye(3))
    for m in range(3):
        partial = Rotation.from_euler(seq[:m + 1], angles[:m + 1]).as_matrix()
        np.testing.assert_allclose(R[5 * (m + 1)], partial, atol=1e-12)
    np.testing.assert_allclose(R[-1], kl.matrix_from_euler(angles, seq), atol=1e-12)


@pytest.mark.parametrize("seq", ["ZYX", "xyz", "YZY"])
def test_every_step_is_an_equal_turn_about_the_stated_axis(seq):
    """R_{f+1} R_fᵀ (a turn in the fixed frame) is the rotation by angle/steps about the
    axis reported for frame f + 1; for fixed angles that axis is a coordinate axis, for
    Euler angles it is the moving frame's axis at the start of the turn."""
    angles = np.array([0.9, -0.6, 1.4])
    steps = 4
    R, axes, stage = rotation_steps(angles, seq, steps=steps)
    letters = "xyz"
    for f in range(len(R) - 1):
        m = stage[f + 1]
        step = R[f + 1] @ R[f].T
        expect = kl.matrix_from_axis_angle(axes[f + 1], angles[m] / steps)
        np.testing.assert_allclose(step, expect, atol=1e-12)
        k = letters.index(seq[m].lower())
        if seq.islower():
            np.testing.assert_allclose(axes[f + 1], np.eye(3)[k])
        else:
            np.testing.assert_allclose(axes[f + 1], R[steps * m][:, k], atol=1e-12)
    assert stage.tolist() == [0] + [m for m in range(3) for _ in range(steps)]


def test_bad_input_names_what_was_expected():
    with pytest.raises(kl.KinlibError, match="seq"):
        rotation_steps([0, 0, 0], "ZYx")
    with pytest.raises(kl.KinlibError, match="angles"):
        rotation_steps([0, 0], "ZYX")
    with pytest.raises(kl.KinlibError, match="three angles, shape \\(3,\\)"):
        rotation_steps(np.zeros((2, 3)), "ZYX")
    with pytest.raises(kl.KinlibError, match="steps"):
        rotation_steps([0, 0, 0], "ZYX", steps=0)
    with pytest.raises(kl.KinlibError, match="panels"):
        animate_rotation_sequences([])
    with pytest.raises(kl.KinlibError, match="panels\\[0\\]"):
        animate_rotation_sequences([([0, 0, 0],)])
    with pytest.raises(kl.KinlibError, match="hold"):
        animate_rotation_sequences([([0, 0, 0], "ZYX")], hold=-1)
    with pytest.raises(kl.KinlibError, match="length"):
        animate_rotation_sequences([([0, 0, 0], "ZYX")], length=0.0)


def test_the_player_has_one_picture_per_frame_and_closes_its_figure():
    before = plt.get_fignums()
    player = animate_rotation_sequences([([0.5, 0.4, 0.3], "ZYX", ("α", "β", "γ")),
                                         ([0.3, 0.4, 0.5], "xyz")], steps=2, hold=1)
    assert player.data.count("data:image/png") == 3 * 2 + 1 + 1
    assert plt.get_fignums() == before


def test_each_frame_is_rendered_once():
    """The player renders every frame once, into its PNG (not again for the screen)."""
    from unittest import mock

    from matplotlib.figure import Figure

    draws = []
    draw = Figure.draw

    def counted(self, renderer):
        draws.append(self)
        return draw(self, renderer)

    with mock.patch.object(Figure, "draw", counted):
        player = animate_rotation_sequences([([0.5, 0.4, 0.3], "ZYX")], steps=2, hold=1)
    frames = player.data.count("data:image/png")
    assert frames == 3 * 2 + 1 + 1 and len(draws) == frames
