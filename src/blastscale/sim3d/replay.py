"""Replay stored motion: the bodies' surfaces and the monitoring points in the world at each recorded time,
from the poses (:data:`~.results.MOTION_VARIABLES`) a 3D result keeps.

Pure numpy on plain arrays (positions [m], unit quaternions (w, x, y, z)); a quaternion that lost its unit
length (interpolated, rounded in a file) is normalised first. Any length unit works as long as it is the same
for positions, vertices and local points (a specimen up-scaled to prototype units replays in prototype units).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .rotations import quaternion_to_matrix

__all__ = [
    "rotations",
    "point_positions",
    "world_vertices",
    "points_of",
    "Motion",
    "motion_of",
    "frame_count",
    "SYSTEM_LABELS",
]


def rotations(quaternion) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of quaternions (..., 4) (w, x, y, z), normalised first."""
    q = np.asarray(quaternion, dtype=float)
    return quaternion_to_matrix(q / np.linalg.norm(q, axis=-1, keepdims=True))


def point_positions(position, quaternion, point_body, point_local) -> np.ndarray:
    """World positions (n, npoint, 3) [m] of points fixed on bodies.

    Parameters
    ----------
    position : array (n, nbody, 3)
        Centres of mass (body frame origins) [m].
    quaternion : array (n, nbody, 4)
        Orientations, body to world (w, x, y, z).
    point_body : array of int (npoint,)
        The body carrying each point.
    point_local : array (npoint, 3)
        Each point in its body's frame [m].
    """
    pb = np.asarray(point_body, dtype=int)
    R = rotations(np.asarray(quaternion)[:, pb])
    return np.asarray(position)[:, pb] + np.einsum("npij,pj->npi", R, np.asarray(point_local, dtype=float))


def world_vertices(position, quaternion, vertices) -> np.ndarray:
    """World positions (n, nbody, nvertex, 3) [m] of every body's vertices (NaN padding stays NaN).

    ``position`` (n, nbody, 3) [m], ``quaternion`` (n, nbody, 4), ``vertices`` (nbody, nvertex, 3) [m] in
    each body's frame."""
    R = rotations(quaternion)
    return np.asarray(position)[:, :, None, :] + np.einsum("nbij,bvj->nbvi", R, np.asarray(vertices, dtype=float))


def points_of(ds) -> np.ndarray:
    """:func:`point_positions` of a dataset holding the stored motion (one system: a
    :attr:`~.results.Response3D.dataset`, or one ``system`` of a study's ``sim3d`` group)."""
    return point_positions(
        ds["body_position"].values,
        ds["body_quaternion"].values,
        ds["point_body"].values,
        ds["point_local_position"].values,
    )


@dataclass(frozen=True, eq=False)
class Motion:
    """The stored motion of one or more systems on one time axis, ready to draw (prototype units).

    Attributes
    ----------
    time : array (n,)
        Recorded times [s] (prototype time; the specimen's up-scaled onto them).
    labels : tuple of str
        One per system ("prototype", "model (specimen, up-scaled)").
    position : array (nsys, n, nbody, 3)
        Centres of mass [m].
    quaternion : array (nsys, n, nbody, 4)
        Orientations (w, x, y, z).
    vertices : array (nbody, nvertex, 3)
        Each body's surface in its frame [m] (NaN-padded).
    faces : array of int (nbody, nface, 3)
        Outward triangles (-1-padded).
    bodies : tuple of str
        Body names.
    """

    time: np.ndarray
    labels: tuple
    position: np.ndarray
    quaternion: np.ndarray
    vertices: np.ndarray
    faces: np.ndarray
    bodies: tuple

    @property
    def duration(self) -> float:
        """Simulated time shown [s] (prototype time)."""
        return float(self.time[-1] - self.time[0])

    def frame_indices(self, fps: float, speed: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """The recorded states shown by an animation at ``fps`` frames per second of playback, ``speed`` x
        real time: N = max(2, round(fps x duration / speed)) frames (:func:`frame_count`), evenly over the
        run from its first to its last recorded time, each the nearest recorded state. Returns (indices (N,),
        their times [s])."""
        n = frame_count(self.duration, fps, speed)
        want = self.time[0] + np.linspace(0.0, self.duration, n)
        idx = np.clip(np.searchsorted(self.time, want), 1, len(self.time) - 1)
        idx = np.where(np.abs(self.time[idx - 1] - want) <= np.abs(self.time[idx] - want), idx - 1, idx)
        return idx, self.time[idx]

    @property
    def front_x(self) -> float:
        """The structure's front at the first record [m]: the smallest x of any vertex of the first system
        (the charge stands ``standoff`` in front of it:
        :func:`blastscale.similitude.effects.charge_position`)."""
        return float(np.nanmin(self.world(0, [0])[0][..., 0]))

    def world(self, system: int, indices) -> np.ndarray:
        """World vertices (len(indices), nbody, nvertex, 3) [m] of system ``system`` at recorded ``indices``."""
        return world_vertices(self.position[system, indices], self.quaternion[system, indices], self.vertices)

    def largest_displacement(self) -> np.ndarray:
        """Each body's largest displacement of its centre of mass from time 0, (nsys, nbody) [m]."""
        return np.linalg.norm(self.position - self.position[:, :1], axis=-1).max(axis=1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper corners (3,) [m] of every vertex of every system at every recorded time."""
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        step = max(1, len(self.time) // 200)  # a sample of the states is enough for the axes' limits
        for s in range(len(self.labels)):
            v = self.world(s, np.r_[np.arange(0, len(self.time), step), len(self.time) - 1])
            lo, hi = np.minimum(lo, np.nanmin(v, axis=(0, 1, 2))), np.maximum(hi, np.nanmax(v, axis=(0, 1, 2)))
        return lo, hi


def frame_count(duration: float, fps: float, speed: float = 1.0) -> int:
    """Frames of an animation of ``duration`` [s] of simulated (prototype) time at ``fps`` frames per second
    of playback and ``speed`` x real time: round(fps x duration / speed), at least 2 (the first and the
    last state)."""
    return max(2, int(round(fps * duration / speed)))


#: The systems' labels in a study's histories, by its ``system`` coordinate.
SYSTEM_LABELS = {"prototype": "prototype", "model": "model (specimen, up-scaled)"}


def motion_of(ds) -> Motion:
    """The :class:`Motion` of a dataset holding the stored motion: a study's ``sim3d`` group (a ``system``
    dimension: prototype and the specimen up-scaled) or one :attr:`~.results.Response3D.dataset`."""
    systems = [str(s) for s in ds["system"].values] if "system" in ds.dims else ["prototype"]
    one = ds.isel(system=0) if "system" in ds.dims else ds

    def stacked(name):
        return ds[name].values if "system" in ds[name].dims else ds[name].values[None]

    return Motion(
        time=np.asarray(ds["time"].values, dtype=float),
        labels=tuple(SYSTEM_LABELS.get(s, s) for s in systems),
        position=stacked("body_position"),
        quaternion=stacked("body_quaternion"),
        vertices=one["body_vertices"].values,
        faces=one["body_faces"].values.astype(int),
        bodies=tuple(str(b) for b in ds["body"].values),
    )
