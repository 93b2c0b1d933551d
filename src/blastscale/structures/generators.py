"""Generators of masonry assemblies: walls, arches, portals (trilithons), as :class:`~.assembly.Assembly`.

Orientation (the blast comes from -x): every generated structure faces it, its plane is y-z, its
thickness (wall), depth (arch) or column width (portal) along x, centred on x = 0; the ground is z = 0.
Interfaces are not declared here: the assembly finds them by geometry.

* :func:`wall` -- courses of equal units in stack or running bond; a running course (the 2nd, 4th,
  ...) starts and ends with a half unit, so its joints fall at the middle of the units below
  (the running-bond generators of LMGC90's and COMPAS's wall templates do the same).
* :func:`arch` -- ``voussoirs`` equal wedges of a circular arch of centreline radius R, radial
  thickness t and depth d, spanning ``embrace_deg`` symmetric about the crown; each voussoir is the
  convex hull of its 8 corners (intrados and extrados are chords), joints radial (the stereotomy
  of Ochsendorf 2002's minimum-thickness analysis). With ``pier_height_m`` > 0 a pier stands under
  each springer, its top the springing joint; a semicircular arch without piers springs from the ground.
* :func:`portal` -- two square columns (monolithic or of ``drums`` equal drums) and a free lintel
  on top (the trilithon; the rocking frame of Makris & Vassiliou 2013).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive_scalar, check_range
from .assembly import Assembly
from .convex_block import ConvexBlock

__all__ = ["wall", "arch", "portal", "box_vertices_from_bounds", "BONDS"]

#: Bond patterns of :func:`wall`.
BONDS = ("running", "stack")
#: Most blocks a generator makes (the engine's cost grows with the count; docs/assemblies.md).
MAX_BLOCKS = 2000


def box_vertices_from_bounds(x0, x1, y0, y1, z0, z1) -> np.ndarray:
    """The 8 corners (8, 3) of the axis-aligned box between bounds ``x0..x1``, ``y0..y1``, ``z0..z1`` [m] (a box
    of half-sizes centred on the axis: :func:`blastscale.structures.base.centred_box_vertices`)."""
    return np.array(list(itertools.product((x0, x1), (y0, y1), (z0, z1))), dtype=float)


def _whole(name: str, value, lo: int, hi: int = MAX_BLOCKS) -> int:
    if (
        isinstance(value, bool)
        or not isinstance(value, (int, float, np.integer, np.floating))
        or not (math.isfinite(value) and float(value).is_integer() and lo <= value <= hi)
    ):
        raise BlastscaleInputError(f"{name} = {value!r} is out of range: valid range is whole numbers {lo}-{hi}")
    return int(value)


def wall(
    length_m: float = 4.0,
    height_m: float = 3.0,
    thickness_m: float = 0.5,
    courses: int = 10,
    units_per_course: int = 8,
    bond: str = "running",
    density_kg_m3: float = 2000.0,
) -> Assembly:
    """A dry-stone wall facing the blast (plane y-z, thickness along x).

    Parameters
    ----------
    length_m, height_m, thickness_m : float
        Wall length (along y), height and thickness (along x) [m], > 0.
    courses : int
        Number of courses (rows), >= 1; each ``height_m / courses`` high.
    units_per_course : int
        Full units per course, >= 1, each ``length_m / units_per_course`` long.
    bond : {"running", "stack"}
        Stack bond: every course the same. Running bond: every second course shifted by half a
        unit, a half unit at each of its ends (``units_per_course + 1`` blocks).
    density_kg_m3 : float
        [kg/m^3].

    Returns
    -------
    Assembly
        Blocks named ``C{course}U{unit}`` (from 1, bottom course first, from -y).
    """
    L = check_positive_scalar("wall length_m", length_m, "m")
    H = check_positive_scalar("wall height_m", height_m, "m")
    t = check_positive_scalar("wall thickness_m", thickness_m, "m")
    nc = _whole("wall courses", courses, 1)
    nu = _whole("wall units_per_course", units_per_course, 1)
    check_choice("wall bond", bond, BONDS)
    if nc * (nu + 1) > MAX_BLOCKS:
        raise BlastscaleInputError(
            f"wall courses x units_per_course = {nc} x {nu} is out of range: at most {MAX_BLOCKS} blocks"
        )
    u, h = L / nu, H / nc
    blocks = []
    for c in range(nc):
        joints = np.arange(nu + 1) * u
        if bond == "running" and c % 2 == 1:
            joints = np.concatenate([[0.0], (np.arange(nu) + 0.5) * u, [L]])
        joints[-1] = L
        for k, (y0, y1) in enumerate(zip(joints[:-1], joints[1:])):
            blocks.append(
                ConvexBlock(
                    f"C{c + 1}U{k + 1}",
                    box_vertices_from_bounds(
                        -t / 2, t / 2, y0 - L / 2, y1 - L / 2, c * h, (c + 1) * h if c < nc - 1 else H
                    ),
                    density_kg_m3,
                )
            )
    params = (
        ("length_m", L),
        ("wall_height_m", H),
        ("wall_thickness_m", t),
        ("courses", nc),
        ("units_per_course", nu),
        ("bond", bond),
    )
    return Assembly(tuple(blocks), kind="wall", parameters=params, check=False)


def arch(
    radius_m: float = 2.5,
    thickness_m: float = 0.5,
    depth_m: float = 1.0,
    voussoirs: int = 15,
    embrace_deg: float = 180.0,
    pier_height_m: float = 0.0,
    density_kg_m3: float = 2000.0,
) -> Assembly:
    """A circular arch of voussoirs facing the blast (plane y-z, depth along x).

    Parameters
    ----------
    radius_m : float
        Radius R of the centreline [m], > 0.
    thickness_m : float
        Radial thickness t [m], 0 < t < 2 R.
    depth_m : float
        Depth d along x [m], > 0.
    voussoirs : int
        Number of equal voussoirs, >= 1.
    embrace_deg : float
        Angle the arch spans, symmetric about the crown [deg], (0, 360): 180 is semicircular.
    pier_height_m : float
        Height of the lowest point of each springing joint above the ground [m], >= 0; > 0 puts a pier
        (a block with vertical sides, its top the springing joint) under each springer. An arch whose
        springing joints are not horizontal (embrace other than 180 deg) needs piers.
    density_kg_m3 : float
        [kg/m^3].

    Returns
    -------
    Assembly
        Voussoirs ``V1``.. from the -y springer; piers ``pier-L`` (-y), ``pier-R``.
    """
    R = check_positive_scalar("arch radius_m", radius_m, "m")
    t = float(check_range("arch thickness_m", thickness_m, 0.0, 2.0 * R, "m", lo_open=True, hi_open=True))
    d = check_positive_scalar("arch depth_m", depth_m, "m")
    n = _whole("arch voussoirs", voussoirs, 1)
    beta = float(check_range("arch embrace_deg", embrace_deg, 0.0, 360.0, "deg", lo_open=True, hi_open=True))
    hp = float(check_range("arch pier_height_m", pier_height_m, 0.0, math.inf, "m"))
    if hp == 0.0 and abs(beta - 180.0) > 1e-9:
        raise BlastscaleInputError(
            f"arch embrace_deg = {beta:g} needs pier_height_m > 0: its springing joints are "
            "inclined (only a semicircular arch, 180 deg, springs from the ground)"
        )
    ri, ro = R - t / 2, R + t / 2
    th0 = math.radians(90.0 - beta / 2.0)  # springers at th0 and pi - th0, angles from +y towards +z
    zc = hp - min(ri * math.sin(th0), ro * math.sin(th0))  # the lowest springing point at z = pier height

    def ring(phi, r):
        return r * math.cos(phi), zc + r * math.sin(phi)

    def prism(poly2d):
        return np.array([(x, y, z) for (y, z) in poly2d for x in (-d / 2, d / 2)], dtype=float)

    blocks = []
    phis = math.pi - th0 - np.arange(n + 1) * math.radians(beta) / n  # from the -y springer over the crown
    if abs(beta - 180.0) <= 1e-9:
        phis[0], phis[-1] = math.pi, 0.0
    for k in range(n):
        a, b = phis[k], phis[k + 1]
        pts = [ring(a, ri), ring(a, ro), ring(b, ro), ring(b, ri)]
        pts = [(y, 0.0 if abs(z) < 1e-12 * R else z) for y, z in pts]
        blocks.append(ConvexBlock(f"V{k + 1}", prism(pts), density_kg_m3))
    if hp > 0.0:
        for name, phi in (("pier-L", phis[0]), ("pier-R", phis[-1])):
            (yi, zi), (yo, zo) = ring(phi, ri), ring(phi, ro)
            blocks.append(ConvexBlock(name, prism([(yi, 0.0), (yo, 0.0), (yo, zo), (yi, zi)]), density_kg_m3))
    params = (
        ("radius_m", R),
        ("arch_thickness_m", t),
        ("depth_m", d),
        ("voussoirs", n),
        ("embrace_deg", beta),
        ("pier_height_m", hp),
    )
    return Assembly(tuple(blocks), kind="arch", parameters=params, check=False)


def portal(
    column_height_m: float = 4.0,
    column_width_m: float = 0.8,
    span_m: float = 3.0,
    lintel_height_m: float = 1.0,
    lintel_overhang_m: float = 0.3,
    drums: int = 1,
    density_kg_m3: float = 2000.0,
) -> Assembly:
    """A trilithon facing the blast: two square columns and a free lintel on top (plane y-z).

    Parameters
    ----------
    column_height_m, column_width_m : float
        Column height and side (square section, also the lintel's depth along x) [m], > 0.
    span_m : float
        Clear span between the columns [m], > 0.
    lintel_height_m : float
        [m], > 0.
    lintel_overhang_m : float
        Lintel beyond each column's outer face [m], >= 0.
    drums : int
        Drums per column, >= 1 (1: monolithic).
    density_kg_m3 : float
        [kg/m^3].

    Returns
    -------
    Assembly
        Blocks ``col-L`` / ``col-R`` (or ``col-L-1``.. from the base), then ``lintel``.
    """
    Hc = check_positive_scalar("portal column_height_m", column_height_m, "m")
    w = check_positive_scalar("portal column_width_m", column_width_m, "m")
    s = check_positive_scalar("portal span_m", span_m, "m")
    hl = check_positive_scalar("portal lintel_height_m", lintel_height_m, "m")
    o = float(check_range("portal lintel_overhang_m", lintel_overhang_m, 0.0, math.inf, "m"))
    nd = _whole("portal drums", drums, 1)
    blocks = []
    for side, yc in (("L", -(s + w) / 2), ("R", (s + w) / 2)):
        for k in range(nd):
            name = f"col-{side}" if nd == 1 else f"col-{side}-{k + 1}"
            z1 = Hc if k == nd - 1 else (k + 1) * Hc / nd
            blocks.append(
                ConvexBlock(
                    name,
                    box_vertices_from_bounds(-w / 2, w / 2, yc - w / 2, yc + w / 2, k * Hc / nd, z1),
                    density_kg_m3,
                )
            )
    half = s / 2 + w + o
    blocks.append(
        ConvexBlock("lintel", box_vertices_from_bounds(-w / 2, w / 2, -half, half, Hc, Hc + hl), density_kg_m3)
    )
    params = (
        ("column_height_m", Hc),
        ("column_width_m", w),
        ("span_m", s),
        ("lintel_height_m", hl),
        ("lintel_overhang_m", o),
        ("drums", nd),
    )
    return Assembly(tuple(blocks), kind="portal", parameters=params, check=False)
