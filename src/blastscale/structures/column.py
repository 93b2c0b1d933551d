"""Multi-drum stone columns: drums of square or circular section stacked without mortar.

The paper's columns (Masi et al., Sec. "Application to multi-drum masonry columns"): 10 m high,
ten 1 m drums, section side / diameter tapering linearly from 1.65 m at the base to 1.28 m at
the top (after the Parthenon's Doric columns), marble. Each drum is a frustum: of a square
pyramid for the square section, of a regular ``sides``-gon (default 32, vertices on the circle
of the nominal diameter) for the circular one. Mass properties are exact for these solids
(:func:`~.base.frustum_mass_properties`).

Each drum's solid (``RigidBody.vertices``: the frustum's two rings) is what its mass, volume, centre of
mass and inertia are, and what ``show`` and the report draw and print. Contact geometry for the
engine (docs/design.md, "Multi-drum columns on MuJoCo") is not the solid: each drum collides as the
right prism of its *base* section (box / polygon prism, ``RigidBody.shape``) carrying the frustum's
exact mass and inertia; drum k+1's base then rests fully on drum k's (wider) top, which is the exact
contact patch, while frustum meshes whose faces coincide at the joints are ill-conditioned.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive, check_positive_scalar, check_range
from .base import (
    BoxGeometry,
    Face,
    MonitoringPoint,
    PrismGeometry,
    RigidBody,
    as_vertex_tuple,
    frustum_vertices,
    polygon_ring,
    rectangle_ring,
    tapered_face,
)
from .frustum import frustum_mass_properties, polygon_section_constants

__all__ = ["MultiDrumColumn", "SECTIONS", "MIN_SIDES", "MAX_SIDES", "TOP_WIDTH_RATIO_RANGE", "MAX_DRUMS"]

#: Section shapes.
SECTIONS = ("square", "circular")
#: Fewest / most polygon sides of a circular drum (8 keeps the section within 8 % of the circle's
#: area; more than 256 only costs collision time).
MIN_SIDES, MAX_SIDES = 8, 256
#: Allowed top/base width ratio: tapered (entasis-free) to prismatic; a top wider than the base
#: would overhang the base-section contact prisms the engine builds.
TOP_WIDTH_RATIO_RANGE = (0.25, 1.0)
#: Most drums in one column.
MAX_DRUMS = 200


@dataclass(frozen=True)
class MultiDrumColumn:
    """A column of rigid drums stacked on a rigid ground.

    Parameters
    ----------
    section : {"square", "circular"}
        Cross-section shape.
    drums : int
        Number of drums N, 1 <= N <= 200.
    height : float
        Total height [m].
    base_width : float
        Side (square) or diameter (circular) at the base [m].
    top_width : float
        Side or diameter at the top [m], 0.25-1.0 x ``base_width``; the width tapers linearly
        with height.
    sides : int
        Polygon sides of a circular drum, 8-256 (ignored for a square section).
    density : float
        rho [kg/m^3] (marble 2700).
    drum_heights : sequence of float, optional
        Height of each drum from the base up [m], summing to ``height``; default equal drums.
    extra_points : sequence of MonitoringPoint
        User monitoring points added after the default P-1..P-N.
    """

    section: str = "square"
    drums: int = 10
    height: float = 10.0
    base_width: float = 1.65
    top_width: float = 1.28
    sides: int = 32
    density: float = 2700.0
    drum_heights: tuple | None = None
    extra_points: tuple = ()

    def __post_init__(self):
        check_choice("section", self.section, SECTIONS)
        for name, v, lo, hi in (("drums", self.drums, 1, MAX_DRUMS), ("sides", self.sides, MIN_SIDES, MAX_SIDES)):
            if (
                isinstance(v, bool)
                or not isinstance(v, (int, float, np.integer, np.floating))
                or not (math.isfinite(v) and float(v).is_integer() and lo <= v <= hi)
            ):
                raise BlastscaleInputError(f"{name} = {v!r} is out of range: valid range is whole numbers {lo}-{hi}")
        object.__setattr__(self, "drums", int(self.drums))
        object.__setattr__(self, "sides", int(self.sides))
        check_positive_scalar("height", self.height, "m")
        check_positive_scalar("base width", self.base_width, "m")
        check_positive_scalar("top width", self.top_width, "m")
        lo, hi = TOP_WIDTH_RATIO_RANGE
        check_range("top width", self.top_width, lo * self.base_width, hi * self.base_width, "m")
        check_positive_scalar("density", self.density, "kg/m^3")
        if self.drum_heights is not None:
            hs = tuple(float(x) for x in np.atleast_1d(check_positive("drum heights", self.drum_heights, "m")))
            if len(hs) != self.drums:
                raise BlastscaleInputError(f"drum heights has {len(hs)} values: must have one per drum ({self.drums})")
            if abs(sum(hs) - self.height) > 1e-9 * self.height:
                raise BlastscaleInputError(
                    f"drum heights sum = {sum(hs):.9g} m is out of range: must equal height = {self.height:.9g} m"
                )
            object.__setattr__(self, "drum_heights", hs)
        for p in self.extra_points:
            if not isinstance(p, MonitoringPoint) or not 0 <= p.body < self.drums:
                raise BlastscaleInputError(
                    f"extra point = {p!r} is out of range: must be a MonitoringPoint on a body 0-{self.drums - 1}"
                )

    # geometry ------------------------------------------------------------------------
    @property
    def heights(self) -> tuple:
        """Drum heights from the base up [m]."""
        return self.drum_heights if self.drum_heights is not None else (self.height / self.drums,) * self.drums

    @property
    def joint_heights(self) -> np.ndarray:
        """Heights of the drum bases, then the top, shape (N + 1,) [m]."""
        return np.concatenate([[0.0], np.cumsum(self.heights)])

    def width_at(self, z) -> np.ndarray:
        """Side / diameter at height z [m] (linear taper)."""
        return self.base_width + (self.top_width - self.base_width) * np.asarray(z, dtype=float) / self.height

    @property
    def mass(self) -> float:
        """Total mass [kg]."""
        return float(sum(b.mass for b in self.bodies))

    @property
    def front_x(self) -> float:
        """x of the base drum's front face at the ground [m]: -side/2 (square), minus the base
        polygon's inradius (circular, a flat faces the charge)."""
        if self.section == "square":
            return -0.5 * self.base_width
        return -0.5 * self.base_width * math.cos(math.pi / self.sides)

    @property
    def bodies(self) -> tuple:
        """The drums "D-1" (base) .. "D-N" (top) as :class:`~.base.RigidBody`."""
        return _drums(self)

    @property
    def interfaces(self) -> tuple:
        """(-1, 0), (0, 1), ..., (N-2, N-1): ground-base and every adjacent pair of drums."""
        return tuple((i - 1, i) for i in range(self.drums))

    @property
    def monitoring_points(self) -> tuple:
        """ "P-1".."P-N" at each drum's front-face centre, then ``extra_points``."""
        pts = tuple(
            MonitoringPoint(f"P-{i + 1}", i, next(f.centre for f in b.faces if f.label == "front"))
            for i, b in enumerate(self.bodies)
        )
        return pts + tuple(self.extra_points)

    def describe(self) -> dict:
        """Geometry and material, SI keys."""
        return {
            "kind": "multi-drum column",
            "section": self.section,
            "drums": self.drums,
            "height_m": self.height,
            "base_width_m": self.base_width,
            "top_width_m": self.top_width,
            "sides": self.sides if self.section == "circular" else None,
            "density_kg_m3": self.density,
            "drum_heights_m": list(self.heights),
            "mass_kg": self.mass,
        }

    def scaled(self, factors) -> "MultiDrumColumn":
        """The geometrically similar column: lengths x ``factors.length`` (lambda), density x
        ``factors.density`` (gamma) (``factors``: a :class:`~blastscale.similitude.ScalingFactors`)."""
        L = check_positive_scalar("scale", factors.length)
        g = check_positive_scalar("density ratio", factors.density)
        return replace(
            self,
            height=self.height * L,
            base_width=self.base_width * L,
            top_width=self.top_width * L,
            density=self.density * g,
            drum_heights=None if self.drum_heights is None else tuple(h * L for h in self.drum_heights),
            extra_points=tuple(replace(p, position=tuple(x * L for x in p.position)) for p in self.extra_points),
        )


@functools.lru_cache(maxsize=256)  # a frozen column's drums never change: built once (they cost ~1 ms)
def _drums(col: MultiDrumColumn) -> tuple:
    z = col.joint_heights
    s = col.width_at(z)
    out = []
    n = col.drums
    for i in range(n):
        H, s0, s1 = col.heights[i], float(s[i]), float(s[i + 1])
        top_contact = i < n - 1
        if col.section == "square":
            mp = frustum_mass_properties(s0, s1, H, col.density)
            zc = mp.z_com
            faces = (
                tapered_face("front", s0 / 2, s1 / 2, s0, s1, H, zc, math.pi),
                tapered_face("rear", s0 / 2, s1 / 2, s0, s1, H, zc, 0.0),
                tapered_face("side", s0 / 2, s1 / 2, s0, s1, H, zc, -math.pi / 2),
                tapered_face("side", s0 / 2, s1 / 2, s0, s1, H, zc, math.pi / 2),
            )
            load = faces[0]
            shape = BoxGeometry(s0 / 2, s0 / 2, H / 2, H / 2 - zc)
            solid = frustum_vertices(rectangle_ring(s0 / 2, s0 / 2), rectangle_ring(s1 / 2, s1 / 2), -zc, H - zc)
            top_area, base_area, support = s1 * s1, s0 * s0, s0 / 2
        else:
            a, k = polygon_section_constants(col.sides)
            R0, R1 = s0 / 2, s1 / 2
            mp = frustum_mass_properties(R0, R1, H, col.density, a, k)
            zc = mp.z_com
            ci, si = math.cos(math.pi / col.sides), math.sin(math.pi / col.sides)
            faces = []
            for j in range(col.sides):
                ang = math.pi + 2.0 * math.pi * j / col.sides
                label = "front" if j == 0 else "rear" if 2 * j == col.sides else "side"
                faces.append(tapered_face(label, R0 * ci, R1 * ci, 2 * R0 * si, 2 * R1 * si, H, zc, ang))
            faces = tuple(faces)
            # Method A: the projected silhouette, diameter x height (tapered)
            load = tapered_face("front", R0, R1, s0, s1, H, zc, math.pi)
            shape = PrismGeometry(R0, col.sides, H / 2, H / 2 - zc)
            solid = frustum_vertices(polygon_ring(R0, col.sides), polygon_ring(R1, col.sides), -zc, H - zc)
            top_area, base_area, support = a * R1 * R1, a * R0 * R0, R0 * ci
        faces = faces + (
            Face("top", (0.0, 0.0, H - zc), (0.0, 0.0, 1.0), top_area, top_contact),
            Face("bottom", (0.0, 0.0, -zc), (0.0, 0.0, -1.0), base_area, True),
        )
        out.append(
            RigidBody(
                f"D-{i + 1}",
                mp.mass,
                (0.0, 0.0, float(z[i]) + zc),
                mp.inertia,
                shape,
                faces,
                load,
                -zc,
                math.atan2(support, zc),
                mp.volume,
                as_vertex_tuple(solid),
            )
        )
    return tuple(out)
