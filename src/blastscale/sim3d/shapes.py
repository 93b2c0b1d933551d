"""The engine shapes of rigid bodies: each writes its own MJCF ``<geom>`` (and assets) and knows its base points
and its loaded front face.

Boxes (:class:`BoxShape`), prisms (:class:`PrismShape`) and convex meshes (:class:`MeshShape`) provide the same
members; :func:`engine_shape` picks one for a structure body's contact geometry. Body frame: origin at the centre
of mass, x = width 2b (the blast pushes towards +x onto the -x face), y = depth 2w, z = height 2h; lengths in
metres, densities in kg/m^3. The scene that places them is :mod:`.model`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError
from ..structures.base import BoxGeometry, PrismGeometry
from ..structures.block import RectangularBlock
from ..structures.convex_block import ConvexGeometry
from .contact import mjcf_number

__all__ = ["BoxShape", "FrontFace", "MeshShape", "PrismShape", "engine_shape"]


@dataclass(frozen=True)
class FrontFace:
    """The face loaded by the blast (paper's Method A), in the body frame.

    Attributes
    ----------
    centre : tuple of float
        Face centre relative to the centre of mass [m].
    normal : tuple of float
        Unit inward normal (direction of the pressure force) [-].
    area : float
        Loaded area S [m^2].
    """

    centre: tuple[float, float, float]
    normal: tuple[float, float, float]
    area: float


@dataclass(frozen=True)
class BoxShape:
    """A box of half-sizes (b, w, h) [m] along body x, y, z, density [kg/m^3], its centre
    ``centre_z`` [m] above the body's centre of mass (a square drum: the box of its base section
    carrying the frustum's inertia)."""

    half_width: float
    half_depth: float
    half_height: float
    density: float
    centre_z: float = 0.0

    @classmethod
    def from_block(cls, block: RectangularBlock) -> "BoxShape":
        """The box of a :class:`~blastscale.structures.block.RectangularBlock` (2b x 2w x 2h)."""
        return cls(block.b, block.w, block.h, block.density)

    @property
    def mass(self) -> float:
        """Mass of the box [kg]."""
        return 8.0 * self.half_width * self.half_depth * self.half_height * self.density

    @property
    def half_height_below_com(self) -> float:
        """Distance from the centre of mass down to the base [m]."""
        return self.half_height - self.centre_z

    def base_points(self) -> np.ndarray:
        """The four base corners in the body frame, shape (4, 3) [m]."""
        b, w, z = self.half_width, self.half_depth, self.centre_z - self.half_height
        return np.array([[b, w, z], [b, -w, z], [-b, w, z], [-b, -w, z]], dtype=float)

    def pivot_points(self) -> np.ndarray:
        """Mid-points of the rear (+x) and front (-x) base edges in the body frame, shape (2, 3) [m]."""
        b, z = self.half_width, self.centre_z - self.half_height
        return np.array([[b, 0.0, z], [-b, 0.0, z]], dtype=float)

    def front_face(self) -> FrontFace:
        """The -x face, loaded towards +x: area 2h x 2w."""
        return FrontFace(
            (-self.half_width, 0.0, self.centre_z), (1.0, 0.0, 0.0), 4.0 * self.half_height * self.half_depth
        )

    def mjcf_assets(self, name: str) -> str:
        """No assets for a primitive box."""
        return ""

    def contact_geoms(self, name: str) -> list[str]:
        """Names of the geoms in this body's contact pairs (one box here; a base made of
        several geoms lists them all)."""
        return [name]

    def mjcf_geom(self, name: str) -> str:
        """The ``<geom>`` element; its collision settings come from the scene's ``<default>``
        (:func:`build_scene`)."""
        return (
            f'<geom name="{name}" type="box" size="{mjcf_number(self.half_width)} {mjcf_number(self.half_depth)} {mjcf_number(self.half_height)}" '
            f'pos="0 0 {mjcf_number(self.centre_z)}" density="{mjcf_number(self.density)}"/>'
        )


@dataclass(frozen=True)
class MeshShape:
    """A convex mesh of a general block (:class:`~blastscale.structures.convex_block.ConvexGeometry`:
    its hull's vertices in the body frame); MuJoCo takes their convex hull, as the block is."""

    geometry: ConvexGeometry
    density: float

    def vertex_array(self) -> np.ndarray:
        """The mesh's vertices in the body frame (n, 3) [m]."""
        return self.geometry.array()

    def base_points(self) -> np.ndarray:
        """The lowest vertices at rest, body frame [m]."""
        return self.geometry.base_points()

    def mjcf_assets(self, name: str) -> str:
        """The ``<mesh>`` asset (vertices in the body frame; MuJoCo takes their convex hull)."""
        v = " ".join(mjcf_number(x) for x in self.vertex_array().ravel())
        return f'<mesh name="{name}_mesh" vertex="{v}"/>'

    def contact_geoms(self, name: str) -> list[str]:
        """The one mesh geom."""
        return [name]

    def mjcf_geom(self, name: str) -> str:
        """The mesh ``<geom>``; its collision settings come from the scene's ``<default>``."""
        return f'<geom name="{name}" type="mesh" mesh="{name}_mesh" density="{mjcf_number(self.density)}"/>'


@dataclass(frozen=True)
class PrismShape(MeshShape):
    """A convex mesh: the right prism on a regular polygon (a "circular" drum), from
    :class:`~blastscale.structures.base.PrismGeometry`; never a cylinder primitive (MuJoCo's
    cylinder contacts gained energy in our column tests, docs/design.md)."""

    geometry: PrismGeometry

    def vertex_array(self) -> np.ndarray:
        """The prism's vertices in the body frame (2 x sides, 3) [m]."""
        return self.geometry.vertices()


def engine_shape(geometry, density: float):
    """The engine shape of a structure body's contact geometry
    (:class:`~blastscale.structures.base.BoxGeometry` -> :class:`BoxShape`,
    :class:`~blastscale.structures.base.PrismGeometry` -> :class:`PrismShape`)."""
    if isinstance(geometry, BoxGeometry):
        return BoxShape(geometry.half_width, geometry.half_depth, geometry.half_height, density, geometry.centre_z)
    if isinstance(geometry, PrismGeometry):
        return PrismShape(geometry, density)
    if isinstance(geometry, ConvexGeometry):
        return MeshShape(geometry, density)
    if hasattr(geometry, "mjcf_geom") and hasattr(geometry, "contact_geoms"):
        return geometry  # already an engine shape (e.g. a custom contact base, benchmarks/bench_sim3d.py)
    raise BlastscaleInputError(f"shape = {geometry!r} is not known: valid kinds are BoxGeometry, PrismGeometry")
