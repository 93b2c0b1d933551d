"""Build the MuJoCo model (an MJCF string written in code) of rigid bodies on a rigid plane.

The geometry comes from :mod:`blastscale.structures`. Each body is described by a
:class:`BodySpec`: a shape that knows how to write its own MJCF ``<geom>`` (and assets), its
mass, the points of its base (for uplift and sliding recorders) and its loaded front face
(for the blast force): boxes (:class:`BoxShape`), prisms and convex meshes (:class:`MeshShape`)
provide the same members (:mod:`.shapes`). An assembly's supports are geoms of the world
body (the ground).

Conventions (world frame): z up, the ground plane is z = 0, the blast comes from -x and
pushes towards +x; the loaded front face is the body's -x face, its inward normal the
body's +x axis. Each body frame sits at the centre of mass with principal axes along the
block's edges (x = width 2b, y = depth 2w, z = height 2h).

Interfaces (surfaces in contact at rest) are explicit ``<pair>`` elements with the parameters of
:class:`~.contact.ContactSettings`; every other two surfaces collide through MuJoCo's broad phase
with the same parameters on every geom (so MuJoCo's mixing of two geoms' settings returns them
unchanged) and engage after a small overlap; the bodies are numbered for the solver
(:mod:`.collision`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..constants import STANDARD_GRAVITY
from ..structures.block import RectangularBlock
from .collision import BROAD_PHASE, body_order, engagement_depth, side_joints
from .contact import ContactSettings, mjcf_number
from .initial import tilt_bodies
from .shapes import engine_shape

__all__ = ["BodySpec", "Scene", "build_scene", "block_scene", "compile_scene", "structure_scene"]


@dataclass(frozen=True)
class BodySpec:
    """One free rigid body: a shape, the world position of its centre of mass [m], its
    orientation (unit quaternion w, x, y, z) and, optionally, explicit mass [kg] and inertia about
    the body axes [kg m^2]: principal (3,) or the full tensor (6,) ``(Ixx, Iyy, Izz, Ixy, Ixz, Iyz)``
    of a general block (otherwise MuJoCo computes them from the shape's density)."""

    name: str
    shape: object
    position: tuple[float, float, float]
    quaternion: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
    mass: float | None = None
    inertia: tuple | None = None

    def mjcf_inertial(self) -> str:
        """The ``<inertial>`` element at the body origin (the centre of mass), or ""."""
        if self.mass is None:
            return ""
        i = " ".join(mjcf_number(x) for x in self.inertia)
        kind = "fullinertia" if len(self.inertia) == 6 else "diaginertia"
        return f'<inertial pos="0 0 0" mass="{mjcf_number(self.mass)}" {kind}="{i}"/>'


@dataclass(frozen=True, eq=False)
class Scene:
    """A compiled MuJoCo model and what the simulation needs to drive and record it.

    Attributes
    ----------
    xml : str
        The MJCF text.
    mj_model : mujoco.MjModel
        The compiled MuJoCo model.
    bodies : tuple of BodySpec
        The free bodies, in the structure's order.
    contact : ContactSettings
        The settings the model was built with.
    gravity : float
        Gravitational acceleration [m/s^2].
    body_ids : ndarray of int (nbody,)
        MuJoCo's body id of each of ``bodies`` (:func:`~.collision.body_order`; 1, 2, ... unless the
        bodies were renumbered for the solver). Per-body MuJoCo arrays are read as ``d.xpos[body_ids]``
        and free-joint state as :meth:`qpos_index` / :meth:`qvel_index`.
    settled : dict or None
        Where :func:`~.integrate.integrate` keeps the state at the end of settling, shared by every scene of the
        same model (:func:`~.reference.reference_scene`'s cache); None: settled on every run.
    """

    xml: str
    mj_model: object = field(repr=False)
    bodies: tuple
    contact: ContactSettings
    gravity: float
    body_ids: np.ndarray = field(default=None, repr=False)
    settled: dict | None = field(default=None, repr=False)

    def __post_init__(self):
        if self.body_ids is None:
            object.__setattr__(self, "body_ids", np.arange(1, len(self.bodies) + 1))

    def qpos_index(self) -> np.ndarray:
        """Indices into MuJoCo's ``qpos`` giving the bodies' (x, y, z, qw, qx, qy, qz) in the
        structure's order, shape (7 nbody,)."""
        return ((self.body_ids[:, None] - 1) * 7 + np.arange(7)).ravel()

    def qvel_index(self) -> np.ndarray:
        """Indices into MuJoCo's ``qvel`` giving the bodies' (v, omega_body) in the structure's
        order, shape (6 nbody,)."""
        return ((self.body_ids[:, None] - 1) * 6 + np.arange(6)).ravel()


def _free_body_xml(b: BodySpec) -> str:
    """The ``<body>`` element of a free body: its pose, free joint, inertial and geoms."""
    pos = " ".join(mjcf_number(float(v)) for v in b.position)
    quat = " ".join(mjcf_number(float(v)) for v in b.quaternion)
    return (
        f'<body name="{b.name}" pos="{pos}" quat="{quat}">'
        f'<freejoint name="{b.name}_free"/>{b.mjcf_inertial()}{b.shape.mjcf_geom(f"{b.name}_geom")}</body>'
    )


def build_scene(
    bodies, contact: ContactSettings, gravity=STANDARD_GRAVITY, pairs=None, fixed=(), compile=True, side_pairs=()
) -> Scene:
    """Compile free rigid bodies on a rigid ground plane into a MuJoCo model.

    Parameters
    ----------
    bodies : sequence of BodySpec
        Bodies (each gets a free joint: 3 translations + 3 rotations).
    contact : ContactSettings
        Contact, time-step and solver settings.
    gravity : float
        Gravitational acceleration g [m/s^2], > 0, along -z.
    pairs : sequence of (int, int), optional
        The interfaces: bodies in contact at rest, by index (-1 = ground), one explicit ``<pair>``
        per geom pair with the settings of ``contact``; every other two surfaces collide as
        :mod:`.collision` says. Default: every body with the ground.
    fixed : sequence of BodySpec
        Supports welded to the ground (no joint: geoms of MuJoCo's world body, placed at ``position``,
        unrotated); part of the ground (-1) in ``pairs`` and in the collision rules.
    compile : bool
        Compile the MJCF (:func:`compile_scene`); False: ``mj_model`` is None (the text alone, a cache key).
    side_pairs : collection of (int, int)
        The interfaces among ``pairs`` that are side joints (:func:`~.collision.side_joints`): they engage once
        their faces overlap by :func:`~.collision.engagement_depth`, the others at contact (:mod:`.collision`,
        rule 1).

    Returns
    -------
    Scene

    Notes
    -----
    Multi-point convex collision (MuJoCo's ``multiccd``) is required for flat drum-on-drum
    contacts: without it a 10-drum column drifts 41-119 mm at rest (docs/design.md). It is on by
    default in MuJoCo >= 3.17 (a disable flag); the MJCF says ``multiccd="enable"`` and the
    compiled model is checked. The Jacobian layout is ``contact.jacobian``
    (:func:`~.solver_choice.default_jacobian`: dense for one body, sparse for a stack; MuJoCo 4.0.0's
    sparse-factorisation bug, fixed in 4.0.1, is not reached by our scenes, docs/performance.md).
    """
    g = float(check_positive("gravity", gravity, "m/s^2"))
    bodies = tuple(bodies)
    if not bodies:
        raise BlastscaleInputError("bodies = () is out of range: at least one body is needed")
    n = len(bodies)
    pairs = tuple((-1, i) for i in range(n)) if pairs is None else tuple(tuple(p) for p in pairs)
    order = body_order(pairs, n)
    depth = engagement_depth(contact.time_constant, g)
    fixed = tuple(fixed)
    assets = "".join(b.shape.mjcf_assets(f"{b.name}_geom") for b in [bodies[k] for k in order] + list(fixed))
    worldbody = ['<geom name="ground" type="plane" size="0 0 1"/>'] + [  # supports: geoms of the world body
        f'<frame pos="{" ".join(mjcf_number(float(v)) for v in b.position)}">{b.shape.mjcf_geom(f"{b.name}_geom")}'
        "</frame>"
        for b in fixed
    ]
    ground = ["ground"] + [g for b in fixed for g in b.shape.contact_geoms(f"{b.name}_geom")]
    worldbody += [_free_body_xml(bodies[k]) for k in order]

    def geoms(i):
        return ground if i < 0 else bodies[i].shape.contact_geoms(f"{bodies[i].name}_geom")

    def body(i):
        return "world" if i < 0 else bodies[i].name

    def xml_pairs(which, margin, side=frozenset()):  # margin [m]: 0 at contact; side pairs at -depth (.collision)
        attrs = {False: contact.mjcf_pair_attributes(margin), True: contact.mjcf_pair_attributes(-depth)}
        return [
            f'<pair geom1="{a}" geom2="{b}" {attrs[(i, j) in side]}/>'
            for i, j in which
            for a in geoms(i)
            for b in geoms(j)
        ]

    contacts = xml_pairs(pairs, 0.0, {tuple(p) for p in side_pairs})  # rule 1 of .collision: interfaces, in order
    seen = {tuple(sorted(p)) for p in pairs}
    if len(seen) == n * (n + 1) // 2:
        default = 'contype="0" conaffinity="0"'  # every two surfaces are an interface: nothing else can touch
    elif contact.geom_expressible:  # rule 2: every other two surfaces through the broad phase
        default = f"{BROAD_PHASE} {contact.mjcf_geom_attributes(-depth)}"
        contacts += [f'<exclude body1="{body(i)}" body2="{body(j)}"/>' for i, j in sorted(seen)]
    else:  # rule 2 with solreffriction: explicit pairs
        default = 'contype="0" conaffinity="0"'
        extra = [(i, j) for i in range(-1, n) for j in range(i + 1, n) if (i, j) not in seen]
        contacts += xml_pairs(extra, -depth)
    asset_block = f"<asset>{assets}</asset>" if assets else ""
    # the solver's arena grows with the contacts: ~0.5 MB per body beyond the default (200 blocks: 64 + 100 MB)
    size = f'<size memory="{64 + n // 2}M"/>' if n > 20 else ""
    xml = (
        '<mujoco model="blastscale">'
        '<compiler angle="radian" boundmass="0" boundinertia="0"/>'
        f"{contact.mjcf_option(g)}{size}<default><geom {default}/></default>{asset_block}"
        f"<worldbody>{''.join(worldbody)}</worldbody><contact>{''.join(contacts)}</contact></mujoco>"
    )
    ids = np.empty(n, dtype=int)
    ids[order] = np.arange(1, n + 1)
    scene = Scene(xml=xml, mj_model=None, bodies=bodies, contact=contact, gravity=g, body_ids=ids)
    return compile_scene(scene) if compile else scene


def compile_scene(scene: Scene) -> Scene:
    """``scene`` with its MJCF compiled into ``mj_model`` (multi-point convex collision checked on)."""
    import mujoco

    mj_model = mujoco.MjModel.from_xml_string(scene.xml)
    if mj_model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_MULTICCD:
        raise RuntimeError("MuJoCo multiccd is disabled: flat drum-on-drum contacts would get one point")
    return replace(scene, mj_model=mj_model)


def structure_scene(
    structure, contact: ContactSettings, gravity: float = STANDARD_GRAVITY, *, rotation: float = 0.0, compile=True
) -> Scene:
    """The MuJoCo model of any structure of :mod:`blastscale.structures` at rest: one free body
    per ``structure.bodies`` entry with its exact mass and inertia, its contact geometry
    (:func:`engine_shape`), one contact pair per ``structure.interfaces`` entry; every other
    two bodies, and every body and the ground, may touch as they move (:mod:`.collision`). An
    assembly's supports (``structure.fixed_shapes``) are welded to the ground, part of it.

    Parameters
    ----------
    structure : structure
        E.g. :class:`~blastscale.structures.RectangularBlock`,
        :class:`~blastscale.structures.MultiDrumColumn`.
    contact : ContactSettings
        Contact, time-step and solver settings (the same on every interface).
    gravity : float
        g [m/s^2].
    rotation : float
        Initial tilt theta_0 [rad] of the whole structure about its lowest body's base edge
        (:func:`tilt_bodies`); 0: standing upright.
    compile : bool
        Compile the model (:func:`build_scene`).

    Returns
    -------
    Scene
    """
    density = float(structure.describe()["density_kg_m3"])
    specs = [
        BodySpec(b.name, engine_shape(b.shape, density), tuple(b.com), mass=b.mass, inertia=tuple(b.inertia))
        for b in structure.bodies
    ]
    fixed = [
        BodySpec(name, engine_shape(shape, density), com) for name, shape, com in getattr(structure, "fixed_shapes", ())
    ]
    side = side_joints(getattr(structure, "interface_details", ()))
    return build_scene(tilt_bodies(specs, rotation), contact, gravity, structure.interfaces, fixed, compile, side)


def block_scene(
    block: RectangularBlock,
    contact: ContactSettings | None = None,
    gravity: float = STANDARD_GRAVITY,
    *,
    rotation: float = 0.0,
) -> Scene:
    """A single rectangular block standing on the ground (optionally tilted onto a base edge):
    :func:`structure_scene` of the block.

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

    Returns
    -------
    Scene
    """
    if not isinstance(block, RectangularBlock):
        raise BlastscaleInputError(f"block = {block!r} is not a RectangularBlock")
    return structure_scene(block, ContactSettings() if contact is None else contact, gravity, rotation=rotation)
