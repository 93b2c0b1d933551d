"""A general rigid block and its derived geometry: any convex polyhedron, with its density.

A :class:`ConvexBlock` is the convex hull of its vertices (world frame at rest, metres, z up) with its
density [kg/m^3]. Its derived geometry (mass [kg], volume [m^3], centre of mass [m], inertia [kg m^2],
faces, engine contact shape, height [m]) is what :class:`~.assembly.Assembly` builds its bodies from:
a block that is an axis-aligned box gets the box's closed-form mass properties (equal to the
polyhedron's to round-off) and a box contact shape; any other block the polyhedron's exact mass
properties (:func:`~.polyhedron.polyhedron_mass_properties`) and a convex mesh of its vertices
(:class:`ConvexGeometry`), a non-diagonal inertia tensor passed whole (MuJoCo ``fullinertia``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_positive_scalar
from .base import BoxGeometry, RigidBody, as_vertex_tuple
from .polyhedron import hull_of, polyhedron_faces, polyhedron_mass_properties

__all__ = ["BlockGeometry", "ConvexBlock", "ConvexGeometry", "block_geometry", "given_block_geometry"]


@dataclass(frozen=True)
class ConvexBlock:
    """A rigid block: the convex hull of ``vertices`` (world frame at rest [m]) of ``density`` [kg/m^3]."""

    name: str
    vertices: tuple
    density: float

    def __post_init__(self):
        v = np.asarray(self.vertices, dtype=float)
        object.__setattr__(self, "vertices", as_vertex_tuple(v))
        check_positive_scalar(f"density of block {self.name!r}", self.density, "kg/m^3")
        hull_of(v, self.name)

    @property
    def points(self) -> np.ndarray:
        """The vertices (n, 3) [m]."""
        return np.asarray(self.vertices, dtype=float)


@dataclass(frozen=True)
class ConvexGeometry:
    """Contact geometry: the convex hull of ``vertices`` (body frame: relative to the centre of mass) [m]."""

    vertices: tuple

    def array(self) -> np.ndarray:
        """The vertices (n, 3) [m]."""
        return np.asarray(self.vertices, dtype=float)

    def base_points(self) -> np.ndarray:
        """The lowest vertices at rest (within 1e-9 of the block's size), body frame [m]."""
        v = self.array()
        z = v[:, 2]
        return v[z <= z.min() + 1e-9 * float(np.ptp(v, axis=0).max())]

    @property
    def support_radius(self) -> tuple:
        """Half-extent of the base along x and y [m] (the lowest vertices' extent)."""
        b = self.base_points()
        return (0.5 * float(np.ptp(b[:, 0])), 0.5 * float(np.ptp(b[:, 1])))


def _is_box(faces) -> bool:
    return len(faces) == 6 and all(np.sort(np.abs(f.normal))[-1] > 1.0 - 1e-12 for f in faces)


@dataclass(frozen=True)
class BlockGeometry:
    """Derived geometry of one block of an assembly (:func:`block_geometry`, :func:`given_block_geometry`).

    Attributes
    ----------
    mass : float
        [kg]
    volume : float
        [m^3]
    com : numpy.ndarray
        Centre of mass, world frame at rest [m].
    inertia : tuple
        About the centre of mass [kg m^2]: the principal diagonal (3 values) or the full tensor (Ixx, Iyy,
        Izz, Ixy, Ixz, Iyz).
    faces : list
        The faces of the block's solid (:func:`~blastscale.structures.polyhedron.polyhedron_faces`).
    shape : object
        The contact shape (a box or the convex hull about the centre of mass).
    height : float
        Vertical extent [m].
    """

    mass: float
    volume: float
    com: np.ndarray
    inertia: tuple
    faces: list
    shape: object
    height: float


def block_geometry(block: ConvexBlock) -> BlockGeometry:
    """The mass properties, faces and contact shape of ``block`` from its vertices and density: a box in
    closed form (its masses bitwise those of earlier releases), any other hull through
    :func:`~blastscale.structures.polyhedron.polyhedron_mass_properties`."""
    v = block.points
    faces = polyhedron_faces(v, block.name)
    if _is_box(faces):
        lo, hi = v.min(axis=0), v.max(axis=0)
        a, d, c = hi - lo
        vol = a * d * c
        m = block.density * a * d * c  # in this order: the engine's masses of earlier releases, bitwise
        com = 0.5 * (lo + hi)
        inertia = tuple(
            float(x) for x in (m * (d * d + c * c) / 12.0, m * (a * a + c * c) / 12.0, m * (a * a + d * d) / 12.0)
        )
        shape = BoxGeometry(0.5 * a, 0.5 * d, 0.5 * c)
    else:
        mp = polyhedron_mass_properties(v, block.density, block.name)
        m, vol, com, I = mp.mass, mp.volume, mp.centroid, mp.inertia
        off = np.abs(I - np.diag(np.diag(I))).max()
        inertia = (
            tuple(np.diag(I)) if off <= 1e-12 * np.trace(I) else (I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2])
        )
        inertia = tuple(float(x) for x in inertia)
        hull = hull_of(v, block.name)
        shape = ConvexGeometry(as_vertex_tuple(v[hull.vertices] - com))
    return BlockGeometry(
        float(m), float(vol), np.asarray(com, dtype=float), inertia, faces, shape, float(np.ptp(v[:, 2]))
    )


def given_block_geometry(block: ConvexBlock, body: RigidBody) -> BlockGeometry:
    """The geometry of a block made from a structure's body (:func:`as_assembly`): the body's own mass,
    volume, centre of mass, inertia and contact shape, the faces of its solid."""
    v = block.points
    return BlockGeometry(
        body.mass,
        body.volume,
        np.asarray(body.com, dtype=float),
        tuple(body.inertia),
        polyhedron_faces(v, block.name),
        body.shape,
        float(np.ptp(v[:, 2])),
    )
