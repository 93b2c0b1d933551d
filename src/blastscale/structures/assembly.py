"""Assemblies of general rigid blocks: any convex polyhedron, in any position at rest.

A :class:`ConvexBlock` (:mod:`.convex_block`) is the convex hull of its vertices (world frame at rest,
metres, z up, the ground at z = 0) with its density; its mass properties are exact for the polyhedron
(:func:`~.polyhedron.polyhedron_mass_properties`). An :class:`Assembly` of N blocks exposes the
structure interface of :mod:`.base` (``bodies``, ``interfaces``, ``monitoring_points``,
``front_x``, ``scaled``, ``describe``), with everything that depends on contact found by geometry
(:mod:`.interfaces`): the interfaces (coplanar, opposed, overlapping faces, with their overlap
polygons), the ``in_contact`` flag of each face, each face's **exposed** area and centroid (the face
minus the interfaces on it: what Method C loads), and the checks of a block model.

Engine geometry: a block that is an axis-aligned box becomes a box (its closed-form mass properties,
equal to the polyhedron's to round-off), any other block a convex mesh of its vertices
(:class:`ConvexGeometry`, :mod:`.convex_block`); a non-diagonal inertia tensor is passed whole (MuJoCo ``fullinertia``).

**Supports** (``Assembly(..., supports=...)``, COMPAS's ``is_support`` blocks): blocks fixed to the
ground, not simulated. They take part in the checks (they may reach below the ground and carry the
others: a block resting on a support is connected to the ground) and in the interfaces, where a
support counts as the ground (index -1); they are not among ``bodies`` (and not in ``mass``); the
engine welds the ones that rise above the ground to the world (:attr:`Assembly.fixed_shapes`).

Collapse of an assembly (``collapse_rule = "fallen"``, :mod:`blastscale.sim3d.record`): a block
*fell* when at some recorded time its centre of mass lies below its rest height by more than
:data:`FALL_DROP_FRACTION` of the block's own height, or it has turned by more than
:data:`FALL_TILT_DEG` (it lies on another face); the assembly collapsed when any block fell.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_positive_scalar
from .base import Face, MonitoringPoint, RigidBody, as_vertex_tuple
from .convex_block import ConvexBlock, block_geometry, given_block_geometry
from .interfaces import CONTACT_TOLERANCE, check_assembly, find_interfaces
from .polyhedron import face_label

__all__ = ["Assembly", "as_assembly", "FALL_DROP_FRACTION", "FALL_TILT_DEG"]

#: A block fell when its centre of mass dropped by more than this fraction of its own height [-].
FALL_DROP_FRACTION = 0.5
#: ... or when it turned by more than this angle [deg] (it lies on another face).
FALL_TILT_DEG = 45.0
#: A face whose exposed area is below this fraction of its area is in contact [-].
COVERED_FRACTION = 1e-6


@dataclass(frozen=True)
class Assembly:
    """N convex blocks standing on a rigid ground (z = 0), free to rock, slide and fall.

    Parameters
    ----------
    blocks : sequence of ConvexBlock
        The blocks, at rest; names must be unique.
    extra_points : sequence of MonitoringPoint
        User monitoring points (body index, body-frame position [m]) after the default ones.
    kind : str
        What generated it ("assembly", "wall", "arch", "portal"), for ``describe()``.
    parameters : tuple of (str, value)
        The generator's parameters, SI keys, for ``describe()``.
    check : bool
        Check the block model (overlaps, floating blocks, millimetres; :func:`~.interfaces.check_assembly`).
    supports : sequence of ConvexBlock
        Blocks fixed to the ground (module docstring); their names are unique among all blocks.
    source_bodies : tuple of RigidBody
        When the blocks are another structure's bodies (:func:`as_assembly`: one per block, their solids'
        vertices the blocks'): their mass, volume, centre of mass, inertia and contact shape are kept as
        given, not integrated again; empty otherwise. ``scaled`` and ``rounded`` copies integrate again.
    """

    blocks: tuple
    extra_points: tuple = ()
    kind: str = "assembly"
    parameters: tuple = ()
    check: bool = True
    supports: tuple = ()
    source_bodies: tuple = ()

    collapse_rule = "fallen"

    def __post_init__(self):
        blocks = tuple(self.blocks)
        if not blocks:
            raise BlastscaleInputError("blocks = () is out of range: an assembly needs at least one block")
        object.__setattr__(self, "blocks", blocks)
        object.__setattr__(self, "supports", tuple(self.supports))
        names = [b.name for b in blocks + self.supports]
        seen: set = set()
        dup = sorted({n for n in names if n in seen or seen.add(n)})  # one pass (a file of 10^5 blocks)
        if dup:
            raise BlastscaleInputError(f"block name {dup[0]!r} is used twice: block names must be unique")
        for p in self.extra_points:
            if not isinstance(p, MonitoringPoint) or not 0 <= p.body < len(blocks):
                raise BlastscaleInputError(
                    f"point = {p!r} is out of range: must be a MonitoringPoint on a block 0-{len(blocks) - 1}"
                )
        if self.source_bodies and len(self.source_bodies) != len(blocks):
            raise BlastscaleInputError(
                f"source bodies = {len(self.source_bodies)} is out of range: must be one per block ({len(blocks)})"
            )
        if self.check:
            everything = blocks + self.supports
            faces = [x.faces for x in self._geometries + self._support_geometries]
            check_assembly(
                names, [b.points for b in everything], faces, self._all_interfaces, self.size, fixed=len(self.supports)
            )

    # -- derived geometry (computed once) ------------------------------------------------
    @functools.cached_property
    def _geometries(self) -> list:
        if self.source_bodies:
            return [given_block_geometry(b, body) for b, body in zip(self.blocks, self.source_bodies)]
        return [block_geometry(b) for b in self.blocks]

    @functools.cached_property
    def _support_geometries(self) -> list:
        return [block_geometry(b) for b in self.supports]

    @property
    def size(self) -> float:
        """Largest extent of the assembly, supports included [m]."""
        v = np.vstack([b.points for b in self.blocks + self.supports])
        return float(np.ptp(v, axis=0).max())

    @functools.cached_property
    def _all_interfaces(self) -> tuple:
        """Interfaces among blocks and supports, supports numbered after the blocks."""
        return tuple(find_interfaces([g.faces for g in self._geometries + self._support_geometries], self.size))

    @functools.cached_property
    def interface_details(self) -> tuple:
        """The :class:`~.interfaces.Interface` list (ground first), found by geometry; an interface
        with a support is one with the ground (-1, its normal into the block), unless it lies in the
        ground plane (z = 0), where the plane's own interface is the same contact."""
        n, tol = len(self.blocks), CONTACT_TOLERANCE * self.size
        ground, joints = [], []
        for itf in self._all_interfaces:
            if itf.second < n:
                (ground if itf.first < 0 else joints).append(itf)
            elif 0 <= itf.first < n and not np.all(np.abs(np.asarray(itf.polygon)[:, 2]) <= tol):
                # block - support: the support is the ground (in the ground plane: the plane's own interface)
                ground.append(
                    replace(
                        itf, first=-1, second=itf.first, normal=tuple(-x for x in itf.normal), faces=(-1, itf.faces[0])
                    )
                )
        return tuple(sorted(ground, key=lambda i: i.second)) + tuple(joints)

    @property
    def interfaces(self) -> tuple:
        """Pairs (i, j) of blocks in contact at rest, ground (or a support) = -1 (ground ones first),
        each pair once."""
        return tuple(dict.fromkeys(itf.pair for itf in self.interface_details))

    @property
    def fixed_shapes(self) -> tuple:
        """(name, contact geometry, centre [m]) of each support that rises above the ground (a
        support wholly below it is the ground plane as far as contact goes), for the engine."""
        tol = 1e-6 * self.size
        return tuple(
            (b.name, g.shape, tuple(float(x) for x in g.com))
            for b, g in zip(self.supports, self._support_geometries)
            if b.points[:, 2].max() > tol
        )

    @functools.cached_property
    def bodies(self) -> tuple:
        """One :class:`~.base.RigidBody` per block: exact mass properties, engine geometry, faces in
        the body frame with their exposed area and centroid, the Method A face (the exposed face
        turned most towards -x, by projected exposed area)."""
        covered: dict = {}
        for itf in self.interface_details:
            for blk, fk in ((itf.first, itf.faces[0]), (itf.second, itf.faces[1])):
                if blk >= 0:
                    covered.setdefault((blk, fk), []).append((itf.area, np.asarray(itf.centroid)))
        out = []
        for i, (b, g) in enumerate(zip(self.blocks, self._geometries)):
            faces = []
            for k, f in enumerate(g.faces):
                parts = covered.get((i, k), [])
                a_cov = sum(a for a, _ in parts)
                exposed = max(f.area - a_cov, 0.0)
                touching = exposed <= COVERED_FRACTION * f.area
                cent = (
                    f.centroid
                    if not parts or touching
                    else (f.area * f.centroid - sum(a * c for a, c in parts)) / exposed
                )
                faces.append(
                    Face(
                        face_label(f.normal),
                        tuple(float(x) for x in cent - g.com),
                        tuple(float(x) for x in f.normal),
                        float(f.area if not parts else exposed),
                        touching,
                        as_vertex_tuple(f.vertices - g.com),
                    )
                )
            load = _load_face(faces)
            zb = float(np.min(b.points[:, 2]) - g.com[2])
            sx, sy = g.shape.support_radius
            out.append(
                RigidBody(
                    b.name,
                    g.mass,
                    tuple(float(x) for x in g.com),
                    g.inertia,
                    g.shape,
                    tuple(faces),
                    load,
                    zb,
                    math.atan2(min(sx, sy), max(-zb, 1e-300)),
                    g.volume,
                    as_vertex_tuple(b.points - g.com),
                )
            )
        return tuple(out)

    @property
    def heights(self) -> tuple:
        """Each block's vertical extent at rest [m] (the fall rule's reference)."""
        return tuple(g.height for g in self._geometries)

    @property
    def monitoring_points(self) -> tuple:
        """One point per block, named after it, at its Method A face's centre (the exposed front), then
        ``extra_points``."""
        pts = tuple(MonitoringPoint(b.name, i, b.load_face.centre) for i, b in enumerate(self.bodies))
        return pts + tuple(self.extra_points)

    @property
    def front_x(self) -> float:
        """x of the front (the smallest x of any block) [m]: the charge stands at ``front_x - standoff``."""
        return float(min(b.points[:, 0].min() for b in self.blocks))

    @property
    def mass(self) -> float:
        """Total mass [kg]."""
        return float(sum(g.mass for g in self._geometries))

    @property
    def volume(self) -> float:
        """Total volume [m^3]."""
        return float(sum(g.volume for g in self._geometries))

    def describe(self) -> dict:
        """Kind, size (supports included), blocks, mass (supports excluded) and the generator's
        parameters (SI keys); ``supports`` (their number) when there are any."""
        v = np.vstack([b.points for b in self.blocks + self.supports])
        dens = {b.density for b in self.blocks}
        out = {
            "kind": self.kind,
            **dict(self.parameters),
            "blocks": len(self.blocks),
            "height_m": float(v[:, 2].max()),
            "length_m": float(np.ptp(v[:, 1])),
            "thickness_m": float(np.ptp(v[:, 0])),
            "density_kg_m3": float(next(iter(dens))) if len(dens) == 1 else float(self.mass / self.volume),
            "mass_kg": self.mass,
            "interfaces": len(self.interface_details),
        }
        if self.supports:
            out["supports"] = len(self.supports)
        return out

    # -- scaling ---------------------------------------------------------------------------
    def scaled(self, factors) -> "Assembly":
        """The geometrically similar assembly: coordinates x ``factors.length`` (lambda), densities x
        ``factors.density`` (gamma)."""
        L = check_positive_scalar("scale", factors.length)
        g = check_positive_scalar("density ratio", factors.density)
        return self._remade(lambda v: np.asarray(v, dtype=float) * L, g, L)

    def rounded(self, length: float, digits: int = 12) -> "Assembly":
        """A copy with coordinates quantised to ``length * 10**-digits`` and densities to ``digits``
        significant digits (the engine's reference units: a structure and its exactly scaled model
        then give bitwise the same blocks)."""
        q = float(length) * 10.0 ** (-digits)
        return self._remade(lambda v: np.round(np.asarray(v, dtype=float) / q) * q, 1.0, 1.0, digits)

    def _remade(self, fv, density_factor, length_factor, digits=None) -> "Assembly":
        def dens(d):
            x = d * density_factor
            return float(f"{x:.{digits}g}") if digits else x

        blocks = tuple(replace(b, vertices=fv(b.points), density=dens(b.density)) for b in self.blocks)
        supports = tuple(replace(b, vertices=fv(b.points), density=dens(b.density)) for b in self.supports)
        pts = tuple(
            replace(p, position=tuple(float(x) for x in np.asarray(p.position) * length_factor))
            for p in self.extra_points
        )
        params = tuple(
            (k, v * length_factor if k.endswith("_m") and isinstance(v, float) else v) for k, v in self.parameters
        )
        return Assembly(blocks, pts, self.kind, params, check=False, supports=supports)


def _load_face(faces) -> Face:
    """The exposed face turned most towards -x (largest projected exposed area); a zero-area front
    face when the block shows no face to -x."""
    best = None
    for f in faces:
        proj = -f.normal[0] * f.area
        if not f.in_contact and proj > 1e-12 * f.area and (best is None or proj > best[0]):
            best = (proj, f)
    if best is not None:
        return best[1]
    return Face("front", (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0), 0.0, True)


def as_assembly(structure) -> "Assembly":
    """``structure`` as an :class:`Assembly` (itself when it is one): one block per body, the convex hull
    of the body's solid (:attr:`~.base.RigidBody.vertices`: a block's box, a drum's frustum) placed at its
    centre of mass at rest, keeping the body's mass, volume, inertia and contact shape
    (``source_bodies``): what is drawn and described is what the engine simulates."""
    if isinstance(structure, Assembly):
        return structure
    d = structure.describe()
    bodies = tuple(structure.bodies)
    blocks = tuple(
        ConvexBlock(
            b.name, np.asarray(b.vertices) + np.asarray(b.com), float(d.get("density_kg_m3") or b.mass / b.volume)
        )
        for b in bodies
    )
    return Assembly(blocks, kind=str(d.get("kind", "structure")), check=False, source_bodies=bodies)
