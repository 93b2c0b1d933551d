"""Structure geometry behind one interface (:mod:`.base`): rigid bodies with exact mass properties,
faces in the body frame, interfaces and monitoring points. Monolithic blocks and multi-drum columns
(:mod:`.block`, :mod:`.column`), and assemblies of any convex blocks (:mod:`.assembly`, the blocks
:mod:`.convex_block`, their interfaces found by geometry, :mod:`.interfaces`) generated as walls, arches and portals
(:mod:`.generators`) or read from block-model files (:mod:`.block_files`)."""

from .assembly import Assembly, as_assembly
from .base import (
    BoxGeometry,
    Face,
    MonitoringPoint,
    PrismGeometry,
    RestMassProperties,
    RigidBody,
    rest_mass_properties,
    top_monitoring_point,
)
from .block import RectangularBlock
from .block_files import read_block_model
from .column import SECTIONS, MultiDrumColumn
from .convex_block import ConvexBlock, ConvexGeometry
from .from_spec import STRUCTURE_BUILDERS, from_spec, is_block
from .frustum import frustum_mass_properties
from .generators import arch, portal, wall
from .materials import MATERIALS, Material, material_density
from .polyhedron import polyhedron_faces, polyhedron_mass_properties

__all__ = [
    "Assembly",
    "as_assembly",
    "ConvexBlock",
    "ConvexGeometry",
    "arch",
    "portal",
    "wall",
    "read_block_model",
    "polyhedron_faces",
    "polyhedron_mass_properties",
    "BoxGeometry",
    "Face",
    "MonitoringPoint",
    "MultiDrumColumn",
    "PrismGeometry",
    "RectangularBlock",
    "RigidBody",
    "RestMassProperties",
    "rest_mass_properties",
    "SECTIONS",
    "frustum_mass_properties",
    "top_monitoring_point",
    "STRUCTURE_BUILDERS",
    "from_spec",
    "is_block",
    "MATERIALS",
    "Material",
    "material_density",
]
