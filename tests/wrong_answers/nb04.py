"""Notebook 04: wrong answers a student would write."""

import numpy as np

WRONG = {
    "04.1": [
        # α + γ kept, the rule of β = −90°: 20° − 30° = 60° + γ'
        (np.deg2rad(20 - 30 - 60), "sign"),
        (-30 + (60 - 20), "degrees"),              # the right angle, worked out in degrees
        (np.deg2rad(-30), "unchanged"),            # "γ stays, only α moves"
    ],
    "04.2": [(1, "coincide"), (3, "three")],
    "04.3": [("a", "orientation"), ("c", "matrix")],
    "04.4": [("a", "slide"), ("c", "extrinsic")],
    "04.5": [
        ([-np.pi / 2, np.pi / 2], "tait-bryan"),   # the lock of Z-Y-X
        ([0, 180], "degrees"),
        ([0.0], "missing"),
        ([0, 3.14], "rounded"),                    # π typed as 3.14
    ],
}
