"""Rotations of recorded bodies: matrices from MuJoCo's quaternions, the rocking angle about y."""

from __future__ import annotations

import numpy as np

__all__ = ["quaternion_to_matrix", "tilt_angle"]


def quaternion_to_matrix(q) -> np.ndarray:
    """Rotation matrices (..., 3, 3) from unit quaternions (..., 4) ordered (w, x, y, z)."""
    q = np.asarray(q, dtype=float)
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
        ],
        -2,
    )


def tilt_angle(R) -> np.ndarray:
    """Rotation about the pivot axis y [rad]: ``atan2(R[0, 2], R[2, 2])`` for matrices (..., 3, 3)."""
    R = np.asarray(R, dtype=float)
    return np.arctan2(R[..., 0, 2], R[..., 2, 2])
