"""Build the MuJoCo model (an MJCF string written in code) of rigid bodies on a rigid plane.

The geometry comes from :mod:`blastscale.structures`. Each body is described by a
:class:`BodySpec`: a shape that knows how to write its own MJCF ``<geom>`` (and assets), its
mass, the points of its base (for uplift and sliding recorders) and its loaded front face
(for the blast force). Boxes (:class:`BoxShape`, from
:class:`~blastscale.structures.block.RectangularBlock`) are implemented; a convex-mesh shape
for the drums of multi-drum columns only has to provide the same members
(``mjcf_geom``, ``mjcf_assets``, ``contact_geoms``, ``base_points``, ``pivot_points``,
``front_face``, ``mass``).

Conventions (world frame): z up, the ground plane is z = 0, the blast comes from -x and
pushes towards +x; the loaded front face is the body's -x face, its inward normal the
body's +x axis. Each body frame sits at the centre of mass with principal axes along the
block's edges (x = width 2b, y = depth 2w, z = height 2h).

Contacts are explicit ``<pair>`` elements between the plane and every body geom, so the
contact parameters of :class:`~.contact.ContactSettings` apply exactly (no MuJoCo mixing of
two geoms' ``solref``, which silently averages in the plane's default 20 ms), and the
frictional directions can get their own ``solreffriction``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .contact import ContactSettings

__all__ = ["BoxShape", "FrontFace", "BodySpec", "Scene", "build_scene", "block_scene"]


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
    """A homogeneous box of half-sizes (b, w, h) [m] along body x, y, z and density [kg/m^3]."""

    half_width: float
    half_depth: float
    half_height: float
    density: float

    @classmethod
    def from_block(cls, block: RectangularBlock) -> "BoxShape":
        """The box of a :class:`~blastscale.structures.block.RectangularBlock` (2b x 2w x 2h)."""
        return cls(block.b, block.w, block.h, block.density)

    @property
    def mass(self) -> float:
        """Mass [kg]."""
        return 8.0 * self.half_width * self.half_depth * self.half_height * self.density

    @property
    def half_height_below_com(self) -> float:
        """Distance from the centre of mass down to the base [m]."""
        return self.half_height

    def base_points(self) -> np.ndarray:
        """The four base corners in the body frame, shape (4, 3) [m]."""
        b, w, h = self.half_width, self.half_depth, self.half_height
        return np.array([[b, w, -h], [b, -w, -h], [-b, w, -h], [-b, -w, -h]], dtype=float)

    def pivot_points(self) -> np.ndarray:
        """Mid-points of the rear (+x) and front (-x) base edges in the body frame, shape (2, 3) [m]."""
        b, h = self.half_width, self.half_height
        return np.array([[b, 0.0, -h], [-b, 0.0, -h]], dtype=float)

    def front_face(self) -> FrontFace:
        """The -x face, loaded towards +x: area 2h x 2w."""
        return FrontFace((-self.half_width, 0.0, 0.0), (1.0, 0.0, 0.0), 4.0 * self.half_height * self.half_depth)

    def mjcf_assets(self, name: str) -> str:
        """No assets for a primitive box."""
        return ""

    def contact_geoms(self, name: str) -> list[str]:
        """Names of the geoms paired with the ground (one box here; a drum or a base made of
        several geoms lists them all)."""
        return [name]

    def mjcf_geom(self, name: str) -> str:
        """The ``<geom>`` element. Collisions come from explicit pairs only (contype = conaffinity = 0)."""
        return (
            f'<geom name="{name}" type="box" size="{float(self.half_width)!r} {float(self.half_depth)!r} {float(self.half_height)!r}" '
            f'density="{float(self.density)!r}" contype="0" conaffinity="0"/>'
        )


@dataclass(frozen=True)
class BodySpec:
    """One free rigid body: a shape and the world position of its centre of mass [m]."""

    name: str
    shape: BoxShape
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True, eq=False)
class Scene:
    """A compiled MuJoCo model and what the simulation needs to drive and record it.

    Attributes
    ----------
    xml : str
        The MJCF text.
    model : mujoco.MjModel
        The compiled model.
    bodies : tuple of BodySpec
        The free bodies, in MuJoCo body order (body id = index + 1).
    contact : ContactSettings
        The settings the model was built with.
    gravity : float
        Gravitational acceleration [m/s^2].
    """

    xml: str
    model: object = field(repr=False)
    bodies: tuple
    contact: ContactSettings
    gravity: float

    def body_id(self, index: int = 0) -> int:
        """MuJoCo id of body ``index``."""
        return index + 1


def build_scene(bodies, contact: ContactSettings, gravity: float = STANDARD_GRAVITY) -> Scene:
    """Compile free rigid bodies on a rigid ground plane into a MuJoCo model.

    Parameters
    ----------
    bodies : sequence of BodySpec
        Bodies (each gets a free joint: 3 translations + 3 rotations).
    contact : ContactSettings
        Contact, time-step and solver settings.
    gravity : float
        Gravitational acceleration g [m/s^2], > 0, along -z.

    Returns
    -------
    Scene
    """
    import mujoco  # imported here: the rest of blastscale works without MuJoCo installed

    g = float(check_positive("gravity", gravity, "m/s^2"))
    bodies = tuple(bodies)
    if not bodies:
        raise BlastscaleInputError("bodies = () is out of range: at least one body is needed")
    assets = "".join(b.shape.mjcf_assets(f"{b.name}_geom") for b in bodies)
    worldbody = ['<geom name="ground" type="plane" size="0 0 1" contype="0" conaffinity="0"/>']
    pairs = []
    for b in bodies:
        px, py, pz = (float(v) for v in b.position)
        qw, qx, qy, qz = (float(v) for v in b.quaternion)
        worldbody.append(
            f'<body name="{b.name}" pos="{float(px)!r} {float(py)!r} {float(pz)!r}" quat="{float(qw)!r} {float(qx)!r} {float(qy)!r} {float(qz)!r}">'
            f'<freejoint name="{b.name}_free"/>{b.shape.mjcf_geom(f"{b.name}_geom")}</body>'
        )
        pairs.extend(
            f'<pair geom1="ground" geom2="{g}" {contact.mjcf_pair_attributes()}/>'
            for g in b.shape.contact_geoms(f"{b.name}_geom")
        )
    asset_block = f"<asset>{assets}</asset>" if assets else ""
    xml = (
        '<mujoco model="blastscale">'
        '<compiler angle="radian" boundmass="0" boundinertia="0"/>'
        f"{contact.mjcf_option(g)}{asset_block}"
        f'<worldbody>{"".join(worldbody)}</worldbody><contact>{"".join(pairs)}</contact></mujoco>'
    )
    model = mujoco.MjModel.from_xml_string(xml)
    return Scene(xml=xml, model=model, bodies=bodies, contact=contact, gravity=g)


def block_scene(
    block: RectangularBlock,
    contact: ContactSettings | None = None,
    gravity: float = STANDARD_GRAVITY,
    *,
    rotation: float = 0.0,
    shape_type: type = None,
) -> Scene:
    """A single rectangular block standing on the ground (optionally tilted onto its +x edge).

    Parameters
    ----------
    block : RectangularBlock
        The block (2b along x, 2w along y, 2h along z).
    contact : ContactSettings, optional
        Default :class:`ContactSettings()` (full-scale settings).
    gravity : float
        g [m/s^2].
    rotation : float
        Initial tilt theta_0 [rad] about the y axis, resting on the +x base edge when > 0 and on
        the -x edge when < 0; |theta_0| < pi/2.
    shape_type : type, optional
        Class with ``from_block(block)`` building the body's shape; default :class:`BoxShape`.

    Returns
    -------
    Scene
    """
    contact = ContactSettings() if contact is None else contact
    shape = (BoxShape if shape_type is None else shape_type).from_block(block)
    th = float(rotation)
    if not abs(th) < math.pi / 2:
        raise BlastscaleInputError(f"initial rotation = {th:.6g} rad is out of range: valid range is (-pi/2, pi/2)")
    b, h = shape.half_width, shape.half_height
    s = 1.0 if th >= 0 else -1.0
    # pivot edge at x = s*b, z = 0; centre of mass rotated about it by th (positive: top towards +x)
    x = s * b - s * b * math.cos(th) + h * math.sin(th)
    z = b * abs(math.sin(th)) + h * math.cos(th)
    quat = (math.cos(th / 2), 0.0, math.sin(th / 2), 0.0)  # rotation th about +y: body z tilts towards +x
    return build_scene([BodySpec("block", shape, (x, 0.0, z), quat)], contact, gravity)
