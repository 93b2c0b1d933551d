"""Geometry and inertia of a monolithic rectangular block standing on a rigid base.

Notation of the paper (Masi et al., Sec. "Validation of the scaling laws"): the block measures
``2b x 2h x 2w`` (width along the blast direction x, height along z, depth along y);
``r = sqrt(b^2 + h^2)`` is the distance from a base edge (rocking pivot) to the centre of
mass, ``alpha = atan(b/h)`` the slenderness angle, ``J_o = 4/3 m r^2`` the moment of inertia
about the pivot edge and ``p = sqrt(3 g / (4 r))`` the frequency parameter (Housner 1963).
The blast loads the front face, of area ``S = 2h x 2w``, whose centre lies at height h.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from .._validate import check_positive_scalar, check_range
from ..constants import STANDARD_GRAVITY
from .base import BoxGeometry, Face, MonitoringPoint, RigidBody, as_vertex_tuple, centred_box_vertices

__all__ = ["RectangularBlock"]


@dataclass(frozen=True)
class RectangularBlock:
    """A homogeneous rectangular block, all sizes full lengths in SI.

    Parameters
    ----------
    height : float
        Full height 2h [m].
    width : float
        Full width 2b [m], measured along the blast direction (the rocking plane).
    depth : float
        Full depth 2w [m], across the rocking plane. It cancels out of the planar
        equation of motion; default 1 m.
    density : float
        Material density rho [kg/m^3], default 2000 (the paper's prototype).
    """

    height: float
    width: float
    depth: float = 1.0
    density: float = 2000.0

    def __post_init__(self):
        check_positive_scalar("height", self.height, "m")
        check_positive_scalar("width", self.width, "m")
        check_positive_scalar("depth", self.depth, "m")
        check_positive_scalar("density", self.density, "kg/m^3")

    @classmethod
    def from_slenderness(cls, height: float, alpha: float, depth: float = 1.0, density: float = 2000.0):
        """Block of full ``height`` [m] and slenderness angle ``alpha`` [rad], 0 < alpha < pi/2:
        width = height * tan(alpha)."""
        check_positive_scalar("height", height, "m")
        check_range("slenderness angle alpha", alpha, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True)
        return cls(height=height, width=height * math.tan(alpha), depth=depth, density=density)

    # geometry ------------------------------------------------------------
    @property
    def b(self) -> float:
        """Half-width b [m]."""
        return 0.5 * self.width

    @property
    def h(self) -> float:
        """Half-height h [m]."""
        return 0.5 * self.height

    @property
    def w(self) -> float:
        """Half-depth w [m]."""
        return 0.5 * self.depth

    @property
    def r(self) -> float:
        """Pivot-to-centre-of-mass distance r = sqrt(b^2 + h^2) [m]."""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Slenderness angle alpha = atan(b/h) [rad]."""
        return math.atan2(self.b, self.h)

    @property
    def volume(self) -> float:
        """Volume 2b * 2h * 2w [m^3]."""
        return self.width * self.height * self.depth

    @property
    def mass(self) -> float:
        """Mass m = rho V [kg]."""
        return self.density * self.volume

    @property
    def front_area(self) -> float:
        """Loaded front-face area S = 2h * 2w [m^2]."""
        return self.height * self.depth

    @property
    def inertia_pivot(self) -> float:
        """Moment of inertia about the pivot edge J_o = 4/3 m r^2 [kg m^2]."""
        return 4.0 / 3.0 * self.mass * self.r**2

    @property
    def inertia_centroid(self) -> tuple[float, float, float]:
        """Principal moments of inertia about the centre of mass (x, y, z axes) [kg m^2]."""
        m = self.mass
        a, d, c = self.width, self.depth, self.height
        return (m * (d**2 + c**2) / 12.0, m * (a**2 + c**2) / 12.0, m * (a**2 + d**2) / 12.0)

    def frequency_parameter(self, gravity: float = STANDARD_GRAVITY) -> float:
        """Housner's frequency parameter p = sqrt(3 g / (4 r)) [rad/s] (Housner 1963)."""
        check_positive_scalar("gravity", gravity, "m/s^2")
        return math.sqrt(3.0 * gravity / (4.0 * self.r))

    # the structure interface (structures.base) ----------------------------------------
    @property
    def bodies(self) -> tuple:
        """The one rigid body, named "block", standing on the ground centred on x = y = 0."""
        b, w, h = self.b, self.w, self.h
        faces = (
            Face("front", (-b, 0.0, 0.0), (-1.0, 0.0, 0.0), self.height * self.depth),
            Face("rear", (b, 0.0, 0.0), (1.0, 0.0, 0.0), self.height * self.depth),
            Face("side", (0.0, -w, 0.0), (0.0, -1.0, 0.0), self.height * self.width),
            Face("side", (0.0, w, 0.0), (0.0, 1.0, 0.0), self.height * self.width),
            Face("top", (0.0, 0.0, h), (0.0, 0.0, 1.0), self.width * self.depth),
            Face("bottom", (0.0, 0.0, -h), (0.0, 0.0, -1.0), self.width * self.depth, True),
        )
        return (
            RigidBody(
                "block",
                self.mass,
                (0.0, 0.0, h),
                self.inertia_centroid,
                BoxGeometry(b, w, h),
                faces,
                faces[0],
                -h,
                self.alpha,
                self.volume,
                as_vertex_tuple(centred_box_vertices(b, w, h)),
            ),
        )

    @property
    def interfaces(self) -> tuple:
        """((-1, 0),): the block on the ground."""
        return ((-1, 0),)

    @property
    def monitoring_points(self) -> tuple:
        """One point, "P-1", at the front-face centre."""
        return (MonitoringPoint("P-1", 0, (-self.b, 0.0, 0.0)),)

    @property
    def front_x(self) -> float:
        """x of the front face [m] (the block is centred on x = 0)."""
        return -self.b

    def describe(self) -> dict:
        """Geometry and material, SI keys."""
        return {
            "kind": "rectangular block",
            "height_m": self.height,
            "width_m": self.width,
            "depth_m": self.depth,
            "density_kg_m3": self.density,
            "mass_kg": self.mass,
            "alpha_rad": self.alpha,
        }

    def scaled(self, factors) -> "RectangularBlock":
        """The geometrically similar block: lengths x ``factors.length`` (lambda), density x
        ``factors.density`` (gamma) (``factors``: a :class:`~blastscale.similitude.ScalingFactors`)."""
        length_factor = check_positive_scalar("scale", factors.length)
        density_factor = check_positive_scalar("density ratio", factors.density)
        return replace(
            self,
            height=self.height * length_factor,
            width=self.width * length_factor,
            depth=self.depth * length_factor,
            density=self.density * density_factor,
        )
