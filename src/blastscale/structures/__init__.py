"""Structure geometry: monolithic blocks and multi-drum columns behind one interface
(:mod:`.base`): rigid bodies with exact mass properties, faces in the body frame, interfaces and
monitoring points."""

from .base import BoxGeometry, Face, MonitoringPoint, PrismGeometry, RigidBody, frustum_mass_properties
from .block import STANDARD_GRAVITY, RectangularBlock
from .column import SECTIONS, MultiDrumColumn
from .from_spec import STRUCTURE_BUILDERS, from_spec, is_block
from .materials import MATERIALS, Material, material_density

__all__ = [
    "BoxGeometry",
    "Face",
    "MonitoringPoint",
    "MultiDrumColumn",
    "PrismGeometry",
    "RectangularBlock",
    "RigidBody",
    "SECTIONS",
    "STANDARD_GRAVITY",
    "frustum_mass_properties",
    "STRUCTURE_BUILDERS",
    "from_spec",
    "is_block",
    "MATERIALS",
    "Material",
    "material_density",
]
