"""The structure interface read by the 3D engine and the blast loads: rigid bodies, faces, points.

Every structure (:class:`~.block.RectangularBlock`, :class:`~.column.MultiDrumColumn`) exposes

* ``bodies``: :class:`RigidBody` from the base up, each with its **solid** (``vertices``: the body is
  their convex hull) and the solid's exact mass, volume, centre of mass and inertia, the shape the
  engine builds its contact geometry from (:class:`BoxGeometry`, :class:`PrismGeometry`; not always
  the solid: a tapered drum collides as the prism of its base section) and its faces (:class:`Face`,
  body frame, outward unit normals). This is the one geometry of a structure: the engine, ``show``,
  the drawings and the report read these bodies (:func:`rest_mass_properties` for the totals);
* ``interfaces``: pairs ``(i, j)`` of bodies in contact at rest (ground = -1);
* ``monitoring_points``: :class:`MonitoringPoint` (default: the front-face centre of each body);
* ``front_x``: x of the lowest front face (the charge stands at ``front_x - standoff``);
* ``scaled(length_factor, density_factor)`` and ``describe()``.

Frames: world z up, ground z = 0, blast from -x towards +x; each body frame sits at the centre
of mass with axes along the world axes at rest.

Mass properties of a linearly tapered prism (the solid of a tapered drum): :mod:`.frustum`;
its faces: :func:`tapered_face`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "BoxGeometry",
    "Face",
    "MonitoringPoint",
    "PrismGeometry",
    "RigidBody",
    "RestMassProperties",
    "as_vertex_tuple",
    "centred_box_vertices",
    "frustum_vertices",
    "polygon_ring",
    "rectangle_ring",
    "rest_mass_properties",
    "tapered_face",
    "top_monitoring_point",
]


@dataclass(frozen=True)
class Face:
    """A plane face of a rigid body, in the body frame.

    Attributes
    ----------
    label : str
        "front" (faces -x, towards the charge), "rear", "side", "top" or "bottom".
    centre : tuple of float
        Centroid relative to the body's centre of mass [m].
    normal : tuple of float
        OUTWARD unit normal [-]; a pressure p pushes with ``-p * area * (R @ normal)``.
    area : float
        True face area [m^2] (for a tapered front face the slanted trapezoid; its projection
        on the y-z plane is ``area * |normal_x|``).
    in_contact : bool
        True when the face touches the ground or a neighbouring body at rest.
    vertices : tuple of tuple
        The face polygon in the body frame [m] (general blocks, :mod:`.assembly`; empty otherwise).
        A face of an assembly partly covered by an interface carries its **exposed** area and the
        exposed part's centroid in ``area`` and ``centre`` (what Method C loads); ``vertices`` is the
        whole face.
    """

    label: str
    centre: tuple
    normal: tuple
    area: float
    in_contact: bool = False
    vertices: tuple = ()


@dataclass(frozen=True)
class MonitoringPoint:
    """A point fixed to a body whose motion is recorded.

    Attributes
    ----------
    name : str
        "P-1", "P-2", ... (or a user name).
    body : int
        Index of the body in ``structure.bodies``.
    position : tuple of float
        Position in the body frame (relative to the centre of mass) [m].
    """

    name: str
    body: int
    position: tuple


@dataclass(frozen=True)
class BoxGeometry:
    """Contact geometry: a box of half-sizes (b, w, h) [m] along body x, y, z whose centre lies
    ``centre_z`` [m] above the body's centre of mass."""

    half_width: float
    half_depth: float
    half_height: float
    centre_z: float = 0.0

    def base_points(self) -> np.ndarray:
        """The four base corners in the body frame, shape (4, 3) [m]."""
        b, w, z = self.half_width, self.half_depth, self.centre_z - self.half_height
        return np.array([[b, w, z], [b, -w, z], [-b, w, z], [-b, -w, z]], dtype=float)

    @property
    def support_radius(self) -> tuple:
        """Half-extent of the base along body x and y [m] (toppling and overhang checks)."""
        return (self.half_width, self.half_depth)


@dataclass(frozen=True)
class PrismGeometry:
    """Contact geometry: a right prism on a regular polygon of ``sides`` vertices and
    circumradius ``radius`` [m], half-height ``half_height`` [m], centred ``centre_z`` [m] above
    the centre of mass. A flat faces -x (the polygon is turned by pi/sides)."""

    radius: float
    sides: int
    half_height: float
    centre_z: float = 0.0

    def polygon(self) -> np.ndarray:
        """Polygon vertices (sides, 2) [m] in the body x-y plane, a flat facing -x."""
        return polygon_ring(self.radius, self.sides)

    def vertices(self) -> np.ndarray:
        """Prism vertices (2 sides, 3) [m] in the body frame (base ring, then top ring)."""
        p = self.polygon()
        return frustum_vertices(p, p, self.centre_z - self.half_height, self.centre_z + self.half_height)

    def base_points(self) -> np.ndarray:
        """The base ring's vertices in the body frame, shape (sides, 3) [m]."""
        return self.vertices()[: self.sides]

    @property
    def support_radius(self) -> tuple:
        """Inradius of the base polygon along x and y [m] (a conservative support extent)."""
        r = self.radius * math.cos(math.pi / self.sides)
        return (r, r)


@dataclass(frozen=True)
class RigidBody:
    """One rigid body of a structure.

    Attributes
    ----------
    name : str
        "block", "D-1", "D-2", ...
    mass : float
        Mass [kg].
    com : tuple of float
        World position of the centre of mass at rest [m].
    inertia : tuple of float
        Principal moments about body axes x, y, z through the centre of mass [kg m^2] (the axes
        are the world axes at rest).
    shape : BoxGeometry or PrismGeometry
        Contact geometry for the engine (body frame): what MuJoCo collides, not always the solid (a
        tapered drum collides as the box or polygon prism of its base section, docs/sim3d.md).
    faces : tuple of Face
        Faces in the body frame, outward normals.
    load_face : Face
        The face Method A loads (the reflected pulse on the whole projected front): the front
        face of a box or a square drum; for a polygonal drum the projected silhouette of its
        front (width = diameter, tapered), normal as a square drum's front face.
    base_height : float
        Height of the body's base above its centre of mass, negative [m] (``-z_c``).
    toppling_angle : float
        Tilt [rad] at which the body's centre of mass passes over its base edge
        (``atan(support half-width / z_c)``).
    volume : float
        Volume of the solid [m^3] (``mass`` = density x ``volume``).
    vertices : tuple of tuple
        The solid's vertices in the body frame [m]; the body is their convex hull (a box, a frustum,
        a general block). ``mass``, ``volume``, ``com`` and ``inertia`` are this solid's, and it is
        what ``show`` and the report draw.
    """

    name: str
    mass: float
    com: tuple
    inertia: tuple
    shape: object
    faces: tuple
    load_face: Face
    base_height: float
    toppling_angle: float
    volume: float
    vertices: tuple


@dataclass(frozen=True)
class RestMassProperties:
    """Totals of a structure's bodies at rest: ``mass`` [kg], ``volume`` [m^3] and ``centre_of_mass``
    (world position at rest, a tuple of 3 floats) [m]."""

    mass: float
    volume: float
    centre_of_mass: tuple


def rest_mass_properties(bodies) -> RestMassProperties:
    """Total mass, volume and centre of mass at rest of ``bodies`` (:class:`RigidBody`): the sums of
    the solids the engine simulates (the centre of mass is the mass-weighted mean of the bodies')."""
    bodies = tuple(bodies)
    m = np.array([b.mass for b in bodies], dtype=float)
    c = np.array([b.com for b in bodies], dtype=float)
    M = float(sum(b.mass for b in bodies))  # summed as every structure's ``mass`` and the run summary's
    return RestMassProperties(M, float(sum(b.volume for b in bodies)), tuple(float(x) for x in m @ c / M))


def polygon_ring(radius: float, sides: int) -> np.ndarray:
    """The vertices (sides, 2) [m] of a regular polygon of circumradius ``radius`` [m] in the x-y plane,
    turned by pi/sides so that a flat faces -x (the charge), counter-clockwise."""
    a = (np.arange(sides) + 0.5) * 2.0 * math.pi / sides + math.pi
    return radius * np.column_stack([np.cos(a), np.sin(a)])


def frustum_vertices(base, top, z_base: float, z_top: float) -> np.ndarray:
    """The vertices (2 k, 3) [m] of the solid between a base polygon (k, 2) at height ``z_base`` and a top
    polygon (k, 2) at ``z_top`` [m] (base ring, then top ring): a prism when they are equal, a frustum
    when the top is the base scaled about the axis."""
    base, top = np.asarray(base, dtype=float), np.asarray(top, dtype=float)
    return np.vstack(
        [
            np.column_stack([base, np.full(len(base), float(z_base))]),
            np.column_stack([top, np.full(len(top), float(z_top))]),
        ]
    )


def centred_box_vertices(half_width: float, half_depth: float, half_height: float, centre_z: float = 0.0) -> np.ndarray:
    """The eight corners (8, 3) [m] of a box of half-sizes (b, w, h) [m] along x, y, z centred ``centre_z``
    [m] above the origin (a box between bounds: :func:`blastscale.structures.generators.box_vertices_from_bounds`)."""
    ring = rectangle_ring(half_width, half_depth)
    return frustum_vertices(ring, ring, centre_z - half_height, centre_z + half_height)


def rectangle_ring(half_width: float, half_depth: float) -> np.ndarray:
    """The corners (4, 2) [m] of a rectangle of half-sizes (b, w) along x, y, centred on the axis,
    counter-clockwise."""
    return np.array(
        [[-half_width, -half_depth], [half_width, -half_depth], [half_width, half_depth], [-half_width, half_depth]],
        dtype=float,
    )


def as_vertex_tuple(points) -> tuple:
    """Points (n, 3) [m] as a tuple of float triples (hashable, for :attr:`RigidBody.vertices`)."""
    return tuple(tuple(float(x) for x in p) for p in np.asarray(points, dtype=float).reshape(-1, 3))


def top_monitoring_point(structure) -> MonitoringPoint:
    """The structure's "top": its highest monitoring point at rest, for every kind (the crown of an arch,
    the lintel of a portal, the top drum of a column, the top course of a wall).

    Heights are those at rest in the world frame, ``z = bodies[p.body].com[2] + p.position[2]`` [m].
    Points level to 1e-9 of the highest (a course of equal blocks, the two crown voussoirs of an even
    arch) go to the last of them, so that a structure and its scaled copy name the same point.

    Parameters
    ----------
    structure : structure
        Anything with ``bodies`` (:class:`RigidBody`) and ``monitoring_points`` (:class:`MonitoringPoint`).

    Returns
    -------
    MonitoringPoint
    """
    points = tuple(structure.monitoring_points)
    bodies = structure.bodies
    z = np.array([bodies[p.body].com[2] + p.position[2] for p in points], dtype=float)
    level = z >= z.max() - 1e-9 * max(float(np.abs(z).max()), np.finfo(float).tiny)
    return points[int(np.flatnonzero(level)[-1])]


def tapered_face(
    label: str,
    d0: float,
    d1: float,
    w0: float,
    w1: float,
    height: float,
    z_com: float,
    angle: float,
    in_contact: bool = False,
) -> Face:
    """A side face of a linearly tapered prism, as a trapezoid in the body frame.

    The face lies at the horizontal distance d(z) = d0 + (d1 - d0) z / H from the body axis,
    in the horizontal direction ``angle`` [rad] (pi: -x, the front), and is w(z) wide
    (w0 at the base, w1 at the top). Centroid at ``z_f = H (w0 + 2 w1) / (3 (w0 + w1))`` above
    the base; outward normal ``(H e, d0 - d1) / slant`` with e the horizontal unit vector of
    ``angle`` and ``slant = sqrt(H^2 + (d0 - d1)^2)``; area ``(w0 + w1)/2 * slant`` [m^2], whose
    projection on the vertical plane normal to e is the trapezoid ``(w0 + w1) H / 2``.

    Parameters
    ----------
    label : str
        Face label.
    d0, d1 : float
        Distance of the face from the axis at the base and at the top [m].
    w0, w1 : float
        Face width at the base and at the top [m].
    height : float
        H [m].
    z_com : float
        Height of the body's centre of mass above its base [m] (the body frame origin).
    angle : float
        Direction of the outward normal's horizontal part [rad], from +x towards +y.
    in_contact : bool
        Whether the face touches a neighbour.

    Returns
    -------
    Face
    """
    H = height
    zf = H * (w0 + 2.0 * w1) / (3.0 * (w0 + w1))
    d = d0 + (d1 - d0) * zf / H
    slant = math.hypot(H, d0 - d1)
    c, s = math.cos(angle), math.sin(angle)
    c, s = (0.0 if abs(c) < 1e-15 else c), (0.0 if abs(s) < 1e-15 else s)
    centre = (d * c, d * s, zf - z_com)
    normal = (H * c / slant, H * s / slant, (d0 - d1) / slant)
    return Face(label, centre, normal, 0.5 * (w0 + w1) * slant, in_contact)
