"""Recorders and the result of a 3D single-block run (pure numpy on recorded states).

Definitions (world frame: z up, blast towards +x):

* rotation theta [rad]: tilt of the body's z axis in the x-z plane, ``atan2(R_xz, R_zz)``,
  positive when the top moves towards +x (rocking about the rear, +x, base edge). For planar
  motion it is the rocking angle of the paper's Eq. (eom).
* sliding [m]: x displacement of the base edge the block rests on (the +x edge when
  theta >= 0, the -x edge otherwise) from its upright position. Pure rocking about a fixed
  edge gives zero sliding; pure translation gives the displacement of the block.
* uplift [m]: height of the lowest base corner above the plane (negative values are the
  soft contact's penetration, a few micrometres at full scale); > 0 means flight.
* overturned: the centre of mass passed over a base edge, |theta| > alpha = atan(b/h)
  (beyond it gravity drives the block down; Housner 1963).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validate import check_positive

__all__ = ["Block3DResult", "quaternion_to_matrix", "tilt_angle"]


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


@dataclass(frozen=True, eq=False)
class Block3DResult:
    """Time histories of a single rigid block on a plane (MuJoCo run), SI units.

    Attributes
    ----------
    time : ndarray (n,)
        Time after shock arrival [s].
    rotation : ndarray (n,)
        Rocking angle theta about y [rad] (see module docstring).
    angular_velocity : ndarray (n,)
        World angular velocity about y, d theta/dt for planar motion [rad/s].
    sliding : ndarray (n,)
        x displacement of the supporting base edge [m].
    base_centre_x, com_x : ndarray (n,)
        x displacement of the base centre and of the centre of mass [m].
    com_z : ndarray (n,)
        Height of the centre of mass [m].
    velocity_x, velocity_z : ndarray (n,)
        Velocity of the centre of mass [m/s].
    uplift : ndarray (n,)
        Height of the lowest base corner [m].
    n_contacts : ndarray (n,) of int
        Active contact points (0 flight, 1-2 on an edge or corner, 4 flat on the base).
    alpha : float
        Slenderness angle atan(b/h) [rad].
    half_width, half_height : float
        b and h of the block [m] (for drawings).
    impulse_delivered : float or None
        Blast momentum applied to the body, sum of F_n dt [N*s] (None for an up-scaled result
        made without the momentum factor).
    settings : dict
        Contact settings and run parameters used.
    """

    time: np.ndarray
    rotation: np.ndarray
    angular_velocity: np.ndarray
    sliding: np.ndarray
    base_centre_x: np.ndarray
    com_x: np.ndarray
    com_z: np.ndarray
    velocity_x: np.ndarray
    velocity_z: np.ndarray
    uplift: np.ndarray
    n_contacts: np.ndarray
    alpha: float
    half_width: float
    half_height: float
    impulse_delivered: float | None
    settings: dict = field(default_factory=dict)

    @property
    def overturned(self) -> bool:
        """True when |theta| exceeded alpha (centre of mass beyond the pivot edge)."""
        return bool(np.max(np.abs(self.rotation)) > self.alpha)

    @property
    def overturn_time(self) -> float | None:
        """First recorded time with |theta| > alpha [s]; None if the block did not overturn
        (as :attr:`blastscale.rocking.RockingResult.overturn_time`; JSON ``null``)."""
        idx = np.flatnonzero(np.abs(self.rotation) > self.alpha)
        return float(self.time[idx[0]]) if idx.size else None

    @property
    def max_rotation(self) -> float:
        """max |theta| [rad]."""
        return float(np.max(np.abs(self.rotation)))

    @property
    def max_sliding(self) -> float:
        """max |sliding| [m]."""
        return float(np.max(np.abs(self.sliding)))

    @property
    def final_sliding(self) -> float:
        """Sliding at the end of the run [m]."""
        return float(self.sliding[-1])

    @property
    def max_uplift(self) -> float:
        """Largest height of the lowest base corner [m] (flight when > 0)."""
        return float(np.max(self.uplift))

    def summary(self) -> dict:
        """The scalar outcomes, keys with units (the CLI's JSON); ``overturn_time_s`` is None
        when the block did not overturn, so the dict is strict JSON (no NaN)."""
        return {
            "overturned": self.overturned,
            "overturn_time_s": self.overturn_time,
            "max_rotation_rad": self.max_rotation,
            "max_sliding_m": self.max_sliding,
            "final_sliding_m": self.final_sliding,
            "max_uplift_m": self.max_uplift,
            "peak_angular_velocity_rad_s": float(np.max(np.abs(self.angular_velocity))),
            "peak_velocity_x_m_s": float(np.max(np.abs(self.velocity_x))),
        }

    def to_dataset(self):
        """The histories as an ``xarray.Dataset`` (dimension ``time``), units in attributes,
        scalar outcomes and settings as dataset attributes (NetCDF-ready)."""
        import xarray as xr

        units = {
            "rotation": "rad", "angular_velocity": "rad/s", "sliding": "m", "base_centre_x": "m", "com_x": "m",
            "com_z": "m", "velocity_x": "m/s", "velocity_z": "m/s", "uplift": "m", "n_contacts": "1",
        }
        data = {k: ("time", getattr(self, k), {"units": u}) for k, u in units.items()}
        attrs = {k: ("none" if v is None else int(v) if isinstance(v, bool) else v) for k, v in self.summary().items()}
        attrs.update(alpha_rad=self.alpha, half_width_m=self.half_width, half_height_m=self.half_height,
                     impulse_delivered_N_s=self.impulse_delivered, source="blastscale.sim3d (MuJoCo)")
        attrs.update({f"setting_{k}": ("none" if v is None else v) for k, v in self.settings.items()
                      if isinstance(v, (int, float, str)) or v is None})
        return xr.Dataset(data, coords={"time": ("time", self.time, {"units": "s"})}, attrs=attrs)

    def upscaled(
        self, length_factor: float, time_factor: float, momentum_factor: float | None = None
    ) -> "Block3DResult":
        """This (model) result in prototype units: lengths / lambda, times / lambda_t,
        velocities / (lambda / lambda_t), angular velocities x lambda_t; angles unchanged; the
        delivered impulse [N*s] / ``momentum_factor`` (gamma sqrt(varsigma) lambda^(7/2), see
        :class:`~blastscale.similitude.ScalingFactors`), or None when that factor is not given."""
        L = float(check_positive("length factor", length_factor))
        T = float(check_positive("time factor", time_factor))
        M = None if momentum_factor is None else float(check_positive("momentum factor", momentum_factor))
        V = L / T
        return Block3DResult(
            time=self.time / T,
            rotation=self.rotation,
            angular_velocity=self.angular_velocity * T,
            sliding=self.sliding / L,
            base_centre_x=self.base_centre_x / L,
            com_x=self.com_x / L,
            com_z=self.com_z / L,
            velocity_x=self.velocity_x / V,
            velocity_z=self.velocity_z / V,
            uplift=self.uplift / L,
            n_contacts=self.n_contacts,
            alpha=self.alpha,
            half_width=self.half_width / L,
            half_height=self.half_height / L,
            impulse_delivered=None if M is None else self.impulse_delivered / M,
            settings={**self.settings, "upscaled_from": {"length_factor": L, "time_factor": T}},
        )
